// The one instantiation of each dense eigen-solve and matrix exponential (dense.h).
#include "flaplag/numerics/dense.h"

#include <Eigen/Eigenvalues>
#include <unsupported/Eigen/MatrixFunctions>

namespace flaplag {
namespace {

template <typename Mat>
RealEigenSystem solve(const Mat& a, bool with_vectors) {
  RealEigenSystem out;
  Eigen::EigenSolver<Mat> es(a, with_vectors);
  if (es.info() != Eigen::Success) return out;
  out.ok = true;
  out.values = es.eigenvalues();
  if (with_vectors) out.vectors = es.eigenvectors();
  return out;
}

template <typename Mat>
double radius(const Mat& a) {
  Eigen::EigenSolver<Mat> es(a, false);
  return es.info() == Eigen::Success ? es.eigenvalues().cwiseAbs().maxCoeff() : 0.0;
}

}  // namespace

RealEigenSystem real_eigen_system(const Eigen::MatrixXd& a, bool with_vectors,
                                  EigenStorage storage) {
  if (storage == EigenStorage::FixedWhenSmall) {
    if (a.rows() == 4 && a.cols() == 4) return solve(Eigen::Matrix4d(a), with_vectors);
    if (a.rows() == 8 && a.cols() == 8) return solve(Eigen::Matrix<double, 8, 8>(a), with_vectors);
  }
  return solve(a, with_vectors);
}

double spectral_radius(const Eigen::MatrixXd& a, EigenStorage storage) {
  if (storage == EigenStorage::FixedWhenSmall) {
    if (a.rows() == 4 && a.cols() == 4) return radius(Eigen::Matrix4d(a));
    if (a.rows() == 8 && a.cols() == 8) return radius(Eigen::Matrix<double, 8, 8>(a));
  }
  return radius(a);
}

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
