// flaplag — the Gauss-Legendre rules used by the numerics (one table for every caller).
//
// Nodes x_i on [-1, 1] and weights w_i (sum 2); the n-point rule is exact for polynomials of
// degree 2n - 1.  On [a, b]: int f ~ (b - a)/2 sum w_i f(m + r x_i), m the midpoint, r the half
// width.  The two-point rule is used by the Magnus integrators in its unit-interval form: nodes
// 1/2 -/+ kGauss2Offset of the step (magnus4_step).
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

// The composite eight-point rule on [lo, hi] in `panels` equal panels (>= 1): fn(psi, weight) at
// every node, panel by panel, so that sum weight f(psi) ~ int_lo^hi f.
template <typename Fn>
inline void composite_gauss8(double lo, double hi, int panels, Fn&& fn) {
  const double h = (hi - lo) / panels;
  for (int q = 0; q < panels; ++q) {
    const double mid = lo + (q + 0.5) * h;
    for (int i = 0; i < 8; ++i) fn(mid + 0.5 * h * kX8[i], 0.5 * h * kW8[i]);
  }
}

// One step of the fourth-order Magnus integrator over [a, b] with two-point Gauss nodes:
//   Omega = c1 (A(psi1) + A(psi2)) + c2 [A(psi2), A(psi1)],  Phi <- exp(Omega) Phi,
// c1 = h/2, c2 = sqrt(3) h^2 / 12.  The method is symmetric: its global error expands in h^4,
// h^6, ...  Every Magnus kernel (Eigen, fixed size, wide) takes its nodes and weights here.
struct Magnus4Step {
  double psi1, psi2, c1, c2;
};
inline Magnus4Step magnus4_step(double a, double b) {
  const double h = b - a;
  return {a + (0.5 - kGauss2Offset) * h, a + (0.5 + kGauss2Offset) * h, 0.5 * h,
          0.5 * kGauss2Offset * h * h};
}

}  // namespace flaplag::gauss
