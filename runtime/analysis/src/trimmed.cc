// The continuation of a rotor trimmed at every advance ratio: see trimmed.h.
#include "trimmed.h"

#include <algorithm>
#include <map>
#include <memory>
#include <optional>
#include <utility>

#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "fold.h"
#include "internal.h"

namespace flaplag::internal {

TrimResult hover_trim(const RotorParameters& p, const TransitionOptions& t, const TrimOptions& o,
                      Linearization about) {
  t.Check();
  o.Check();
  if (o.kind == TrimKind::None) {
    throw InvalidInput("trim", "none", "nothing to trim: use thrust or moment");
  }
  TrimResult hover = trim(p, 0.0, o, nullptr, about);
  if (hover.status == Status::Failed) {
    throw InvalidInput("thrust_coefficient", round_trip_text(o.thrust_coefficient),
                       "the rotor cannot be trimmed in hover: " + hover.message);
  }
  return hover;
}

// The trims of one continuation (one point, sweep, track or critical search), by mu: the last
// one made at each mu.
struct TrimmedContinuation::Evaluations {
  std::map<double, TrimResult> used;
  const TrimResult* at(double mu) const {
    const auto it = used.find(mu);
    return it == used.end() ? nullptr : &it->second;
  }
};

TrimmedContinuation::TrimmedContinuation(const RotorParameters& p, const TransitionOptions& t,
                                         const TrimOptions& o, Linearization about,
                                         TrimResult hover, HoverModes modes)
    : params_(p),
      transition_(t),
      options_(o),
      periodic_(about == Linearization::PeriodicEquilibrium),
      hover_(std::move(hover)),
      modes_(std::move(modes)) {}

FloquetFunction TrimmedContinuation::function(const std::shared_ptr<Evaluations>& e) const {
  // Moment trim: warm start from the previous trim (the continuation moves in small steps of
  // mu; the cold start can land on another branch where the response is large).  Thrust trim:
  // always from the blade-element estimate, which is close and keeps each mu's trim independent
  // of the order of evaluation.
  auto previous = std::make_shared<TrimResult>(hover_);
  // About the periodic equilibrium both trims start warm: the previous trim's q° saves the
  // continuation from hover at every evaluation.
  const bool warm = options_.kind == TrimKind::Moment || periodic_;
  // A cold trim depends on mu alone: the search evaluates some mu more than once (at two zeta
  // tolerances, or again after a scan), and gets the same trim without solving again.
  auto cold = std::make_shared<std::map<double, TrimResult>>();
  return [this, e, previous, warm, cold](double mu, double zeta_tolerance) {
    FloquetSample out;
    TrimResult tr;
    if (const auto it = cold->find(mu); !warm && it != cold->end()) {
      tr = it->second;
    } else {
      tr = trim(params_, mu, options_, warm ? previous.get() : nullptr, about());
      if (!warm && tr.status != Status::Failed) {
        if (cold->size() > 4096) cold->clear();
        cold->emplace(mu, tr);
      }
    }
    if (tr.status != Status::Failed) *previous = tr;
    if (e->used.size() > 4096) e->used.clear();
    e->used[mu] = tr;
    if (tr.status == Status::Failed) {
      out.status = Status::Failed;
      out.message = "trim failed at mu = " + round_trip_text(mu) + ": " + tr.message;
      return out;
    }
    const Analysis an(tr.parameters, transition_, OperatingCondition::At(tr));
    // About the periodic equilibrium: the trim's own q° (the one whose thrust was trimmed).
    out = periodic_ ? an.floquet(tr.equilibrium, zeta_tolerance) : an.floquet(mu, zeta_tolerance);
    // A sample is never better than its trim: not converged or outside the validity envelope
    // makes it (at least) Warning, whatever its own status (trim_problem; an unstable trimmed
    // system is no problem of the sample: the exponents say so).
    const std::string problem = trim_problem(tr);
    if (!problem.empty())
      out.Worsen(Status::Warning, "trim at mu = " + round_trip_text(mu) + ": " + problem);
    return out;
  };
}

// The trims of the reported points of a sweep or track, in order (a point without a trim of its
// own, which cannot happen along a continuation, gets a failed one naming it).
std::vector<TrimResult> TrimmedContinuation::trims_of(const Evaluations& e,
                                                      const SweepResult& r) const {
  std::vector<TrimResult> trims;
  for (const PointResult& pt : r.points) {
    if (const TrimResult* x = e.at(pt.mu)) {
      trims.push_back(*x);
    } else {
      TrimResult none;
      none.mu = pt.mu;
      none.kind = options_.kind;
      none.target = options_.thrust_coefficient;
      none.parameters = params_;
      none.linearization = about();
      none.status = Status::Failed;
      none.message = "no trim at mu = " + round_trip_text(pt.mu);
      trims.push_back(std::move(none));
    }
  }
  return trims;
}

// A critical result rests on the trims at mu_c and at each interval's ends: their problems
// (trim_problem) make it at least Warning.
void TrimmedContinuation::rests_on_trims(const Evaluations& e, RotorCritical& r) const {
  if (r.mu_c) {
    if (const TrimResult* x = e.at(*r.mu_c)) r.trim = *x;
  }
  if (r.status == Status::Failed) return;
  std::vector<double> ends;
  for (const InstabilityInterval& iv : r.intervals) {
    ends.push_back(iv.onset);
    if (iv.end) ends.push_back(*iv.end);
  }
  for (double mu : ends) {
    const TrimResult* x = e.at(mu);
    if (x == nullptr) continue;
    const std::string problem = trim_problem(*x);
    if (!problem.empty())
      r.Worsen(Status::Warning, "the trim at mu = " + round_trip_text(mu) +
                                    ", where the result is found, is not sound: " + problem);
  }
}

RotorPoint TrimmedContinuation::point(double mu, double scan_step) const {
  const auto e = std::make_shared<Evaluations>();
  SweepResult sw =
      sweep_exponents(modes_, function(e), mu, mu, scan_step, transition_.zeta_tolerance);
  const bool none = sw.points.empty();
  RotorPoint r = point_at_end(std::move(sw), mu);
  if (none) return r;  // no point, no trim it rests on
  sort_for_output(r.exponents);
  SweepResult one;
  one.points.push_back(r);
  r.trim = trims_of(*e, one).front();
  return r;
}

RotorSweep TrimmedContinuation::sweep(double mu0, double mu1, double step,
                                      const std::atomic<bool>* cancel,
                                      const ProgressFunction& progress) const {
  const auto e = std::make_shared<Evaluations>();
  FloquetFunction f = function(e);
  if (cancel != nullptr || progress)
    f = ticking(std::move(f),
                std::make_shared<Ticker>(sweep_grid(mu0, mu1, step), step, cancel, progress));
  RotorSweep r;
  static_cast<SweepResult&>(r) =
      sweep_exponents(modes_, f, mu0, mu1, step, transition_.zeta_tolerance);
  for (PointResult& pt : r.points) sort_for_output(pt.exponents);
  r.trims = trims_of(*e, r);
  return r;
}

RotorSweep TrimmedContinuation::track(const std::vector<double>& mus, double scan_step,
                                      const std::atomic<bool>* cancel,
                                      const ProgressFunction& progress) const {
  const auto e = std::make_shared<Evaluations>();
  FloquetFunction f = function(e);
  if (cancel != nullptr || progress)
    f = ticking(std::move(f), std::make_shared<Ticker>(mus, scan_step, cancel, progress));
  RotorSweep r;
  static_cast<SweepResult&>(r) =
      track_exponents(modes_, f, mus, scan_step, transition_.zeta_tolerance);
  for (PointResult& pt : r.points) sort_for_output(pt.exponents);
  r.trims = trims_of(*e, r);
  return r;
}

RotorCritical TrimmedContinuation::critical(const CriticalOptions& c) const {
  c.Check();
  const auto e = std::make_shared<Evaluations>();
  CriticalOptions co = c;
  co.scan_zeta_tolerance = std::min(c.scan_zeta_tolerance, transition_.zeta_tolerance);
  RotorCritical r;
  if (!periodic_) {
    static_cast<CriticalResult&>(r) = find_critical(modes_, function(e), co);
    sort_for_output(r.exponents);
    rests_on_trims(*e, r);
    return r;
  }
  // About the periodic equilibrium the trimmed branch can end at a fold (fold.h): the probe is
  // the trim itself, continued from its last success.
  const FoldWatch watch;
  static_cast<CriticalResult&>(r) = find_critical(modes_, watch.wrap(function(e)), co);
  std::optional<TrimResult> last;
  const EquilibriumProbe probe = [&](double mu, PeriodicSystem* lin, double*) {
    TrimResult x = trim(params_, mu, options_, last ? &*last : nullptr, about());
    if (x.status == Status::Failed) return false;
    *lin = x.equilibrium.linearization;
    last = std::move(x);
    return true;
  };
  report_fold(r, watch, probe, co);
  sort_for_output(r.exponents);
  // A fold's mu_c is the probe's trim, not one of the search's.
  if (last && r.mu_c && *r.mu_c == last->mu) e->used[last->mu] = *last;
  rests_on_trims(*e, r);
  return r;
}

}  // namespace flaplag::internal
