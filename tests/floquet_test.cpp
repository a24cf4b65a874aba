// Floquet exponents from Phi(2 pi, 0): eqs 3.16-3.19, principal omega, Liouville residual;
// exact exponents of exactly solvable periodic systems through every transition method; a
// defective multiplier; zero multipliers, singular and non-finite Phi.
#include "flaplag/numerics/floquet.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/numerics/dense.h"
#include "periodic_fixtures.h"
#include "test_util.h"

namespace flaplag::floquet_test {
namespace {

using fixtures::with_eigenvalues;
using testing::AbsClose;
using testing::RelClose;

// Distance of x to the nearest integer.
double frac_dist(double x) { return std::abs(x - std::round(x)); }

void check_constant(const std::vector<std::pair<double, double>>& pairs) {
  const Eigen::MatrixXd A = with_eigenvalues(pairs);
  const Eigen::MatrixXd phi = matrix_exponential(kTwoPi * A);
  const FloquetResult r = floquet_exponents(phi, kTwoPi * A.trace());
  ASSERT_EQ(A.rows(), static_cast<Eigen::Index>(r.exponents.size()));
  // Every eigenvalue of A appears, with omega equal modulo an integer (eqs 3.16-3.19).
  for (const auto& [z, w] : pairs) {
    for (double sign : {1.0, -1.0}) {
      bool found = false;
      for (const FloquetExponent& e : r.exponents)
        if (std::abs(e.zeta - z) < 1e-12 && frac_dist(e.omega - sign * w) < 1e-12) found = true;
      EXPECT_TRUE(found) << "eigenvalue " << z << " + " << sign * w << " i";
    }
  }
  for (const FloquetExponent& e : r.exponents) {
    EXPECT_GT(e.omega, -0.5);
    EXPECT_LE(e.omega, 0.5);
    EXPECT_TRUE(RelClose(1.0, e.eigenvector.norm(), 1e-14));
    // Phi v = Lambda v.
    EXPECT_LT(
        (phi.cast<std::complex<double>>() * e.eigenvector - e.multiplier * e.eigenvector).norm(),
        1e-12 * phi.norm());
    EXPECT_TRUE(RelClose(std::log(std::abs(e.multiplier)) / kTwoPi, e.zeta, 1e-15));
  }
  EXPECT_LT(r.liouville_residual, 1e-12);
}

TEST(Floquet, ConstantMatrixExponentsAreEigenvaluesModuloIntegers) {
  check_constant({{-0.1, 1.28}, {-0.6, 1.17}});                // 4x4: fixed-size path, omega > 1/2
  check_constant({{-0.02, 0.3}, {0.05, 2.71}, {-0.3, 0.45}});  // 6x6: generic path
}

TEST(Floquet, PrincipalOmegaOfRealMultipliers) {
  Eigen::MatrixXd phi = Eigen::MatrixXd::Zero(3, 3);
  phi.diagonal() << -2.0, -0.5, 1.0;  // det = 1 = exp(0)
  const FloquetResult r = floquet_exponents(phi, 0.0);
  ASSERT_EQ(3u, r.exponents.size());
  for (const FloquetExponent& e : r.exponents) {
    if (e.multiplier.real() < 0) {
      EXPECT_EQ(0.5, e.omega);  // +1/2, never -1/2
      EXPECT_TRUE(RelClose(std::log(2.0) / kTwoPi, std::abs(e.zeta), 1e-15));
    } else {
      EXPECT_EQ(0.0, e.omega);
    }
  }
  EXPECT_LT(r.liouville_residual, 1e-15);
}

TEST(Floquet, LiouvilleResidualMeasuresDeterminantError) {
  const Eigen::MatrixXd A = with_eigenvalues({{-0.1, 1.28}, {-0.6, 1.17}});
  Eigen::MatrixXd phi = matrix_exponential(kTwoPi * A);
  const double tr = kTwoPi * A.trace();
  EXPECT_LT(floquet_exponents(phi, tr).liouville_residual, 1e-12);
  phi.col(0) *= 1.0 + 1e-3;  // det scales by the same factor
  EXPECT_TRUE(RelClose(1e-3, floquet_exponents(phi, tr).liouville_residual, 1e-9));
}

// ---------------------------------------------------------------------------------------------
// Exactly solvable systems through every transition method.

// Exponent lambda_k = eig(B) of an exact case with the condition number kappa_k = ||x_k|| ||y_k||
// / |y_k^H x_k| of its multiplier Lambda_k = e^{2 pi lambda_k} (right eigenvectors x = P(0) v of
// Phi, left ones the rows of X^{-1}).
struct ExactExponent {
  std::complex<double> lambda;
  double kappa;
};

std::vector<ExactExponent> exact_exponents(const fixtures::ExactCase& c) {
  const RealEigenSystem es = real_eigen_system(c.B, true, EigenStorage::Dynamic);
  const Eigen::MatrixXcd X = c.frame.P(0.0).cast<std::complex<double>>() * es.vectors;
  const Eigen::MatrixXcd Y = fixtures::inverse(X);
  std::vector<ExactExponent> out;
  for (Eigen::Index k = 0; k < X.cols(); ++k)
    out.push_back({es.values(k), X.col(k).norm() * Y.row(k).norm()});
  return out;
}

// Every exact exponent is matched by a computed one within the first-order perturbation bound
// of a simple eigenvalue: |d Lambda_k| <= kappa_k ||E||_2, so |d zeta|, |d omega| <= kappa_k
// ||E||_2 / (2 pi |Lambda_k|), with E = Phi - Phi_exact plus the eigen-solver's backward error
// (10 n eps ||Phi||_2); a factor 2 covers the second-order term.  omega is compared modulo 1.
void expect_exponents(const fixtures::ExactCase& c, const Eigen::MatrixXd& phi,
                      const char* method) {
  const FloquetResult r = floquet_exponents(phi, c.sys.trace_integral());
  ASSERT_EQ(Status::Ok, r.status) << r.message;
  const double n = static_cast<double>(phi.rows());
  const double e2 =
      fixtures::operator_norm(phi - c.phi) +
      10.0 * n * std::numeric_limits<double>::epsilon() * fixtures::operator_norm(c.phi);
  std::vector<bool> used(r.exponents.size(), false);
  for (const ExactExponent& x : exact_exponents(c)) {
    const double tol = 2.0 * x.kappa * e2 / (kTwoPi * std::exp(kTwoPi * x.lambda.real()));
    std::size_t best = 0;
    double dist = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < r.exponents.size(); ++k) {
      const double d = std::abs(r.exponents[k].zeta - x.lambda.real()) +
                       frac_dist(r.exponents[k].omega - x.lambda.imag());
      if (!used[k] && d < dist) {
        dist = d;
        best = k;
      }
    }
    used[best] = true;
    const FloquetExponent& e = r.exponents[best];
    EXPECT_TRUE(AbsClose(x.lambda.real(), e.zeta, tol))
        << c.name << ", " << method << ": zeta of " << x.lambda;
    EXPECT_TRUE(AbsClose(0.0, frac_dist(e.omega - x.lambda.imag()), tol))
        << c.name << ", " << method << ": omega of " << x.lambda << " (computed " << e.omega << ")";
  }
}

// The exponents of the exact cases (periodic_fixtures.h) are eig(B): 2 and 4 states, with and
// without a reversed sector, Markus-Yamabe (1/2 and -1).  Methods at the paper's setting (Hsu
// K = 50, J = 4: relative Phi error 0.013 .. 0.024 on these systems) and finer (Hsu K = 400:
// 2e-4 .. 4e-4; RK4 N = 200: 1e-7 .. 2e-5; Magnus 50: below 2e-7).  transition_test bounds
// these Phi errors a priori by the methods' orders; here the tolerance is the
// eigenvalue-perturbation bound on the actual Phi error, which tests the extraction.
TEST(Floquet, ExactSystemsExponentsAreEigenvaluesOfB) {
  for (const fixtures::ExactCase& c : fixtures::exact_cases()) {
    expect_exponents(c, transition_matrix_rk4(c.sys, 200), "rk4 N = 200");
    expect_exponents(c, transition_matrix_hsu(c.sys, 50, 4), "hsu K = 50 J = 4");
    expect_exponents(c, transition_matrix_hsu(c.sys, 400, 4), "hsu K = 400 J = 4");
    expect_exponents(c, transition_matrix_magnus4(c.sys, 50).phi, "magnus 50");
    expect_exponents(c, c.phi, "exact Phi");  // the extraction alone: to rounding
  }
}

// A defective multiplier: B = [[-0.1, 1], [0, -0.1]] (a Jordan block) in the 2-state frame, so
// Phi = P(0) Lambda [[1, 2 pi], [0, 1]] P(0)^{-1} with the double multiplier
// Lambda = e^{-0.2 pi}.  Perturbing Lambda I + N (N nilpotent, ||N||_F = 3.35 here) by E moves
// the eigenvalues to Lambda + nu, nu^2 - tr(E) nu + det(N + E) = 0 with |det(N + E)| <=
// ||N||_F ||E||_F + ||E||_F^2 / 2 (2 x 2: det(N + E) = tr(adj(N) E) + det E), hence
//   |nu| <= |tr E| / 2 + sqrt(|tr E|^2 / 4 + ||N||_F ||E||_F + ||E||_F^2 / 2):
// the exponents are accurate only to about the square root of the method error (RK4 N = 200:
// ||E|| ~ 3e-7, |nu| = 3e-4 within the bound 1e-3), while the mean of the pair, tr(Phi + E) / 2,
// keeps first-order accuracy.  The bound applies to zeta and to omega (|d ln Lambda| <= |nu| /
// (|Lambda| - |nu|)).
TEST(Floquet, DefectiveMultiplierToSquareRootOfMethodError) {
  Eigen::MatrixXd B(2, 2);
  B << -0.1, 1.0, 0.0, -0.1;
  const fixtures::Frame f = fixtures::frame2(), fs = fixtures::frame2(0.7, 0.8 * kPi);
  const Eigen::MatrixXd exact = fixtures::reducible_phi(B, f);
  const double Lambda = std::exp(-0.2 * kPi);
  const double nF = (exact - Lambda * Eigen::MatrixXd::Identity(2, 2)).norm();
  const double eps = std::numeric_limits<double>::epsilon();
  for (const PeriodicSystem& s : {fixtures::reducible_system(B, f, 6),
                                  fixtures::reducible_system(B, f, 6, &fs, 0.8 * kPi, 1.8 * kPi)}) {
    const double tr = s.trace_integral();
    const std::pair<const char*, Eigen::MatrixXd> runs[] = {
        {"rk4 N = 100", transition_matrix_rk4(s, 100)},
        {"rk4 N = 200", transition_matrix_rk4(s, 200)},
        {"hsu K = 200 J = 4", transition_matrix_hsu(s, 200, 4)},
        {"magnus 50", transition_matrix_magnus4(s, 50).phi},
        {"exact", exact}};
    double split[2] = {0.0, 0.0};
    int i = 0;
    for (const auto& [method, phi] : runs) {
      SCOPED_TRACE(method);
      const FloquetResult r = floquet_exponents(phi, tr);
      ASSERT_EQ(2u, r.exponents.size());
      ASSERT_EQ(Status::Ok, r.status);
      const Eigen::MatrixXd E = phi - exact;
      const double ef = E.norm() + 10.0 * eps * exact.norm();  // plus eigen-solve rounding
      const double te = std::abs(E.trace()) + 10.0 * eps * exact.norm();
      const double nu = te / 2 + std::sqrt(te * te / 4 + nF * ef + ef * ef / 2);
      const double tol = nu / (kTwoPi * (Lambda - nu));
      for (const FloquetExponent& e : r.exponents) {
        EXPECT_LE(std::abs(e.multiplier - Lambda), nu);
        EXPECT_TRUE(AbsClose(-0.1, e.zeta, tol));
        EXPECT_TRUE(AbsClose(0.0, e.omega, tol));
      }
      const std::complex<double> mean =
          0.5 * (r.exponents[0].multiplier + r.exponents[1].multiplier);
      EXPECT_LE(std::abs(mean - Lambda), te / 2);
      if (i < 2) split[i++] = std::abs(r.exponents[0].multiplier - r.exponents[1].multiplier);
    }
    // The square-root law itself: RK4's error falls 16-fold from N = 100 to 200, the split of
    // the pair only 4-fold.
    EXPECT_GT(std::log2(split[0] / split[1]), 1.7);
    EXPECT_LT(std::log2(split[0] / split[1]), 2.3);
  }
}

// ---------------------------------------------------------------------------------------------
// Liouville, det Phi(2 pi) = exp(int_0^{2 pi} tr A), on random periodic systems.

// Uniform in [-1, 1) from the raw mt19937 output, whose sequence the C++ standard fixes (the
// distributions are implementation-defined): the same systems on every platform.
double uniform(std::mt19937& g) { return static_cast<double>(g()) / 4294967296.0 * 2.0 - 1.0; }

// n x n, harmonics to 3/rev with entries of size 0.5 / (1 + k), constant part shifted by -0.2 I;
// optionally a sector [0.9 pi, 1.6 pi + 0.01) with its own random harmonics.
PeriodicSystem random_system(int n, bool sector, std::mt19937& g) {
  auto fill = [&](HarmonicSet& set) {
    set.A.assign(7, Eigen::MatrixXd::Zero(n, n));
    for (int h = 0; h < 7; ++h)
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) set.A[h](i, j) = 0.5 * uniform(g) / (1 + (h + 1) / 2);
    set.A[0].diagonal().array() -= 0.2;
  };
  HarmonicSet normal;
  fill(normal);
  PeriodicSystem s(normal);
  if (sector) {
    HarmonicSet reversed;
    fill(reversed);
    s.add_harmonic_piece(0.9 * kPi, 1.6 * kPi + 0.01, reversed);
  }
  return s;
}

// Sizes 2 .. 8 (the fixed-size kernels 2, 4, 6, 8 and the dynamic one), with and without a
// sector.  Each method has its own reason for the identity to hold:
//  - Hsu with converged Taylor series (J = 20: remainder (Delta L)^21 / 21! < 1e-30) multiplies
//    exact exponentials of Delta C_k, det e^X = e^{tr X}, and sum Delta tr C_k = int tr A
//    exactly (exact interval means split at the sector edges): only rounding remains, about
//    K n^2 eps cond(Phi);
//  - Hsu J = 4: log det T4(X) - tr X = sum_i (ln T4(x_i) - x_i) = -sum_i x_i^5 / 120 + O(x^6)
//    over the eigenvalues x_i of X = Delta C_k, |x_i| <= Delta L: residual <= K n (Delta L)^5
//    / 120 to leading order (factor 1.5 for the rest);
//  - RK4: n times the a priori model of periodic_fixtures.h (the same one-step remainder);
//  - Magnus (extrapolated): first order in its error E, |det(Phi + E) / det Phi - 1| <=
//    n ||Phi^{-1}||_2 ||E||_2 (E measured against 400 steps; factor 2).
TEST(Floquet, LiouvilleIdentityOnRandomSystems) {
  std::mt19937 g(20240601u);
  const double eps = std::numeric_limits<double>::epsilon();
  for (int n = 2; n <= 8; ++n) {
    for (bool sector : {false, true}) {
      const PeriodicSystem s = random_system(n, sector, g);
      SCOPED_TRACE("n = " + std::to_string(n) + (sector ? ", sector" : ""));
      const double tr = s.trace_integral();
      const double dn = n;
      const fixtures::SystemScale sc = fixtures::scale_of(s);
      const Eigen::MatrixXd ref = transition_matrix_magnus4(s, 400).phi;
      const double inv = fixtures::operator_norm(fixtures::inverse(ref));
      const double cond = fixtures::operator_norm(ref) * inv;

      EXPECT_LT(floquet_exponents(transition_matrix_hsu(s, 30, 20), tr).liouville_residual,
                30 * dn * dn * eps * cond);
      const double d = kTwoPi / 50;
      EXPECT_LT(floquet_exponents(transition_matrix_hsu(s, 50, 4), tr).liouville_residual,
                1.5 * 50 * dn * std::pow(d * sc.L, 5) / 120);
      EXPECT_LT(floquet_exponents(transition_matrix_rk4(s, 100), tr).liouville_residual,
                4.0 * dn * fixtures::rk4_error_model(sc, 100));
      const Eigen::MatrixXd m = transition_matrix_magnus4(s, 50).phi;
      EXPECT_LT(floquet_exponents(m, tr).liouville_residual,
                2.0 * dn * inv * fixtures::operator_norm(m - ref) + dn * dn * eps * cond);
      // ... and a wrong trace integral is seen: 1e-6 in int tr A changes the residual by 1e-6.
      EXPECT_TRUE(RelClose(
          1e-6, floquet_exponents(transition_matrix_hsu(s, 30, 20), tr + 1e-6).liouville_residual,
          1e-3));
    }
  }
}

// det Phi and exp(int tr A) both under- or overflow once |int tr A| > 709; the residual comes
// from log|det Phi| and stays exact (before: 0 * inf = NaN).  Its rounding floor is set by the
// size of the logarithms: n terms ln|u_ii| of size |int tr A| / n, each to relative eps, their
// sum and the trace integral itself, so about 4 n |int tr A| eps (1e-11 for n = 8 and
// |int tr A| = 1600).  Also a negative determinant.
TEST(Floquet, LiouvilleResidualOfExtremeDeterminants) {
  const double eps = std::numeric_limits<double>::epsilon();
  for (int n : {4, 8}) {  // fixed-size and dynamic paths
    const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
    for (double a : {-200.0, 100.0}) {  // det = e^{-200 n} underflows, e^{100 n} overflows
      const double tr = a * n;
      EXPECT_LT(floquet_exponents(std::exp(a) * I, tr).liouville_residual,
                4.0 * n * std::abs(tr) * eps);
    }
    // The same through an integrator: A = -30 I, Phi = e^{-60 pi} I, int tr A = -60 pi n.
    // Magnus is exact for constant A (Omega = h A, Pade exponential), so only rounding remains.
    const PeriodicSystem s(HarmonicSet{{-30.0 * I}, {}});
    const double tr = s.trace_integral();
    const FloquetResult r = floquet_exponents(transition_matrix_magnus4(s, 10).phi, tr);
    EXPECT_LT(r.liouville_residual, 4.0 * n * std::abs(tr) * eps);
    for (const FloquetExponent& e : r.exponents) EXPECT_TRUE(RelClose(-30.0, e.zeta, 1e-13));
  }
  Eigen::MatrixXd phi = Eigen::MatrixXd::Zero(2, 2);
  phi.diagonal() << -std::exp(1.0), 1.0;  // det = -e, exp(int tr A) = e: residual 2
  EXPECT_TRUE(RelClose(2.0, floquet_exponents(phi, 1.0).liouville_residual, 1e-15));
}

// ---------------------------------------------------------------------------------------------
// Zero multipliers, singular and non-finite Phi.

// A zero multiplier cannot come from a smooth ODE (Phi is always invertible), but
// floquet_exponents must still map it: zeta = -inf, omega = 0 (also for a -0.0 entry, whose
// std::arg is pi), the other exponents exact, status Ok, residual 1 (det = 0).
TEST(Floquet, ZeroMultiplierIsMinusInfinity) {
  for (int n : {3, 4}) {  // dynamic and fixed-size paths
    for (double zero : {0.0, -0.0}) {
      Eigen::MatrixXd phi = Eigen::MatrixXd::Zero(n, n);
      phi.diagonal().head(3) << zero, 0.5, 2.0;
      if (n == 4) phi(3, 3) = -1.0;
      const FloquetResult r = floquet_exponents(phi, 0.0);
      ASSERT_EQ(Status::Ok, r.status);
      EXPECT_EQ(1.0, r.liouville_residual);
      int zeros = 0;
      for (const FloquetExponent& e : r.exponents) {
        const double m = e.multiplier.real();
        EXPECT_EQ(0.0, e.multiplier.imag());
        if (m == 0.0) {
          ++zeros;
          EXPECT_EQ(-std::numeric_limits<double>::infinity(), e.zeta);
          EXPECT_EQ(0.0, e.omega);
        } else {
          EXPECT_TRUE(RelClose(std::log(std::abs(m)) / kTwoPi, e.zeta, 1e-15));
          EXPECT_EQ(m < 0 ? 0.5 : 0.0, e.omega);
        }
        EXPECT_TRUE(RelClose(1.0, e.eigenvector.norm(), 1e-15));
      }
      EXPECT_EQ(1, zeros);
    }
  }
  // A nilpotent Phi: every multiplier zero.
  Eigen::MatrixXd nil = Eigen::MatrixXd::Zero(3, 3);
  nil(0, 1) = nil(1, 2) = 1.0;
  for (const FloquetExponent& e : floquet_exponents(nil, 0.0).exponents) {
    EXPECT_EQ(-std::numeric_limits<double>::infinity(), e.zeta);
    EXPECT_EQ(0.0, e.omega);
  }
}

// An exactly singular, non-diagonal Phi (rank one, eigenvalues 0 and 5; 4 x 4: rank two,
// eigenvalues 0, 0, and those of a 2 x 2 block): no UB, status Ok, residual 1; the zero
// multiplier may come back as rounding (|Lambda| <= 10 eps ||Phi||) instead of exactly 0.
TEST(Floquet, SingularTransitionMatrix) {
  const double eps = std::numeric_limits<double>::epsilon();
  Eigen::MatrixXd r1(2, 2);
  r1 << 1.0, 2.0, 2.0, 4.0;
  Eigen::MatrixXd r2 = Eigen::MatrixXd::Zero(4, 4);
  r2.topLeftCorner(2, 2) << 0.3, -0.8, 0.8, 0.3;  // 0.3 +- 0.8 i
  const Eigen::MatrixXd S =
      with_eigenvalues({{0.1, 0.2}, {-0.3, 0.4}}) + 2.0 * Eigen::MatrixXd::Identity(4, 4);
  r2 = S * r2 * fixtures::inverse(S);
  for (const Eigen::MatrixXd& phi : {r1, r2}) {
    const FloquetResult r = floquet_exponents(phi, 0.0);
    ASSERT_EQ(Status::Ok, r.status);
    EXPECT_TRUE(RelClose(1.0, r.liouville_residual, 1e-12));  // det ~ rounding, not exactly 0
    int zeros = 0;
    for (const FloquetExponent& e : r.exponents) {
      EXPECT_FALSE(std::isnan(e.zeta));
      EXPECT_FALSE(std::isnan(e.omega));
      if (std::abs(e.multiplier) <= 10 * eps * phi.norm()) {
        ++zeros;
        EXPECT_LT(e.zeta, std::log(10 * eps * phi.norm()) / kTwoPi + 1e-12);
      } else if (phi.rows() == 2) {
        EXPECT_TRUE(RelClose(std::log(5.0) / kTwoPi, e.zeta, 1e-14));
      } else {
        EXPECT_TRUE(RelClose(0.5 * std::log(0.73) / kTwoPi, e.zeta, 1e-12));
        EXPECT_TRUE(RelClose(std::atan2(0.8, 0.3) / kTwoPi, std::abs(e.omega), 1e-12));
      }
    }
    EXPECT_EQ(phi.rows() / 2, zeros);
  }
}

// A diverged integration (NaN or inf in Phi) is an outcome, not an exception: Status::Failed
// with a message, NaN exponents and residual.
TEST(Floquet, NonFiniteTransitionMatrixIsReportedNotThrown) {
  for (int n : {3, 4}) {
    for (double bad :
         {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::quiet_NaN()}) {
      Eigen::MatrixXd phi = Eigen::MatrixXd::Identity(n, n);
      phi(1, 2) = bad;
      const FloquetResult r = floquet_exponents(phi, 0.0);
      EXPECT_EQ(Status::Failed, r.status);
      EXPECT_NE(std::string::npos, r.message.find("non-finite")) << r.message;
      ASSERT_EQ(static_cast<std::size_t>(n), r.exponents.size());
      for (const FloquetExponent& e : r.exponents) {
        EXPECT_TRUE(std::isnan(e.zeta));
        EXPECT_TRUE(std::isnan(e.omega));
      }
      EXPECT_TRUE(std::isnan(r.liouville_residual));
    }
  }
  // A finite Phi reports Ok exactly when every multiplier and eigenvector is finite (entries
  // near the overflow threshold may overflow inside the eigen-solve).
  for (double scale : {1.0, 1e300, 1e307}) {
    const Eigen::MatrixXd phi = scale * with_eigenvalues({{0.3, 0.7}, {-0.2, 0.1}});
    const FloquetResult r = floquet_exponents(phi, 0.0);
    bool finite = true;
    for (const FloquetExponent& e : r.exponents)
      finite = finite && std::isfinite(std::abs(e.multiplier)) && e.eigenvector.allFinite();
    EXPECT_EQ(finite, r.status == Status::Ok) << "scale " << scale << ": " << r.message;
    EXPECT_EQ(finite, r.message.empty());
  }
}

// Multipliers only (FloquetVectors::OnDemand, into a reused result): the same exponents and
// residual as with eigenvectors, no eigenvectors until add_eigenvectors(), which then gives the
// eigenvectors of the full solve; for the fixed-size (4, 8) and the generic (6) paths, reusing
// one result across sizes.
TEST(Floquet, EigenvectorsOnDemandMatchTheFullSolve) {
  FloquetResult on_demand;
  for (const std::vector<std::pair<double, double>>& pairs :
       std::vector<std::vector<std::pair<double, double>>>{
           {{-0.1, 1.28}, {-0.6, 1.17}},
           {{-0.02, 0.3}, {0.05, 2.71}, {-0.3, 0.45}},
           {{-0.02, 0.3}, {0.05, 2.71}, {-0.3, 0.45}, {-0.01, 3.3}},
           {{-0.1, 1.28}, {-0.6, 1.17}}}) {
    const Eigen::MatrixXd A = with_eigenvalues(pairs);
    const Eigen::MatrixXd phi = matrix_exponential(kTwoPi * A);
    const FloquetResult full = floquet_exponents(phi, kTwoPi * A.trace());
    floquet_exponents(phi, kTwoPi * A.trace(), FloquetVectors::OnDemand, &on_demand);
    ASSERT_EQ(Status::Ok, on_demand.status) << on_demand.message;
    ASSERT_EQ(full.exponents.size(), on_demand.exponents.size());
    EXPECT_TRUE(full.has_eigenvectors());
    EXPECT_FALSE(on_demand.has_eigenvectors());
    EXPECT_EQ(full.liouville_residual, on_demand.liouville_residual);
    for (std::size_t k = 0; k < full.exponents.size(); ++k) {
      EXPECT_EQ(full.exponents[k].multiplier, on_demand.exponents[k].multiplier);
      EXPECT_EQ(full.exponents[k].zeta, on_demand.exponents[k].zeta);
      EXPECT_EQ(full.exponents[k].omega, on_demand.exponents[k].omega);
      EXPECT_EQ(0, on_demand.exponents[k].eigenvector.size());
    }
    FloquetResult added = on_demand;
    ASSERT_TRUE(add_eigenvectors(&added));
    ASSERT_TRUE(added.has_eigenvectors());
    for (std::size_t k = 0; k < full.exponents.size(); ++k) {
      const FloquetExponent& e = added.exponents[k];
      EXPECT_LT((full.exponents[k].eigenvector - e.eigenvector).norm(), 1e-15) << "k = " << k;
      EXPECT_LT(
          (phi.cast<std::complex<double>>() * e.eigenvector - e.multiplier * e.eigenvector).norm(),
          1e-12 * phi.norm());
    }
  }
  // Multipliers in another order than the solver's: each still gets its own eigenvector.
  const Eigen::MatrixXd A = with_eigenvalues({{-0.1, 0.28}, {-0.6, 0.17}});
  const Eigen::MatrixXd phi = matrix_exponential(kTwoPi * A);
  const FloquetResult full = floquet_exponents(phi, kTwoPi * A.trace());
  std::vector<std::complex<double>> reversed;
  for (auto it = full.exponents.rbegin(); it != full.exponents.rend(); ++it)
    reversed.push_back(it->multiplier);
  std::vector<Eigen::VectorXcd> v;
  ASSERT_TRUE(floquet_eigenvectors(phi, reversed, &v));
  ASSERT_EQ(4u, v.size());
  for (std::size_t k = 0; k < 4; ++k)
    EXPECT_LT((phi.cast<std::complex<double>>() * v[k] - reversed[k] * v[k]).norm(), 1e-12);
  // Nothing to compute them from: false, not a crash.
  FloquetResult empty;
  empty.exponents.resize(4);
  EXPECT_FALSE(add_eigenvectors(&empty));
  EXPECT_FALSE(floquet_eigenvectors(phi, {reversed[0]}, &v));
}

// The decomposition computed ahead (on a worker thread, by track_exponents) gives the vectors
// computed from phi itself, bit for bit, in the solver's order and in any other; a Phi that
// cannot be decomposed gives none.
TEST(Floquet, EigenvectorsFromAnEigensystemComputedAheadAreTheSameBits) {
  for (const std::vector<std::pair<double, double>>& pairs :
       std::vector<std::vector<std::pair<double, double>>>{
           {{-0.1, 1.28}, {-0.6, 1.17}},
           {{-0.02, 0.3}, {0.05, 2.71}, {-0.3, 0.45}},
           {{-0.02, 0.3}, {0.05, 2.71}, {-0.3, 0.45}, {-0.01, 3.3}}}) {
    const Eigen::MatrixXd A = with_eigenvalues(pairs);
    const Eigen::MatrixXd phi = matrix_exponential(kTwoPi * A);
    const FloquetResult r = floquet_exponents(phi, kTwoPi * A.trace());
    std::vector<std::complex<double>> order, reversed;
    for (const FloquetExponent& e : r.exponents) order.push_back(e.multiplier);
    reversed.assign(order.rbegin(), order.rend());
    const FloquetEigenSystem ahead = floquet_eigensystem(phi);
    ASSERT_TRUE(ahead.ok);
    for (const auto& m : {order, reversed}) {
      std::vector<Eigen::VectorXcd> from_phi, from_system;
      ASSERT_TRUE(floquet_eigenvectors(phi, m, &from_phi));
      ASSERT_TRUE(floquet_eigenvectors(ahead, m, &from_system));
      ASSERT_EQ(from_phi.size(), from_system.size());
      for (std::size_t k = 0; k < m.size(); ++k) {
        ASSERT_EQ(from_phi[k].size(), from_system[k].size());
        for (Eigen::Index i = 0; i < from_phi[k].size(); ++i)
          EXPECT_EQ(from_phi[k](i), from_system[k](i)) << "k = " << k << ", i = " << i;
      }
    }
  }
  EXPECT_FALSE(floquet_eigensystem(Eigen::MatrixXd::Zero(3, 4)).ok);
  EXPECT_FALSE(
      floquet_eigensystem(Eigen::MatrixXd::Constant(4, 4, std::numeric_limits<double>::infinity()))
          .ok);
  std::vector<Eigen::VectorXcd> v;
  EXPECT_FALSE(floquet_eigenvectors(FloquetEigenSystem{}, {1.0}, &v));
}

TEST(Floquet, InvalidArgumentsThrow) {
  EXPECT_THROW(floquet_exponents(Eigen::MatrixXd::Identity(3, 4), 0.0), InvalidInput);
  EXPECT_THROW(floquet_exponents(Eigen::MatrixXd(0, 0), 0.0), InvalidInput);
  EXPECT_THROW(floquet_exponents(Eigen::MatrixXd::Identity(2, 2), std::nan("")), InvalidInput);
}

}  // namespace
}  // namespace flaplag::floquet_test
