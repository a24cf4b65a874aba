// flaplag — sin(x)/x, the factor of a harmonic's mean over an interval (eqs 4.2-4.5).
#pragma once

#include <cmath>

namespace flaplag::detail {

// sin(x)/x, accurate near 0 (the series keeps full precision where the quotient cancels).
inline double sinc(double x) {
  if (std::abs(x) < 1e-4) {
    const double x2 = x * x;
    return 1.0 - x2 / 6.0 * (1.0 - x2 / 20.0);
  }
  return std::sin(x) / x;
}

}  // namespace flaplag::detail
