// Floquet exponents from Phi(2 pi, 0): eqs 3.16-3.19, principal omega, Liouville residual.
#include "flaplag/core/constants.h"
#include "flaplag/numerics/floquet.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <unsupported/Eigen/MatrixFunctions>

#include "flaplag/core/errors.h"
#include "test_util.h"

namespace flaplag {
namespace {

using testing::AbsClose;
using testing::RelClose;


// Real matrix with eigenvalues z_k +- i w_k (2x2 blocks), mixed by a fixed similarity.
Eigen::MatrixXd with_eigenvalues(const std::vector<std::pair<double, double>>& pairs) {
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

// Distance of x to the nearest integer.
double frac_dist(double x) { return std::abs(x - std::round(x)); }

void check_constant(const std::vector<std::pair<double, double>>& pairs) {
  const Eigen::MatrixXd A = with_eigenvalues(pairs);
  const Eigen::MatrixXd phi = (kTwoPi * A).exp();
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
  Eigen::MatrixXd phi = (kTwoPi * A).exp();
  const double tr = kTwoPi * A.trace();
  EXPECT_LT(floquet_exponents(phi, tr).liouville_residual, 1e-12);
  phi.col(0) *= 1.0 + 1e-3;  // det scales by the same factor
  EXPECT_TRUE(RelClose(1e-3, floquet_exponents(phi, tr).liouville_residual, 1e-9));
}

TEST(Floquet, NonFiniteTransitionMatrixIsReportedNotThrown) {
  Eigen::MatrixXd phi = Eigen::MatrixXd::Identity(4, 4);
  phi(1, 2) = std::numeric_limits<double>::infinity();
  const FloquetResult r = floquet_exponents(phi, 0.0);
  ASSERT_EQ(4u, r.exponents.size());
  for (const FloquetExponent& e : r.exponents) EXPECT_TRUE(std::isnan(e.zeta));
  EXPECT_TRUE(std::isnan(r.liouville_residual));
}

TEST(Floquet, InvalidArgumentsThrow) {
  EXPECT_THROW(floquet_exponents(Eigen::MatrixXd::Identity(3, 4), 0.0), InvalidInput);
  EXPECT_THROW(floquet_exponents(Eigen::MatrixXd(0, 0), 0.0), InvalidInput);
  EXPECT_THROW(floquet_exponents(Eigen::MatrixXd::Identity(2, 2), std::nan("")), InvalidInput);
}

}  // namespace
}  // namespace flaplag
