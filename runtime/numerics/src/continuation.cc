// flaplag — continuation of Floquet exponents in mu, hover labels, critical advance ratio.
#include "flaplag/numerics/continuation.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <memory>
#include <thread>
#include <utility>

#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/core/parallel.h"
#include "flaplag/numerics/brent.h"
#include "zeta_floor.h"

namespace flaplag {
namespace {

constexpr double kAmbiguousSimilarity = 0.5;
// Exponent accuracy asked of continuation steps that are not reported (per rev).
constexpr double kIdentificationTolerance = 1e-3;
// A scan point of find_critical that only has to tell the sign of max zeta - threshold is
// evaluated at kSignFraction times the margin of the previous point (at most
// kIdentificationTolerance), and kept when the sign of f survives moving every zeta by
// kSignMargin times its error estimate.
constexpr double kSignFraction = 0.02;
constexpr double kSignMargin = 10.0;
// Zero multipliers have zeta = -inf; for prediction and matching their zeta is taken as the
// floor (zeta_floor.h).
using detail::kZetaFloor;
// Any mismatch costs at most this: keeps the branch-and-bound's arithmetic finite.
constexpr double kMaxCost = 1e12;

double finite_zeta(double zeta) { return std::max(zeta, kZetaFloor); }

// The distance of two exponents that mode identification uses (ExponentTracker::advance): 2 pi
// |d lambda| with d omega taken modulo integers, about the relative change of the multiplier.
// dz between floored zetas.  sqrt, not hypot: both terms are finite (zeta is floored, omega is
// a principal value plus a continued integer) and an overflow to inf is capped by the caller
// like any huge cost.
double exponent_distance(double dz, double dw) {
  const double dr = dw - std::round(dw);
  return kTwoPi * std::sqrt(dz * dz + dr * dr);
}

std::string fmt(double v) { return short_text(v); }

void require(bool ok, const char* name, double value, const char* reason) {
  if (!ok) throw InvalidInput(name, round_trip_text(value), reason);
}

// Largest n solved exactly (branch and bound); beyond, greedy.  Also the size of the
// stack buffers of ExponentTracker::advance, which allocates nothing up to it.
constexpr int kExactAssignment = 8;

// Minimum-cost assignment of rows (tracked modes) to columns (new exponents); cost(i, j) at
// cost[i + n j] (column-major), match[i] the column of row i.
class Assignment {
 public:
  Assignment(const double* cost, int n) : cost_(cost), n_(n) {}

  void solve(int* match) {
    if (n_ <= kExactAssignment) {
      for (int j = 0; j < n_; ++j) used_[j] = false;
      best_cost_ = std::numeric_limits<double>::infinity();
      for (int i = 0; i < n_; ++i) best_[i] = perm_[i] = -1;
      search(0, 0.0);
      for (int i = 0; i < n_; ++i) match[i] = best_[i];
      return;
    }
    // Greedy: repeatedly take the cheapest remaining pair.
    std::vector<bool> row_done(static_cast<std::size_t>(n_), false), col_done = row_done;
    for (int i = 0; i < n_; ++i) match[i] = -1;
    for (int step = 0; step < n_; ++step) {
      double c = std::numeric_limits<double>::infinity();
      int bi = 0, bj = 0;
      for (int i = 0; i < n_; ++i)
        for (int j = 0; j < n_; ++j)
          if (!row_done[i] && !col_done[j] && at(i, j) < c) {
            c = at(i, j);
            bi = i;
            bj = j;
          }
      row_done[bi] = col_done[bj] = true;
      match[bi] = bj;
    }
  }

 private:
  double at(int i, int j) const { return cost_[i + static_cast<std::size_t>(n_) * j]; }

  // Depth-first over permutations with the partial cost as bound (costs are >= 0).
  void search(int row, double partial) {
    if (partial >= best_cost_) return;
    if (row == n_) {
      best_cost_ = partial;
      for (int i = 0; i < n_; ++i) best_[i] = perm_[i];
      return;
    }
    for (int j = 0; j < n_; ++j) {
      if (used_[j]) continue;
      used_[j] = true;
      perm_[row] = j;
      search(row + 1, partial + at(row, j));
      used_[j] = false;
    }
  }

  const double* cost_;
  int n_;
  int perm_[kExactAssignment] = {}, best_[kExactAssignment] = {};
  bool used_[kExactAssignment] = {};
  double best_cost_ = 0.0;
};

// Everything the search needs at one trial mu.
struct Trial {
  double mu = 0.0;
  double f = 0.0;  // max zeta - zeta_threshold
  ExponentTracker tracker;
  TrackReport report;
  std::optional<double> error;  // the sample's error estimate of the largest zeta
  double liouville_residual = 0.0;
  // The sign of f holds for every exponent moved by kSignMargin times its error estimate.
  bool sign_certain = false;
};

// Whether max_k zeta_k - threshold keeps its sign when every zeta_k moves by kSignMargin times
// its estimated error (false without estimates).
bool sign_certain(const FloquetSample& s, double threshold) {
  const std::size_t n = s.floquet.exponents.size();
  if (n == 0 || s.zeta_errors.size() != n) return false;
  double lo = -std::numeric_limits<double>::infinity(), hi = lo;
  for (std::size_t k = 0; k < n; ++k) {
    const double z = s.floquet.exponents[k].zeta, e = kSignMargin * s.zeta_errors[k];
    if (!std::isfinite(e)) return false;
    lo = std::max(lo, z - e);
    hi = std::max(hi, z + e);
  }
  return hi <= threshold || lo > threshold;
}

// Each tracked exponent's own error estimate: the sample's estimate of the exponent with the same
// multiplier (the tracker copies it bit for bit), the largest when several share it.
void attach_zeta_errors(std::vector<LabelledExponent>& tracked, const FloquetSample& s) {
  if (s.zeta_errors.size() != s.floquet.exponents.size()) return;
  for (LabelledExponent& x : tracked) {
    for (std::size_t k = 0; k < s.zeta_errors.size(); ++k) {
      if (s.floquet.exponents[k].multiplier != x.multiplier || !std::isfinite(s.zeta_errors[k]))
        continue;
      x.zeta_error = std::max(x.zeta_error.value_or(0.0), s.zeta_errors[k]);
    }
  }
}

// Error estimate of the largest zeta of a sample (the one that decides stability).
std::optional<double> largest_zeta_error(const FloquetSample& s) {
  if (s.zeta_errors.size() != s.floquet.exponents.size() || s.zeta_errors.empty()) return s.error;
  std::size_t k = 0;
  for (std::size_t i = 1; i < s.floquet.exponents.size(); ++i)
    if (s.floquet.exponents[i].zeta > s.floquet.exponents[k].zeta) k = i;
  return s.zeta_errors[k];
}

// The scratch of ExponentTracker::advance: on the stack up to kExactAssignment modes (the
// prediction up to kStackPrediction), so that nothing allocates on the common path.
class AdvanceScratch {
 public:
  explicit AdvanceScratch(int n) {
    if (n > kStackPrediction) {
      big_zeta_.resize(static_cast<std::size_t>(n));
      big_omega_.resize(static_cast<std::size_t>(n));
      predicted_zeta = big_zeta_.data();
      predicted_omega = big_omega_.data();
    }
    if (n > kExactAssignment) {
      cost_big_.resize(static_cast<std::size_t>(n) * n);
      sim_big_.resize(static_cast<std::size_t>(n) * n);
      match_big_.resize(static_cast<std::size_t>(n));
      cost = cost_big_.data();
      sim = sim_big_.data();
      match = match_big_.data();
    }
  }
  AdvanceScratch(const AdvanceScratch&) = delete;
  AdvanceScratch& operator=(const AdvanceScratch&) = delete;

 private:
  static constexpr int kStackPrediction = 64;
  static constexpr int kSmall = kExactAssignment;
  double zeta_small_[kStackPrediction], omega_small_[kStackPrediction];
  double cost_small_[kSmall * kSmall], sim_small_[kSmall * kSmall];
  int match_small_[kSmall];
  std::vector<double> big_zeta_, big_omega_, cost_big_, sim_big_;
  std::vector<int> match_big_;

 public:
  // The predicted zeta and omega of tracked mode i; cost(i, j) and the eigenvector similarity
  // at [i + n j]; the new exponent match[i] assigned to tracked mode i.
  double* predicted_zeta = zeta_small_;
  double* predicted_omega = omega_small_;
  double* cost = cost_small_;
  double* sim = sim_small_;
  int* match = match_small_;
};

// Why the exponents of `next` cannot be tracked (it failed, or they are not finite), if so.
std::optional<std::string> untrackable(const FloquetResult& next) {
  if (next.status == Status::Failed) return next.message + "; tracking state unchanged";
  const bool given_vectors = next.has_eigenvectors();
  for (const FloquetExponent& e : next.exponents) {
    if (!std::isfinite(e.multiplier.real()) || !std::isfinite(e.multiplier.imag()) ||
        std::isnan(e.zeta) || std::isnan(e.omega) ||
        (given_vectors && !e.eigenvector.allFinite())) {
      return std::string("non-finite multipliers or eigenvectors; tracking state unchanged");
    }
  }
  return std::nullopt;
}

// The exponents predicted at mu: linear in mu through the last two states (`now` and
// `before`, t the step to mu in units of the last one) when extrapolating, else `now`.
void predict(const std::vector<LabelledExponent>& now,
             const std::vector<std::complex<double>>& before, bool extrapolate, double t,
             double* pz, double* pw) {
  for (std::size_t i = 0; i < now.size(); ++i) {
    const LabelledExponent& e = now[i];
    const double z = finite_zeta(e.zeta);
    pz[i] = z + (extrapolate ? t * (z - finite_zeta(before[i].real())) : 0.0);
    pw[i] = e.omega + (extrapolate ? t * (e.omega - before[i].imag()) : 0.0);
  }
}

// Cost of assigning tracked mode i to new exponent j: eigenvector dissimilarity plus the
// distance of the new exponent from the prediction (omega modulo integers), times 2 pi so
// that it is the relative change of the multiplier for small steps.  Both terms are O(1)
// for a wrong match.  The distance term, first.
void distance_costs(const FloquetResult& next, const double* pz, const double* pw, int n,
                    double* cost) {
  for (int j = 0; j < n; ++j) {
    const FloquetExponent& e = next.exponents[j];
    for (int i = 0; i < n; ++i) {
      const std::size_t ij = static_cast<std::size_t>(i) + static_cast<std::size_t>(n) * j;
      const double c = exponent_distance(finite_zeta(e.zeta) - pz[i], e.omega - pw[i]);
      cost[ij] = std::isfinite(c) ? std::min(c, kMaxCost) : kMaxCost;
    }
  }
}

// Whether the multipliers decide (then `match` is the assignment): when they leave no doubt,
// each tracked exponent's nearest candidate is distinct, near its prediction and nearer than
// any other by more than the largest eigenvector term (1), so the full cost could not choose
// otherwise.  `cost` holds the distance term alone.
bool decided_by_multipliers(const double* cost, int n, int* match) {
  constexpr int kSmall = kExactAssignment;
  bool decided = true;
  bool taken_small[kSmall] = {};
  std::vector<bool> taken_big(n > kSmall ? static_cast<std::size_t>(n) : 0, false);
  for (int i = 0; i < n && decided; ++i) {
    double d1 = std::numeric_limits<double>::infinity(), d2 = d1;
    int j1 = -1;
    for (int j = 0; j < n; ++j) {
      const double c = cost[i + static_cast<std::size_t>(n) * j];
      if (c < d1) {
        d2 = d1;
        d1 = c;
        j1 = j;
      } else if (c < d2) {
        d2 = c;
      }
    }
    const bool taken = j1 < 0 || (n > kSmall ? bool(taken_big[j1]) : taken_small[j1]);
    decided = !taken && d1 <= ExponentTracker::kMultiplierStep && d2 - d1 > 1.0;
    if (decided) {
      match[i] = j1;
      if (n > kSmall)
        taken_big[j1] = true;
      else
        taken_small[j1] = true;
    }
  }
  return decided;
}

// The eigenvectors of the exponents of `next` in `vectors` (given, or computed from its Phi),
// or why there are none.
std::optional<std::string> new_eigenvectors(const FloquetResult& next, int n,
                                            std::vector<Eigen::VectorXcd>& vectors) {
  if (next.has_eigenvectors()) {
    vectors.resize(static_cast<std::size_t>(n));
    for (int j = 0; j < n; ++j) vectors[j] = next.exponents[j].eigenvector;
    return std::nullopt;
  }
  std::vector<std::complex<double>> multipliers;
  multipliers.reserve(static_cast<std::size_t>(n));
  for (const FloquetExponent& e : next.exponents) multipliers.push_back(e.multiplier);
  if (next.eigensystem ? floquet_eigenvectors(*next.eigensystem, multipliers, &vectors)
                       : floquet_eigenvectors(next.phi, multipliers, &vectors))
    return std::nullopt;
  return std::string(next.phi.rows() == n
                         ? "the eigenvectors of Phi needed to identify the modes are not finite; "
                           "tracking state unchanged"
                         : "no eigenvectors (nor Phi) to identify close modes by; tracking "
                           "state unchanged");
}

// The eigenvector term added to the costs: 1 - |v_old^H v_new|, the similarity kept in `sim`.
void add_similarity_costs(const std::vector<Eigen::VectorXcd>& old_vectors,
                          const std::vector<Eigen::VectorXcd>& new_vectors, int n, double* sim,
                          double* cost) {
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const std::size_t ij = static_cast<std::size_t>(i) + static_cast<std::size_t>(n) * j;
      sim[ij] = std::abs(old_vectors[i].dot(new_vectors[j]));  // dot() conjugates the left side
      const double c = (1.0 - sim[ij]) + cost[ij];
      cost[ij] = std::isfinite(c) ? std::min(c, kMaxCost) : kMaxCost;
    }
  }
}

// Whether every match[i] is a new exponent's index.
bool is_assignment(const int* match, int n) {
  for (int i = 0; i < n; ++i)
    if (match[i] < 0 || match[i] >= n) return false;
  return true;
}

void warn_if_ambiguous(TrackReport& report) {
  if (report.min_similarity < kAmbiguousSimilarity) {
    report.status = Status::Warning;
    report.message = "ambiguous mode identification (eigenvector similarity " +
                     fmt(report.min_similarity) + "); consider a smaller step";
  }
}

}  // namespace

InstabilityKind classify_crossing(double omega, double tolerance) {
  const double twice = 2.0 * omega;
  return std::abs(twice - std::round(twice)) <= 2.0 * tolerance ? InstabilityKind::Periodic
                                                                : InstabilityKind::Flutter;
}

std::optional<double> damping_ratio(double zeta, double omega) {
  if (zeta == -std::numeric_limits<double>::infinity() && std::isfinite(omega)) return 1.0;
  if (!std::isfinite(zeta) || !std::isfinite(omega)) return std::nullopt;
  const double r = std::hypot(zeta, omega);
  if (r == 0.0) return std::nullopt;
  return -zeta / r;
}

ExponentTracker::ExponentTracker(const HoverModes& hover) {
  if (hover.eigenvalues.empty() || hover.eigenvectors.size() != hover.eigenvalues.size() ||
      hover.labels.size() != hover.eigenvalues.size())
    throw InvalidInput("hover", std::to_string(hover.eigenvalues.size()) + " eigenvalues",
                       "need matching, non-empty eigenvalues, eigenvectors and labels");
  for (std::size_t k = 0; k < hover.eigenvalues.size(); ++k) {
    const std::complex<double> lam = hover.eigenvalues[k];
    LabelledExponent e;
    e.label = hover.labels[k];
    e.zeta = lam.real();
    e.omega = lam.imag();  // exact at mu = 0, integer part included
    e.multiplier = std::exp(kTwoPi * lam);
    exponents_.push_back(std::move(e));
    vectors_.push_back(hover.eigenvectors[k]);
  }
}

bool ExponentTracker::ensure_vectors() const {
  if (vectors_valid_) return true;
  std::vector<std::complex<double>> multipliers;
  multipliers.reserve(exponents_.size());
  for (const LabelledExponent& e : exponents_) multipliers.push_back(e.multiplier);
  vectors_valid_ = last_eigensystem_
                       ? floquet_eigenvectors(*last_eigensystem_, multipliers, &vectors_)
                       : floquet_eigenvectors(last_phi_, multipliers, &vectors_);
  return vectors_valid_;
}

const std::vector<Eigen::VectorXcd>& ExponentTracker::eigenvectors() const {
  ensure_vectors();
  return vectors_;
}

TrackReport ExponentTracker::advance(const FloquetResult& next, double mu) {
  const int n = static_cast<int>(exponents_.size());
  if (static_cast<int>(next.exponents.size()) != n)
    throw InvalidInput("exponents", std::to_string(next.exponents.size()),
                       "expected " + std::to_string(n) + " as tracked");
  TrackReport report;
  auto fail = [&](std::string message) {
    report.status = Status::Failed;
    report.message = std::move(message);
    report.min_similarity = 0.0;
    return report;
  };
  if (std::optional<std::string> why = untrackable(next)) return fail(std::move(*why));

  AdvanceScratch s(n);
  const bool extrapolate =
      std::isfinite(mu) && has_previous_ && mu_ != previous_mu_ && std::isfinite(mu_);
  const double t = extrapolate ? (mu - mu_) / (mu_ - previous_mu_) : 0.0;
  predict(exponents_, previous_, extrapolate, t, s.predicted_zeta, s.predicted_omega);
  distance_costs(next, s.predicted_zeta, s.predicted_omega, n, s.cost);
  const bool decided = !next.has_eigenvectors() && decided_by_multipliers(s.cost, n, s.match);
  const std::vector<Eigen::VectorXcd>* new_vectors = nullptr;
  if (!decided) {
    // The full rule: eigenvectors of both states.
    if (std::optional<std::string> why = new_eigenvectors(next, n, next_vectors_))
      return fail(std::move(*why));
    if (!ensure_vectors())
      return fail(
          "the eigenvectors of the previous state could not be computed; tracking state "
          "unchanged");
    new_vectors = &next_vectors_;
    add_similarity_costs(vectors_, next_vectors_, n, s.sim, s.cost);
    Assignment(s.cost, n).solve(s.match);
  }
  const int* match = s.match;
  if (!is_assignment(match, n))  // unreachable with finite costs; never index with it
    return fail("mode identification found no assignment; tracking state unchanged");

  // The new state: the matched exponents, omega continued.
  previous_.resize(static_cast<std::size_t>(n));
  if (!decided) report.min_similarity = 1.0;
  for (int i = 0; i < n; ++i) {
    const FloquetExponent& e = next.exponents[match[i]];
    LabelledExponent& x = exponents_[i];
    previous_[i] = {finite_zeta(x.zeta), x.omega};
    // omega = principal + k with the integer k that puts omega closest to its prediction.  A
    // zero multiplier has no argument: its omega stays where the mode was last seen.
    if (e.multiplier != std::complex<double>(0.0, 0.0))
      x.omega = e.omega + std::round(s.predicted_omega[i] - e.omega);
    x.zeta = e.zeta;
    x.multiplier = e.multiplier;
    if (new_vectors != nullptr) {
      vectors_[i] = (*new_vectors)[match[i]];
      report.min_similarity =
          std::min(report.min_similarity, s.sim[i + static_cast<std::size_t>(n) * match[i]]);
    }
  }
  // Without new eigenvectors the tracked ones are those of next.phi, computed when needed.
  vectors_valid_ = new_vectors != nullptr;
  if (!vectors_valid_) {
    last_phi_ = next.phi;
    last_eigensystem_ = next.eigensystem;
  }
  if (decided) report.min_similarity = std::numeric_limits<double>::quiet_NaN();
  previous_mu_ = mu_;
  mu_ = mu;
  has_previous_ = std::isfinite(mu);
  warn_if_ambiguous(report);
  return report;
}

int ExponentTracker::most_unstable() const {
  int best = 0;
  for (int i = 1; i < static_cast<int>(exponents_.size()); ++i)
    if (exponents_[i].zeta > exponents_[best].zeta) best = i;
  return best;
}

double ExponentTracker::max_zeta() const { return exponents_[most_unstable()].zeta; }

std::optional<InvalidInput> CriticalOptions::Validate() const {
  return Requirements()
      .InRanges(*this)
      .Require(mu_max / scan_step <= static_cast<double>(kMaxContinuationSteps),
               [&] {
                 return InvalidInput("scan_step", round_trip_text(scan_step),
                                     "too small: mu_max / scan_step must be at most " +
                                         std::to_string(kMaxContinuationSteps) + " steps");
               })
      .Result();
}

namespace {

bool finite(std::complex<double> z) { return std::isfinite(z.real()) && std::isfinite(z.imag()); }
bool zeta_ok(double zeta) {
  return std::isfinite(zeta) || zeta == -std::numeric_limits<double>::infinity();
}
void not_shown(Outcome& o, Status s, const std::string& what) {
  o.Worsen(s, "non-finite " + what + " (not shown)");
}

CriticalResult critical_search(const HoverModes& hover, const FloquetFunction& floquet,
                               const CriticalOptions& opt);

}  // namespace

void check_finite(PointResult& p) {
  const Status before = p.status;
  for (const LabelledExponent& e : p.exponents) {
    if (!zeta_ok(e.zeta) || !std::isfinite(e.omega) || !finite(e.multiplier)) {
      not_shown(p, Status::Failed, "exponent of mode " + e.label);
      break;
    }
  }
  if (!std::isfinite(p.mu)) not_shown(p, Status::Failed, "mu");
  // The exponents are what stability is read from: without them it is unknown.
  if (p.status == Status::Failed && before != Status::Failed) p.stable.reset();
  if (p.liouville_residual && !std::isfinite(*p.liouville_residual))
    not_shown(p, Status::Warning, "Liouville residual");
  if (p.error && !std::isfinite(*p.error)) not_shown(p, Status::Warning, "error estimate");
}

void check_finite(CriticalResult& c) {
  if (c.mu_c && (!std::isfinite(*c.mu_c) || !std::isfinite(c.omega))) {
    not_shown(c, Status::Failed, "mu_c or omega");
    c.mu_c.reset();
  }
  if (c.mu_c_error && !std::isfinite(*c.mu_c_error))
    not_shown(c, Status::Warning, "mu_c error estimate");
  if (!std::isfinite(c.mu_max)) not_shown(c, Status::Failed, "mu_max");
}

CriticalResult find_critical(const HoverModes& hover, const FloquetFunction& floquet,
                             const CriticalOptions& opt) {
  CriticalResult out = critical_search(hover, floquet, opt);
  check_finite(out);
  return out;
}

namespace {

// A stability change to refine: its ends, the tracker the trials between them continue from
// (that at the grid point below the bracket, so that labels and omega integers stay those of
// the continuation), and the zeta slope across it.
struct Bracket {
  Trial lower, upper;
  ExponentTracker from;
  double slope;
};

// The scan's last grid point: its trial, whether that was evaluated for the sign alone
// (CriticalSearch::sign_only), and the tracker one grid point below it.
struct GridPoint {
  Trial at;
  bool loose;
  ExponentTracker below;

  void step_to(Trial next, bool next_loose) {
    below = at.tracker;
    at = std::move(next);
    loose = next_loose;
  }
};

// The stability changes found in one grid interval, and the grid point the search for them
// reached when it covered the next grid interval too.
struct Crossings {
  std::vector<Bracket> brackets;
  std::optional<GridPoint> searched_to;
};

// The search for the critical advance ratio: f(mu) = max zeta - zeta_threshold is scanned
// from hover in steps of scan_step; each change of sign is bracketed at the resolution its
// refinement needs, refined by Brent, and its error verified; onsets and re-stabilizations
// make the instability intervals.
class CriticalSearch {
 public:
  CriticalSearch(const HoverModes& hover, const FloquetFunction& floquet,
                 const CriticalOptions& opt)
      : hover_(hover), floquet_(floquet), opt_(opt) {}

  CriticalResult run();

 private:
  // What the scan does after a grid interval.
  enum class Next { Continue, SkipInterval, Stop, Failed };

  bool hover_decides(const ExponentTracker& tracker);
  Next scan_interval(GridPoint& prev, long i);
  Next resolve_change(GridPoint& prev, const Trial& hi, long i);
  bool search_neighbourhood(const GridPoint& prev, const Trial& hi, long i, double zeta_tolerance,
                            Crossings& found);
  bool bracket_grid_interval(const GridPoint& prev, const Trial& b, long i, double slope0,
                             double zeta_tolerance, Crossings& found);
  Next refine_by_brent(const std::vector<Bracket>& brackets, double zeta_tolerance);
  void record_onset(const Trial& unstable, double mu, std::optional<double> error);
  void conclude(const Trial& last, const Trial& before_last);
  void note_rising_at_mu_max(const Trial& last, const Trial& before_last);

  Trial evaluate(const ExponentTracker& from, double mu, double zeta_tolerance);
  Trial sign_only(const ExponentTracker& from, double mu, double margin, bool& loose);
  std::pair<Trial, Trial> brent(const ExponentTracker& from, const Trial& a, const Trial& b,
                                double zeta_tolerance);
  std::optional<double> crossing_error(const ExponentTracker& from, const Trial& b, const Trial& c,
                                       double slope0, double zeta_tolerance);
  void note(double mu, Status status, const std::string& m);
  void set_mu_c();
  bool failed(const Trial& t);
  void fail(const Trial& t);

  const HoverModes& hover_;
  const FloquetFunction& floquet_;
  const CriticalOptions& opt_;
  CriticalResult out_;
  long steps_ = 0;                    // grid intervals of the scan
  std::optional<Trial> hover_trial_;  // the scan's start
  std::string warnings_;              // the first problem of a point, for the message
  std::string unresolved_;            // the first crossing not resolved to `tolerance`
  std::optional<Trial> failure_;      // a Brent trial that failed
  bool estimates_ = false;            // the FloquetFunction has given an error estimate
};

CriticalResult CriticalSearch::run() {
  out_.mu_max = opt_.mu_max;
  if (hover_.status == Status::Failed) {
    out_.status = Status::Failed;
    out_.message = "hover modes unavailable: " + hover_.message;
    return std::move(out_);
  }
  const ExponentTracker tracker(hover_);
  if (hover_decides(tracker)) return std::move(out_);

  // Bounded by Check(): at most kMaxContinuationSteps (+1 for rounding).
  steps_ = static_cast<long>(std::ceil(opt_.mu_max / opt_.scan_step - 1e-9));
  // Hover, the scan's start: exact exponents, no error estimate.
  hover_trial_ =
      Trial{0.0, tracker.max_zeta() - opt_.zeta_threshold, tracker, {}, std::nullopt, 0.0};
  GridPoint prev{*hover_trial_, false, tracker};
  Trial before_last = *hover_trial_;  // the grid point before the scan's last one
  for (long i = 1; i <= steps_; ++i) {
    Trial before = prev.at;
    const Next next = scan_interval(prev, i);
    if (next == Next::Failed) return std::move(out_);
    if (next == Next::Stop) break;
    before_last = std::move(before);
    if (next == Next::SkipInterval) ++i;  // the next grid interval is searched already
  }
  if (prev.loose && out_.intervals.empty()) {  // its exponents are reported: scan resolution
    prev.at = evaluate(prev.below, prev.at.mu, opt_.scan_zeta_tolerance);
    if (failed(prev.at)) return std::move(out_);
    note(prev.at.mu, prev.at.report.status, prev.at.report.message);
  }
  conclude(prev.at, before_last);
  return std::move(out_);
}

// Whether hover alone gives the answer (true: out_ is final): unstable in hover, or within
// rounding of the threshold.
bool CriticalSearch::hover_decides(const ExponentTracker& tracker) {
  if (hover_.zeta_rounding > 0.0 &&
      std::abs(tracker.max_zeta() - opt_.zeta_threshold) <= hover_.zeta_rounding) {
    // Within rounding of the threshold: neither stable nor unstable is known in hover, and the
    // scan has no sign to start from.
    const LabelledExponent& e = tracker.exponents()[tracker.most_unstable()];
    out_.exponents = tracker.exponents();
    out_.status = Status::Warning;
    out_.message = "the stability of hover is unknown: the least stable mode (" + e.label +
                   ", zeta = " + fmt(e.zeta) + ") is within the rounding level " +
                   fmt(hover_.zeta_rounding) +
                   " of the threshold (a neutral blade); no critical advance ratio is sought";
    return true;
  }
  if (tracker.max_zeta() > opt_.zeta_threshold) {
    const LabelledExponent& e = tracker.exponents()[tracker.most_unstable()];
    out_.hover_unstable = true;
    out_.exponents = tracker.exponents();
    out_.status = Status::Warning;
    out_.message = "unstable in hover (" + e.label + ", zeta = " + fmt(e.zeta) +
                   "): there is no critical advance ratio";
    return true;
  }
  return false;
}

// The scan's grid interval (prev, i scan_step]: the sign of f at its end, and a change of it
// resolved.
CriticalSearch::Next CriticalSearch::scan_interval(GridPoint& prev, long i) {
  const double mu = std::min(static_cast<double>(i) * opt_.scan_step, opt_.mu_max);
  bool hi_loose = false;
  Trial hi = sign_only(prev.at.tracker, mu, std::abs(prev.at.f), hi_loose);
  if (failed(hi)) return Next::Failed;
  estimates_ = estimates_ || hi.error.has_value();
  if ((hi.f > 0.0) == (prev.at.f > 0.0)) {
    note(mu, hi.report.status, hi.report.message);
    prev.step_to(std::move(hi), hi_loose);
    return Next::Continue;
  }
  // A sign change: both ends at the scan resolution, as the plain scan has them.
  if (prev.loose) {
    prev.at = evaluate(prev.below, prev.at.mu, opt_.scan_zeta_tolerance);
    if (failed(prev.at)) return Next::Failed;
    note(prev.at.mu, prev.at.report.status, prev.at.report.message);
    prev.loose = false;
  }
  if (hi_loose) {
    hi = evaluate(prev.at.tracker, mu, opt_.scan_zeta_tolerance);
    if (failed(hi)) return Next::Failed;
  }
  note(mu, hi.report.status, hi.report.message);
  if ((hi.f > 0.0) == (prev.at.f > 0.0)) {  // the sign change was within the loose estimates
    prev.step_to(std::move(hi), false);
    return Next::Continue;
  }
  return resolve_change(prev, hi, i);
}

// A stability change in [prev, hi] seen at the scan resolution: bracketed at the resolution of
// the refinement, refined by Brent and recorded; the scan then moves on past it.
CriticalSearch::Next CriticalSearch::resolve_change(GridPoint& prev, const Trial& hi, long i) {
  const double mu = hi.mu;
  // It is only as good as zeta near it: the refinement asks for a zeta error well below
  // |d zeta/d mu| * tolerance.
  const double slope0 = (hi.f - prev.at.f) / (mu - prev.at.mu);
  const double refine_tolerance =
      std::max(1e-13, std::min(opt_.scan_zeta_tolerance, 0.1 * std::abs(slope0) * opt_.tolerance));
  Trial b = evaluate(prev.at.tracker, mu, refine_tolerance);
  if (failed(b)) return Next::Failed;
  Crossings found;
  if ((b.f > 0.0) == (prev.at.f > 0.0)) {
    if (!search_neighbourhood(prev, hi, i, refine_tolerance, found)) return Next::Failed;
    if (found.brackets.empty()) {  // the change vanished when resolved
      prev.step_to(std::move(b), false);
      return Next::Continue;
    }
  } else if (!bracket_grid_interval(prev, b, i, slope0, refine_tolerance, found)) {
    return Next::Failed;
  }
  const Next refined = refine_by_brent(found.brackets, refine_tolerance);
  if (refined != Next::Continue) return refined;
  if (found.searched_to) {
    prev = std::move(*found.searched_to);
    return Next::SkipInterval;
  }
  prev.step_to(std::move(b), false);
  return Next::Continue;
}

// Seen at the scan resolution but not at mu resolved.  Before calling it vanished, the
// neighbourhood -- this grid interval and the next -- is searched at a finer step (scan_step /
// 10, then / 100), every point resolved as the ends of a bracket are: what the scan saw can be
// a narrow interval of instability next to mu (its resolved zeta within a few error estimates
// of the threshold, where the scan resolution can miss it).  false: failed (out_ is final).
bool CriticalSearch::search_neighbourhood(const GridPoint& prev, const Trial& hi, long i,
                                          double zeta_tolerance, Crossings& found) {
  const double mu = hi.mu;
  const double end_mu = i < steps_ ? std::min(mu + (mu - prev.at.mu), opt_.mu_max) : mu;
  const double width = end_mu - prev.at.mu;
  Trial start = evaluate(prev.below, prev.at.mu, zeta_tolerance);
  if (failed(start)) return false;
  for (int parts : {10, 100}) {
    const int count = static_cast<int>(std::lround(parts * width / (mu - prev.at.mu)));
    Trial at = start;  // the last sub-point, continued along the interval
    ExponentTracker before_at = prev.below;
    for (int j = 1; j <= count && found.brackets.size() < 8; ++j) {
      const double m = j == count ? end_mu : prev.at.mu + width * static_cast<double>(j) / count;
      Trial next = evaluate(at.tracker, m, zeta_tolerance);
      if (failed(next)) return false;
      if ((next.f > 0.0) != (at.f > 0.0)) {
        const double slope = (next.f - at.f) / (next.mu - at.mu);
        found.brackets.push_back({at, next, at.tracker, slope});
      }
      before_at = at.tracker;
      at = std::move(next);
    }
    if (!found.brackets.empty()) {
      if (end_mu > mu) found.searched_to = GridPoint{std::move(at), false, std::move(before_at)};
      return true;
    }
  }
  note(mu, Status::Warning,
       "a stability change seen at the scan resolution vanished when resolved (zeta = " +
           fmt(hi.f + opt_.zeta_threshold) +
           " at the scan resolution), and no change was found at steps of scan_step / 100 "
           "from mu = " +
           fmt(prev.at.mu) + " to " + fmt(end_mu));
  return true;
}

// The grid interval [prev, b] as the bracket of a change seen resolved at b.  The lower end is
// resolved too when its scan value is within twice its error estimate of the threshold: its
// sign may be wrong, and then the crossing lies below it and Brent would stop at the grid
// point (the exact-mode typical blade at gamma = 8.5: zeta = -2.8e-7 at the scan point 1.16
// with an error of 1.5e-6; mu_c was reported as 1.16 with a warning instead of 1.15993).  If
// the resolved sign is that of the upper end, the bracket is the grid interval below,
// continued from the tracker at its lower end.  false: failed (out_ is final).
bool CriticalSearch::bracket_grid_interval(const GridPoint& prev, const Trial& b, long i,
                                           double slope0, double zeta_tolerance, Crossings& found) {
  Trial lower = prev.at;
  std::optional<Trial> stepped_back;  // the upper end of the grid interval below
  const ExponentTracker* from = &prev.at.tracker;
  if (prev.at.mu > 0.0 && prev.at.error && std::abs(prev.at.f) <= 2.0 * *prev.at.error) {
    Trial a = evaluate(prev.below, prev.at.mu, zeta_tolerance);
    if (failed(a)) return false;
    if ((a.f > 0.0) != (b.f > 0.0)) {
      lower = std::move(a);
    } else {
      const double mu_lo = static_cast<double>(i - 2) * opt_.scan_step;
      Trial c = mu_lo > 0.0 ? evaluate(prev.below, mu_lo, zeta_tolerance) : *hover_trial_;
      if (failed(c)) return false;
      if ((c.f > 0.0) != (b.f > 0.0)) {
        lower = std::move(c);
        stepped_back = std::move(a);
        from = &prev.below;
      }
    }
  }
  const double slope =
      stepped_back ? (stepped_back->f - lower.f) / (stepped_back->mu - lower.mu) : slope0;
  Trial upper = stepped_back ? std::move(*stepped_back) : b;
  const ExponentTracker from_copy = *from;
  found.brackets.push_back({std::move(lower), std::move(upper), from_copy, slope});
  return true;
}

// Each bracket refined by Brent and its error verified: an onset opens an instability
// interval (the first only, unless all_intervals), a re-stabilization ends the last one.
CriticalSearch::Next CriticalSearch::refine_by_brent(const std::vector<Bracket>& brackets,
                                                     double zeta_tolerance) {
  for (const Bracket& k : brackets) {
    const bool onset = k.lower.f <= 0.0;
    auto [bb, cc] = brent(k.from, k.lower, k.upper, zeta_tolerance);
    if (failure_) {
      fail(*failure_);
      return Next::Failed;
    }
    const Trial& unstable = bb.f > 0.0 ? bb : cc;
    const std::optional<double> err = crossing_error(k.from, bb, cc, k.slope, zeta_tolerance);
    if (onset) {
      record_onset(unstable, bb.mu, err);
      if (!opt_.all_intervals) return Next::Stop;
    } else if (!out_.intervals.empty()) {
      out_.intervals.back().end = bb.mu;
      out_.intervals.back().end_error = err;
    }
  }
  return Next::Continue;
}

// An instability interval opening at mu, in the least stable mode of `unstable`.
void CriticalSearch::record_onset(const Trial& unstable, double mu, std::optional<double> error) {
  const LabelledExponent& x = unstable.tracker.exponents()[unstable.tracker.most_unstable()];
  InstabilityInterval iv;
  iv.onset = mu;
  iv.onset_error = error;
  iv.mode = x.label;
  // A conjugate pair crosses together; report the member with omega >= 0.
  iv.omega = std::abs(x.omega);
  iv.kind = classify_crossing(x.omega, opt_.periodic_omega_tolerance);
  out_.intervals.push_back(iv);
  if (out_.intervals.size() == 1) out_.exponents = unstable.tracker.exponents();
}

// The result of a scan that ran to its end (`last` its last grid point) or stopped at mu_c.
void CriticalSearch::conclude(const Trial& last, const Trial& before_last) {
  if (out_.intervals.empty()) {
    out_.exponents = last.tracker.exponents();
    out_.status = warnings_.empty() ? Status::Ok : Status::Warning;
    out_.message = "stable up to mu_max = " + fmt(opt_.mu_max);
    note_rising_at_mu_max(last, before_last);
  } else {
    set_mu_c();
    out_.status = warnings_.empty() && unresolved_.empty() ? Status::Ok : Status::Warning;
    if (opt_.all_intervals) {
      out_.Worsen(out_.status, std::to_string(out_.intervals.size()) +
                                   " instability interval(s) up to mu_max = " + fmt(opt_.mu_max));
    }
  }
  out_.Worsen(out_.status, unresolved_);
  out_.Worsen(out_.status, warnings_);
}

// "Stable up to mu_max" says nothing about what lies beyond: when the least stable zeta still
// rises over the scan's last grid interval (by more than the two error estimates), the result
// says so, so that a convergence study ending at mu_max is not read as "stable".
void CriticalSearch::note_rising_at_mu_max(const Trial& last, const Trial& before_last) {
  if (before_last.mu >= last.mu) return;
  // A grid point evaluated for its sign only has too loose an error for a slope: it is
  // evaluated again at the scan's tolerance, as the last point is (one evaluation).
  Trial before = before_last;
  if (before.mu > 0.0 && before.error.value_or(0.0) > opt_.scan_zeta_tolerance) {
    before = evaluate(before_last.tracker, before_last.mu, opt_.scan_zeta_tolerance);
    if (before.report.status == Status::Failed) return;
  }
  const double margin = last.error.value_or(0.0) + before.error.value_or(0.0);
  if (!(last.f - before.f > margin)) return;
  const double rate = (last.f - before.f) / (last.mu - before.mu);
  out_.Note("the least stable zeta is still rising at mu_max: " +
            fmt(before.f + opt_.zeta_threshold) + " at mu = " + fmt(before.mu) + ", " +
            fmt(last.f + opt_.zeta_threshold) + " at mu = " + fmt(last.mu) + " (" + fmt(rate) +
            " per unit mu); an instability beyond mu_max is not excluded (raise `mu_max`)");
}

// f at mu, the exponents continued from `from`.
Trial CriticalSearch::evaluate(const ExponentTracker& from, double mu, double zeta_tolerance) {
  const FloquetSample sample = floquet_(mu, zeta_tolerance);
  ++out_.evaluations;
  Trial t{mu, 0.0, from, {}, largest_zeta_error(sample), sample.floquet.liouville_residual};
  if (sample.status == Status::Failed) {
    t.report.status = Status::Failed;
    t.report.message = sample.message;
    return t;
  }
  t.report = t.tracker.advance(sample.floquet, mu);
  if (t.report.status == Status::Ok && sample.status != Status::Ok) {
    t.report.status = sample.status;
    t.report.message = sample.message;
  }
  t.f = t.tracker.max_zeta() - opt_.zeta_threshold;
  t.sign_certain = sample.status == Status::Ok && sign_certain(sample, opt_.zeta_threshold);
  return t;
}

// A scan point only has to tell the sign of f; far from the threshold that needs much less
// than scan_zeta_tolerance.  sign_only() evaluates at a tolerance scaled to the margin of the
// previous point and keeps the result when its own error estimates leave the sign beyond
// doubt (sign_certain(), sample resolved); otherwise, and for every
// point whose value is used (both ends of a bracket, the last point reported), the point is
// evaluated at scan_zeta_tolerance exactly as without the shortcut, so mu_c, its error and
// the reported exponents do not change.  `loose` marks a trial evaluated this way.
Trial CriticalSearch::sign_only(const ExponentTracker& from, double mu, double margin,
                                bool& loose) {
  const double tol = std::max(opt_.scan_zeta_tolerance,
                              std::min(kIdentificationTolerance, kSignFraction * margin));
  loose = false;
  // Only a FloquetFunction that estimates its errors can be asked for the sign alone.
  if (tol > opt_.scan_zeta_tolerance && estimates_) {
    Trial t = evaluate(from, mu, tol);
    if (t.report.status == Status::Ok && t.sign_certain) {
      loose = true;
      return t;
    }
  }
  return evaluate(from, mu, opt_.scan_zeta_tolerance);
}

// Brent's method (brent.h) on f(mu) = max zeta - zeta_threshold over [a.mu, b.mu] (signs of
// a.f and b.f differ), every trial continued from `from`.  Returns the trials (b, c): b the
// estimate, [b, c] the final bracket.  A trial that fails stops it (failure_).
std::pair<Trial, Trial> CriticalSearch::brent(const ExponentTracker& from, const Trial& a,
                                              const Trial& b, double zeta_tolerance) {
  std::vector<Trial> trials{a, b};  // by BrentPoint::index
  auto f = [&](double mu) {
    trials.push_back(evaluate(from, mu, zeta_tolerance));
    const Trial& t = trials.back();
    if (t.report.status == Status::Failed) {
      failure_ = t;
      return std::numeric_limits<double>::quiet_NaN();  // stops the iteration
    }
    return t.f;
  };
  BrentOptions bo;
  bo.tolerance = opt_.tolerance;
  bo.max_evaluations = 200;
  const BrentResult r = brent_zero(f, a.mu, a.f, b.mu, b.f, bo);
  const BrentPoint& other = r.root.index == r.lo.index ? r.hi : r.lo;
  return std::make_pair(trials[static_cast<std::size_t>(r.root.index)],
                        trials[static_cast<std::size_t>(other.index)]);
}

// Error of a crossing.  With a zeta error e the true crossing lies where |f| <= e, not only
// within e / |slope| of mu_c: zeta(mu) can be curved (shallow crossings) or kinked (at mu = 1
// the reversed region changes form).  So the linear estimate d = e / |slope| is verified by
// evaluating f at mu_c -+ 2d: the bound holds when f < -2e below and f > +2e above (for an
// onset; mirrored for a re-stabilization); otherwise d doubles, up to 10 scan steps.
std::optional<double> CriticalSearch::crossing_error(const ExponentTracker& from, const Trial& b,
                                                     const Trial& c, double slope0,
                                                     double zeta_tolerance) {
  if (!b.error && !c.error) return std::nullopt;
  const double slope = c.mu != b.mu && c.f != b.f ? (c.f - b.f) / (c.mu - b.mu) : slope0;
  double e = std::max(b.error.value_or(0.0), c.error.value_or(0.0));
  const double sign = slope0 > 0.0 ? 1.0 : -1.0;  // +1: onset (f rises through 0)
  double d = std::max(0.5 * std::abs(c.mu - b.mu), e / std::abs(slope));
  bool verified = false;
  while (!verified) {
    const double lo = std::max(0.0, b.mu - 2.0 * d), hi = b.mu + 2.0 * d;
    Trial tl = evaluate(from, lo, zeta_tolerance);
    Trial th = evaluate(from, hi, zeta_tolerance);
    if (tl.report.status == Status::Failed || th.report.status == Status::Failed) break;
    e = std::max({e, tl.error.value_or(0.0), th.error.value_or(0.0)});
    // A Richardson estimate is not a bound: ask for a margin of twice the estimate.
    verified = (lo == 0.0 || sign * tl.f < -2.0 * e) && sign * th.f > 2.0 * e;
    if (verified || 2.0 * d > 10.0 * opt_.scan_step) break;
    d *= 2.0;
  }
  const double err = 2.0 * d;
  if ((err > 10.0 * opt_.tolerance || !verified) && unresolved_.empty()) {
    unresolved_ = "the crossing at mu = " + fmt(b.mu) +
                  " is not resolved to `tolerance`: estimated error " + fmt(err) +
                  (verified ? "" : " or more") + " (zeta error " + fmt(e) +
                  " per rev at a zeta slope of " + fmt(slope) + " per unit mu); increase `steps`";
  }
  return err;
}

// Keeps the first problem of a point for the result's message.
void CriticalSearch::note(double mu, Status status, const std::string& m) {
  if (status != Status::Ok && warnings_.empty()) warnings_ = "at mu = " + fmt(mu) + ": " + m;
}

// mu_c, its mode, omega and kind from the first interval's onset, and the message's start.
void CriticalSearch::set_mu_c() {
  const InstabilityInterval& first = out_.intervals.front();
  out_.mu_c = first.onset;
  out_.mu_c_error = first.onset_error;
  out_.mode = first.mode;
  out_.omega = first.omega;
  out_.kind = first.kind;
  out_.message = "unstable above mu_c = " + fmt(first.onset) + " (" + out_.mode + ", " +
                 kind_name(out_.kind) + ", omega = " + fmt(out_.omega) + ")";
}

// Whether t failed; then the search ends with that failure (fail()).
bool CriticalSearch::failed(const Trial& t) {
  if (t.report.status != Status::Failed) return false;
  fail(t);
  return true;
}

void CriticalSearch::fail(const Trial& t) {
  if (!out_.intervals.empty()) {
    // all_intervals, past mu_c: the onsets found stand (mu_c is known); only the scan for
    // further intervals ends here, and the last interval's end is then unknown.
    set_mu_c();
    out_.status = Status::Warning;
    out_.message += "; the scan for further instability intervals stopped at mu = " + fmt(t.mu) +
                    " (the intervals are known only below it): " + t.report.message;
    return;
  }
  out_.status = Status::Failed;
  out_.message = "at mu = " + fmt(t.mu) + ": " + t.report.message;
  out_.exponents = t.tracker.exponents();
}

CriticalResult critical_search(const HoverModes& hover, const FloquetFunction& floquet,
                               const CriticalOptions& opt) {
  opt.Check();
  if (!floquet) throw InvalidInput("floquet", "empty", "a FloquetFunction is required");
  return CriticalSearch(hover, floquet, opt).run();
}

void check_track(const std::vector<double>& mus, double max_step, double zeta_tolerance) {
  require(std::isfinite(max_step) && max_step > 0.0, "step", max_step, "must be > 0");
  require(!mus.empty(), "mu", 0.0, "need at least one advance ratio");
  double last = 0.0;
  for (double mu : mus) {
    require(std::isfinite(mu) && mu >= last && mu <= kMaxAdvanceRatio, "mu", mu,
            "advance ratios must be nondecreasing in [0, 1000]");
    last = mu;
  }
  require(last / max_step + static_cast<double>(mus.size()) <=
              static_cast<double>(kMaxContinuationSteps),
          "step", max_step, "too small: at most 1000000 continuation steps");
  require(std::isfinite(zeta_tolerance) && zeta_tolerance > 0.0, "zeta_tolerance", zeta_tolerance,
          "must be > 0");
}

// One evaluation of a continuation: a step that only carries the identification (reported
// false) or a reported point.
struct Evaluation {
  double mu = 0.0;
  bool reported = false;
};

// The evaluations that reach each of mus from the one before (from hover for the first) in
// equal steps no longer than max_step, in order.
std::vector<Evaluation> evaluations(const std::vector<double>& mus, double max_step) {
  std::vector<Evaluation> plan;
  double at = 0.0;
  for (double mu : mus) {
    const long pre = static_cast<long>(std::ceil((mu - at) / max_step - 1e-9));
    for (long i = 1; i < pre; ++i)
      plan.push_back({at + (mu - at) * static_cast<double>(i) / static_cast<double>(pre), false});
    plan.push_back({mu, true});
    at = mu;
  }
  return plan;
}

// The identification along a continuation: takes the samples in order and builds the result.
class TrackPass {
 public:
  TrackPass(const HoverModes& hover, double zeta_tolerance)
      : tracker_(hover), zeta_tolerance_(zeta_tolerance) {}

  // The tolerance each evaluation is asked for.  Steps that are not reported only carry the
  // identification: kIdentificationTolerance is plenty.
  double tolerance(const Evaluation& e) const {
    return e.reported ? zeta_tolerance_ : std::max(zeta_tolerance_, kIdentificationTolerance);
  }

  // false: the continuation stops here (out() is final).
  bool take(const Evaluation& e, const FloquetSample& sample) {
    TrackReport r;
    if (sample.status == Status::Failed) {
      r.status = Status::Failed;
      r.message = sample.message;
    } else {
      r = tracker_.advance(sample.floquet, e.mu);
    }
    if (!e.reported) {
      if (r.status == Status::Failed) {
        out_.status = Status::Failed;
        out_.message = "continuation failed at mu = " + fmt(e.mu) + ": " + r.message;
        return false;
      }
      // Identification along the way matters; the resolution of points not reported does not.
      if (r.status == Status::Warning) out_.Include(r, where(e.mu));
      return true;
    }
    PointResult p;
    p.mu = e.mu;
    if (std::isfinite(sample.floquet.liouville_residual))
      p.liouville_residual = sample.floquet.liouville_residual;
    p.error = sample.error;
    p.steps = sample.steps;
    p.status = r.status;
    p.message = r.message;
    if (r.status == Status::Failed) {
      check_finite(p);
      out_.points.push_back(std::move(p));
      out_.status = Status::Failed;
      out_.message = "at mu = " + fmt(e.mu) + ": " + r.message;
      return false;
    }
    // A Warning's message, or a note that comes with an Ok sample (what it could not check).
    p.Worsen(sample.status, sample.message);
    p.exponents = tracker_.exponents();
    attach_zeta_errors(p.exponents, sample);
    p.stable = tracker_.max_zeta() <= 0.0;
    // The sign of the largest zeta is known only beyond its own error: the estimate, or the
    // rounding of Phi (a multiplier rho of Phi moves by ~ n eps ||Phi|| in the eigen-solve, its
    // zeta by that over 2 pi |rho|), whichever is larger.
    {
      const LabelledExponent& x = tracker_.exponents()[tracker_.most_unstable()];
      double uncertain = largest_zeta_error(sample).value_or(0.0);
      const Eigen::MatrixXd& phi = sample.floquet.phi;
      const double rho = std::abs(x.multiplier);
      if (phi.size() > 0 && phi.allFinite() && rho > 0.0) {
        const double n = static_cast<double>(phi.rows());
        uncertain = std::max(uncertain, 8.0 * n * n * std::numeric_limits<double>::epsilon() *
                                            phi.cwiseAbs().maxCoeff() / (kTwoPi * rho));
      }
      if (std::isfinite(x.zeta) && std::abs(x.zeta) <= uncertain) {
        p.stable.reset();
        p.Worsen(Status::Warning, "stability unknown: the least stable exponent (" + x.label +
                                      ", zeta = " + fmt(x.zeta) +
                                      " per rev) is within its error (" + fmt(uncertain) +
                                      " per rev) of zero");
      }
    }
    check_finite(p);
    // (An Ok point changes neither the status nor the message: its place is not formatted.)
    if (p.status != Status::Ok) out_.Include(p, where(e.mu));
    out_.points.push_back(std::move(p));
    return true;
  }

  SweepResult& out() { return out_; }

 private:
  static std::string where(double mu) { return "at mu = " + fmt(mu) + ": "; }

  ExponentTracker tracker_;
  double zeta_tolerance_;
  SweepResult out_;
};

// Whether ExponentTracker::advance may need the eigenvectors of r, or of the point before it,
// to identify r's exponents: the multipliers alone decide when every tracked exponent's
// nearest candidate is within kMultiplierStep of its prediction and nearer than every other
// by more than 1, which two candidates further apart than 1 + 2 kMultiplierStep (in
// exponent_distance, a metric) guarantee for a distinct nearest one.  A miss (a jump, two tracked
// predictions close to each other) costs only time: advance then computes the vectors itself.
bool has_close_candidates(const FloquetResult& r) {
  constexpr double kApart = 1.0 + 2.0 * ExponentTracker::kMultiplierStep;
  const std::size_t n = r.exponents.size();
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t k = j + 1; k < n; ++k) {
      const double d =
          exponent_distance(finite_zeta(r.exponents[j].zeta) - finite_zeta(r.exponents[k].zeta),
                            r.exponents[j].omega - r.exponents[k].omega);
      if (!(d > kApart)) return true;
    }
  return false;
}

// Computes the eigen-decomposition that advance may need ahead, on the worker's thread.
void add_eigensystem(FloquetSample& s) {
  if (s.status == Status::Failed || s.floquet.eigensystem || s.floquet.phi.size() == 0) return;
  s.floquet.eigensystem =
      std::make_shared<const FloquetEigenSystem>(floquet_eigensystem(s.floquet.phi));
}

SweepResult hover_failed(const HoverModes& hover) {
  SweepResult out;
  out.status = Status::Failed;
  out.message = "hover modes unavailable: " + hover.message;
  return out;
}

// The first evaluation of every stretch of `plan` (`length` reported points and the steps
// that lead to each), then plan.size(): stretch s is the evaluations first[s] .. first[s + 1]
// - 1.
std::vector<std::size_t> stretch_starts(const std::vector<Evaluation>& plan, std::size_t length) {
  std::vector<std::size_t> first{0};
  for (std::size_t i = 0, reported = 0; i < plan.size(); ++i)
    if (plan[i].reported && ++reported % length == 0 && i + 1 < plan.size()) first.push_back(i + 1);
  first.push_back(plan.size());
  return first;
}

// The end of the window of stretches from w0 whose samples are held at once.
std::size_t window_end(const std::vector<std::size_t>& first, std::size_t w0) {
  const std::size_t stretches = first.size() - 1;
  std::size_t w1 = w0 + 1;
  while (w1 < stretches && w1 - w0 < kStretchesInMemory &&
         first[w1 + 1] - first[w0] <= kSamplesInMemory)
    ++w1;
  return w1;
}

// The stretches w0 .. w1 - 1 of a continuation's plan, evaluated in parallel (one
// FloquetFunction each); the calling thread identifies the finished stretches in order between
// its own (the other threads go on evaluating), so that the identification overlaps the
// evaluations.
class ParallelWindow {
 public:
  ParallelWindow(const std::vector<Evaluation>& plan, const std::vector<std::size_t>& first,
                 std::size_t w0, std::size_t w1, TrackPass& pass)
      : plan_(plan),
        first_(first),
        w0_(w0),
        w1_(w1),
        begin_(first[w0]),
        pass_(pass),
        samples_(first[w1] - first[w0]),
        thrown_(w1 - w0),
        thrown_at_(w1 - w0, kNone),
        done_(new std::atomic<bool>[w1 - w0]),
        next_k_(w0),
        next_i_(first[w0]) {
    for (std::size_t k = 0; k < w1 - w0; ++k) done_[k] = false;
  }

  // false: the pass stopped (its result is final).  Rethrows what an evaluation or the
  // identification threw.
  bool run(const std::vector<FloquetFunction>& functions, int threads) {
    const std::thread::id caller = std::this_thread::get_id();
    parallel_for(w1_ - w0_, threads, nullptr, {}, [&](std::size_t k) {
      evaluate_stretch(functions[k], k);
      done_[k].store(true, std::memory_order_release);
      if (std::this_thread::get_id() == caller) identify_finished();
    });
    identify_finished();
    if (rethrow_) std::rethrow_exception(rethrow_);
    return !ended_;
  }

 private:
  static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

  // Stretch w0 + k in order, until it ends, fails or passes where the pass is known to stop.
  void evaluate_stretch(const FloquetFunction& f, std::size_t k) {
    const std::size_t a = first_[w0_ + k], b = first_[w0_ + k + 1];
    bool close_before = false;
    for (std::size_t i = a; i < b && i <= stop_.load(); ++i) {
      FloquetSample& sample = samples_[i - begin_];
      try {
        sample = f(plan_[i].mu, pass_.tolerance(plan_[i]));
      } catch (...) {
        thrown_[k] = std::current_exception();
        thrown_at_[k] = i;
        lower_stop(i);
        break;
      }
      if (sample.status == Status::Failed) {
        lower_stop(i);
        break;
      }
      // The identification of sample i may need its vectors and those of sample i - 1, and
      // that of sample i + 1 those of sample i.
      const bool close = !sample.floquet.has_eigenvectors() && has_close_candidates(sample.floquet);
      try {
        if (close || close_before) add_eigensystem(sample);
        if (close && i > a) add_eigensystem(samples_[i - 1 - begin_]);
      } catch (...) {  // out of memory: the identification computes them itself if needed
      }
      close_before = close;
    }
  }

  // The finished stretches not yet identified, in order, up to the first unfinished one.
  void identify_finished() {
    while (!ended_ && next_k_ < w1_ && done_[next_k_ - w0_].load(std::memory_order_acquire)) {
      for (; next_i_ < first_[next_k_ + 1]; ++next_i_) {
        bool more = false;
        if (thrown_at_[next_k_ - w0_] == next_i_) {
          rethrow_ = thrown_[next_k_ - w0_];
        } else {
          try {
            more = pass_.take(plan_[next_i_], samples_[next_i_ - begin_]);
          } catch (...) {
            rethrow_ = std::current_exception();
          }
        }
        if (!more) {
          ended_ = true;
          lower_stop(next_i_);
          return;
        }
      }
      ++next_k_;
    }
  }

  void lower_stop(std::size_t i) {
    std::size_t s = stop_.load();
    while (i < s && !stop_.compare_exchange_weak(s, i)) {
    }
  }

  const std::vector<Evaluation>& plan_;
  const std::vector<std::size_t>& first_;
  const std::size_t w0_, w1_, begin_;
  TrackPass& pass_;
  std::vector<FloquetSample> samples_;
  std::vector<std::exception_ptr> thrown_;
  std::vector<std::size_t> thrown_at_;
  // The first evaluation at which the pass is known to stop (a Failed sample or a throw):
  // later ones are not needed.
  std::atomic<std::size_t> stop_{kNone};
  std::unique_ptr<std::atomic<bool>[]> done_;
  std::size_t next_k_, next_i_;  // the next evaluation to identify, and its stretch
  bool ended_ = false;           // the pass stopped (Failed, a throw to pass on, or its own stop)
  std::exception_ptr rethrow_;
};

}  // namespace

SweepResult track_exponents(const HoverModes& hover, const FloquetFunction& floquet,
                            const std::vector<double>& mus, double max_step,
                            double zeta_tolerance) {
  check_track(mus, max_step, zeta_tolerance);
  if (!floquet) throw InvalidInput("floquet", "empty", "a FloquetFunction is required");
  if (hover.status == Status::Failed) return hover_failed(hover);
  TrackPass pass(hover, zeta_tolerance);
  for (const Evaluation& e : evaluations(mus, max_step))
    if (!pass.take(e, floquet(e.mu, pass.tolerance(e)))) break;
  return std::move(pass.out());
}

std::size_t continuation_stretch(std::size_t points) {
  const std::size_t even = (points + kContinuationStretches - 1) / kContinuationStretches;
  return std::clamp(even, kMinStretch, kMaxStretch);
}

SweepResult track_exponents(const HoverModes& hover, const FloquetFunctionFactory& make,
                            const std::vector<double>& mus, double max_step, double zeta_tolerance,
                            int threads) {
  check_track(mus, max_step, zeta_tolerance);
  if (auto p = threads_problem(threads)) throw *p;
  if (!make) throw InvalidInput("floquet", "empty", "a FloquetFunctionFactory is required");
  if (hover.status == Status::Failed) return hover_failed(hover);
  const std::vector<Evaluation> plan = evaluations(mus, max_step);
  // Stretch s: the reported points s L .. (s + 1) L - 1 and the steps that lead to each.
  const std::vector<std::size_t> first = stretch_starts(plan, continuation_stretch(mus.size()));
  const std::size_t stretches = first.size() - 1;
  TrackPass pass(hover, zeta_tolerance);
  auto new_function = [&] {
    FloquetFunction f = make();
    if (!f) throw InvalidInput("floquet", "empty", "the factory made an empty FloquetFunction");
    return f;
  };
  for (std::size_t w0 = 0; w0 < stretches;) {
    const std::size_t w1 = window_end(first, w0);
    const std::size_t begin = first[w0], end = first[w1];
    if (end - begin > kSamplesInMemory) {
      // One stretch too long to hold (many steps between reported points): evaluated and
      // identified as it goes, the same evaluations in the same order.
      const FloquetFunction f = new_function();
      for (std::size_t i = begin; i < end; ++i)
        if (!pass.take(plan[i], f(plan[i].mu, pass.tolerance(plan[i]))))
          return std::move(pass.out());
      w0 = w1;
      continue;
    }
    std::vector<FloquetFunction> functions;
    for (std::size_t k = w0; k < w1; ++k) functions.push_back(new_function());
    if (!ParallelWindow(plan, first, w0, w1, pass).run(functions, threads))
      return std::move(pass.out());
    w0 = w1;
  }
  return std::move(pass.out());
}

std::vector<double> sweep_grid(double mu0, double mu1, double step) {
  require(std::isfinite(mu0) && mu0 >= 0.0 && mu0 <= kMaxAdvanceRatio, "mu0", mu0,
          "must be >= 0 and <= 1000");
  require(std::isfinite(mu1) && mu1 >= mu0 && mu1 <= kMaxAdvanceRatio, "mu1", mu1,
          "must be >= mu0 and <= 1000");
  require(std::isfinite(step) && step > 0.0, "step", step, "must be > 0");
  require(mu1 / step <= static_cast<double>(kMaxContinuationSteps), "step", step,
          "too small: at most 1000000 continuation steps");
  std::vector<double> mus;
  const long m = static_cast<long>(std::floor((mu1 - mu0) / step + 1e-9));
  for (long i = 0; i <= m; ++i) mus.push_back(mu0 + static_cast<double>(i) * step);
  if (mus.back() < mu1 - 1e-12 * std::max(1.0, mu1))
    mus.push_back(mu1);
  else
    mus.back() = std::min(mus.back(), mu1);
  return mus;
}

SweepResult sweep_exponents(const HoverModes& hover, const FloquetFunction& floquet, double mu0,
                            double mu1, double step, double zeta_tolerance) {
  return track_exponents(hover, floquet, sweep_grid(mu0, mu1, step), step, zeta_tolerance);
}

// ---- the damping criterion --------------------------------------------------------------------

const LabelledExponent* dominant_exponent(const PointResult& p, const std::string& label) {
  const LabelledExponent* best = nullptr;
  for (const LabelledExponent& e : p.exponents) {
    if (e.label != label) continue;
    if (best == nullptr || e.zeta > best->zeta ||
        (e.zeta == best->zeta && e.omega >= 0.0 && best->omega < 0.0)) {
      best = &e;
    }
  }
  return best;
}

std::vector<std::string> distinct_labels(const std::vector<std::string>& labels) {
  std::vector<std::string> out;
  for (const std::string& l : labels) {
    if (std::find(out.begin(), out.end(), l) == out.end()) out.push_back(l);
  }
  return out;
}

void check_damping_criterion(double criterion) {
  ThrowIfInvalid(
      Requirements().InRange("damping_criterion", criterion, kDampingCriterionRange).Result());
}

namespace {

// One mode's damping ratio at a sweep point, with what decides whether it resolves a crossing.
struct RatioAt {
  double mu = 0.0;
  double ratio = 0.0;
  bool resolved = false;  // not failed, with an error estimate, farther than it from C
};

std::optional<RatioAt> ratio_at(const PointResult& p, const std::string& label, double criterion) {
  const LabelledExponent* e = dominant_exponent(p, label);
  if (e == nullptr) return std::nullopt;
  const std::optional<double> r = damping_ratio(e->zeta, e->omega);
  if (!r) return std::nullopt;
  RatioAt a{p.mu, *r, false};
  // The mode's own error estimate where the point has one (a heavily damped flap mode's wider
  // estimate does not blur a lightly damped lag mode's crossing), else the point's largest.
  const std::optional<double> error = e->zeta_error ? e->zeta_error : p.error;
  if (p.status != Status::Failed && error && std::isfinite(*error)) {
    const double modulus = std::hypot(e->zeta, e->omega);
    // zeta = -inf (a zero multiplier): ratio 1, as far from any C < 1 as a ratio can be.
    const double spread = std::isfinite(modulus) ? *error / modulus : 0.0;
    a.resolved = std::abs(*r - criterion) > spread;
  }
  return a;
}

DampingCrossing crossing_of(const SweepResult& s, const std::string& label, double criterion) {
  DampingCrossing c;
  c.mode = label;
  std::optional<RatioAt> above;  // the last point with a ratio, at or above C
  bool gap = false;              // a point without a ratio since then (or before the first)
  for (const PointResult& p : s.points) {
    const std::optional<RatioAt> at = ratio_at(p, label, criterion);
    if (!at) {
      gap = true;
      continue;
    }
    if (at->ratio >= criterion) {
      above = at;
      gap = false;
      continue;
    }
    c.mu_below = at->mu;
    if (!above) {
      // Below at the first point with a ratio: at the sweep's start, or after points without one.
      c.status = gap ? CrossingStatus::Unresolved : CrossingStatus::BelowAtStart;
      if (!gap) c.mu = at->mu;
      return c;
    }
    c.mu_above = above->mu;
    // r_above >= C > r_below: the fraction lies in [0, 1).
    const double t = (criterion - above->ratio) / (at->ratio - above->ratio);
    c.mu = above->mu + t * (at->mu - above->mu);
    c.status = (gap || !above->resolved || !at->resolved) ? CrossingStatus::Unresolved
                                                          : CrossingStatus::Crossed;
    return c;
  }
  // A sweep that stopped at a failed point does not know the rest of the range.
  const bool stopped = !s.points.empty() && s.points.back().status == Status::Failed;
  c.status = stopped ? CrossingStatus::Unresolved : CrossingStatus::NotCrossed;
  return c;
}

}  // namespace

std::vector<DampingCrossing> damping_crossings(const SweepResult& s,
                                               const std::vector<std::string>& labels,
                                               double criterion) {
  check_damping_criterion(criterion);
  std::vector<DampingCrossing> out;
  for (const std::string& l : labels) out.push_back(crossing_of(s, l, criterion));
  return out;
}

void apply_damping_criterion(SweepResult& s, const std::vector<std::string>& labels,
                             double criterion) {
  s.damping_crossings = damping_crossings(s, labels, criterion);
  s.damping_criterion = criterion;
}

}  // namespace flaplag
