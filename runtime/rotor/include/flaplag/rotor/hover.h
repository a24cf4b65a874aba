// flaplag — the hover static equilibrium and the flap/lag labels of the hover modes.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <limits>
#include <string>
#include <vector>

#include "flaplag/core/outcome.h"
#include "flaplag/model_api.h"
#include "flaplag/numerics/continuation.h"

namespace flaplag {

// Hover static equilibrium (eqs 2.29-2.32) and hover stability.
struct HoverResult : Outcome {
  double inflow = 0.0;                            // lambda, eq 2.24
  Eigen::VectorXd q0;                             // [g0_1..g0_M, h0_1..h0_N]
  Eigen::MatrixXd A0;                             // constant A at mu = 0
  std::vector<std::complex<double>> eigenvalues;  // eig(A0), per rev
  std::vector<std::string> labels;                // "flap"/"lag" per eigenvalue ("flap1", "flap2",
                                                  // ... when the model has several modes of a kind)
  bool stable = true;
  // The least stable eigenvalue's real part is within the rounding level of zero
  // (hover_zeta_rounding): its sign, and so the stability of hover, is unknown (status
  // Warning; `stable` then holds only the sign found).
  bool neutral = false;
};

// Failed, with "non-finite hover equilibrium or eigenvalue (not shown)" in the message, when
// the inflow, q0 or an eigenvalue is not finite (Analysis checks its hover result so).
void check_finite(HoverResult& h);

// The rounding level of the real parts of eig(A0), per rev: the eigen-solve is backward
// stable, so an eigenvalue moves by about n eps ||A0|| (a few ulps of the matrix' norm); 8 n
// eps ||A0||_F leaves room for the modest non-normality of the blade's A0.
inline double hover_zeta_rounding(const Eigen::MatrixXd& A0) {
  return 8.0 * static_cast<double>(A0.rows()) * std::numeric_limits<double>::epsilon() * A0.norm();
}

// A0 is 2(M+N) x 2(M+N) in the state ordering of model_api.h (M, N >= 0, M + N >= 1).  An
// eigenvalue is a flap mode when the flap displacements g dominate its eigenvector
// (|g|^2 >= |h|^2) and a lag mode otherwise; its number is 1 + the index of the largest
// displacement component, its label model::mode_label ("flap", "flap2", "lag").  Throws
// InvalidInput for wrong sizes or NaN.
HoverModes label_hover_modes(const Eigen::MatrixXd& A0, int flap_modes, int lag_modes);

}  // namespace flaplag
