// The fixed-size eigen-solve of dense.h (EigenStorage::FixedWhenSmall): Eigen::EigenSolver<
// Eigen::Matrix4d>, instantiated once.
#include "dense_solve.h"

namespace flaplag {

namespace dense_detail {

RealEigenSystem solve_fixed4(const Eigen::MatrixXd& a, bool with_vectors) {
  return solve(Eigen::Matrix4d(a), with_vectors);
}

double radius_fixed4(const Eigen::MatrixXd& a) { return radius(Eigen::Matrix4d(a)); }

}  // namespace dense_detail

}  // namespace flaplag
