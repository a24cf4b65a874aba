// The dense helpers of periodic_fixtures.h against matrices whose inverse and operator norm are
// known in closed form (they are the references of other tests, so they are checked first).
#include "periodic_fixtures.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <complex>

#include "test_util.h"

namespace flaplag {
namespace {

using testing::AbsClose;
using testing::RelClose;

TEST(FixtureInverse, TwoByTwoInClosedForm) {
  Eigen::MatrixXd m(2, 2);
  m << 4.0, 7.0, 2.0, 6.0;  // det 10
  const Eigen::MatrixXd inv = fixtures::inverse(m);
  const double expected[2][2] = {{0.6, -0.7}, {-0.2, 0.4}};
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) EXPECT_TRUE(AbsClose(expected[i][j], inv(i, j), 1e-15));
}

// A zero first pivot: elimination without row exchanges would divide by zero.
TEST(FixtureInverse, NeedsRowExchanges) {
  Eigen::MatrixXd m(4, 4);
  m << 0.0, 2.0, 1.0, 0.0,  //
      3.0, 0.0, 0.0, 1.0,   //
      0.0, 1.0, 0.0, 4.0,   //
      1.0, 0.0, 5.0, 0.0;
  const Eigen::MatrixXd inv = fixtures::inverse(m);
  ASSERT_TRUE(inv.allFinite());
  const Eigen::MatrixXd left = inv * m, right = m * inv;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      EXPECT_TRUE(AbsClose(i == j ? 1.0 : 0.0, left(i, j), 1e-14)) << i << "," << j;
      EXPECT_TRUE(AbsClose(i == j ? 1.0 : 0.0, right(i, j), 1e-14)) << i << "," << j;
    }
}

// Upper triangular [[i, m01], [0, 2]]: the inverse is [[-i, -m01 / (2 i)], [0, 1/2]].
TEST(FixtureInverse, Complex) {
  Eigen::MatrixXcd m = Eigen::MatrixXcd::Zero(2, 2);
  m(0, 0) = {0.0, 1.0};
  m(1, 1) = 2.0;
  m(0, 1) = {1.0, -1.0};
  const Eigen::MatrixXcd inv = fixtures::inverse(m);
  const std::complex<double> m01(1.0, -1.0), i(0.0, 1.0);
  EXPECT_LT(std::abs(inv(0, 0) - (-i)), 1e-15);
  EXPECT_LT(std::abs(inv(1, 1) - 0.5), 1e-15);
  EXPECT_LT(std::abs(inv(1, 0)), 1e-15);
  EXPECT_LT(std::abs(inv(0, 1) - (-m01 / (i * 2.0))), 1e-15);
}

TEST(FixtureOperatorNorm, Diagonal) {
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(3, 3);
  m.diagonal() << 3.0, -5.0, 1.0;
  EXPECT_TRUE(RelClose(5.0, fixtures::operator_norm(m), 1e-15));
}

// u v^T has the one singular value |u| |v|; a scaled rotation has both equal to the scale.
TEST(FixtureOperatorNorm, RankOneAndRotation) {
  Eigen::VectorXd u(3), v(3);
  u << 1.0, -2.0, 2.0;  // |u| = 3
  v << 0.0, 3.0, 4.0;   // |v| = 5
  EXPECT_TRUE(RelClose(15.0, fixtures::operator_norm(u * v.transpose()), 1e-14));
  Eigen::MatrixXd r(2, 2);
  r << std::cos(0.3), -std::sin(0.3), std::sin(0.3), std::cos(0.3);
  EXPECT_TRUE(RelClose(2.5, fixtures::operator_norm(2.5 * r), 1e-14));
  // Not square: 2 x 3 with orthogonal rows of lengths 2 and 7.
  Eigen::MatrixXd w(2, 3);
  w << 2.0, 0.0, 0.0, 0.0, 0.0, 7.0;
  EXPECT_TRUE(RelClose(7.0, fixtures::operator_norm(w), 1e-15));
}

}  // namespace
}  // namespace flaplag
