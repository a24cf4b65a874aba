// flaplag — the validity envelope of the ordering models: the one place that says which
// controls and deflections the equations can describe.
//
// The ordering scheme of the derivation (eps ~ 0.1-0.2) keeps terms by their order in eps with
// small angles (sin x = x, cos x = 1) and linear, unstalled aerodynamics (lift slope a, no
// stall).  Outside the limits below the equations still give numbers, but not those of the
// blade they describe; results there come back with status Warning naming the quantity, its
// value and the limit:
//   - pitch |theta0|, |theta1c|, |theta1s| <= kMaxPitch = 0.35 rad (20 deg): the pitch enters
//     as O(eps^(1/2)) through sin theta ~ theta, cos theta ~ 1; at 20 deg these are off by 2 %
//     and 6 %, the size of the terms the ordering drops;
//   - the mean blade angle of attack at 3/4 radius, theta0 - lambda / 0.75 (the angle of the
//     hover blade-element estimate, inflow ratio lambda) within kMaxAngleOfAttack = 0.26 rad
//     (15 deg): the lift is linear in the angle of attack only below stall, which sets in
//     near 12-15 deg for rotor airfoils; the local angle on the retreating side in fast
//     forward flight is not checked (it is not part of the ordering's input);
//   - the flap tip deflection of the hover equilibrium |w/l| <= kMaxFlapDeflection = 0.35
//     (a slope of 20 deg): the ordering takes it O(eps) with cos ~ 1 for the deflected blade.
#pragma once

#include <cmath>
#include <string>

#include "flaplag/core/format.h"
#include "flaplag/rotor/parameters.h"

namespace flaplag {

inline constexpr double kMaxPitch = 0.35;           // rad, |theta0|, |theta1c|, |theta1s|
inline constexpr double kMaxAngleOfAttack = 0.26;   // rad, |theta0 - lambda / 0.75|
inline constexpr double kMaxFlapDeflection = 0.35;  // |w/l| at the tip, hover equilibrium

// "" inside the envelope; otherwise "outside the model's validity envelope: <quantity> = <value>
// (limit <limit>)[; ...]", every quantity outside named.  p's pitch (theta = theta0, theta1c,
// theta1s), the inflow ratio lambda used with it and the hover equilibrium's flap tip
// deflection w/l (NaN: not checked).
inline std::string validity_warning(const RotorParameters& p, double inflow, double flap_tip) {
  std::string out;
  auto check = [&](const char* name, double value, double limit, const char* unit,
                   const char* why) {
    if (!(std::abs(value) > limit)) return;  // NaN: not checked
    out += std::string(out.empty() ? "" : "; ") + name + " = " + short_text(value) + unit + " (|" +
           name + "| <= " + short_text(limit) + unit + ": " + why + ")";
  };
  const char* pitch = "small-angle ordering";
  check("theta0", p.theta, kMaxPitch, " rad", pitch);
  check("theta1c", p.theta1c, kMaxPitch, " rad", pitch);
  check("theta1s", p.theta1s, kMaxPitch, " rad", pitch);
  check("alpha_0.75", p.theta - inflow / 0.75, kMaxAngleOfAttack, " rad",
        "linear aerodynamics below stall; theta0 - lambda/0.75");
  check("flap_tip", flap_tip, kMaxFlapDeflection, "",
        "O(eps) flap deflection w/l of the hover equilibrium");
  return out.empty() ? out : "outside the model's validity envelope: " + out;
}

}  // namespace flaplag
