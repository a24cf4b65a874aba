// The fixed-size eigen-solves of dense.h (EigenStorage::FixedWhenSmall, fixed_eigenvalues): one
// instantiation of Eigen::EigenSolver<Eigen::Matrix4d> for all of them.
#include "dense_solve.h"

namespace flaplag {

namespace dense_detail {

RealEigenSystem solve_fixed4(const Eigen::MatrixXd& a, bool with_vectors) {
  return solve(Eigen::Matrix4d(a), with_vectors);
}

double radius_fixed4(const Eigen::MatrixXd& a) { return radius(Eigen::Matrix4d(a)); }

}  // namespace dense_detail

bool fixed_eigenvalues(const Eigen::Matrix4d& a, Eigen::Vector4cd* values) {
  Eigen::EigenSolver<Eigen::Matrix4d> es(a, false);
  if (es.info() != Eigen::Success) return false;
  *values = es.eigenvalues();
  return true;
}

}  // namespace flaplag
