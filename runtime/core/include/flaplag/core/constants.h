// flaplag — mathematical constants used across the libraries (one definition each).
#pragma once

namespace flaplag {

inline constexpr double kPi = 3.141592653589793238462643383279502884;
inline constexpr double kTwoPi = 2.0 * kPi;   // period T of psi = Omega t (one revolution)
inline constexpr double kHalfPi = 0.5 * kPi;  // bound of the angles (pitch, cone, droop)

}  // namespace flaplag
