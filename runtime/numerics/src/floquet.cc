// flaplag — characteristic multipliers and exponents of Phi(2 pi, 0) (eqs 3.15-3.20).
#include "flaplag/numerics/floquet.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <complex>
#include <limits>
#include <string>
#include <utility>

#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"

namespace flaplag {
namespace {

// Liouville, det Phi(T) = exp(int_0^T tr A): the relative residual |det Phi e^{-int tr A} - 1|.
// While det Phi and exp(-int tr A) are both representable (the rotor case) it is computed from
// them directly; otherwise (|int tr A| > 700, or det Phi under- or overflowing, where the
// product would be 0 * inf = NaN) from log|det Phi| and the sign of det Phi by LU.  A singular
// Phi gives 1.
template <typename Mat>
double liouville_residual(const Mat& phi, double trace_integral) {
  const double det = phi.determinant();
  if (std::isnormal(det) && std::abs(trace_integral) < 700.0)
    return std::abs(det * std::exp(-trace_integral) - 1.0);
  const Eigen::PartialPivLU<Mat> lu(phi);
  double log_abs = 0.0;
  double sign = static_cast<double>(lu.permutationP().determinant());  // +-1
  const auto& u = lu.matrixLU();
  for (Eigen::Index i = 0; i < u.rows(); ++i) {
    const double d = u(i, i);
    if (d == 0.0) return 1.0;  // det = 0: |0 - exp(int tr A)| / exp(int tr A)
    if (d < 0.0) sign = -sign;
    log_abs += std::log(std::abs(d));
  }
  return std::abs(sign * std::exp(log_abs - trace_integral) - 1.0);
}

template <typename Solver>
FloquetResult extract(const Solver& es, double residual) {
  FloquetResult out;
  const auto& values = es.eigenvalues();
  const auto& vectors = es.eigenvectors();
  const Eigen::Index n = values.size();
  out.exponents.resize(static_cast<std::size_t>(n));
  bool finite = true;
  for (Eigen::Index k = 0; k < n; ++k) {
    FloquetExponent& e = out.exponents[static_cast<std::size_t>(k)];
    e.multiplier = values(k);
    const double mod = std::abs(e.multiplier);
    e.eigenvector = vectors.col(k);
    const double nv = e.eigenvector.norm();
    if (nv > 0.0) e.eigenvector /= nv;
    finite = finite && std::isfinite(mod) && std::isfinite(nv);
    if (mod == 0.0) {
      // A zero multiplier (exact nilpotent part): zeta = -inf and, whatever the signs of the
      // zeros, omega = 0.
      e.zeta = -std::numeric_limits<double>::infinity();
      e.omega = 0.0;
      continue;
    }
    e.zeta = std::log(mod) / kTwoPi;  // eq 3.18
    // eq 3.19 with the principal value in (-1/2, 1/2]: std::arg gives [-pi, pi], and -pi
    // (a negative real multiplier with imaginary part -0.0) is the same point as +pi.
    double arg = std::arg(e.multiplier);
    if (arg <= -kPi) arg = kPi;
    e.omega = arg / kTwoPi;
  }
  out.liouville_residual = residual;
  if (!finite) {
    out.status = Status::Failed;
    out.message = "the eigen-solve of Phi gave non-finite multipliers or eigenvectors";
  }
  return out;
}

// NaN exponents: how a diverged integration or an unconverged eigen-solve is reported.
FloquetResult nan_result(Eigen::Index n, std::string message) {
  FloquetResult out;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.exponents.resize(static_cast<std::size_t>(n));
  for (FloquetExponent& e : out.exponents) {
    e.multiplier = {nan, nan};
    e.zeta = e.omega = nan;
    e.eigenvector = Eigen::VectorXcd::Constant(n, {nan, nan});
  }
  out.liouville_residual = nan;
  out.status = Status::Failed;
  out.message = std::move(message);
  return out;
}

template <int N>
FloquetResult fixed_size(const Eigen::MatrixXd& phi, double trace_integral,
                         const char* unconverged) {
  using Mat = Eigen::Matrix<double, N, N>;
  const Mat p = phi;
  Eigen::EigenSolver<Mat> es(p, true);
  if (es.info() != Eigen::Success) return nan_result(N, unconverged);
  return extract(es, liouville_residual(p, trace_integral));
}

}  // namespace

FloquetResult floquet_exponents(const Eigen::MatrixXd& phi, double trace_integral) {
  if (phi.rows() != phi.cols() || phi.rows() < 1)
    throw InvalidInput("phi", std::to_string(phi.rows()) + "x" + std::to_string(phi.cols()),
                       "transition matrix must be square and non-empty");
  if (!std::isfinite(trace_integral))
    throw InvalidInput("trace_integral", "non-finite", "must be finite");
  // A diverged integration is a numerical outcome: NaN exponents and Status::Failed.
  if (!phi.allFinite()) return nan_result(phi.rows(), "Phi has non-finite entries");
  const char* unconverged = "the eigen-solve of Phi did not converge";
  // Fixed-size solvers for the common 4x4 and 8x8 cases (1x1 and 2x2 modes) keep the
  // eigen-solve off the heap.
  if (phi.rows() == 4) return fixed_size<4>(phi, trace_integral, unconverged);
  if (phi.rows() == 8) return fixed_size<8>(phi, trace_integral, unconverged);
  Eigen::EigenSolver<Eigen::MatrixXd> es(phi, true);
  if (es.info() != Eigen::Success) return nan_result(phi.rows(), unconverged);
  return extract(es, liouville_residual(phi, trace_integral));
}

}  // namespace flaplag
