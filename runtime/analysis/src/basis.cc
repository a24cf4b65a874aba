// flaplag analysis — the error of the exact modes' discretization in a result: the same result
// computed with the reference discretization (rotor/parameters.h, reference_basis: the
// neighbouring Galerkin basis, or finite elements against Galerkin for a blade table and the
// other way round), and the change included in the result's error estimates and status.
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <tuple>

#include "flaplag/blade/rotating_modes.h"
#include "flaplag/core/format.h"
#include "flaplag/rotor/blade_table.h"
#include "internal.h"

namespace flaplag::internal {

namespace {

// Worse than tolerance by this factor: not resolved (the same rule as the crossing's own error,
// CriticalSearch::crossing_error).
constexpr double kUnresolvedFactor = 10.0;

std::string functions(int basis) { return basis_description(basis); }

// With the 1974 shapes the neighbouring basis gives no bound (BasisCheck::monotone).  Measured
// on the typical case (mu_c 0.58540, 0.58494, 0.58471, 0.58460, 0.58454 ... 0.58446 with 5, 6,
// 7, 8, 9 ... 12 functions): the change to the next basis is about half the distance to 12.
void note_monotone(Outcome& r) {
  r.Note(
      "with the 1974 mode shapes the results converge monotonically in the basis size, so "
      "basis_error (the change to the neighbouring basis) is no bound: it was about half the "
      "error for the typical case's mu_c");
}

// What to do about a basis that does not resolve the modes: a larger one, unless it is the
// largest already (then its error estimate carries the change, `what`).
std::string remedy(int basis, const std::string& what) {
  if (basis == kElementBasis)
    return "the finite elements are the finer discretization (the change is mostly the Galerkin "
           "modes' error) and it is included in " +
           what;
  if (basis > 0 && basis < kMaxBasisFunctions) return "use a larger `basis`";
  return "the basis is already the largest (" + functions(basis) + "): the change is included in " +
         what;
}

// |a - b| added to an error estimate that may be absent.
void add(std::optional<double>& error, double change) { error = error.value_or(0.0) + change; }

}  // namespace

BasisCheck basis_check(const RotorParameters& p, int flap_modes, int lag_modes) {
  BasisCheck c;
  // Imported shapes (RotorParameters::mode_shapes) come from no Galerkin basis.
  if (p.modes != ModeKind::Exact || p.mode_shapes) return c;
  c.basis = p.basis == kElementBasis ? kElementBasis : galerkin_basis(p);
  c.reference = reference_basis(p, flap_modes, lag_modes);
  c.monotone = p.paper_1974_shapes;
  if (c.reference == 0) {
    c.problem = "no other basis holds " + std::to_string(std::max(flap_modes, lag_modes)) +
                " modes per direction";
  }
  return c;
}

RotorParameters BasisCheck::reference_parameters(const RotorParameters& p) const {
  RotorParameters r = p;
  r.basis = reference;
  // A dimensional table's first frequencies are results of its stiffness: the reference
  // computes them with its own discretization, so that the change includes their error.
  if (p.blade && p.blade->origin.dimensional)
    std::tie(r.omega_flap, r.omega_lag) = stiffness_frequencies(r, p.blade);
  return r;
}

void BasisCheck::unknown(Outcome& r, const std::string& why) const {
  r.Worsen(Status::Warning, "the error of the exact modes' basis (" + functions(basis) +
                                ") is not estimated: " + why);
}

void BasisCheck::fold(CriticalResult& r, const CriticalResult* ref) const {
  if (basis == 0) return;
  r.basis = basis;
  if (r.status == Status::Failed) return;
  if (ref == nullptr) return unknown(r, problem);
  const std::string with = "with " + functions(reference);
  if (ref->status == Status::Failed) return unknown(r, with + ": " + ref->message);
  if (r.hover_unstable != ref->hover_unstable || r.mu_c.has_value() != ref->mu_c.has_value()) {
    return unknown(r, with + " the answer differs: " + ref->message);
  }
  if (!r.mu_c) return;  // stable (or unstable in hover) with either basis
  double largest = 0.0;
  const double tolerance = tolerance_;
  for (std::size_t i = 0; i < r.intervals.size(); ++i) {
    InstabilityInterval& iv = r.intervals[i];
    if (i >= ref->intervals.size()) {
      return unknown(r, with + " the interval of instability from mu = " + short_text(iv.onset) +
                            " is not found");
    }
    const InstabilityInterval& other = ref->intervals[i];
    const double onset = std::abs(iv.onset - other.onset);
    add(iv.onset_error, onset);
    largest = std::max(largest, onset);
    if (iv.end.has_value() != other.end.has_value()) {
      return unknown(r, with + " the interval of instability from mu = " + short_text(iv.onset) +
                            " ends otherwise");
    }
    if (iv.end) {
      const double end = std::abs(*iv.end - *other.end);
      add(iv.end_error, end);
      largest = std::max(largest, end);
    }
  }
  const double change = std::abs(*r.mu_c - *ref->mu_c);
  r.basis_error = change;
  add(r.mu_c_error, change);
  if (monotone) note_monotone(r);
  if (!r.intervals.empty()) r.mu_c_error = r.intervals.front().onset_error;
  if (largest > kUnresolvedFactor * tolerance) {
    r.Worsen(Status::Warning,
             "the exact modes are not resolved in their basis: " + functions(basis) + " against " +
                 functions(reference) + " change mu_c (or an interval end) by " +
                 short_text(largest) + ", more than 10 `tolerance`; " +
                 remedy(basis, "the error estimate of mu_c"));
  }
}

void BasisCheck::fold(PointResult& r, const PointResult* ref) const {
  if (basis == 0) return;
  r.basis = basis;
  if (r.status == Status::Failed) return;
  if (ref == nullptr) return unknown(r, problem);
  const std::string with = "with " + functions(reference);
  if (ref->status == Status::Failed) return unknown(r, with + ": " + ref->message);
  // Each exponent against the nearest of the same label (the basis moves them little).
  double change = 0.0, top = -std::numeric_limits<double>::infinity(), top_change = 0.0;
  bool resolved = true;
  for (LabelledExponent& e : r.exponents) {
    double best = std::numeric_limits<double>::infinity(), dz = 0.0;
    for (const LabelledExponent& o : ref->exponents) {
      if (o.label != e.label) continue;
      const double d = std::hypot(o.zeta - e.zeta, o.omega - e.omega);
      if (d < best && std::isfinite(o.zeta) && std::isfinite(e.zeta)) {
        best = d;
        dz = std::abs(o.zeta - e.zeta);
      }
    }
    if (!std::isfinite(best)) continue;  // -inf zeta: no finite change to report
    if (e.zeta_error) *e.zeta_error += dz;
    change = std::max(change, dz);
    if (e.zeta > top) {
      top = e.zeta;
      top_change = dz;
    }
    if (dz > kUnresolvedFactor * tolerance_ * std::max(1.0, 100.0 * std::abs(e.zeta)))
      resolved = false;
  }
  r.basis_error = change;
  add(r.error, change);
  if (monotone) note_monotone(r);
  if (!resolved) {
    r.Worsen(Status::Warning,
             "the exact modes are not resolved in their basis: " + functions(basis) + " against " +
                 functions(reference) + " change a zeta by " + short_text(change) +
                 " per rev, more than 10 `zeta_tolerance`; " + remedy(basis, "the error estimate"));
  }
  // The sign of the largest zeta is known only outside its change with the basis (the method's
  // own error was judged by the continuation).
  if (r.stable && std::isfinite(top)) {
    const double e = top_change;
    if (std::abs(top) <= e) {
      r.stable.reset();
      r.Worsen(Status::Warning, "stability unknown: the largest zeta (" + short_text(top) +
                                    ") is within its error estimate " + short_text(e) +
                                    " of 0: its change with the basis");
    }
  }
}

void BasisCheck::fold(SweepResult& r, const SweepResult* ref) const {
  if (basis == 0) return;
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    PointResult& p = r.points[i];
    const PointResult* other = ref != nullptr && i < ref->points.size() && ref->points[i].mu == p.mu
                                   ? &ref->points[i]
                                   : nullptr;
    if (ref != nullptr && other == nullptr) {
      p.basis = basis;
      if (p.status != Status::Failed)
        unknown(p, "with " + functions(reference) + " the sweep stopped before mu = " +
                       short_text(p.mu) + (ref->message.empty() ? "" : ": " + ref->message));
    } else {
      fold(p, other);
    }
    r.Include(p, "at mu = " + short_text(p.mu) + ": ");
  }
}

}  // namespace flaplag::internal
