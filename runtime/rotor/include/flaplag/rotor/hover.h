// flaplag — the hover static equilibrium and the flap/lag labels of the hover modes.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "flaplag/core/fields.h"
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
  // q0 by the name of its coordinate, direction after direction ("g0_1", ..., "h0_1", ...;
  // named by Analysis from the model's directions).
  std::vector<std::pair<std::string, double>> equilibrium;
};

// A hover exponent as a document lists it: an eigenvalue of A0 with its label.
struct HoverExponent {
  double zeta = 0.0;
  double omega = 0.0;
  std::string label;
};

constexpr auto describe(Tag<HoverExponent>) {
  return std::make_tuple(
      Field{"zeta", &HoverExponent::zeta, "1/rev", "real part of the eigenvalue (> 0: unstable)"},
      Field{"omega", &HoverExponent::omega, "per rev", "imaginary part of the eigenvalue"},
      Computed{"damping_ratio",
               +[](const HoverExponent& e) { return damping_ratio(e.zeta, e.omega); },
               "- (fraction of critical)", "-zeta/|lambda|, as an Exponent's"},
      Field{"label", &HoverExponent::label, "", "the mode: flap, lag (flap2, ...)"});
}

// The eigenvalues with their labels.
inline std::vector<HoverExponent> hover_exponents(const HoverResult& h) {
  std::vector<HoverExponent> e;
  for (std::size_t i = 0; i < h.eigenvalues.size(); ++i)
    e.push_back(
        {h.eigenvalues[i].real(), h.eigenvalues[i].imag(), i < h.labels.size() ? h.labels[i] : ""});
  return e;
}

// Hover's stability as shown: unknown when the analysis failed or hover is neutral.
inline std::optional<bool> hover_stable(const HoverResult& h) {
  if (h.status == Status::Failed || h.neutral) return std::nullopt;
  return h.stable;
}

// Documents (a `hover` object) hold the rows of kHoverDocumentRows; Python has every row.
constexpr auto describe(Tag<HoverResult>) {
  using H = HoverResult;
  return std::make_tuple(
      Field{"inflow", &H::inflow, "-", "the inflow ratio lambda (eq 2.24)"},
      Field{"equilibrium", &H::equilibrium, "-",
            "the static equilibrium q0 by coordinate: g0_1, ... (flap), h0_1, ... (lag)"},
      Field{"A0", &H::A0, "1/rev", "the constant A at mu = 0"},
      Field{"eigenvalues", &H::eigenvalues, "1/rev", "eig(A0), per rev"},
      Field{"labels", &H::labels, "", "the mode label of each eigenvalue"},
      Computed{"exponents", &hover_exponents, "", "the eigenvalues with their labels"},
      Computed{"stable", &hover_stable, "",
               "every zeta <= 0; null when unknown (failed, or the largest zeta is within the "
               "rounding level of 0)"},
      Field{"status", &H::status, "", "how it went (as every result's)"},
      Field{"message", &H::message, "", "what went wrong or was found", kFieldMessage});
}

// The rows of HoverResult in a document's `hover`.
inline constexpr const char* kHoverDocumentRows[] = {"inflow", "equilibrium", "exponents",
                                                     "stable", "status",      "message"};

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
