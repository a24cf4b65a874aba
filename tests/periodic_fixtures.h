// Periodic systems shared by the numerics tests and the transition bench (header-only, needs
// only flaplag_numerics):
//
//  - rotor_like(): THE rotor-like 4x4 system whose accuracy figures transition.cc quotes;
//  - harmonics_of(): exact harmonic coefficients of a matrix trigonometric polynomial;
//  - reducible_system(): Lyapunov-reducible systems y = P(psi) z, z' = B z, whose transition
//    matrix P(0) e^{2 pi B} P(0)^{-1} and exponents eig(B) are known exactly.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "flaplag/core/constants.h"
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
  return P0 * (kTwoPi * B).exp() * P0.inverse();
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

}  // namespace flaplag::fixtures
