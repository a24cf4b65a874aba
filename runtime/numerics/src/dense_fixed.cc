// The fixed-size eigen-solves of dense.h (EigenStorage::FixedWhenSmall): 4 and 8 rows.
#include "dense_solve.h"

namespace flaplag::dense_detail {

template <int N>
RealEigenSystem solve_fixed(const Eigen::MatrixXd& a, bool with_vectors) {
  return solve(Eigen::Matrix<double, N, N>(a), with_vectors);
}

template <int N>
double radius_fixed(const Eigen::MatrixXd& a) {
  return radius(Eigen::Matrix<double, N, N>(a));
}

template RealEigenSystem solve_fixed<4>(const Eigen::MatrixXd&, bool);
template RealEigenSystem solve_fixed<8>(const Eigen::MatrixXd&, bool);
template double radius_fixed<4>(const Eigen::MatrixXd&);
template double radius_fixed<8>(const Eigen::MatrixXd&);

}  // namespace flaplag::dense_detail
