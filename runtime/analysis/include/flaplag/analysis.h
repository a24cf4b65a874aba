// flaplag — stability analysis of the coupled flap-lag blade at advance ratio mu.
//
// Typical use (no I/O inside; safe to call in a loop):
//   flaplag::RotorParameters p;                 // the paper's typical case
//   flaplag::Analysis an(p, {});                // Hsu K = 50, J = 4
//   auto crit = an.critical({});                // mu_c, mode, omega, kind
//
// Invalid parameters throw InvalidInput from the constructor.  Numerical outcomes (unstable
// hover, unconverged search, defective multipliers) come back with a Status and a message.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "flaplag/blade/blade.h"
#include "flaplag/rotor/hover.h"
#include "flaplag/numerics/floquet.h"
#include "flaplag/model_api.h"
#include "flaplag/rotor/parameters.h"
#include "flaplag/numerics/periodic_system.h"
#include "flaplag/core/status.h"

namespace flaplag {

// One labelled characteristic exponent.
struct ModeExponent {
  std::string label;   // "flap", "lag" ("flap1", "flap2", ... when there are several modes)
  double zeta = 0.0;   // real part, per rev
  double omega = 0.0;  // imaginary part, per rev, integer fixed by continuation from hover
  std::complex<double> multiplier;
};

struct PointResult {
  double mu = 0.0;
  std::vector<ModeExponent> exponents;  // sorted by label, then by omega
  double liouville_residual = 0.0;
  double error_estimate = 0.0;  // reference method only
  bool stable = true;
  Status status = Status::Ok;
  std::string message;
};

struct SweepResult {
  std::vector<PointResult> points;
  Status status = Status::Ok;
  std::string message;
};

struct CriticalOptions {
  double mu_max = 2.0;      // scan limit
  double scan_step = 0.01;  // continuation / scan step in mu
  double tolerance = 1e-5;  // on mu_c
};

struct CriticalResult {
  bool found = false;  // false: stable up to mu_max
  double mu_c = 0.0;
  std::string mode;    // "flap"/"lag"
  double omega = 0.0;  // per rev at mu_c, >= 0 (either member of a crossing pair)
  InstabilityKind kind = InstabilityKind::Flutter;
  double mu_max = 0.0;
  Status status = Status::Ok;
  std::string message;
};

// The numbers an auditor needs at one (mu, psi).
struct SystemSnapshot {
  double mu = 0.0, psi = 0.0;
  std::string region;  // "normal" or "reversed"
  Eigen::MatrixXd A;
  Eigen::VectorXd f;
  std::vector<std::pair<std::string, double>> aero_integrals;         // normal region values
  std::vector<std::pair<std::string, double>> aero_integrals_region;  // values used at psi
  std::vector<std::pair<std::string, double>> structural_integrals;
};

class Analysis {
 public:
  Analysis(const RotorParameters& params, const TransitionOptions& options);
  ~Analysis();
  Analysis(Analysis&&) noexcept;
  Analysis& operator=(Analysis&&) noexcept;

  const RotorParameters& parameters() const;
  const TransitionOptions& options() const;
  const model::ModelDescriptor& model() const;
  const ModeSet& modes() const;

  const HoverResult& hover() const;
  PeriodicSystem system(double mu) const;  // throws InvalidInput for mu < 0 or NaN
  SystemSnapshot snapshot(double mu, double psi) const;

  // Exponents at mu with labels from continuation (steps of at most scan_step from hover).
  PointResult point(double mu, double scan_step = 0.01) const;
  // Sweep mu0..mu1 inclusive with the given step (mu0 >= 0, mu1 >= mu0, step > 0).
  SweepResult sweep(double mu0, double mu1, double step) const;
  CriticalResult critical(const CriticalOptions& opt) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Compiled models (generated/), in name order.
const std::vector<const model::ModelDescriptor*>& compiled_models();
// Throws InvalidInput("model", name, ...) when unknown.
const model::ModelDescriptor& find_model(const std::string& name);

}  // namespace flaplag
