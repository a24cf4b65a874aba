// flaplag analysis (internal) — a critical search about the periodic equilibrium that ends at a
// fold of the equilibrium branch.
//
// At a fold (saddle-node) of the branch of periodic equilibria q°(mu) through hover a real
// Floquet multiplier of the linearization about q° reaches +1, and beyond it there is no
// equilibrium nearby: the blade loses its equilibrium, a divergence-type (0 per rev) loss of
// stability.  find_critical (numerics) only sees failed evaluations there; FoldWatch records
// where they started, and report_fold turns a search that failed that way into mu_c at the fold:
// bisection on the existence of q° (continued from the last mu where it exists), the multiplier's
// approach to 1 (|Lambda - 1|^2 ~ mu_f - mu near a fold) as a second estimate, kind periodic at
// omega = 0, and a message saying that the branch ends there.
#pragma once

#include <functional>
#include <memory>

#include "flaplag/numerics/continuation.h"
#include "flaplag/numerics/periodic_system.h"

namespace flaplag::internal {

// Wraps a FloquetFunction; `equilibrium_failed(sample)` says whether a failed sample failed for
// want of the periodic equilibrium (not, e.g., an overflow).
struct FoldWatch {
  struct State {
    double last_ok = 0.0;  // largest mu < first_failed with a successful sample
    double first_failed = -1.0;
  };
  std::shared_ptr<State> state = std::make_shared<State>();
  FloquetFunction wrap(FloquetFunction f) const;
};

// Existence of the equilibrium at mu (continued from the probe's own last success, which then
// moves to mu) and, when it exists, the linearization about it in *lin.  When it does not,
// *reached (if the probe knows it) is the largest mu below mu where the continuation still
// converged (the probe's start then moves there), else left alone.
using EquilibriumProbe = std::function<bool(double mu, PeriodicSystem* lin, double* reached)>;

// When r failed without mu_c and the watch saw the equilibrium fail: mu_c at the fold (see
// above); otherwise r is left alone.  o: the search's options (tolerance on mu_c).
void report_fold(CriticalResult& r, const FoldWatch& watch, const EquilibriumProbe& probe,
                 const CriticalOptions& o);

}  // namespace flaplag::internal
