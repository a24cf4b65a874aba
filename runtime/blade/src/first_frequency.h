// flaplag blade — the stiffness of a requested first rotating frequency (not installed): the
// checks of the frequency and the root of the increasing concave first eigenvalue, shared by the
// Galerkin modes (rotating_modes.cc) and the finite-element modes (blade_elements.cc).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "flaplag/blade/rotating_modes.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"

namespace flaplag::internal {

inline const char* option_name(BendingDirection dir) {
  return dir == BendingDirection::Flap ? "omega_flap" : "omega_lag";
}
inline const char* direction_name(BendingDirection dir) {
  return dir == BendingDirection::Flap ? "flap" : "lag";
}

// Throws InvalidInput naming omega_flap / omega_lag unless omega is finite and positive.
inline void check_first_frequency(BendingDirection dir, double omega) {
  if (!std::isfinite(omega) || omega <= 0.0) {
    throw InvalidInput(option_name(dir), round_trip_text(omega),
                       std::string("first rotating ") + direction_name(dir) +
                           " frequency by Omega must be finite and positive");
  }
}
inline void check_first_frequencies(double omega_flap, double omega_lag) {
  check_first_frequency(BendingDirection::Flap, omega_flap);
  check_first_frequency(BendingDirection::Lag, omega_lag);
}

// Throws InvalidInput unless omega^2 exceeds lambda0, the first eigenvalue without bending
// stiffness (centrifugal stiffening only) of `discretization` ("this blade", ...).
inline void check_above_limit(BendingDirection dir, double omega, double lambda0,
                              const std::string& discretization) {
  if (!(omega * omega > lambda0)) {
    throw InvalidInput(option_name(dir), round_trip_text(omega),
                       std::string("first rotating ") + direction_name(dir) +
                           " frequency must exceed the k -> 0 (centrifugal stiffening only) "
                           "limit " +
                           round_trip_text(std::sqrt(std::max(lambda0, 0.0))) + " of " +
                           discretization);
  }
}

// The x >= 0 with lambda_1(x) = target, for lambda_1 increasing and concave in x (a minimum of
// Rayleigh quotients linear in x); eval(x) gives lambda_1(x) and its slope.  Newton on a
// concave increasing function lands left of the root after at most one step and then climbs
// monotonically; the bracket [lo, hi] with bisection fallback guards rounding.  Stops when
// |lambda_1 - target| <= tolerance eps target or the step is below 4 eps x.
template <typename Eval>
double solve_concave(Eval eval, double target, double x, double tolerance) {
  double lo = 0.0;
  double hi = std::numeric_limits<double>::infinity();
  for (int it = 0; it < 200; ++it) {
    const auto [lambda1, slope] = eval(x);
    const double f = lambda1 - target;
    if (f == 0.0) return x;
    if (f < 0.0) {
      lo = x;
    } else {
      hi = x;
    }
    double next = x - f / slope;
    if (!(next > lo && next < hi)) next = std::isfinite(hi) ? 0.5 * (lo + hi) : 2.0 * x + 1.0;
    if (std::abs(f) <= tolerance * std::numeric_limits<double>::epsilon() * target) return x;
    if (std::abs(next - x) <= 4.0 * std::numeric_limits<double>::epsilon() * x) return next;
    x = next;
  }
  return x;
}

}  // namespace flaplag::internal
