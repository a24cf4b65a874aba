// flaplag — the Floquet evaluators (one per transition method) and the step control that
// resolves their exponents to a tolerance (docs/numerics.md).
#include "flaplag/numerics/floquet_evaluator.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/numerics/dense.h"
#include "zeta_floor.h"

namespace flaplag {
namespace {

// Fewest steps of the automatic rule: the paper's K = 50.  A request looser than the options'
// own tolerance on a method with raw levels (Magnus4) starts at 24: Magnus4 with its Richardson
// pass is sixth order, and 24 steps give zeta to 3e-8 per rev on the typical case at mu = 0.8
// and to 2.5e-6 on the 2x2 exact model at mu = 1.4 (bench/README.md, accuracy per time), far
// inside the 1e-3 of a scan point's sign check.
constexpr int kMinAutomaticSteps = 50;
constexpr int kMinLooseLevelSteps = 24;

using detail::kZetaFloor;  // zeta of a multiplier that underflowed (zeta_floor.h)

// ---------------------------------------------------------------------------------------------
// The methods.

class Rk4Evaluator final : public FloquetEvaluator {
 public:
  explicit Rk4Evaluator(const TransitionOptions& o) : FloquetEvaluator(o) {}
  int order() const override { return 4; }
  Eigen::MatrixXd transition(const PeriodicSystem& sys, int steps) const override {
    return transition_matrix_rk4(sys, steps);
  }
};

class HsuEvaluator final : public FloquetEvaluator {
 public:
  explicit HsuEvaluator(const TransitionOptions& o) : FloquetEvaluator(o) {}
  // interval means O(h^2); J = 1 Taylor truncation O(h)
  int order() const override { return std::min(options().terms, 2); }
  Eigen::MatrixXd transition(const PeriodicSystem& sys, int steps) const override {
    return transition_matrix_hsu(sys, steps, options().terms);
  }
  bool has_pair() const override { return true; }
  void transition_pair(const PeriodicSystem& sys, int steps, Eigen::MatrixXd* phi,
                       Eigen::MatrixXd* half) const override {
    transition_matrix_hsu_pair(sys, steps, options().terms, phi, half);
  }
};

class Magnus4Evaluator final : public FloquetEvaluator {
 public:
  explicit Magnus4Evaluator(const TransitionOptions& o) : FloquetEvaluator(o) {}
  // transition_matrix_magnus4 returns its own Richardson extrapolation
  int order() const override { return 6; }
  Eigen::MatrixXd transition(const PeriodicSystem& sys, int steps) const override {
    return transition_matrix_magnus4(sys, steps).phi;
  }
  int level_order(const PeriodicSystem& sys) const override { return sys.has_evaluator() ? 0 : 4; }
  Eigen::MatrixXd level(const PeriodicSystem& sys, int steps, int bisections) const override {
    return transition_matrix_magnus4_level(sys, steps, bisections);
  }
};

// ---------------------------------------------------------------------------------------------
// One transition matrix's Floquet analysis and its rounding floor.

// max |eigenvalue| of a (0 when the eigen-solve fails); fixed-size solvers for the 4- and
// 8-state models keep it off the heap (the automatic start solves up to ten per evaluation).
double spectral_radius(const Eigen::MatrixXd& a) {
  return flaplag::spectral_radius(a, EigenStorage::FixedWhenSmall);
}

// One transition matrix's Floquet analysis and its rounding floor: an eigenvalue of Phi below
// ~n eps ||Phi|| is lost in rounding, so a zeta below ln(that) / 2 pi is only a bound.
struct Evaluated {
  FloquetResult floquet;
  double zeta_floor = kZetaFloor;
  double log_norm = 0.0;  // ln ||Phi||_F
};

// The Floquet analysis of one transition matrix.
Evaluated evaluated(const Eigen::MatrixXd& phi, double trace) {
  Evaluated e;
  // Multipliers only: the mode identification (continuation.h) asks for the eigenvectors
  // (from e.floquet.phi) only where two candidates are close.
  floquet_exponents(phi, trace, FloquetVectors::OnDemand, &e.floquet);
  // n max|Phi_ij| bounds ||Phi||_2 without the overflow of a sum of squares.
  const double n = static_cast<double>(phi.rows());
  const double big = phi.allFinite() ? phi.cwiseAbs().maxCoeff() : 0.0;
  if (big > 0.0) {
    e.log_norm = std::log(n) + std::log(big);
    e.zeta_floor = std::max(
        kZetaFloor,
        (std::log(64.0 * n * std::numeric_limits<double>::epsilon()) + e.log_norm) / kTwoPi);
  }
  return e;
}

bool finite(const Evaluated& e) {
  for (const FloquetExponent& x : e.floquet.exponents)
    if (!std::isfinite(x.multiplier.real()) || !std::isfinite(x.multiplier.imag())) return false;
  return !e.floquet.exponents.empty();
}

// |zeta_k(fine) - zeta_k(coarse)| for each exponent of `fine`, the multipliers paired greedily
// by distance; zeta below each matrix's rounding floor counts as the floor (both are "zero" to
// the precision of Phi).
std::vector<double> zeta_differences(const Evaluated& fine_e, const Evaluated& coarse_e) {
  const FloquetResult& fine = fine_e.floquet;
  const FloquetResult& coarse = coarse_e.floquet;
  const double floor = std::max(fine_e.zeta_floor, coarse_e.zeta_floor);
  const std::size_t n = fine.exponents.size();
  std::vector<double> d(n, 0.0);
  std::vector<bool> used(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    const std::complex<double> a = fine.exponents[i].multiplier;
    double best = std::numeric_limits<double>::infinity();
    std::size_t bj = 0;
    for (std::size_t j = 0; j < n; ++j) {
      if (used[j]) continue;
      const double dist = std::abs(a - coarse.exponents[j].multiplier);
      if (dist < best) {
        best = dist;
        bj = j;
      }
    }
    used[bj] = true;
    d[i] = std::abs(std::max(fine.exponents[i].zeta, floor) -
                    std::max(coarse.exponents[bj].zeta, floor));
  }
  return d;
}

// ||Phi||_1 ||Phi^-1||_1 (infinity for a singular or non-finite Phi).
double condition_number(const Eigen::MatrixXd& phi) {
  if (phi.size() == 0 || !phi.allFinite()) return std::numeric_limits<double>::infinity();
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(phi);
  const Eigen::MatrixXd inverse = lu.inverse();
  if (!inverse.allFinite()) return std::numeric_limits<double>::infinity();
  return phi.cwiseAbs().colwise().sum().maxCoeff() * inverse.cwiseAbs().colwise().sum().maxCoeff();
}

// Every harmonic coefficient of sys finite (and A at the middle of each evaluator piece, where
// the exact reversed flow has its largest values).
bool system_finite(const PeriodicSystem& sys) {
  bool finite = true;
  for (const HarmonicSet& set : sys.sets)
    for (const Eigen::MatrixXd& a : set.A) finite = finite && a.allFinite();
  for (const SystemPiece& p : sys.pieces)
    if (p.set < 0) finite = finite && sys.A(0.5 * (p.begin + p.end)).allFinite();
  return finite;
}

// ---------------------------------------------------------------------------------------------
// The automatic start.

// (psi, harmonic_basis(h, psi) for h < kTabulatedHarmonics) at the azimuths of automatic_start
// that do not depend on the system: the eight fixed ones and 3 pi / 2 (the middle of a sector
// centred on the retreating blade).  A system with more harmonics computes them.
constexpr int kTabulatedHarmonics = 32;
using StartBasis = std::vector<std::pair<double, std::vector<double>>>;
const StartBasis& start_basis() {
  static const StartBasis table = [] {
    StartBasis t;
    auto tabulate = [&t](double psi) {
      psi = reduce_azimuth(psi);
      std::vector<double> v(static_cast<std::size_t>(kTabulatedHarmonics));
      for (int h = 0; h < kTabulatedHarmonics; ++h)
        v[static_cast<std::size_t>(h)] = harmonic_basis(h, psi);
      t.emplace_back(psi, std::move(v));
    };
    for (int k = 0; k < 8; ++k) tabulate((k + 0.5) * kTwoPi / 8.0);
    tabulate(1.5 * kPi);
    return t;
  }();
  return table;
}

// A(psi) of sys into *a: the varying region's callback, else the harmonic sum as
// PeriodicSystem::A forms it (the same operations), with the basis from start_basis() where it
// is tabulated.
void start_matrix(const PeriodicSystem& sys, double psi, Eigen::MatrixXd* a) {
  psi = reduce_azimuth(psi);
  const SystemPiece& piece = sys.pieces[static_cast<std::size_t>(sys.piece_at(psi))];
  if (piece.set < 0) {
    *a = sys.A(psi);
    return;
  }
  const HarmonicSet& set = sys.sets[static_cast<std::size_t>(piece.set)];
  const std::vector<double>* table = nullptr;
  for (const auto& [at, values] : start_basis())
    if (at == psi && values.size() >= set.A.size()) table = &values;
  a->setZero(sys.n, sys.n);
  for (std::size_t h = 0; h < set.A.size(); ++h)
    *a += (table ? (*table)[h] : harmonic_basis(static_cast<int>(h), psi)) * set.A[h];
}

// The automatic starting K: |lambda| h <= 1 for the largest eigenvalue of A(psi) at a few
// azimuths of each region (the spectrum sets the step a fixed-step method needs), even and at
// least min_steps.  `floor` (>= min_steps) is the count the caller starts at anyway (a steps
// hint): an azimuth whose induced norm min(||A||_1, ||A||_inf) >= rho(A) keeps |lambda| h <= 1
// at that count cannot raise K, and its eigen-solve is skipped (the same K at a fifth of the
// cost).  Without a varying region ||A(psi)||_1 <= sum_h ||A_h||_1 for every psi: when that
// bound keeps every azimuth below the floor, none is evaluated.
int automatic_start(const PeriodicSystem& sys, int min_steps, int floor) {
  if (!sys.has_evaluator()) {
    double bound = 0.0;
    for (const HarmonicSet& set : sys.sets) {
      double sum = 0.0;
      for (const Eigen::MatrixXd& h : set.A) sum += h.cwiseAbs().colwise().sum().maxCoeff();
      bound = std::max(bound, sum);
    }
    if (bound * kTwoPi <= floor - 1) return min_steps;  // as when every one is skipped
  }
  double rho = 0.0;
  Eigen::MatrixXd a;  // one buffer for every azimuth
  auto add = [&](double psi) {
    start_matrix(sys, psi, &a);
    const double bound =
        std::min(a.cwiseAbs().colwise().sum().maxCoeff(), a.cwiseAbs().rowwise().sum().maxCoeff());
    if (bound * kTwoPi <= floor - 1) return;
    rho = std::max(rho, spectral_radius(a));
  };
  for (int k = 0; k < 8; ++k) add((k + 0.5) * kTwoPi / 8.0);
  for (const SystemPiece& p : sys.pieces)  // the middle of each piece of another kind
    if (p.set != 0) add(0.5 * (p.begin + p.end));
  const double k = std::ceil(rho * kTwoPi / 1.0);
  if (!(k <= kMaxAutomaticSteps)) return kMaxAutomaticSteps;
  // an even count, so that K/2 is a whole number
  const int ki = std::max(min_steps, static_cast<int>(k));
  return ki + (ki % 2);
}

// ---------------------------------------------------------------------------------------------
// The step control: one resolved evaluation of one system (docs/numerics.md).

class StepControl {
 public:
  StepControl(const FloquetEvaluator& method, const PeriodicSystem& sys, double zeta_tolerance,
              StepsHint* hint)
      : method_(method),
        sys_(sys),
        tolerance_(zeta_tolerance),
        hint_(hint),
        automatic_(method.options().steps == TransitionOptions::kAutomatic),
        order_(method.order()) {}

  FloquetSample run(const std::string& system_note) {
    if (!system_finite(sys_)) {
      FloquetSample out;
      out.status = Status::Failed;
      out.message =
          "the periodic system overflows at this mu (the parameters are too extreme "
          "for double precision)";
      return out;
    }
    trace_ = sys_.trace_integral();
    choose_start();
    if (!automatic_)
      fixed_steps();
    else if (raw_order_ > 0)
      raw_levels();
    else
      ladder();
    return report(system_note);
  }

 private:
  // The first K: the user's, or the automatic start (raised to the hint's count).  A request
  // looser than the options' tolerance (a sign check of the mu_c scan, a continuation step
  // that is not reported) walks the method's raw levels when it has them; every result at the
  // options' tolerance or tighter is computed by the ladder, so it does not change.
  void choose_start() {
    if (!automatic_) {
      steps_ = method_.options().steps;
      return;
    }
    if (tolerance_ > method_.options().zeta_tolerance) raw_order_ = method_.level_order(sys_);
    const int min_steps = raw_order_ > 0 ? kMinLooseLevelSteps : kMinAutomaticSteps;
    const int hinted = raw_order_ == 0 && hint_ != nullptr ? hint_->find(tolerance_) : 0;
    steps_ = std::max(automatic_start(sys_, min_steps, std::max(min_steps, hinted)), hinted);
  }

  Evaluated at(int steps) const { return evaluated(method_.transition(sys_, steps), trace_); }

  // The allowed error of exponent k of fine_: zeta_tolerance * max(1, 100 |zeta_k|).
  double allowed(std::size_t k) const {
    const double z = std::abs(std::max(fine_.floquet.exponents[k].zeta, fine_.zeta_floor));
    return tolerance_ * std::max(1.0, 100.0 * (std::isfinite(z) ? z : 0.0));
  }
  bool resolved(const std::vector<double>& err) const {
    for (std::size_t k = 0; k < err.size(); ++k)
      if (!(err[k] <= allowed(k))) return false;
    return true;
  }
  // The largest error / allowed ratio.
  double excess(const std::vector<double>& err) const {
    double q = 0.0;
    for (std::size_t k = 0; k < err.size(); ++k) q = std::max(q, err[k] / allowed(k));
    return q;
  }

  // Fixed steps (the user's K): the estimate compares with 2K, which is nearer the asymptotic
  // regime than K/2 (at K = 25 Hsu's error is far from c h^2 on shallow crossings);
  // error(K) = (zeta_K - zeta_2K) 2^p / (2^p - 1).
  void fixed_steps() {
    fine_ = at(steps_);
    const double richardson = std::ldexp(1.0, order_) - 1.0;
    const bool finer = 2 * steps_ <= TransitionOptions::kMaxSteps;
    const std::optional<Evaluated> other =
        finer ? std::optional<Evaluated>(at(2 * steps_))
              : (steps_ >= 2 ? std::optional<Evaluated>(at(steps_ / 2)) : std::nullopt);
    if (finite(fine_) && other && finite(*other)) {
      err_ = zeta_differences(fine_, *other);
      for (double& e : err_) e *= finer ? (richardson + 1.0) / richardson : 1.0 / richardson;
    }
  }

  // Raw levels P_l (order r = raw_order_) on the grid of K/2 steps bisected l times, each
  // computed once; R_l = (2^r P_{l+1} - P_l) / (2^r - 1) is the method's extrapolated result at
  // K/2 * 2^l steps.  First R_0 with the raw estimate |zeta(R_0) - zeta(P_0)| / 2^r, then the
  // pairs (R_l, R_{l+1}) with the method's order, one new level per doubling.
  void raw_levels() {
    const double raw = std::ldexp(1.0, raw_order_);
    const double richardson = std::ldexp(1.0, order_) - 1.0;
    const int base = steps_ / 2;
    std::vector<Eigen::MatrixXd> P;
    P.push_back(method_.level(sys_, base, 0));
    P.push_back(method_.level(sys_, base, 1));
    auto extrapolated = [&](std::size_t l) {
      return evaluated((raw * P[l + 1] - P[l]) / (raw - 1.0), trace_);
    };
    Evaluated coarse = extrapolated(0);
    steps_ = base;
    bool done = false;
    const Evaluated p0 = evaluated(P[0], trace_);
    if (finite(coarse) && finite(p0)) {
      fine_ = std::move(coarse);
      err_ = zeta_differences(fine_, p0);
      for (double& e : err_) e /= raw;
      done = resolved(err_);
      if (!done) coarse = std::move(fine_);
    }
    while (!done) {
      steps_ *= 2;
      P.push_back(method_.level(sys_, base, static_cast<int>(P.size())));
      fine_ = extrapolated(P.size() - 2);
      if (!finite(fine_) || !finite(coarse)) {
        err_.clear();
        break;
      }
      err_ = zeta_differences(fine_, coarse);
      for (double& e : err_) e /= richardson;
      if (resolved(err_) || 2 * steps_ > kMaxAutomaticSteps) break;
      coarse = std::move(fine_);
    }
  }

  // The next K after an unresolved one with excess q: 1.2 K q^(1/p) clamped to [lo K, hi K],
  // at least kMinAutomaticSteps, even (so that a warm start's K / 2 is a whole number).
  int predicted(double q, double lo, double hi) const {
    const double factor =
        std::isfinite(q) ? std::clamp(1.2 * std::pow(q, 1.0 / order_), lo, hi) : hi;
    const double k = std::ceil(factor * steps_);
    if (!(k < kMaxAutomaticSteps)) return kMaxAutomaticSteps;
    const int ki = std::max(kMinAutomaticSteps, static_cast<int>(k));
    return ki + (ki % 2);
  }

  // The automatic ladder: K against the previous level Kc (K/2 at the start, from one pass
  // when the method has a pair), error(K) = |zeta_K - zeta_Kc| / ((K / Kc)^p - 1); an
  // unresolved K is followed by predicted(q, 1.5, 4); the hint gets predicted(q, 0.75, 1).
  void ladder() {
    int coarse_steps = steps_ / 2;
    std::optional<Evaluated> coarse;
    if (method_.has_pair() && steps_ % 2 == 0) {
      Eigen::MatrixXd phi, half;
      method_.transition_pair(sys_, steps_, &phi, &half);
      fine_ = evaluated(phi, trace_);
      coarse = evaluated(half, trace_);
    } else {
      fine_ = at(steps_);
      coarse = at(coarse_steps);
    }
    double q = std::numeric_limits<double>::infinity();
    for (;;) {
      if (!finite(fine_) || !finite(*coarse)) {
        err_.clear();
        break;
      }
      err_ = zeta_differences(fine_, *coarse);
      const double divisor =
          std::pow(static_cast<double>(steps_) / coarse_steps, static_cast<double>(order_)) - 1.0;
      for (double& e : err_) e /= divisor;
      q = excess(err_);
      if (resolved(err_) || steps_ >= kMaxAutomaticSteps) break;
      coarse = std::move(fine_);
      coarse_steps = steps_;
      steps_ = predicted(q, 1.5, 4.0);
      fine_ = at(steps_);
    }
    if (hint_ != nullptr && finite(fine_)) hint_->put(tolerance_, predicted(q, 0.75, 1.0));
  }

  // The sample of fine_ with its estimate and what is not clean about it.
  FloquetSample report(const std::string& system_note) {
    const bool is_resolved = !err_.empty() && resolved(err_);
    FloquetSample out;
    out.steps = steps_;
    const bool fine_finite = finite(fine_);
    const double zeta_floor = fine_.zeta_floor;
    const double log_norm = fine_.log_norm;
    out.floquet = std::move(fine_.floquet);
    if (!fine_finite) {
      out.status = Status::Failed;
      out.message = "the transition matrix overflowed or its eigenvalues did not converge at " +
                    std::to_string(steps_) +
                    " steps: an exponent is too large for double precision over one revolution";
      return out;
    }
    std::string note;
    for (double e : err_) {
      if (!std::isfinite(e)) {  // cannot happen with finite floors; never report a NaN
        err_.clear();
        break;
      }
    }
    if (!err_.empty()) {
      out.error = *std::max_element(err_.begin(), err_.end());
      out.zeta_errors = err_;
      if (!is_resolved) {
        note = "exponents not resolved: estimated zeta error " + short_text(*out.error) +
               " per rev at " + std::to_string(steps_) + " steps (tolerance " +
               short_text(tolerance_) + "); " +
               (automatic_ ? "the automatic limit of " + std::to_string(kMaxAutomaticSteps) +
                                 " steps is reached"
                           : "increase `steps`");
      }
      liouville_check(log_norm, &out, &note);
    } else if (steps_ < 2) {
      note = "no error estimate with 1 step; increase `steps`";
    }
    int below = 0;
    for (const FloquetExponent& e : out.floquet.exponents) below += e.zeta < zeta_floor ? 1 : 0;
    if (below > 0) {
      note += std::string(note.empty() ? "" : "; ") + std::to_string(below) +
              " exponent(s) below the rounding floor of the transition matrix (zeta < " +
              short_text(zeta_floor) + " per rev): their zeta is only known to be below that bound";
    }
    if (!system_note.empty()) note += std::string(note.empty() ? "" : "; ") + system_note;
    if (!note.empty()) {
      out.status = Status::Warning;
      out.message = note + (out.message.empty() ? "" : "; " + out.message);
    }
    return out;
  }

  // det Phi = exp(int tr A) can be checked only when that determinant is above the rounding of
  // det computed from Phi.  That rounding is at most ~ eps ||Phi||^n relative to det Phi; where
  // that bound is too coarse (several modes, some strongly damped: the blade models with more
  // than one mode per direction) the relative rounding of det Phi is eps cond(Phi) (a
  // backward-stable LU moves Phi by eps ||Phi||, det Phi by that times ||Phi^-1|| relative),
  // which is checked instead; the residual means nothing only where that is not small either.
  void liouville_check(double log_norm, FloquetSample* out, std::string* note) const {
    const double n = static_cast<double>(out->floquet.exponents.size());
    const double eps = std::numeric_limits<double>::epsilon();
    double rounding = 0.0;  // relative rounding of det Phi beyond the first bound
    if (trace_ < std::log(1e3 * eps) + n * log_norm) {
      const double condition = condition_number(out->floquet.phi);
      if (std::isfinite(condition) && 1e3 * eps * condition < 1.0) {
        rounding = n * eps * condition;
      } else {
        out->floquet.liouville_residual = std::numeric_limits<double>::quiet_NaN();
        // Said, not warned: the exponents do not depend on this check.
        out->message =
            "no Liouville residual: det Phi = exp(int tr A) = exp(" + short_text(trace_) +
            ") is below the rounding of the determinant of Phi " +
            (std::isfinite(condition) ? "(condition number " + short_text(condition) + ")"
                                      : std::string("(Phi is singular to working precision)"));
      }
    }
    const double residual = out->floquet.liouville_residual;
    const double implied = kTwoPi * n * *out->error;
    if (std::isfinite(residual) && residual > 100.0 * (implied + rounding) + 1e-9) {
      *note += std::string(note->empty() ? "" : "; ") + "Liouville residual " +
               short_text(residual) +
               " far above the error estimate: the exponents are not resolved; increase `steps`";
    }
  }

  const FloquetEvaluator& method_;
  const PeriodicSystem& sys_;
  const double tolerance_;
  StepsHint* const hint_;
  const bool automatic_;
  const int order_;
  int raw_order_ = 0;  // > 0: this request walks the method's raw levels
  double trace_ = 0.0;
  int steps_ = 0;
  Evaluated fine_;
  std::vector<double> err_;
};

}  // namespace

int StepsHint::find(double zeta_tolerance) const {
  for (const auto& [t, k] : last_)
    if (t == zeta_tolerance) return k;
  return 0;
}

void StepsHint::put(double zeta_tolerance, int steps) {
  for (auto& [t, k] : last_)
    if (t == zeta_tolerance) {
      k = steps;
      return;
    }
  last_.emplace_back(zeta_tolerance, steps);
}

std::unique_ptr<FloquetEvaluator> FloquetEvaluator::Create(const TransitionOptions& given,
                                                           int state_size) {
  given.Check();
  TransitionOptions options = given;
  if (options.method == TransitionMethod::Automatic) options.method = automatic_method(state_size);
  switch (options.method) {
    case TransitionMethod::RK4:
      return std::make_unique<Rk4Evaluator>(options);
    case TransitionMethod::Hsu:
      return std::make_unique<HsuEvaluator>(options);
    case TransitionMethod::Magnus4:
      return std::make_unique<Magnus4Evaluator>(options);
    case TransitionMethod::Automatic:  // resolved above
      break;
  }
  throw InvalidInput("method", std::to_string(static_cast<int>(options.method)), "unknown method");
}

FloquetEvaluator::~FloquetEvaluator() = default;

void FloquetEvaluator::transition_pair(const PeriodicSystem& sys, int steps, Eigen::MatrixXd* phi,
                                       Eigen::MatrixXd* half) const {
  *phi = transition(sys, steps);
  *half = transition(sys, steps / 2);
}

int FloquetEvaluator::level_order(const PeriodicSystem&) const { return 0; }

Eigen::MatrixXd FloquetEvaluator::level(const PeriodicSystem&, int, int) const {
  throw InvalidInput("method", method_name(options_.method), "has no raw levels");
}

FloquetSample FloquetEvaluator::evaluate(const PeriodicSystem& sys, double zeta_tolerance,
                                         StepsHint* hint, const std::string& system_note) const {
  if (!(std::isfinite(zeta_tolerance) && zeta_tolerance > 0.0))
    throw InvalidInput("zeta_tolerance", round_trip_text(zeta_tolerance), "must be > 0");
  return StepControl(*this, sys, zeta_tolerance, hint).run(system_note);
}

}  // namespace flaplag
