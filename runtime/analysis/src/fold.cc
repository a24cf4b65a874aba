// The fold of the periodic-equilibrium branch as the end of the critical search (fold.h).
#include "fold.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include "flaplag/core/format.h"
#include "flaplag/numerics/floquet.h"

namespace flaplag::internal {

FloquetFunction FoldWatch::wrap(FloquetFunction f) const {
  auto s = state;
  // The search asks the same mu again right away at a finer zeta tolerance (the scan's step
  // past the end of the branch, a bracket's end).  A failure there is the equilibrium's (or
  // the trim's), from the same last success, so the same failure: it is not solved again.
  auto failed = std::make_shared<std::optional<std::pair<double, FloquetSample>>>();
  return [s, f, failed](double mu, double tol) {
    if (*failed && (*failed)->first == mu) return (*failed)->second;
    FloquetSample out = f(mu, tol);
    if (out.status == Status::Failed)
      *failed = std::make_pair(mu, out);
    else
      failed->reset();
    if (out.status == Status::Failed) {
      if (s->first_failed < 0.0 || mu < s->first_failed) s->first_failed = mu;
    } else if (s->first_failed < 0.0 || mu < s->first_failed) {
      s->last_ok = std::max(s->last_ok, mu);
    }
    return out;
  };
}

namespace {

// min |Lambda_k - 1| of the linearization (RK4, 4096 steps: the multiplier near 1 is the
// slowest-varying one and needs no more), and the multiplier that attains it.
double distance_to_one(const PeriodicSystem& lin) {
  const FloquetResult fl =
      floquet_exponents(transition_matrix_rk4(lin, 4096), lin.trace_integral());
  double d = std::numeric_limits<double>::infinity();
  for (const FloquetExponent& e : fl.exponents)
    d = std::min(d, std::abs(e.multiplier - std::complex<double>(1.0)));
  return d;
}

// Where the branch ends: q° exists at lo (lin_lo its linearization), not at hi.
struct BranchEnd {
  double lo, hi;
  PeriodicSystem lin_lo;
};

// Bisection on existence from the watch's last success and first failure; each probe continues
// from the last mu where q° exists (and a failed one tells how far its continuation got, which
// is then the lower end).  Nothing when the last success is not reproducible.
std::optional<BranchEnd> bracket_branch_end(const FoldWatch::State& s,
                                            const EquilibriumProbe& probe,
                                            const CriticalOptions& o) {
  BranchEnd e;
  e.lo = std::min(s.last_ok, s.first_failed);
  e.hi = s.first_failed;
  double reached = -1.0;
  if (!probe(e.lo, &e.lin_lo, &reached)) return std::nullopt;
  PeriodicSystem lin;
  bool lin_current = true;
  for (int i = 0; i < 60 && e.hi - e.lo > 0.25 * o.tolerance; ++i) {
    const double mid = 0.5 * (e.lo + e.hi);
    reached = -1.0;
    if (probe(mid, &lin, &reached)) {
      e.lo = mid;
      e.lin_lo = lin;
      lin_current = true;
    } else {
      e.hi = mid;
      // The continuation got as far as `reached` in a coarse truncation (the automatic K
      // continues at few harmonics): a lower end only if the converged q° exists there too.
      const double got = reached;
      if (got > e.lo && got < mid) {
        reached = -1.0;
        if (probe(got, &lin, &reached)) {
          e.lo = got;
          e.lin_lo = lin;
          lin_current = true;
        } else {
          e.hi = got;
        }
      }
    }
  }
  if (!lin_current && !probe(e.lo, &e.lin_lo, &reached)) return std::nullopt;
  return e;
}

// Second estimate of the fold: |Lambda - 1|^2 is linear in mu near it, extrapolated to 0 with
// the slope from a point below e.lo (d_lo: |Lambda - 1| at e.lo).
std::optional<double> extrapolated_fold(const BranchEnd& e, double d_lo,
                                        const EquilibriumProbe& probe, const CriticalOptions& o) {
  const double below = e.lo - std::max(200.0 * o.tolerance, 20.0 * (e.hi - e.lo));
  PeriodicSystem lin;
  double reached = -1.0;
  if (below > 0.0 && probe(below, &lin, &reached)) {
    const double d_below = distance_to_one(lin);
    const double slope = (d_below * d_below - d_lo * d_lo) / (e.lo - below);
    if (slope > 0.0) return e.lo + d_lo * d_lo / slope;
  }
  return std::nullopt;
}

// mu_c at the fold mid (error `error`): divergence, 0 per rev, in the mode reported with the
// multiplier nearest 1 (the continuation's last).
void set_fold(CriticalResult& r, double mid, double error) {
  r.mu_c = mid;
  r.mu_c_error = error;
  r.omega = 0.0;
  r.kind = InstabilityKind::Periodic;
  double best = std::numeric_limits<double>::infinity();
  for (const LabelledExponent& e : r.exponents) {
    const double d = std::abs(e.multiplier - std::complex<double>(1.0));
    if (d < best) {
      best = d;
      r.mode = e.label;
    }
  }
  InstabilityInterval iv;
  iv.onset = mid;
  iv.onset_error = error;
  iv.mode = r.mode;
  iv.omega = 0.0;
  iv.kind = InstabilityKind::Periodic;
  r.intervals.assign(1, iv);
}

}  // namespace

void report_fold(CriticalResult& r, const FoldWatch& watch, const EquilibriumProbe& probe,
                 const CriticalOptions& o) {
  const FoldWatch::State& s = *watch.state;
  if (r.status != Status::Failed || r.mu_c || r.hover_unstable || s.first_failed <= 0.0) return;
  const std::optional<BranchEnd> end = bracket_branch_end(s, probe, o);
  if (!end) return;  // not reproducible: leave the failure as it is
  const double lo = end->lo, hi = end->hi;
  const double d_lo = distance_to_one(end->lin_lo);
  const std::optional<double> extrapolated = extrapolated_fold(*end, d_lo, probe, o);
  const std::string bracket = "(" + short_text(lo) + ", " + short_text(hi) + ")";
  // A fold: the multiplier is near 1 where the branch ends.  Otherwise the failure stays one.
  if (!(d_lo < 0.05)) {
    // (d_lo is infinite when the multipliers could not be computed: no "inf" in a message.)
    r.Worsen(r.status, "the periodic equilibrium ends in " + bracket +
                           (std::isfinite(d_lo)
                                ? " but no Floquet multiplier approaches 1 there (min |Lambda - "
                                  "1| = " +
                                      short_text(d_lo) + ")"
                                : " but the Floquet multipliers of the linearization there "
                                  "could not be computed (non-finite)") +
                           ": not identified as a fold");
    return;
  }
  const double mid = 0.5 * (lo + hi);
  // With all_intervals an onset may have been found before the fold: mu_c is that onset, not
  // the fold, which is only named.
  if (!r.intervals.empty()) {
    r.Worsen(r.status, "the periodic equilibrium branch ends at a fold near mu = " +
                           short_text(mid) + " (bracket " + bracket + ")");
    return;
  }
  // Conservative: near the fold the existence test (convergence of the continuation) depends a
  // little on the path of the probes, so the whole bracket and twice the extrapolation's offset.
  double error = hi - lo;
  if (extrapolated) error = std::max(error, 2.0 * std::abs(*extrapolated - mid));
  set_fold(r, mid, error);
  std::string msg =
      "the periodic equilibrium branch from hover ends at a fold at mu_c = " + short_text(mid) +
      " (bracket " + bracket + ", a real Floquet multiplier at " + short_text(1.0 - d_lo) +
      " where it last exists";
  if (extrapolated)
    msg += ", |Lambda - 1|^2 extrapolated to 0 at mu = " + short_text(*extrapolated);
  msg += "): the blade loses its equilibrium there (divergence, 0 per rev)";
  if (error <= o.tolerance) {
    r.status = Status::Ok;
    r.message = msg;
  } else {
    r.status = Status::Warning;
    r.message = msg + "; not resolved to the tolerance " + short_text(o.tolerance) +
                " (estimated error " + short_text(error) + ")";
  }
}

}  // namespace flaplag::internal
