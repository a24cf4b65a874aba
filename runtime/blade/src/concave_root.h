// flaplag blade — the root of an increasing concave first eigenvalue (not installed): shared by
// the Galerkin modes (rotating_modes.cc) and the finite-element modes (blade_elements.cc), which
// both solve for the stiffness that gives a requested first rotating frequency.
#pragma once

#include <cmath>
#include <limits>

namespace flaplag::internal {

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
