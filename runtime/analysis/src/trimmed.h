// flaplag analysis — the continuation of a rotor trimmed at every advance ratio (Analysis with
// OperatingCondition::Trimmed; not installed).  Each evaluation trims the rotor at its mu
// (trim.h) and analyses the rotor at that trim; the results carry the trims they rest on.
#pragma once

#include <atomic>
#include <vector>

#include "flaplag/analysis.h"
#include "flaplag/numerics/continuation.h"
#include "flaplag/trim.h"

namespace flaplag::internal {

// The trim in hover a trimmed analysis starts from (its modes are labelled there).  Checks t and
// o (o.kind thrust or moment, else InvalidInput "trim"); InvalidInput("thrust_coefficient")
// when the rotor cannot be trimmed in hover.
TrimResult hover_trim(const RotorParameters& p, const TransitionOptions& t, const TrimOptions& o,
                      Linearization about);

class TrimmedContinuation {
 public:
  // p: the rotor as given (its controls are replaced by each trim's); hover: hover_trim(p, t, o);
  // modes: the hover modes of the rotor at that trim; about: what every trim trims (trim.h).
  TrimmedContinuation(const RotorParameters& p, const TransitionOptions& t, const TrimOptions& o,
                      Linearization about, TrimResult hover, HoverModes modes);

  // As Analysis::point, sweep, track and critical with this basis (the caller folds the basis
  // error in); mu, scan_step and the options checked here as there.
  RotorPoint point(double mu, double scan_step) const;
  RotorSweep sweep(double mu0, double mu1, double step, const std::atomic<bool>* cancel,
                   const ProgressFunction& progress) const;
  RotorSweep track(const std::vector<double>& mus, double scan_step,
                   const std::atomic<bool>* cancel, const ProgressFunction& progress) const;
  RotorCritical critical(const CriticalOptions& c) const;

 private:
  struct Evaluations;  // the trims one continuation made, by mu
  FloquetFunction function(const std::shared_ptr<Evaluations>& e) const;
  std::vector<TrimResult> trims_of(const Evaluations& e, const SweepResult& r) const;
  void rests_on_trims(const Evaluations& e, RotorCritical& r) const;
  Linearization about() const {
    return periodic_ ? Linearization::PeriodicEquilibrium : Linearization::HoverEquilibrium;
  }

  RotorParameters params_;
  TransitionOptions transition_;
  TrimOptions options_;
  bool periodic_;     // about the periodic equilibrium
  TrimResult hover_;  // the trim at mu = 0
  HoverModes modes_;
};

}  // namespace flaplag::internal
