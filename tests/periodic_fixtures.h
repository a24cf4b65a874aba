// Periodic systems shared by the numerics tests and the transition bench (compiled once in
// periodic_fixtures.cc, the library flaplag_test_fixtures):
//
//  - rotor_like(): THE rotor-like 4x4 system whose accuracy figures transition.cc quotes (also
//    timed by bench/transition_bench.cpp);
//  - harmonics_of(): exact harmonic coefficients of a matrix trigonometric polynomial;
//  - reducible_system(): Lyapunov-reducible systems y = P(psi) z, z' = B z, whose transition
//    matrix P(0) e^{2 pi B} P(0)^{-1} and exponents eig(B) are known exactly; exact_cases()
//    collects them (2 and 4 states, with and without a sector) with the Markus-Yamabe example;
//  - scale_of(), rk4_error_model(), hsu_error_model(): a priori leading-term error models that
//    justify the tolerances of the transition tests;
//  - sector_as_varying(), clipped_scalar(): systems with a varying region (the exact reversed
//    flow's point-wise A(psi)), one equal to a sector system, one with a closed-form Phi;
//  - operator_norm(), inverse(): the dense operations the tests' checks need beyond
//    flaplag/numerics/dense.h, compiled once here rather than instantiated in every test.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <utility>
#include <vector>

#include "flaplag/numerics/periodic_system.h"

namespace flaplag::fixtures {

// A rotor-like hover matrix, y = [g', g, h', h]: flap (omega ~ 1.17/rev, zeta ~ -0.15) and
// lightly damped lag (omega ~ 1.28/rev, zeta ~ -0.02) oscillators with weak coupling.
Eigen::MatrixXd rotor_hover_matrix();

// The rotor-like 4x4 periodic system: rotor_hover_matrix() plus harmonics to 4/rev in the rows
// of the accelerations (h = 1 .. 8, amplitudes falling as 1/k), a reversed-flow sector
// [5 pi/4, 7 pi/4) in which the damping and flap-lag coupling harmonics change sign, and a
// strong 1/rev flap stiffness term 3 cos psi (so that |A(psi)| reaches about 5).
PeriodicSystem rotor_like();

// The system with `normal` over the period and `reversed` on the sector [begin, end).
PeriodicSystem with_sector(HarmonicSet normal, HarmonicSet reversed, double begin, double end);
// The harmonic set of the piece that contains psi (a harmonic piece).
const HarmonicSet& set_at(const PeriodicSystem& s, double psi);

using MatrixFn = std::function<Eigen::MatrixXd(double)>;

// Harmonic coefficients (index convention of periodic_system.h: 1, cos psi, sin psi, cos 2 psi,
// ...) of an n x n matrix trigonometric polynomial F of degree <= `degree`.  The trapezoidal
// rule with M = 4 (degree + 1) > 2 degree equally spaced points is exact for the products
// F cos k psi, F sin k psi (k <= degree), so the coefficients are exact up to rounding.
// Callers check the degree assumption by evaluating the expansion off the sample points.
std::vector<Eigen::MatrixXd> harmonics_of(const MatrixFn& F, int n, int degree);

// A smooth invertible frame P(psi) and its derivative, both 2 pi-periodic.
struct Frame {
  MatrixFn P, dP;
};

// y = P(psi) z with z' = B z gives y' = A(psi) y with A = P' P^{-1} + P B P^{-1}.  Both P and
// P^{-1} below are trigonometric polynomials, so A has a finite harmonic expansion of degree
// <= `degree` (the caller's bound).  With a sector, the reversed region uses its own frame,
// which must equal the normal one at both sector edges (y is continuous, A jumps); then
//   Phi(2 pi, 0) = P(0) e^{2 pi B} P(0)^{-1}  and the Floquet exponents are eig(B) exactly.
PeriodicSystem reducible_system(const Eigen::MatrixXd& B, const Frame& normal, int degree,
                                const Frame* reversed = nullptr, double sector_begin = 0.0,
                                double sector_end = 0.0);

Eigen::MatrixXd reducible_phi(const Eigen::MatrixXd& B, const Frame& normal);

// dA/dpsi inside the region that contains psi, from the harmonic coefficients.
Eigen::MatrixXd A_rate(const PeriodicSystem& s, double psi);

// Sizes that set the leading error terms: L = max ||A(psi)||_2, C = max ||[A, A']||_2 (sampled
// on 2000 points; both regions).
struct SystemScale {
  double L = 0.0;
  double C = 0.0;
};
SystemScale scale_of(const PeriodicSystem& s);

// A priori leading-term error models of Phi(2 pi, 0) relative to max |Phi| (T = 2 pi, h the
// step).  They ignore the propagation of the local errors by Phi(2 pi, psi) (of order 1 for the
// decaying systems used here), so the tests allow a factor 4.
//  RK4 (order 4): the one-step remainder (h A)^5 / 5! accumulated over T / h steps,
//    T (h L)^4 L / 120.
//  Hsu (order 2, eq 3.29): exp(Delta C_k) with C_k the interval mean misses the second Magnus
//    term Delta^3 [A, A'] / 12 on every interval, T Delta^2 C / 12, plus the Taylor remainder
//    of J terms, T (Delta L)^J L / (J + 1)!.
double rk4_error_model(const SystemScale& s, int steps);
double hsu_error_model(const SystemScale& s, int intervals, int terms);

// Rotation by angle t and its derivative d/dt.
Eigen::Matrix2d rotation(double t);
Eigen::Matrix2d rotation_rate(double t);

// 2 states: P = R(psi) U(psi), U = [[1, u], [0, 1]] with u = 0.5 sin psi + 0.3 cos 2 psi + c
// sin(psi - s0) (c = 0 in the normal region).  U^{-1} = [[1, -u], [0, 1]] and R' R^T = J, so
// A = J + R (U' U^{-1} + U B U^{-1}) R^T: deg U B U^{-1} <= 4 (its u^2 term) and R ... R^T adds
// 2, so deg A <= 6.  The sin(psi - s0) term vanishes at s0 and s0 + pi, so a sector
// [s0, s0 + pi) with c != 0 keeps P continuous.
Frame frame2(double c = 0.0, double s0 = 0.0);

// 4 states: P = diag(R(psi), R(2 psi)) (I + N(psi)), N strictly upper triangular with entries
// of degree 1 (plus c sin(psi - s0) in N(0, 3)).  (I + N)^{-1} = I - N + N^2 - N^3 has degree
// 3, so N' (I + N)^{-1} and (I + N) B (I + N)^{-1} have degree <= 4; conjugation by the
// rotations (1 and 2/rev, R_i X_ij R_j^T) adds up to 4, so deg A <= 8.
Frame frame4(double c = 0.0, double s0 = 0.0);

// Real n x n matrix with eigenvalues z_k +- i w_k (one 2 x 2 block per pair), mixed by a fixed
// well-conditioned similarity.
Eigen::MatrixXd with_eigenvalues(const std::vector<std::pair<double, double>>& pairs);

// The Markus-Yamabe example (L. Markus, H. Yamabe, Osaka Math. J. 12, 1960), written from
// first principles:
//   A(psi) = [[-1 + 1.5 cos^2, 1 - 1.5 cos sin], [-1 - 1.5 sin cos, -1 + 1.5 sin^2]]
//          = [[-1/4, 1], [-1, -1/4]] + 3/4 cos 2psi [[1, 0], [0, -1]] - 3/4 sin 2psi [[0, 1], [1,
//          0]]
// (cos^2 = (1 + cos 2psi) / 2, sin^2 = (1 - cos 2psi) / 2, sin cos = sin 2psi / 2).  Its
// eigenvalues -1/4 +- i sqrt(7)/4 have negative real parts for every psi, yet
//   y1 = e^{psi/2} (-cos psi, sin psi),  y2 = e^{-psi} (sin psi, cos psi)
// solve y' = A y (substitute: row 1 of A y1 is e^{psi/2} (cos + sin - 1.5 cos (cos^2 + sin^2))
// = e^{psi/2} (sin - cos / 2) = (y1)_1', and likewise for the other three components).  So
// y = P z with P = [[-cos, sin], [sin, cos]], z' = diag(1/2, -1) z: Phi(2 pi) =
// diag(e^{pi}, e^{-2 pi}), exponents 1/2 and -1, omega 0 (the trace, -1/2, is their sum).
PeriodicSystem markus_yamabe();
Frame markus_yamabe_frame();

// A periodic system with an exactly known transition matrix and exponents eig(B).
struct ExactCase {
  const char* name;
  PeriodicSystem sys;
  Eigen::MatrixXd B;    // z' = B z, y = P(psi) z
  Frame frame;          // P in the normal region (psi = 0 lies there)
  Frame reversed;       // P in the sector (equal to `frame` without one)
  Eigen::MatrixXd phi;  // Phi(2 pi, 0) = P(0) e^{2 pi B} P(0)^{-1}
};

// 2 and 4 states, with and without a sector (P continuous, A jumping at its edges), and the
// Markus-Yamabe example.  Exponents: -0.15 +- 1.0805i (2 states; omega 1.08 > 1/2 checks the
// integer ambiguity); flap-like -0.15 +- 1.17i and lag-like -0.02 +- 1.28i (4 states).
std::vector<ExactCase> exact_cases();

// The same system with its sector replaced by a varying region whose evaluator sums the
// sector's harmonics point by point: every integrator must give what it gives on the sector.
PeriodicSystem sector_as_varying(const PeriodicSystem& sector);

// A scalar system shaped like the exact reversed-flow region: -0.05 + 0.7 cos psi on [0, pi),
// and 0.3 + 0.9 clamp(-sin psi, 0, c) on the varying region [pi, 2 pi), which is not smooth at
// the breaks pi + asin c and 2 pi - asin c.  clipped_log_phi() is ln Phi(2 pi) in closed form:
// -0.05 pi + 0.3 pi + 0.9 (2 (1 - cos a) + c (pi - 2 a)), a = asin c.
PeriodicSystem clipped_scalar(double c = 0.6);

double clipped_log_phi(double c = 0.6);

// The operator 2-norm of m (its largest singular value: the square root of the spectral radius
// of m^T m, by the library's eigen-solve) and the inverse of a square nonsingular m (Gauss-Jordan
// elimination with partial pivoting).  Both agree with Eigen's operatorNorm() and inverse() to
// rounding; they are references for the checks, not the code under test.
double operator_norm(const Eigen::MatrixXd& m);
Eigen::MatrixXd inverse(const Eigen::MatrixXd& m);
Eigen::MatrixXcd inverse(const Eigen::MatrixXcd& m);

}  // namespace flaplag::fixtures
