// flaplag analysis — helpers shared by the sources of the analysis library (not installed).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "flaplag/analysis.h"
#include "flaplag/blade/blade.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/core/parallel.h"
#include "flaplag/model_api.h"
#include "flaplag/numerics/continuation.h"
#include "flaplag/rotor/periodic_equilibrium.h"
#include "flaplag/rotor/system_builder.h"
#include "flaplag/rotor/validity.h"

namespace flaplag::internal {

// The error of the exact modes' discretization (basis.cc): a result is computed again with the
// reference discretization (rotor/parameters.h, reference_basis) and fold() adds the change to its
// error estimates (mu_c_error and the interval errors; a point's error_estimate), sets `basis`
// and `basis_error`, and makes it a Warning when the change exceeds 10 times the tolerance, or
// when it cannot be estimated.  Nothing for the assumed mode (basis == 0).
struct BasisCheck {
  int basis = 0;      // the functions used, or kElementBasis; 0: assumed mode
  int reference = 0;  // the basis compared with (or kElementBasis); 0: none (problem says why)
  std::string problem;
  // The 1974 mode shapes (RotorParameters::paper_1974_shapes) converge monotonically, not
  // alternately, in the basis size: the change to the neighbouring basis is then no bound, and
  // fold() notes so.
  bool monotone = false;
  double tolerance_ = 0.0;  // mu_c `tolerance` (critical) or `zeta_tolerance` (points)

  bool active() const { return basis != 0 && reference != 0; }
  RotorParameters reference_parameters(const RotorParameters& p) const;
  void fold(CriticalResult& r, const CriticalResult* ref) const;
  void fold(PointResult& r, const PointResult* ref) const;
  void fold(SweepResult& r, const SweepResult* ref) const;

 private:
  void unknown(Outcome& r, const std::string& why) const;
};
BasisCheck basis_check(const RotorParameters& p, int flap_modes, int lag_modes);

// mu in [0, kMaxAdvanceRatio], else InvalidInput(name, ...).
inline void check_mu(double mu, const char* name) {
  if (!std::isfinite(mu) || mu < 0.0 || mu > kMaxAdvanceRatio) {
    throw InvalidInput(name, round_trip_text(mu),
                       "advance ratio must be >= 0 and <= " + round_trip_text(kMaxAdvanceRatio));
  }
}

// The cancel flag and progress of a continuation (Analysis::sweep and track, fixed or
// trimmed): every FloquetFunction made by ticking() looks at the flag first (set: throws
// Cancelled) and counts its evaluation.  The evaluations planned are those of the plan of
// track_exponents: for each advance ratio, the equal steps from the one before that reach it.
struct Ticker {
  Ticker(const std::vector<double>& mus, double step, const std::atomic<bool>* c,
         ProgressFunction p)
      : cancel(c), progress(std::move(p)) {
    double at = 0.0;
    for (double mu : mus) {
      const double pre = std::ceil((mu - at) / step - 1e-9);
      total += pre > 1.0 ? static_cast<std::size_t>(pre) : 1;
      at = mu;
    }
  }
  const std::atomic<bool>* cancel;
  ProgressFunction progress;
  std::mutex mutex;
  std::size_t done = 0, total = 0;
};

// The progress of pass `pass` (0-based) of `passes` over the same work (a result and the same
// result with the reference basis, BasisCheck): each pass counts its share of one total, so
// that a progress bar moves on through the reference pass instead of waiting at 100 %.
inline ProgressFunction pass_progress(const ProgressFunction& progress, int pass, int passes) {
  if (!progress || passes <= 1) return progress;
  return [progress, pass, passes](std::size_t done, std::size_t total) {
    progress(static_cast<std::size_t>(pass) * total + done,
             static_cast<std::size_t>(passes) * total);
  };
}

inline FloquetFunction ticking(FloquetFunction f, std::shared_ptr<Ticker> ticker) {
  return [f = std::move(f), ticker = std::move(ticker)](double mu, double tol) {
    if (ticker->cancel != nullptr && ticker->cancel->load()) throw Cancelled();
    FloquetSample sample = f(mu, tol);
    if (ticker->progress) {
      const std::lock_guard<std::mutex> lock(ticker->mutex);
      ticker->done = std::min(ticker->done + 1, ticker->total);
      ticker->progress(ticker->done, ticker->total);
    }
    return sample;
  };
}

// The point at mu of a continuation from hover to mu (sweep_exponents): its last point, no
// better than a problem met on the way (identification); Failed when there is none.
inline RotorPoint point_at_end(SweepResult sw, double mu) {
  RotorPoint r;
  r.mu = mu;
  if (sw.points.empty()) {
    r.status = Status::Failed;
    r.message = sw.message.empty() ? "continuation from hover failed" : sw.message;
    return r;
  }
  static_cast<PointResult&>(r) = std::move(sw.points.back());
  r.mu = mu;
  if (r.status != Status::Failed) {
    if (sw.status > r.status) r.Worsen(sw.status, sw.message);
  } else if (r.message.empty()) {
    r.message = sw.message;
  }
  return r;
}

// Sorted by label, then omega descending: the order in which results are shown.  Stable (an
// insertion sort: a handful of exponents, no temporary buffer).
inline void sort_for_output(std::vector<LabelledExponent>& v) {
  auto before = [](const LabelledExponent& a, const LabelledExponent& b) {
    return a.label != b.label ? a.label < b.label : a.omega > b.omega;
  };
  for (std::size_t i = 1; i < v.size(); ++i)
    for (std::size_t j = i; j > 0 && before(v[j], v[j - 1]); --j) std::swap(v[j], v[j - 1]);
}

// The harmonic balance behind the linearization about the periodic equilibrium, for the
// analysis and the trim alike (the stability comes from the analysis' own Floquet evaluation,
// so none here).
inline PeriodicEquilibriumOptions equilibrium_options() {
  PeriodicEquilibriumOptions o;
  o.check_stability = false;
  return o;
}

// About the periodic equilibrium: the harmonic balance integrates the nonlinear loads region
// by region with the normal and the sector integrals; the exact circle has no such form there
// (it would silently be left out).  Refused up front, by the analysis and the trim alike.
inline void require_sector(const RotorParameters& p, Linearization about) {
  if (about != Linearization::PeriodicEquilibrium || !p.exact_reversed_flow) return;
  throw InvalidInput("exact_reversed_flow", "true",
                     "the periodic equilibrium (`linearization`) is built with the "
                     "Appendix D sector: use the sector (`exact_reversed_flow` = false)");
}

// A periodic equilibrium as a result keeps it: without its linearization (rebuilt by
// Analysis::floquet(mu)), which would make a result of many points large.
inline PeriodicEquilibrium without_linearization(PeriodicEquilibrium eq) {
  eq.linearization = PeriodicSystem{};
  return eq;
}

// The tip deflection by l of each direction (model_api.h DirectionBlock, in state order: flap
// w/l, lag v/l) of the modal displacements q0 + y, y a state in the order of model_api.h and q0
// (M + N values, coordinate order) the hover equilibrium, or none.
inline std::vector<double> tip_deflections(const ModeSet& modes, int M, int N,
                                           const Eigen::VectorXd& y,
                                           const Eigen::VectorXd* q0 = nullptr) {
  std::vector<double> out;
  for (const model::DirectionBlock& b : model::direction_blocks(M, N)) {
    const auto& shapes = modes.shapes(b.direction);
    double tip = 0.0;
    for (int k = 0; k < b.modes; ++k) {
      const double q = y(b.displacement_index(k));
      tip += shapes[k]->value(0, 1.0) * (q0 != nullptr ? (*q0)(b.first_coordinate + k) + q : q);
    }
    out.push_back(tip);
  }
  return out;
}

// One TipMotion per direction, named, empty.
inline std::vector<TipMotion> tip_motions(int M, int N) {
  std::vector<TipMotion> out;
  for (const model::DirectionBlock& b : model::direction_blocks(M, N))
    out.push_back(TipMotion{b.name, {}, {}, {}, std::nullopt});
  return out;
}

// Appends the deflections of one state (tip_deflections) to the motions' `deflection`.
inline void append_deflections(std::vector<TipMotion>& tips, const std::vector<double>& d) {
  for (std::size_t i = 0; i < tips.size(); ++i) tips[i].deflection.push_back(d[i]);
}

// The validity envelope (rotor/validity.h) of the operating point a builder describes: its
// pitch, inflow and the flap tip deflection of its hover equilibrium.
inline std::string validity_of(const detail::SystemBuilder& b) {
  const model::ModelDescriptor& m = b.model();
  double flap_tip = std::numeric_limits<double>::quiet_NaN();
  if (b.hover().q0.size() == m.flap_modes + m.lag_modes) {
    flap_tip = 0.0;
    for (int k = 0; k < m.flap_modes; ++k)
      flap_tip += b.modes().shapes(model::Direction::Flap)[k]->value(0, 1.0) * b.hover().q0(k);
  }
  return validity_warning(b.params(), b.inflow(), flap_tip);
}

}  // namespace flaplag::internal
