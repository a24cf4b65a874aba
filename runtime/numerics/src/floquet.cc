// flaplag — characteristic multipliers and exponents of Phi(2 pi, 0) (eqs 3.15-3.20).
#include "flaplag/core/constants.h"
#include "flaplag/numerics/floquet.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <complex>
#include <limits>
#include <string>

#include "flaplag/core/errors.h"

namespace flaplag {
namespace {


template <typename Solver>
FloquetResult extract(const Solver& es, double det, double trace_integral) {
  FloquetResult out;
  const auto& values = es.eigenvalues();
  const auto& vectors = es.eigenvectors();
  const Eigen::Index n = values.size();
  out.exponents.resize(static_cast<std::size_t>(n));
  for (Eigen::Index k = 0; k < n; ++k) {
    FloquetExponent& e = out.exponents[static_cast<std::size_t>(k)];
    e.multiplier = values(k);
    const double mod = std::abs(e.multiplier);
    // eq 3.18; a zero multiplier (exact nilpotent part) has zeta = -inf.
    e.zeta = mod > 0.0 ? std::log(mod) / kTwoPi : -std::numeric_limits<double>::infinity();
    // eq 3.19 with the principal value in (-1/2, 1/2]: std::arg gives [-pi, pi], and -pi
    // (a negative real multiplier with imaginary part -0.0) is the same point as +pi.
    double arg = std::arg(e.multiplier);
    if (arg <= -kPi) arg = kPi;
    e.omega = arg / kTwoPi;
    e.eigenvector = vectors.col(k);
    const double nv = e.eigenvector.norm();
    if (nv > 0.0) e.eigenvector /= nv;
  }
  // Liouville: det Phi(T) = exp(int_0^T tr A); relative residual computed as
  // |det exp(-int tr A) - 1| so that large |int tr A| cannot overflow.
  out.liouville_residual = std::abs(det * std::exp(-trace_integral) - 1.0);
  return out;
}

// NaN exponents: how a diverged integration or an unconverged eigen-solve is reported.
FloquetResult nan_result(Eigen::Index n) {
  FloquetResult out;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.exponents.resize(static_cast<std::size_t>(n));
  for (FloquetExponent& e : out.exponents) {
    e.multiplier = {nan, nan};
    e.zeta = e.omega = nan;
    e.eigenvector = Eigen::VectorXcd::Constant(n, {nan, nan});
  }
  out.liouville_residual = nan;
  return out;
}

}  // namespace

FloquetResult floquet_exponents(const Eigen::MatrixXd& phi, double trace_integral) {
  if (phi.rows() != phi.cols() || phi.rows() < 1)
    throw InvalidInput("phi", std::to_string(phi.rows()) + "x" + std::to_string(phi.cols()),
                       "transition matrix must be square and non-empty");
  if (!std::isfinite(trace_integral))
    throw InvalidInput("trace_integral", "non-finite", "must be finite");
  // A diverged integration is a numerical outcome: NaN exponents, no exception.
  if (!phi.allFinite()) return nan_result(phi.rows());
  // Fixed-size solver for the common 4x4 case keeps the eigen-solve off the heap.
  if (phi.rows() == 4) {
    const Eigen::Matrix4d p = phi;
    Eigen::EigenSolver<Eigen::Matrix4d> es(p, true);
    if (es.info() != Eigen::Success) return nan_result(4);
    return extract(es, p.determinant(), trace_integral);
  }
  Eigen::EigenSolver<Eigen::MatrixXd> es(phi, true);
  if (es.info() != Eigen::Success) return nan_result(phi.rows());
  return extract(es, phi.determinant(), trace_integral);
}

}  // namespace flaplag
