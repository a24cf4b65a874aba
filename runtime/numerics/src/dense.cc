// The one instantiation of each dense eigen-solve (dense.h); the fixed sizes are in
// dense_fixed.cc, the matrix exponentials in dense_exp.cc.
#include "flaplag/numerics/dense.h"

#include "dense_solve.h"

namespace flaplag {

using dense_detail::radius;
using dense_detail::radius_fixed4;
using dense_detail::solve;
using dense_detail::solve_fixed4;

RealEigenSystem real_eigen_system(const Eigen::MatrixXd& a, bool with_vectors,
                                  EigenStorage storage) {
  if (storage == EigenStorage::FixedWhenSmall) {
    if (a.rows() == 4 && a.cols() == 4) return solve_fixed4(a, with_vectors);
  }
  return solve(a, with_vectors);
}

double spectral_radius(const Eigen::MatrixXd& a, EigenStorage storage) {
  if (storage == EigenStorage::FixedWhenSmall) {
    if (a.rows() == 4 && a.cols() == 4) return radius_fixed4(a);
  }
  return radius(a);
}

}  // namespace flaplag
