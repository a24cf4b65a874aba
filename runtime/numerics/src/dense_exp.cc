// The one instantiation of each matrix exponential of dense.h.
#include <unsupported/Eigen/MatrixFunctions>

#include "flaplag/numerics/dense.h"

namespace flaplag {

Eigen::MatrixXd matrix_exponential(const Eigen::MatrixXd& a) { return a.exp(); }

template <int N>
Eigen::Matrix<double, N, N> matrix_exponential(const Eigen::Matrix<double, N, N>& a) {
  return a.exp();
}
template Eigen::Matrix<double, 2, 2> matrix_exponential<2>(const Eigen::Matrix<double, 2, 2>&);
template Eigen::Matrix<double, 4, 4> matrix_exponential<4>(const Eigen::Matrix<double, 4, 4>&);
template Eigen::Matrix<double, 6, 6> matrix_exponential<6>(const Eigen::Matrix<double, 6, 6>&);
template Eigen::Matrix<double, 8, 8> matrix_exponential<8>(const Eigen::Matrix<double, 8, 8>&);

}  // namespace flaplag
