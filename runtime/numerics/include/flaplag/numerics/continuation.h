// flaplag — mode identification by continuation in the advance ratio mu, and the critical mu.
//
// The Floquet exponents lambda = zeta + i omega of Phi(2 pi) fix omega only up to an integer
// (eq 3.19).  At mu = 0 the system has constant coefficients and the exponents are exactly the
// eigenvalues of A0, integer part included; labels (flap/lag) come from the eigenvectors there.
// ExponentTracker carries both along small steps in mu by matching eigenvectors and multipliers
// and choosing the integer that keeps omega continuous (paper 4.2 step 3: "the degrees of
// freedom are identified by tracing back their history from mu = 0").
//
// Nothing here knows about rotors beyond the state ordering used for the hover labels
// (model_api.h): y = [g'_1..g'_M, g_1..g_M, h'_1..h'_N, h_1..h_N].
//
// Invalid arguments throw InvalidInput; numerical outcomes (non-finite multipliers, ambiguous
// identification, instability in hover) come back as a status and a message.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "flaplag/numerics/floquet.h"
#include "flaplag/core/status.h"

namespace flaplag {

// Periodic when omega is within `tolerance` of an integer or half-integer.
InstabilityKind classify_crossing(double omega, double tolerance = 1e-3);

struct LabelledExponent {
  std::string label;   // "flap", "lag" ("flap2", "lag2", ... when M or N > 1)
  double zeta = 0.0;   // per rev
  double omega = 0.0;  // per rev, integer part fixed by continuation from hover
  std::complex<double> multiplier;
};

// Eigen-decomposition of the hover matrix A0 with a label per eigenvalue (the rotor layer
// labels them: rotor/hover.h).
struct HoverModes {
  std::vector<std::complex<double>> eigenvalues;  // eig(A0), per rev
  std::vector<Eigen::VectorXcd> eigenvectors;     // unit 2-norm
  std::vector<std::string> labels;
  Status status = Status::Ok;
  std::string message;
};

// Outcome of one continuation step.
struct TrackReport {
  double min_similarity = 1.0;  // smallest |v_old^H v_new| in the chosen assignment
  Status status = Status::Ok;
  std::string message;
};

class ExponentTracker {
 public:
  // Starts at hover: exponents = eig(A0), multipliers = exp(2 pi lambda).
  explicit ExponentTracker(const HoverModes& hover);

  // Matches the exponents of `next` (at the neighbouring parameter value `mu`) to the tracked
  // ones.  Each tracked exponent is predicted at mu by linear extrapolation from its last two
  // values (or taken as its last value when mu is NaN or there is no history yet); the
  // assignment minimises  sum (1 - |v_old^H v_new|) + 2 pi |lambda_new - lambda_predicted|,
  // the omega difference taken modulo integers, over all permutations (branch and bound,
  // n <= 8; greedy beyond).  Each omega then gets the integer that puts it closest to its
  // prediction, so a real multiplier keeps omega locked at the integer or half-integer next to
  // where its mode came from, and a conjugate pair passing through a half-integer (where the
  // eigenvectors are momentarily real and the pair indistinguishable) keeps its direction.
  // Non-finite multipliers leave the state unchanged and report Failed; a best match with
  // eigenvector similarity below 0.5 reports Warning.  Throws InvalidInput when the number of
  // exponents differs from the tracked one.
  TrackReport advance(const FloquetResult& next,
                      double mu = std::numeric_limits<double>::quiet_NaN());

  // In hover order (the order of HoverModes), conjugate pairs tracked individually.
  const std::vector<LabelledExponent>& exponents() const { return exponents_; }
  const std::vector<Eigen::VectorXcd>& eigenvectors() const { return vectors_; }
  // Index and value of the largest zeta.
  int most_unstable() const;
  double max_zeta() const;
  double mu() const { return mu_; }  // parameter of the current state (0 at hover)

 private:
  std::vector<LabelledExponent> exponents_;
  std::vector<Eigen::VectorXcd> vectors_;
  std::vector<std::complex<double>> previous_;  // zeta + i omega one step back
  double mu_ = 0.0;
  double previous_mu_ = 0.0;
  bool has_previous_ = false;
};

// The caller builds the periodic system at mu and returns its Floquet analysis.
using FloquetFunction = std::function<FloquetResult(double mu)>;

struct CriticalSearchOptions {
  double mu_max = 2.0;                     // scan limit (> 0)
  double step = 0.01;                      // scan / continuation step (> 0)
  double tolerance = 1e-5;                 // on mu_c (> 0)
  double zeta_tolerance = 0.0;             // unstable means zeta > zeta_tolerance (>= 0)
  double periodic_omega_tolerance = 1e-3;  // see classify_crossing
};

struct CriticalSearchResult {
  bool found = false;  // false: stable up to mu_max
  double mu_c = 0.0;
  std::string label;   // label of the mode that crossed
  double omega = 0.0;  // its omega at mu_c, per rev
  InstabilityKind kind = InstabilityKind::Flutter;
  double mu_max = 0.0;
  std::vector<LabelledExponent> exponents;  // at mu_c (found) or at the last mu scanned
  int evaluations = 0;                      // calls of the FloquetFunction
  Status status = Status::Ok;
  std::string message;
};

// Scans mu = step, 2 step, ... up to mu_max, continuing the exponents from hover.  At the first
// mu where some zeta > zeta_tolerance the crossing is refined by Brent's method on
// max_k zeta_k(mu), each trial advancing a copy of the tracker from the last stable grid point
// (so that labels and omega integers stay those of the continuation).  A mode that turns
// unstable and stable again within one step is not seen.  Unstable in hover: found = true,
// mu_c = 0, status Warning.
CriticalSearchResult find_critical(const HoverModes& hover, const FloquetFunction& floquet,
                                   const CriticalSearchOptions& opt = {});

struct SweepPoint {
  double mu = 0.0;
  std::vector<LabelledExponent> exponents;  // hover order
  double liouville_residual = 0.0;
  bool stable = true;  // all zeta <= 0
  Status status = Status::Ok;
  std::string message;
};

struct ExponentSweep {
  std::vector<SweepPoint> points;
  Status status = Status::Ok;  // worst over the points
  std::string message;
};

// Labelled exponents at mu0, mu0 + step, ..., mu1 (mu1 always included).  The continuation
// starts in hover and reaches mu0 in equal steps of at most `step`.  mu0 >= 0, mu1 >= mu0,
// step > 0.  A Failed step stops the sweep (points so far are kept).
ExponentSweep sweep_exponents(const HoverModes& hover, const FloquetFunction& floquet, double mu0,
                              double mu1, double step);

}  // namespace flaplag
