// flaplag — the Gauss-Legendre rules used by the numerics (one table for every caller).
//
// Nodes x_i on [-1, 1] and weights w_i (sum 2); the n-point rule is exact for polynomials of
// degree 2n - 1.  On [a, b]: int f ~ (b - a)/2 sum w_i f(m + r x_i), m the midpoint, r the half
// width.  The two-point rule is used by the Magnus integrators in its unit-interval form: nodes
// 1/2 -/+ kGauss2Offset of the step.
#pragma once

namespace flaplag::gauss {

// Two points: +-1/sqrt(3); on [0, 1] the nodes are 1/2 -/+ sqrt(3)/6.
inline constexpr double kGauss2Offset = 0.28867513459481287;  // sqrt(3) / 6

// Three points: 0, +-sqrt(3/5); weights 5/9, 8/9, 5/9.
inline constexpr double kX3[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
inline constexpr double kHalfW3[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};  // w_i / 2

// Eight points (exact for degree 15).
inline constexpr double kX8[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                  -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                  0.7966664774136267,  0.9602898564975363};
inline constexpr double kW8[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                  0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                  0.2223810344533745, 0.1012285362903763};

}  // namespace flaplag::gauss
