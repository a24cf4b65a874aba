// flaplag — resolved Floquet evaluations of a periodic system: one transition-matrix method
// (FloquetEvaluator, one class per TransitionMethod, made by Create) and the step control that
// chooses its step count K so that the estimated error of every exponent zeta meets a
// tolerance.  The rules and their derivation: docs/numerics.md.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "flaplag/numerics/continuation.h"
#include "flaplag/numerics/floquet.h"
#include "flaplag/numerics/periodic_system.h"

namespace flaplag {

// Automatic steps never exceed this (a system so stiff that it needs more gets status Warning).
inline constexpr int kMaxAutomaticSteps = 65536;

// The step count that resolved the last automatic evaluation at each tolerance (keyed by the
// exact tolerance).  One continuation (a sweep, track or critical search) shares one hint, so
// that each evaluation starts at the count its predecessor predicted (warm start: the same rule
// and estimate, fewer levels) instead of climbing from the spectral start.
class StepsHint {
 public:
  int find(double zeta_tolerance) const;  // 0: no count at this tolerance yet
  void put(double zeta_tolerance, int steps);

 private:
  std::vector<std::pair<double, int>> last_;  // (zeta_tolerance, steps)
};

// One transition-matrix method and the step control around it, in the shape of Ceres'
// TrustRegionStrategy::Create: the step control asks the method for its order, its transition
// matrix at K steps, and (where the method has them) a K and K/2 pair from one pass or raw
// lower-order levels.  Immutable once made; safe to share between threads.
class FloquetEvaluator {
 public:
  // options.Check() (InvalidInput), then the evaluator of options.method.  An Automatic method
  // becomes automatic_method(state_size), the size of the systems it will evaluate (>= 1, else
  // InvalidInput), and options() names the method it became; state_size is not used otherwise.
  static std::unique_ptr<FloquetEvaluator> Create(const TransitionOptions& options,
                                                  int state_size = 0);
  virtual ~FloquetEvaluator();

  const TransitionOptions& options() const { return options_; }

  // p of the exponent error ~ c K^-p used by the Richardson estimates: RK4 4, Hsu min(J, 2)
  // (interval means O(h^2), one Taylor term O(h)), Magnus4 6 (after its own extrapolation).
  virtual int order() const = 0;
  // Phi(2 pi, 0) at `steps` (1..TransitionOptions::kMaxSteps): transition_matrix(sys, options
  // with steps).
  virtual Eigen::MatrixXd transition(const PeriodicSystem& sys, int steps) const = 0;
  // Whether transition_pair computes K and K/2 in one pass (Hsu) rather than as two calls.
  virtual bool has_pair() const { return false; }
  // Phi at `steps` (even) into *phi and at steps / 2 into *half: bits of transition() at steps,
  // and transition() at steps / 2 to rounding.
  virtual void transition_pair(const PeriodicSystem& sys, int steps, Eigen::MatrixXd* phi,
                               Eigen::MatrixXd* half) const;
  // Raw levels (Magnus4 without its Richardson pass: transition_matrix_magnus4_level) for sys;
  // 0 when the method has none for it, else their order (4).
  virtual int level_order(const PeriodicSystem& sys) const;
  virtual Eigen::MatrixXd level(const PeriodicSystem& sys, int steps, int bisections) const;

  // The Floquet analysis of sys (zeta_tolerance > 0, else InvalidInput) with a Richardson
  // estimate per exponent: fixed options().steps K against 2K; automatic steps from the spectrum
  // of A (>= 50, or the hint's count) growing until every estimate is at most
  // zeta_tolerance max(1, 100 |zeta_k|) or K reaches kMaxAutomaticSteps; hint may be null.
  // Warning when unresolved, below the rounding floor, the Liouville check fails or system_note
  // (what sys rests on, e.g. an approximate equilibrium) is not empty; Failed when sys or Phi
  // overflows.
  FloquetSample evaluate(const PeriodicSystem& sys, double zeta_tolerance,
                         StepsHint* hint = nullptr, const std::string& system_note = "") const;

 protected:
  explicit FloquetEvaluator(const TransitionOptions& options) : options_(options) {}

 private:
  TransitionOptions options_;
};

}  // namespace flaplag
