// flaplag — characteristic multipliers and exponents of Phi(2 pi, 0) (eqs 3.15-3.20).
#include "flaplag/numerics/floquet.h"

#include <Eigen/LU>
#include <cmath>
#include <complex>
#include <limits>
#include <string>
#include <utility>

#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/numerics/dense.h"

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

// zeta and omega of a multiplier (eqs 3.18, 3.19).
void set_exponent(std::complex<double> multiplier, FloquetExponent& e) {
  e.multiplier = multiplier;
  const double mod = std::abs(multiplier);
  if (mod == 0.0) {
    // A zero multiplier (exact nilpotent part): zeta = -inf and, whatever the signs of the
    // zeros, omega = 0.
    e.zeta = -std::numeric_limits<double>::infinity();
    e.omega = 0.0;
    return;
  }
  e.zeta = std::log(mod) / kTwoPi;  // eq 3.18
  // eq 3.19 with the principal value in (-1/2, 1/2]: std::arg gives [-pi, pi], and -pi
  // (a negative real multiplier with imaginary part -0.0) is the same point as +pi.
  double arg = std::arg(multiplier);
  if (arg <= -kPi) arg = kPi;
  e.omega = arg / kTwoPi;
}

// NaN exponents: how a diverged integration or an unconverged eigen-solve is reported.
void nan_result(Eigen::Index n, const char* message, FloquetResult* out) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out->exponents.resize(static_cast<std::size_t>(n));
  for (FloquetExponent& e : out->exponents) {
    e.multiplier = {nan, nan};
    e.zeta = e.omega = nan;
    e.eigenvector = Eigen::VectorXcd::Constant(n, {nan, nan});
  }
  out->liouville_residual = nan;
  out->status = Status::Failed;
  out->message = message;
}

const char* const kUnconverged = "the eigen-solve of Phi did not converge";

// The eigen-solve of p (the fixed 4x4 solver for 4 rows), into *out; the
// Liouville residual on the same Mat type as the solve.
template <typename Mat>
void solve(const Mat& p, double trace_integral, bool vectors, FloquetResult* out) {
  const RealEigenSystem es = real_eigen_system(p, vectors, EigenStorage::FixedWhenSmall);
  if (!es.ok) return nan_result(p.rows(), kUnconverged, out);
  const Eigen::VectorXcd& values = es.values;
  const Eigen::Index n = values.size();
  out->exponents.resize(static_cast<std::size_t>(n));
  bool finite = true;
  for (Eigen::Index k = 0; k < n; ++k) {
    FloquetExponent& e = out->exponents[static_cast<std::size_t>(k)];
    set_exponent(values(k), e);
    finite = finite && std::isfinite(std::abs(e.multiplier));
    if (vectors) {
      e.eigenvector = es.vectors.col(k);
      const double nv = e.eigenvector.norm();
      if (nv > 0.0) e.eigenvector /= nv;
      finite = finite && std::isfinite(nv);
    } else if (e.eigenvector.size() != 0) {
      e.eigenvector.resize(0);
    }
  }
  out->liouville_residual = liouville_residual(p, trace_integral);
  out->status = Status::Ok;
  out->message.clear();
  if (!finite) {
    out->status = Status::Failed;
    out->message = vectors ? "the eigen-solve of Phi gave non-finite multipliers or eigenvectors"
                           : "the eigen-solve of Phi gave non-finite multipliers";
  }
}

}  // namespace

bool FloquetResult::has_eigenvectors() const {
  if (exponents.empty()) return false;
  const Eigen::Index n = static_cast<Eigen::Index>(exponents.size());
  for (const FloquetExponent& e : exponents)
    if (e.eigenvector.size() != n) return false;
  return true;
}

void floquet_exponents(const Eigen::MatrixXd& phi, double trace_integral, FloquetVectors vectors,
                       FloquetResult* out) {
  if (out == nullptr) throw InvalidInput("out", "null", "a FloquetResult to fill is required");
  if (phi.rows() != phi.cols() || phi.rows() < 1)
    throw InvalidInput("phi", std::to_string(phi.rows()) + "x" + std::to_string(phi.cols()),
                       "transition matrix must be square and non-empty");
  if (!std::isfinite(trace_integral))
    throw InvalidInput("trace_integral", "non-finite", "must be finite");
  out->phi = phi;
  // A diverged integration is a numerical outcome: NaN exponents and Status::Failed.
  if (!phi.allFinite()) return nan_result(phi.rows(), "Phi has non-finite entries", out);
  const bool with_vectors = vectors == FloquetVectors::Compute;
  // The fixed-size solver for the most frequent case, 4x4 (1x1 modes).
  if (phi.rows() == 4) return solve(Eigen::Matrix4d(phi), trace_integral, with_vectors, out);
  solve(phi, trace_integral, with_vectors, out);
}

FloquetResult floquet_exponents(const Eigen::MatrixXd& phi, double trace_integral) {
  FloquetResult out;
  floquet_exponents(phi, trace_integral, FloquetVectors::Compute, &out);
  return out;
}

FloquetEigenSystem floquet_eigensystem(const Eigen::MatrixXd& phi) {
  if (phi.rows() != phi.cols() || phi.rows() < 1 || !phi.allFinite()) return {};
  // The same fixed-size solvers as floquet_exponents, so that the same eigenvalues come out.
  RealEigenSystem es = real_eigen_system(phi, true, EigenStorage::FixedWhenSmall);
  FloquetEigenSystem out;
  if (!es.ok) return out;
  out.values = std::move(es.values);
  out.vectors = std::move(es.vectors);
  out.ok = true;
  return out;
}

bool floquet_eigenvectors(const FloquetEigenSystem& system,
                          const std::vector<std::complex<double>>& multipliers,
                          std::vector<Eigen::VectorXcd>* out) {
  if (out == nullptr || !system.ok) return false;
  const Eigen::VectorXcd& values = system.values;
  const Eigen::Index n = values.size();
  if (static_cast<Eigen::Index>(multipliers.size()) != n) return false;
  out->resize(static_cast<std::size_t>(n));
  // The same matrix gives the same eigenvalues in the same order (with or without vectors the
  // Schur form is computed by the same operations): then column k belongs to multiplier k.
  bool same = true;
  for (Eigen::Index k = 0; k < n; ++k)
    same = same && values(k) == multipliers[static_cast<std::size_t>(k)];
  bool used[64] = {};
  std::vector<bool> used_big(n > 64 ? static_cast<std::size_t>(n) : 0, false);
  auto is_used = [&](Eigen::Index j) { return n > 64 ? bool(used_big[j]) : used[j]; };
  for (Eigen::Index k = 0; k < n; ++k) {
    Eigen::Index col = k;
    if (!same) {  // the nearest eigenvalue not yet used
      double best = std::numeric_limits<double>::infinity();
      for (Eigen::Index j = 0; j < n; ++j) {
        const double d = std::abs(values(j) - multipliers[static_cast<std::size_t>(k)]);
        if (!is_used(j) && !(d >= best)) {
          best = d;
          col = j;
        }
      }
      if (n > 64)
        used_big[col] = true;
      else
        used[col] = true;
    }
    Eigen::VectorXcd& v = (*out)[static_cast<std::size_t>(k)];
    v = system.vectors.col(col);
    const double nv = v.norm();
    if (!std::isfinite(nv)) return false;
    if (nv > 0.0) v /= nv;
  }
  return true;
}

bool floquet_eigenvectors(const Eigen::MatrixXd& phi,
                          const std::vector<std::complex<double>>& multipliers,
                          std::vector<Eigen::VectorXcd>* vectors) {
  if (vectors == nullptr) return false;
  return floquet_eigenvectors(floquet_eigensystem(phi), multipliers, vectors);
}

bool add_eigenvectors(FloquetResult* result) {
  if (result == nullptr || result->status == Status::Failed) return false;
  if (result->has_eigenvectors()) return true;
  std::vector<std::complex<double>> multipliers;
  for (const FloquetExponent& e : result->exponents) multipliers.push_back(e.multiplier);
  std::vector<Eigen::VectorXcd> v;
  if (!floquet_eigenvectors(result->phi, multipliers, &v)) return false;
  for (std::size_t k = 0; k < v.size(); ++k) result->exponents[k].eigenvector = std::move(v[k]);
  return true;
}

}  // namespace flaplag
