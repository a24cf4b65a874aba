// Periodic systems shared by the numerics tests and the transition bench (header-only, needs
// only flaplag_numerics):
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
//    flow's point-wise A(psi)), one equal to a sector system, one with a closed-form Phi.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "flaplag/core/constants.h"
#include "flaplag/numerics/dense.h"
#include "flaplag/numerics/periodic_system.h"

namespace flaplag::fixtures {

// A rotor-like hover matrix, y = [g', g, h', h]: flap (omega ~ 1.17/rev, zeta ~ -0.15) and
// lightly damped lag (omega ~ 1.28/rev, zeta ~ -0.02) oscillators with weak coupling.
inline Eigen::MatrixXd rotor_hover_matrix() {
  Eigen::MatrixXd A(4, 4);
  A << -0.3, -1.3914, -0.1, -0.3,  //
      1.0, 0.0, 0.0, 0.0,          //
      0.05, 0.2, -0.04, -1.6388,   //
      0.0, 0.0, 1.0, 0.0;
  return A;
}

// The rotor-like 4x4 periodic system: rotor_hover_matrix() plus harmonics to 4/rev in the rows
// of the accelerations (h = 1 .. 8, amplitudes falling as 1/k), a reversed-flow sector
// [5 pi/4, 7 pi/4) in which the damping and flap-lag coupling harmonics change sign, and a
// strong 1/rev flap stiffness term 3 cos psi (so that |A(psi)| reaches about 5).
inline PeriodicSystem rotor_like() {
  PeriodicSystem s;
  s.n = 4;
  auto fill = [](HarmonicSet& set, double sign) {
    set.A.assign(9, Eigen::MatrixXd::Zero(4, 4));
    set.A[0] = rotor_hover_matrix();
    for (int h = 1; h < 9; ++h) {
      const double w = 1.0 / ((h + 1) / 2);
      set.A[h](0, 0) = sign * 0.4 * w * std::cos(h);
      set.A[h](0, 1) = 1.2 * w * std::sin(1.3 * h);
      set.A[h](0, 3) = 0.5 * w * std::cos(0.7 * h);
      set.A[h](2, 0) = 0.2 * w * std::sin(2.1 * h);
      set.A[h](2, 1) = sign * 0.8 * w * std::cos(1.9 * h);
      set.A[h](2, 2) = 0.1 * w * std::sin(0.4 * h);
      set.A[h](2, 3) = 0.5 * w * std::cos(2.9 * h);
    }
    set.A[1](0, 1) = 3.0;
  };
  fill(s.normal, 1.0);
  fill(s.reversed, -1.0);
  s.has_sector = true;
  s.sector_begin = 1.25 * kPi;
  s.sector_end = 1.75 * kPi;
  return s;
}

using MatrixFn = std::function<Eigen::MatrixXd(double)>;

// Harmonic coefficients (index convention of periodic_system.h: 1, cos psi, sin psi, cos 2 psi,
// ...) of an n x n matrix trigonometric polynomial F of degree <= `degree`.  The trapezoidal
// rule with M = 4 (degree + 1) > 2 degree equally spaced points is exact for the products
// F cos k psi, F sin k psi (k <= degree), so the coefficients are exact up to rounding.
// Callers check the degree assumption by evaluating the expansion off the sample points.
inline std::vector<Eigen::MatrixXd> harmonics_of(const MatrixFn& F, int n, int degree) {
  const int M = 4 * (degree + 1);
  std::vector<Eigen::MatrixXd> c(2 * static_cast<std::size_t>(degree) + 1,
                                 Eigen::MatrixXd::Zero(n, n));
  for (int j = 0; j < M; ++j) {
    const double psi = kTwoPi * j / M;
    const Eigen::MatrixXd f = F(psi);
    c[0] += f / M;
    for (int k = 1; k <= degree; ++k) {
      c[2 * k - 1] += (2.0 / M) * std::cos(k * psi) * f;
      c[2 * k] += (2.0 / M) * std::sin(k * psi) * f;
    }
  }
  return c;
}

// A smooth invertible frame P(psi) and its derivative, both 2 pi-periodic.
struct Frame {
  MatrixFn P, dP;
};

// y = P(psi) z with z' = B z gives y' = A(psi) y with A = P' P^{-1} + P B P^{-1}.  Both P and
// P^{-1} below are trigonometric polynomials, so A has a finite harmonic expansion of degree
// <= `degree` (the caller's bound).  With a sector, the reversed region uses its own frame,
// which must equal the normal one at both sector edges (y is continuous, A jumps); then
//   Phi(2 pi, 0) = P(0) e^{2 pi B} P(0)^{-1}  and the Floquet exponents are eig(B) exactly.
inline PeriodicSystem reducible_system(const Eigen::MatrixXd& B, const Frame& normal, int degree,
                                       const Frame* reversed = nullptr, double sector_begin = 0.0,
                                       double sector_end = 0.0) {
  auto a_of = [&B](const Frame& fr) {
    return [&B, &fr](double psi) -> Eigen::MatrixXd {
      const Eigen::MatrixXd P = fr.P(psi);
      const Eigen::MatrixXd Pinv = P.inverse();
      return fr.dP(psi) * Pinv + P * B * Pinv;
    };
  };
  PeriodicSystem s;
  s.n = static_cast<int>(B.rows());
  s.normal.A = harmonics_of(a_of(normal), s.n, degree);
  if (reversed) {
    s.reversed.A = harmonics_of(a_of(*reversed), s.n, degree);
    s.has_sector = true;
    s.sector_begin = sector_begin;
    s.sector_end = sector_end;
  }
  return s;
}

inline Eigen::MatrixXd reducible_phi(const Eigen::MatrixXd& B, const Frame& normal) {
  const Eigen::MatrixXd P0 = normal.P(0.0);
  return P0 * matrix_exponential(kTwoPi * B) * P0.inverse();
}

// dA/dpsi inside the region that contains psi, from the harmonic coefficients.
inline Eigen::MatrixXd A_rate(const PeriodicSystem& s, double psi) {
  const HarmonicSet& set = s.region(psi);
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(s.n, s.n);
  for (std::size_t h = 1; h < set.A.size(); ++h) {
    const double k = static_cast<double>((h + 1) / 2);
    d += (h % 2 == 1 ? -k * std::sin(k * psi) : k * std::cos(k * psi)) * set.A[h];
  }
  return d;
}

// Sizes that set the leading error terms: L = max ||A(psi)||_2, C = max ||[A, A']||_2 (sampled
// on 2000 points; both regions).
struct SystemScale {
  double L = 0.0;
  double C = 0.0;
};
inline SystemScale scale_of(const PeriodicSystem& s) {
  SystemScale out;
  for (int j = 0; j < 2000; ++j) {
    const double psi = kTwoPi * (j + 0.5) / 2000;
    const Eigen::MatrixXd A = s.A(psi), D = A_rate(s, psi);
    out.L = std::max(out.L, A.operatorNorm());
    out.C = std::max(out.C, (A * D - D * A).operatorNorm());
  }
  return out;
}

// A priori leading-term error models of Phi(2 pi, 0) relative to max |Phi| (T = 2 pi, h the
// step).  They ignore the propagation of the local errors by Phi(2 pi, psi) (of order 1 for the
// decaying systems used here), so the tests allow a factor 4.
//  RK4 (order 4): the one-step remainder (h A)^5 / 5! accumulated over T / h steps,
//    T (h L)^4 L / 120.
//  Hsu (order 2, eq 3.29): exp(Delta C_k) with C_k the interval mean misses the second Magnus
//    term Delta^3 [A, A'] / 12 on every interval, T Delta^2 C / 12, plus the Taylor remainder
//    of J terms, T (Delta L)^J L / (J + 1)!.
inline double rk4_error_model(const SystemScale& s, int steps) {
  const double h = kTwoPi / steps;
  return kTwoPi * std::pow(h * s.L, 4) * s.L / 120.0;
}
inline double hsu_error_model(const SystemScale& s, int intervals, int terms) {
  const double d = kTwoPi / intervals;
  return kTwoPi * d * d * s.C / 12.0 +
         kTwoPi * std::pow(d * s.L, terms) * s.L / std::tgamma(terms + 2.0);
}

// Rotation by angle t and its derivative d/dt.
inline Eigen::Matrix2d rotation(double t) {
  Eigen::Matrix2d R;
  R << std::cos(t), -std::sin(t), std::sin(t), std::cos(t);
  return R;
}
inline Eigen::Matrix2d rotation_rate(double t) {
  Eigen::Matrix2d R;
  R << -std::sin(t), -std::cos(t), std::cos(t), -std::sin(t);
  return R;
}

// 2 states: P = R(psi) U(psi), U = [[1, u], [0, 1]] with u = 0.5 sin psi + 0.3 cos 2 psi + c
// sin(psi - s0) (c = 0 in the normal region).  U^{-1} = [[1, -u], [0, 1]] and R' R^T = J, so
// A = J + R (U' U^{-1} + U B U^{-1}) R^T: deg U B U^{-1} <= 4 (its u^2 term) and R ... R^T adds
// 2, so deg A <= 6.  The sin(psi - s0) term vanishes at s0 and s0 + pi, so a sector
// [s0, s0 + pi) with c != 0 keeps P continuous.
inline Frame frame2(double c = 0.0, double s0 = 0.0) {
  auto u = [=](double p) {
    return 0.5 * std::sin(p) + 0.3 * std::cos(2 * p) + c * std::sin(p - s0);
  };
  auto du = [=](double p) {
    return 0.5 * std::cos(p) - 0.6 * std::sin(2 * p) + c * std::cos(p - s0);
  };
  Frame f;
  f.P = [=](double p) -> Eigen::MatrixXd {
    Eigen::Matrix2d U;
    U << 1.0, u(p), 0.0, 1.0;
    return rotation(p) * U;
  };
  f.dP = [=](double p) -> Eigen::MatrixXd {
    Eigen::Matrix2d U, dU;
    U << 1.0, u(p), 0.0, 1.0;
    dU << 0.0, du(p), 0.0, 0.0;
    return rotation_rate(p) * U + rotation(p) * dU;
  };
  return f;
}

// 4 states: P = diag(R(psi), R(2 psi)) (I + N(psi)), N strictly upper triangular with entries
// of degree 1 (plus c sin(psi - s0) in N(0, 3)).  (I + N)^{-1} = I - N + N^2 - N^3 has degree
// 3, so N' (I + N)^{-1} and (I + N) B (I + N)^{-1} have degree <= 4; conjugation by the
// rotations (1 and 2/rev, R_i X_ij R_j^T) adds up to 4, so deg A <= 8.
inline Frame frame4(double c = 0.0, double s0 = 0.0) {
  auto N = [=](double p) {
    Eigen::Matrix4d n = Eigen::Matrix4d::Zero();
    n(0, 1) = 0.4 * std::cos(p);
    n(0, 2) = 0.3 * std::sin(p) - 0.2;
    n(1, 3) = 0.5 * std::cos(p) + 0.2 * std::sin(p);
    n(2, 3) = -0.3 * std::sin(p);
    n(0, 3) = 0.2 + c * std::sin(p - s0);
    return n;
  };
  auto dN = [=](double p) {
    Eigen::Matrix4d n = Eigen::Matrix4d::Zero();
    n(0, 1) = -0.4 * std::sin(p);
    n(0, 2) = 0.3 * std::cos(p);
    n(1, 3) = -0.5 * std::sin(p) + 0.2 * std::cos(p);
    n(2, 3) = -0.3 * std::cos(p);
    n(0, 3) = c * std::cos(p - s0);
    return n;
  };
  auto Rb = [](double p) {
    Eigen::Matrix4d r = Eigen::Matrix4d::Zero();
    r.topLeftCorner<2, 2>() = rotation(p);
    r.bottomRightCorner<2, 2>() = rotation(2 * p);
    return r;
  };
  auto dRb = [](double p) {
    Eigen::Matrix4d r = Eigen::Matrix4d::Zero();
    r.topLeftCorner<2, 2>() = rotation_rate(p);
    r.bottomRightCorner<2, 2>() = 2.0 * rotation_rate(2 * p);
    return r;
  };
  Frame f;
  f.P = [=](double p) -> Eigen::MatrixXd { return Rb(p) * (Eigen::Matrix4d::Identity() + N(p)); };
  f.dP = [=](double p) -> Eigen::MatrixXd {
    return dRb(p) * (Eigen::Matrix4d::Identity() + N(p)) + Rb(p) * dN(p);
  };
  return f;
}

// Real n x n matrix with eigenvalues z_k +- i w_k (one 2 x 2 block per pair), mixed by a fixed
// well-conditioned similarity.
inline Eigen::MatrixXd with_eigenvalues(const std::vector<std::pair<double, double>>& pairs) {
  const int n = 2 * static_cast<int>(pairs.size());
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(n, n);
  for (int k = 0; k < n / 2; ++k) {
    D(2 * k, 2 * k) = D(2 * k + 1, 2 * k + 1) = pairs[k].first;
    D(2 * k, 2 * k + 1) = -pairs[k].second;
    D(2 * k + 1, 2 * k) = pairs[k].second;
  }
  Eigen::MatrixXd S(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) S(i, j) = (i == j ? 2.0 : 0.0) + 0.3 * std::sin(1.0 + i + 2.0 * j);
  return S * D * S.inverse();
}

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
inline PeriodicSystem markus_yamabe() {
  PeriodicSystem s;
  s.n = 2;
  s.normal.A.assign(5, Eigen::MatrixXd::Zero(2, 2));
  s.normal.A[0] << -0.25, 1.0, -1.0, -0.25;
  s.normal.A[3] << 0.75, 0.0, 0.0, -0.75;   // cos 2 psi
  s.normal.A[4] << 0.0, -0.75, -0.75, 0.0;  // sin 2 psi
  return s;
}
inline Frame markus_yamabe_frame() {
  Frame f;
  f.P = [](double p) -> Eigen::MatrixXd {
    Eigen::Matrix2d m;
    m << -std::cos(p), std::sin(p), std::sin(p), std::cos(p);
    return m;
  };
  f.dP = [](double p) -> Eigen::MatrixXd {
    Eigen::Matrix2d m;
    m << std::sin(p), std::cos(p), std::cos(p), -std::sin(p);
    return m;
  };
  return f;
}

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
inline std::vector<ExactCase> exact_cases() {
  std::vector<ExactCase> out;
  Eigen::MatrixXd B2(2, 2);
  B2 << -0.1, 1.3, -0.9, -0.2;
  const Eigen::MatrixXd B4 = with_eigenvalues({{-0.15, 1.17}, {-0.02, 1.28}});
  const Frame f2 = frame2(), f4 = frame4();
  const Frame f2s = frame2(0.7, 0.8 * kPi), f4s = frame4(0.6, 0.9 * kPi);
  out.push_back({"2 states", reducible_system(B2, f2, 6), B2, f2, f2, reducible_phi(B2, f2)});
  out.push_back({"2 states, sector [0.8 pi, 1.8 pi)",
                 reducible_system(B2, f2, 6, &f2s, 0.8 * kPi, 1.8 * kPi), B2, f2, f2s,
                 reducible_phi(B2, f2)});
  out.push_back({"4 states", reducible_system(B4, f4, 8), B4, f4, f4, reducible_phi(B4, f4)});
  out.push_back({"4 states, sector [0.9 pi, 1.9 pi)",
                 reducible_system(B4, f4, 8, &f4s, 0.9 * kPi, 1.9 * kPi), B4, f4, f4s,
                 reducible_phi(B4, f4)});
  Eigen::MatrixXd Bmy = Eigen::MatrixXd::Zero(2, 2);
  Bmy.diagonal() << 0.5, -1.0;
  const Frame fmy = markus_yamabe_frame();
  out.push_back({"Markus-Yamabe", markus_yamabe(), Bmy, fmy, fmy, reducible_phi(Bmy, fmy)});
  return out;
}

// The same system with its sector replaced by a varying region whose evaluator sums the
// sector's harmonics point by point: every integrator must give what it gives on the sector.
inline PeriodicSystem sector_as_varying(const PeriodicSystem& sector) {
  PeriodicSystem v = sector;
  v.has_sector = false;
  v.has_varying = true;
  v.varying_begin = sector.sector_begin;
  v.varying_end = sector.sector_end;
  const HarmonicSet rev = sector.reversed;
  const int n = sector.n;
  v.varying = [rev, n](double psi, Eigen::MatrixXd& A, Eigen::VectorXd& f) {
    A.setZero(n, n);
    f.setZero(n);
    for (std::size_t h = 0; h < rev.A.size(); ++h)
      A += harmonic_basis(static_cast<int>(h), psi) * rev.A[h];
    for (std::size_t h = 0; h < rev.f.size(); ++h)
      f += harmonic_basis(static_cast<int>(h), psi) * rev.f[h];
  };
  v.reversed = HarmonicSet{};
  return v;
}

// A scalar system shaped like the exact reversed-flow region: -0.05 + 0.7 cos psi on [0, pi),
// and 0.3 + 0.9 clamp(-sin psi, 0, c) on the varying region [pi, 2 pi), which is not smooth at
// the breaks pi + asin c and 2 pi - asin c.  clipped_log_phi() is ln Phi(2 pi) in closed form:
// -0.05 pi + 0.3 pi + 0.9 (2 (1 - cos a) + c (pi - 2 a)), a = asin c.
inline PeriodicSystem clipped_scalar(double c = 0.6) {
  PeriodicSystem s;
  s.n = 1;
  s.normal.A = {Eigen::MatrixXd::Constant(1, 1, -0.05), Eigen::MatrixXd::Constant(1, 1, 0.7)};
  s.has_varying = true;
  s.varying_begin = kPi;
  s.varying_end = kTwoPi;
  const double a = std::asin(c);
  s.varying_breaks = {kPi + a, kTwoPi - a};
  s.varying = [c](double psi, Eigen::MatrixXd& A, Eigen::VectorXd& f) {
    A = Eigen::MatrixXd::Constant(1, 1, 0.3 + 0.9 * std::clamp(-std::sin(psi), 0.0, c));
    f = Eigen::VectorXd::Zero(1);
  };
  return s;
}

inline double clipped_log_phi(double c = 0.6) {
  const double a = std::asin(c);
  return -0.05 * kPi + 0.3 * kPi + 0.9 * (2.0 * (1.0 - std::cos(a)) + c * (kPi - 2.0 * a));
}

}  // namespace flaplag::fixtures
