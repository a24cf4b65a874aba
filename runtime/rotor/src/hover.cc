// flaplag — flap/lag labels of the hover modes.
#include "flaplag/rotor/hover.h"

#include <cmath>
#include <complex>

#include "flaplag/core/errors.h"
#include "flaplag/numerics/dense.h"

namespace flaplag {

void check_finite(HoverResult& h) {
  bool ok = std::isfinite(h.inflow) && h.q0.allFinite();
  for (const std::complex<double>& z : h.eigenvalues)
    ok = ok && std::isfinite(z.real()) && std::isfinite(z.imag());
  if (!ok) h.Worsen(Status::Failed, "non-finite hover equilibrium or eigenvalue (not shown)");
}

HoverModes label_hover_modes(const Eigen::MatrixXd& A0, int flap_modes, int lag_modes) {
  if (flap_modes < 0 || lag_modes < 0 || flap_modes + lag_modes < 1)
    throw InvalidInput("modes",
                       std::to_string(flap_modes) + " flap, " + std::to_string(lag_modes) + " lag",
                       "need M, N >= 0 and M + N >= 1");
  const int M = flap_modes, N = lag_modes, n = 2 * (M + N);
  if (A0.rows() != n || A0.cols() != n)
    throw InvalidInput("A0", std::to_string(A0.rows()) + "x" + std::to_string(A0.cols()),
                       "must be 2(M+N) x 2(M+N) = " + std::to_string(n) + "x" + std::to_string(n));
  if (!A0.allFinite()) throw InvalidInput("A0", "non-finite", "hover matrix must be finite");

  HoverModes out;
  out.zeta_rounding = hover_zeta_rounding(A0);
  const RealEigenSystem es = real_eigen_system(A0, true, EigenStorage::Dynamic);
  if (!es.ok) {
    out.status = Status::Failed;
    out.message = "eigen-decomposition of the hover matrix did not converge";
    return out;
  }
  for (int k = 0; k < n; ++k) {
    Eigen::VectorXcd v = es.vectors.col(k);
    v /= v.norm();
    // The direction whose displacements dominate the eigenvector (the first on a tie).
    const std::vector<model::DirectionBlock> blocks = model::direction_blocks(M, N);
    const model::DirectionBlock* dominant = nullptr;
    Eigen::VectorXcd part;
    for (const model::DirectionBlock& b : blocks) {
      if (b.modes == 0) continue;
      Eigen::VectorXcd d = v.segment(b.displacement_index(0), b.modes);
      if (dominant == nullptr || d.squaredNorm() > part.squaredNorm()) {
        dominant = &b;
        part = std::move(d);
      }
    }
    // One scheme for every model: the first mode of a direction is the direction's name, so
    // that "lag" of a 1 x 1 model and of a 3 x 3 model are the same mode; higher modes add
    // their number ("flap2").
    Eigen::Index idx = 0;
    part.cwiseAbs().maxCoeff(&idx);
    std::string label = model::mode_label(dominant->name, static_cast<int>(idx) + 1);
    out.eigenvalues.push_back(es.values(k));
    out.eigenvectors.push_back(std::move(v));
    out.labels.push_back(std::move(label));
  }
  return out;
}

}  // namespace flaplag
