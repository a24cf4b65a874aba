// flaplag — the dense eigen-solves and matrix exponentials of the numerics, compiled once.
//
// Eigen's EigenSolver and MatrixFunctions exp are templates that cost GCC 10-20 s per
// instantiation; every translation unit that used them paid that again for the same types.
// These functions are thin wrappers that give exactly the bits the templates give inline (same
// types, same flags, the same code compiled once in dense.cc).
#pragma once

#include <Eigen/Core>

namespace flaplag {

// Which EigenSolver instantiation a real eigen-solve uses.  The fixed-size solver serves the
// frequent 4 x 4 solve (1 x 1 modes, every stability point of the typical case); a caller that
// has always used the dynamic one keeps it, so that its results keep their last bits.
enum class EigenStorage {
  Dynamic,         // Eigen::EigenSolver<Eigen::MatrixXd> at every size
  FixedWhenSmall,  // Eigen::EigenSolver<Eigen::Matrix4d> for 4 rows, the dynamic one otherwise
};

// Eigenvalues (and, when with_vectors, the eigenvectors as columns, unnormalized as Eigen gives
// them) of a real square matrix.  ok is false when the QR iteration did not converge; then
// values and vectors are empty.
struct RealEigenSystem {
  bool ok = false;
  Eigen::VectorXcd values;
  Eigen::MatrixXcd vectors;  // empty unless with_vectors
};
RealEigenSystem real_eigen_system(const Eigen::MatrixXd& a, bool with_vectors,
                                  EigenStorage storage);

// max |eigenvalue| of a real square matrix, 0 when the eigen-solve does not converge.
double spectral_radius(const Eigen::MatrixXd& a, EigenStorage storage);

// The eigenvalues of a 4 x 4 real matrix by the solver of FixedWhenSmall, without eigenvectors
// and without a copy to dynamic storage (the comparison kernel of bench/).  false, *values
// untouched, when the QR iteration does not converge.
bool fixed_eigenvalues(const Eigen::Matrix4d& a, Eigen::Vector4cd* values);

// exp(a) by Eigen's scaling and squaring with a Pade approximant (unsupported/MatrixFunctions),
// for a square matrix of any size (an Eigen expression converts to it), and, as a template
// instantiated in dense_exp.cc for N = 2, 4, 6 and 8 only, of those fixed sizes (the Magnus
// steps of transition.cc's fixed-size kernels, and references in the tests and benchmarks).
Eigen::MatrixXd matrix_exponential(const Eigen::MatrixXd& a);
template <int N>
Eigen::Matrix<double, N, N> matrix_exponential(const Eigen::Matrix<double, N, N>& a);

}  // namespace flaplag
