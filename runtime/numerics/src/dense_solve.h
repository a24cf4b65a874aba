// The eigen-solve templates behind dense.h, shared by the translation units that instantiate them:
// dense.cc (dynamic size) and dense_fixed.cc (4 rows).  Three units instead of one because
// GCC's optimizer is superlinear in the size of a unit: split, the same instantiations build in
// three quarters of the CPU time, and in parallel.
#pragma once

#include <Eigen/Eigenvalues>

#include "flaplag/numerics/dense.h"

namespace flaplag::dense_detail {

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

// Eigen::Matrix4d storage (dense_fixed.cc); a has 4 rows and columns.
RealEigenSystem solve_fixed4(const Eigen::MatrixXd& a, bool with_vectors);
double radius_fixed4(const Eigen::MatrixXd& a);

}  // namespace flaplag::dense_detail
