#include "flaplag/analysis.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/core/parallel.h"
#include "flaplag/numerics/continuation.h"
#include "flaplag/rotor/system_builder.h"
#include "flaplag/rotor/validity.h"
#include "fold.h"
#include "internal.h"

namespace flaplag {

const std::vector<const model::ModelDescriptor*>& compiled_models() {
  static const std::vector<const model::ModelDescriptor*> models = [] {
    auto v = model::registered_models();
    std::sort(v.begin(), v.end(),
              [](const model::ModelDescriptor* a, const model::ModelDescriptor* b) {
                return std::string(a->name) < std::string(b->name);
              });
    return v;
  }();
  return models;
}

const model::ModelDescriptor& find_model(const std::string& name) {
  for (const auto* m : compiled_models()) {
    if (name == m->name) return *m;
  }
  std::string known;
  for (const auto* m : compiled_models())
    known += (known.empty() ? "" : ", ") + std::string(m->name);
  throw InvalidInput("model", name, "unknown model (compiled: " + known + ")");
}

const model::ModelDescriptor& find_model(const std::string& base, int flap_modes, int lag_modes) {
  std::string sizes;
  for (const auto* m : compiled_models()) {
    if (base != m->base) continue;
    if (m->flap_modes == flap_modes && m->lag_modes == lag_modes) return *m;
    sizes += (sizes.empty() ? "" : ", ") + std::to_string(m->flap_modes) + "x" +
             std::to_string(m->lag_modes);
  }
  throw InvalidInput("model", base,
                     sizes.empty()
                         ? "no compiled model family of that name"
                         : "has no " + std::to_string(flap_modes) + " flap x " +
                               std::to_string(lag_modes) + " lag model (compiled: " + sizes + ")");
}

namespace {

using internal::check_mu;
using internal::sort_for_output;

// response, simulate and snapshot are of the hover-linearized system: with
// periodic_linearization they would silently answer another question than the one asked.
void require_hover_linearization(const RotorParameters& p, const char* what) {
  if (!p.periodic_linearization) return;
  throw InvalidInput("periodic_linearization", "true",
                     std::string(what) +
                         " is of the system linearized about hover; about the periodic "
                         "equilibrium it is not built (the periodic equilibrium itself is "
                         "periodic_equilibrium(mu))");
}

// v rounded to 12 significant digits (the decimal grid value behind mu0 + k step), as
// strtod of printf's "%.12g" (std::to_chars general with a precision is that format).
double snap12(double v) {
  char buf[32];
  const auto printed = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 12);
  double out = v;
  std::from_chars(buf, printed.ptr, out);
  return out;
}

// The order of a method's error in the step h, for the Richardson estimate from K and K/2.
int method_order(const TransitionOptions& o) {
  switch (o.method) {
    case TransitionMethod::RK4:
      return 4;
    case TransitionMethod::Hsu:
      return std::min(o.terms, 2);  // interval means O(h^2); J = 1 Taylor truncation O(h)
    case TransitionMethod::Magnus4:
      return 6;  // transition_matrix_magnus4 returns its own Richardson extrapolation
  }
  return 1;
}

// Fewest steps of the automatic rule: the paper's K = 50.  A Magnus request looser than the
// analysis's own tolerance (magnus_levels in floquet()) starts at 24: Magnus4 with its
// Richardson pass is sixth order, and 24 steps give zeta to 3e-8 per rev on the typical case at
// mu = 0.8 and to 2.5e-6 on the 2x2 exact model at mu = 1.4 (bench/README.md, accuracy per
// time), far inside the 1e-3 of a scan point's sign check.
constexpr int kMinAutomaticSteps = 50;
constexpr int kMinLooseMagnusSteps = 24;

// ln of the smallest normal double over 2 pi: zeta of a multiplier that underflowed.
const double kZetaFloor = std::log(std::numeric_limits<double>::min()) / kTwoPi;

// max |eigenvalue| of a (0 when the eigen-solve fails); fixed-size solvers for the 4- and
// 8-state models keep it off the heap (the automatic start solves up to ten per evaluation).
template <typename Mat>
double spectral_radius_of(const Mat& a) {
  Eigen::EigenSolver<Mat> es(a, false);
  return es.info() == Eigen::Success ? es.eigenvalues().cwiseAbs().maxCoeff() : 0.0;
}
double spectral_radius(const Eigen::MatrixXd& a) {
  if (a.rows() == 4) return spectral_radius_of(Eigen::Matrix4d(a));
  if (a.rows() == 8) return spectral_radius_of(Eigen::Matrix<double, 8, 8>(a));
  return spectral_radius_of(a);
}

// One transition matrix's Floquet analysis and its rounding floor: an eigenvalue of Phi below
// ~n eps ||Phi|| is lost in rounding, so a zeta below ln(that) / 2 pi is only a bound.
struct Evaluated {
  FloquetResult floquet;
  double zeta_floor = kZetaFloor;
  double log_norm = 0.0;  // ln ||Phi||_F
};

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

}  // namespace

struct Analysis::Impl {
  Impl(const RotorParameters& p, const TransitionOptions& o,
       std::optional<double> inflow = std::nullopt)
      : options(o), builder(p, find_model(p.model), inflow) {
    o.Check();
    const int harmonics = builder.model().n_harmonics;
    auto tabulate = [&](double psi) {
      psi = reduce_azimuth(psi);
      std::vector<double> v(static_cast<std::size_t>(harmonics));
      for (int h = 0; h < harmonics; ++h) v[static_cast<std::size_t>(h)] = harmonic_basis(h, psi);
      start_basis.emplace_back(psi, std::move(v));
    };
    for (int k = 0; k < 8; ++k) tabulate((k + 0.5) * kTwoPi / 8.0);
    tabulate(1.5 * kPi);
    hover = builder.hover();
    const auto& m = builder.model();
    hover_modes = label_hover_modes(hover.A0, m.flap_modes, m.lag_modes);
    hover.eigenvalues = hover_modes.eigenvalues;
    hover.labels = hover_modes.labels;
    if (hover_modes.status != Status::Ok && hover.status == Status::Ok) {
      hover.status = hover_modes.status;
      hover.message = hover_modes.message;
    }
    validity = internal::validity_of(builder);
  }

  // The automatic starting K at mu: |lambda| h <= 1 for the largest eigenvalue of A(psi) at a
  // few azimuths of each region (the spectrum sets the step a fixed-step method needs).
  // `min_steps` is the fewest it returns; `floor` (>= min_steps) is the count the caller starts
  // at anyway (a steps hint): an azimuth that cannot raise K above it needs no eigen-solve either.
  int automatic_start(const PeriodicSystem& sys, int min_steps, int floor) const {
    // An azimuth whose induced norm min(||A||_1, ||A||_inf) >= rho(A) keeps |lambda| h <= 1 at
    // the minimum K with a step to spare cannot raise K: its eigen-solve is skipped (the same
    // K as solving every one, at a fifth of the cost in the common case).
    // Without a varying region, ||A(psi)||_1 <= sum_h ||A_h||_1 for every psi (|cos|, |sin| <=
    // 1): when that bound keeps every azimuth below the floor, no azimuth can raise K and none
    // needs evaluating (the same K as evaluating them).
    if (!sys.has_varying) {
      double bound = 0.0;
      for (const HarmonicSet* set : {&sys.normal, &sys.reversed}) {
        if (set == &sys.reversed && !sys.has_sector) continue;
        double sum = 0.0;
        for (const Eigen::MatrixXd& h : set->A) sum += h.cwiseAbs().colwise().sum().maxCoeff();
        bound = std::max(bound, sum);
      }
      if (bound * kTwoPi <= floor - 1) return min_steps;  // as when every one is skipped
    }
    double rho = 0.0;
    Eigen::MatrixXd a;  // one buffer for every azimuth
    auto add = [&](double psi) {
      // A(psi) of the harmonic regions as PeriodicSystem::A sums it (the same operations),
      // with cos/sin of the harmonics looked up for the azimuths that do not depend on mu.
      psi = reduce_azimuth(psi);
      if (sys.in_varying(psi)) {
        a = sys.A(psi);
      } else {
        const HarmonicSet& set = sys.region(psi);
        const std::vector<double>* table = nullptr;
        for (const auto& [at, values] : start_basis)
          if (at == psi && values.size() >= set.A.size()) table = &values;
        a.setZero(sys.n, sys.n);
        for (std::size_t h = 0; h < set.A.size(); ++h)
          a += (table ? (*table)[h] : harmonic_basis(static_cast<int>(h), psi)) * set.A[h];
      }
      const double bound = std::min(a.cwiseAbs().colwise().sum().maxCoeff(),
                                    a.cwiseAbs().rowwise().sum().maxCoeff());
      if (bound * kTwoPi <= floor - 1) return;
      rho = std::max(rho, spectral_radius(a));
    };
    for (int k = 0; k < 8; ++k) add((k + 0.5) * kTwoPi / 8.0);
    if (sys.has_sector) add(0.5 * (sys.sector_begin + sys.sector_end));
    if (sys.has_varying) add(0.5 * (sys.varying_begin + sys.varying_end));
    const double k = std::ceil(rho * kTwoPi / 1.0);
    if (!(k <= kMaxAutomaticSteps)) return kMaxAutomaticSteps;
    // an even count, so that K/2 is a whole number
    const int ki = std::max(min_steps, static_cast<int>(k));
    return ki + (ki % 2);
  }

  // Phi at `steps` and its exponents (multipliers only: evaluated()).
  Evaluated at(const PeriodicSystem& sys, double trace, int steps) const {
    TransitionOptions o = options;
    o.steps = steps;
    return evaluated(transition_matrix(sys, o).phi, trace);
  }

  // Hsu at `steps` and steps / 2 in one pass (transition_matrix_hsu_pair): {fine, coarse}.
  std::pair<Evaluated, Evaluated> at_pair(const PeriodicSystem& sys, double trace,
                                          int steps) const {
    Eigen::MatrixXd phi, half;
    transition_matrix_hsu_pair(sys, steps, options.terms, &phi, &half);
    return {evaluated(phi, trace), evaluated(half, trace)};
  }

  // The Floquet analysis of one transition matrix.
  static Evaluated evaluated(const Eigen::MatrixXd& phi, double trace) {
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

  static bool finite(const Evaluated& e) {
    for (const FloquetExponent& x : e.floquet.exponents)
      if (!std::isfinite(x.multiplier.real()) || !std::isfinite(x.multiplier.imag())) return false;
    return !e.floquet.exponents.empty();
  }

  // The steps that resolved the last automatic evaluation at each tolerance, shared by the
  // evaluations of one continuation (one sweep, track or critical search: function()).  Along a
  // continuation the step count needed changes little from one mu to the next, so each
  // evaluation starts at the last count of the same tolerance (or the spectral start when that
  // is larger) instead of climbing from the minimum: the same rule and the same error estimate
  // (K/2 against K), fewer levels.  Keyed by the exact tolerance, so that the evaluations a
  // continuation makes at one tolerance (its reported points) depend only on each other: a map
  // line and the plain sweep over the same points give the same bits.
  struct StepsHint {
    std::vector<std::pair<double, int>> last;  // (zeta_tolerance, steps)
    int find(double tol) const {
      for (const auto& [t, k] : last)
        if (t == tol) return k;
      return 0;
    }
    void put(double tol, int steps) {
      for (auto& [t, k] : last)
        if (t == tol) {
          k = steps;
          return;
        }
      last.emplace_back(tol, steps);
    }
  };

  // What one continuation's evaluations carry from one mu to the next (function()).
  struct Continuation {
    StepsHint hint;
    PeriodicSystem system;  // storage reused at every mu
    // About the periodic equilibrium: the equilibria that were not clean (status Warning), by
    // mu, with their message (what a result at that mu rests on).
    std::map<double, std::string> unclean_equilibria;
  };

  FloquetSample floquet(double mu, double zeta_tolerance, Continuation* c = nullptr) const {
    StepsHint* hint = c != nullptr ? &c->hint : nullptr;
    // The linear system about hover (the paper) or about the periodic equilibrium.
    if (builder.params().periodic_linearization) {
      PeriodicEquilibrium eq = equilibrium(mu);
      if (eq.status == Status::Failed) {
        FloquetSample out;
        out.status = Status::Failed;
        out.message = eq.message;
        return out;
      }
      if (c != nullptr && eq.status != Status::Ok && c->unclean_equilibria.size() < 4096)
        c->unclean_equilibria[mu] = eq.message;
      return floquet_of(eq.linearization, zeta_tolerance, eq.message, hint);
    }
    if (c == nullptr) return floquet_of(builder.system(mu), zeta_tolerance, "", hint);
    builder.system(mu, &c->system);
    return floquet_of(c->system, zeta_tolerance, "", hint);
  }

  // One resolved Floquet evaluation of sys; equilibrium_note (the periodic equilibrium's
  // warning, if any) is appended to the message.
  FloquetSample floquet_of(const PeriodicSystem& sys, double zeta_tolerance,
                           const std::string& equilibrium_note, StepsHint* hint = nullptr) const {
    FloquetSample out;
    bool system_finite = true;
    for (const HarmonicSet* set : {&sys.normal, &sys.reversed})
      for (const Eigen::MatrixXd& a : set->A) system_finite = system_finite && a.allFinite();
    if (sys.has_varying)  // the exact region's fully reversed middle (the largest values)
      system_finite =
          system_finite && sys.A(0.5 * (sys.varying_begin + sys.varying_end)).allFinite();
    if (!system_finite) {
      out.status = Status::Failed;
      out.message =
          "the periodic system overflows at this mu (the parameters are too extreme "
          "for double precision)";
      return out;
    }
    const double trace = sys.trace_integral();
    const int order = method_order(options);
    const double richardson = std::ldexp(1.0, order) - 1.0;  // K against 2K or K/2
    const bool automatic = options.steps == TransitionOptions::kAutomatic;
    // Magnus with automatic steps asked for less than the analysis's own tolerance (a sign
    // check of the mu_c scan, a continuation step that is not reported) walks its raw
    // fourth-order levels from 24 steps (magnus_levels below); every result at the analysis's
    // tolerance or tighter (the reported points, both ends of a bracket, the Brent trials) is
    // computed by the rule of the other methods, so it does not change.
    const bool levels = automatic && options.method == TransitionMethod::Magnus4 &&
                        !sys.has_varying && zeta_tolerance > options.zeta_tolerance;
    const int min_steps = levels ? kMinLooseMagnusSteps : kMinAutomaticSteps;
    const int hinted = automatic && !levels && hint != nullptr ? hint->find(zeta_tolerance) : 0;
    int steps = automatic
                    ? std::max(automatic_start(sys, min_steps, std::max(min_steps, hinted)), hinted)
                    : options.steps;

    // The automatic rule's first pair (K and K / 2) by Hsu comes from one pass.
    std::optional<Evaluated> first_coarse;
    Evaluated fine;
    if (automatic && !levels && options.method == TransitionMethod::Hsu && steps % 2 == 0) {
      auto pair = at_pair(sys, trace, steps);
      fine = std::move(pair.first);
      first_coarse = std::move(pair.second);
    } else if (!levels) {
      fine = at(sys, trace, steps);
    }
    auto resolved = [&](const std::vector<double>& err) {
      for (std::size_t k = 0; k < err.size(); ++k) {
        const double z = std::abs(std::max(fine.floquet.exponents[k].zeta, fine.zeta_floor));
        const double allowed = zeta_tolerance * std::max(1.0, 100.0 * (std::isfinite(z) ? z : 0.0));
        if (!(err[k] <= allowed)) return false;
      }
      return true;
    };
    std::vector<double> err;
    if (!automatic) {
      // Fixed steps (the user's K): the estimate compares with 2K, which is nearer the
      // asymptotic regime than K/2 (at K = 25 Hsu's error is far from c h^2 on shallow
      // crossings); error(K) = (zeta_K - zeta_2K) 2^p / (2^p - 1).
      const bool finer = 2 * steps <= TransitionOptions::kMaxSteps;
      const std::optional<Evaluated> other =
          finer ? std::optional<Evaluated>(at(sys, trace, 2 * steps))
                : (steps >= 2 ? std::optional<Evaluated>(at(sys, trace, steps / 2)) : std::nullopt);
      if (finite(fine) && other && finite(*other)) {
        err = zeta_differences(fine, *other);
        for (double& e : err) e *= finer ? (richardson + 1.0) / richardson : 1.0 / richardson;
      }
    } else if (levels) {
      // magnus_levels: P_l, Phi by raw Magnus4 on the grid of K/2 steps bisected l times, each
      // level computed once; R_l = (16 P_{l+1} - P_l) / 15 is transition_matrix_magnus4's
      // result at K/2 * 2^l steps (sixth order).  The request does not need the reference
      // accuracy: first R_0 with the fourth-order estimate of P_1, |zeta(R_0) - zeta(P_0)| / 16
      // (P_0's error is 16 times P_1's), from P_0 + P_1 = 1.5 K steps instead of the 4.5 K of
      // the pair below; if that is not enough, the sixth-order pairs (R_l, R_{l+1}) as in the
      // rule below, one new level per doubling.  Like every Richardson estimate it is not a
      // bound: before the asymptotic regime it can be low for a strongly damped mode (1x1 at
      // mu = 1.4, zeta = -1.49: 1.5e-4 against an error of 2.9e-3, inside the 0.15 that mode
      // is allowed; Floquet.LooseMagnusRequestsMeetTheirClaims).
      const int base = steps / 2;
      std::vector<Eigen::MatrixXd> P;
      P.push_back(transition_matrix_magnus4_level(sys, base, 0));
      P.push_back(transition_matrix_magnus4_level(sys, base, 1));
      auto extrapolated = [&](std::size_t l) {
        return evaluated((16.0 * P[l + 1] - P[l]) / 15.0, trace);
      };
      Evaluated coarse = extrapolated(0);
      steps = base;
      bool done = false;
      const Evaluated raw = evaluated(P[0], trace);
      if (finite(coarse) && finite(raw)) {
        fine = std::move(coarse);
        err = zeta_differences(fine, raw);
        for (double& e : err) e /= 16.0;
        done = resolved(err);
        if (!done) coarse = std::move(fine);
      }
      while (!done) {
        steps *= 2;
        P.push_back(transition_matrix_magnus4_level(sys, base, static_cast<int>(P.size())));
        fine = extrapolated(P.size() - 2);
        if (!finite(fine) || !finite(coarse)) {
          err.clear();
          break;
        }
        err = zeta_differences(fine, coarse);
        for (double& e : err) e /= richardson;
        if (resolved(err) || 2 * steps > kMaxAutomaticSteps) break;
        coarse = std::move(fine);
      }
    } else {
      // Automatic: K against the previous level Kc (K/2 at the start); with the error ~ c K^-p,
      //   error(K) = |zeta_K - zeta_Kc| / ((K / Kc)^p - 1)
      // (the rule's Richardson estimate for any ratio; 1 / (2^p - 1) when Kc = K / 2).  An
      // unresolved K is followed by the K that the estimate predicts with a margin,
      // 1.2 K q^(1/p) for q = the largest error / allowed ratio, at least 1.5 K (so that the
      // estimate's divisor stays >= 1.25 for Hsu) and at most 4 K: fewer intervals than
      // doubling when K is nearly enough.  The next evaluation of the continuation starts at
      // the K so predicted for this point (never below 3/4 of it, so a gently easing point
      // keeps a count it has shown to resolve).
      auto excess = [&](const std::vector<double>& e) {
        double q = 0.0;
        for (std::size_t k = 0; k < e.size(); ++k) {
          const double z = std::abs(std::max(fine.floquet.exponents[k].zeta, fine.zeta_floor));
          const double allowed =
              zeta_tolerance * std::max(1.0, 100.0 * (std::isfinite(z) ? z : 0.0));
          q = std::max(q, e[k] / allowed);
        }
        return q;
      };
      auto predicted = [&](double q, double lo, double hi) {
        const double factor =
            std::isfinite(q) ? std::clamp(1.2 * std::pow(q, 1.0 / order), lo, hi) : hi;
        const double k = std::ceil(factor * steps);
        if (!(k < kMaxAutomaticSteps)) return kMaxAutomaticSteps;
        const int ki = std::max(kMinAutomaticSteps, static_cast<int>(k));
        return ki + (ki % 2);  // even, so that a warm start's K / 2 is a whole number
      };
      int coarse_steps = steps / 2;
      std::optional<Evaluated> coarse =
          first_coarse ? std::move(first_coarse) : at(sys, trace, coarse_steps);
      double q = std::numeric_limits<double>::infinity();
      for (;;) {
        if (!finite(fine) || !finite(*coarse)) {
          err.clear();
          break;
        }
        err = zeta_differences(fine, *coarse);
        const double divisor =
            std::pow(static_cast<double>(steps) / coarse_steps, static_cast<double>(order)) - 1.0;
        for (double& e : err) e /= divisor;
        q = excess(err);
        if (resolved(err) || steps >= kMaxAutomaticSteps) break;
        coarse = std::move(fine);
        coarse_steps = steps;
        steps = predicted(q, 1.5, 4.0);
        fine = at(sys, trace, steps);
      }
      if (hint != nullptr && finite(fine)) hint->put(zeta_tolerance, predicted(q, 0.75, 1.0));
    }
    const bool is_resolved = !err.empty() && resolved(err);
    out.steps = steps;
    const bool fine_finite = finite(fine);
    const double zeta_floor = fine.zeta_floor;
    const double log_norm = fine.log_norm;
    out.floquet = std::move(fine.floquet);
    if (!fine_finite) {
      out.status = Status::Failed;
      out.message = "the transition matrix overflowed or its eigenvalues did not converge at " +
                    std::to_string(steps) +
                    " steps: an exponent is too large for double precision over one revolution";
      return out;
    }
    std::string note;
    for (double e : err) {
      if (!std::isfinite(e)) {  // cannot happen with finite floors; never report a NaN
        err.clear();
        break;
      }
    }
    if (!err.empty()) {
      out.error = *std::max_element(err.begin(), err.end());
      out.zeta_errors = err;
      if (!is_resolved) {
        note = "exponents not resolved: estimated zeta error " + short_text(*out.error) +
               " per rev at " + std::to_string(steps) + " steps (tolerance " +
               short_text(zeta_tolerance) + "); " +
               (automatic ? "the automatic limit of " + std::to_string(kMaxAutomaticSteps) +
                                " steps is reached"
                          : "increase `steps`");
      }
      // det Phi = exp(int tr A) can be checked only when that determinant is above the rounding
      // of det computed from Phi.  That rounding is at most ~ eps ||Phi||^n relative to det Phi;
      // where that bound is too coarse (several modes, some strongly damped: the blade models
      // with more than one mode per direction) the relative rounding of det Phi is eps
      // cond(Phi) (a backward-stable LU moves Phi by eps ||Phi||, det Phi by that times
      // ||Phi^-1|| relative), which is checked instead; the residual means nothing only where
      // that is not small either.
      const double n = static_cast<double>(out.floquet.exponents.size());
      const double eps = std::numeric_limits<double>::epsilon();
      double rounding = 0.0;  // relative rounding of det Phi beyond the first bound
      if (trace < std::log(1e3 * eps) + n * log_norm) {
        const double condition = condition_number(out.floquet.phi);
        if (std::isfinite(condition) && 1e3 * eps * condition < 1.0) {
          rounding = n * eps * condition;
        } else {
          out.floquet.liouville_residual = std::numeric_limits<double>::quiet_NaN();
          // Said, not warned: the exponents do not depend on this check.
          out.message = "no Liouville residual: det Phi = exp(int tr A) = exp(" +
                        short_text(trace) + ") is below the rounding of the determinant of Phi " +
                        "(condition number " + short_text(condition) + ")";
        }
      }
      const double residual = out.floquet.liouville_residual;
      const double implied = kTwoPi * n * *out.error;
      if (std::isfinite(residual) && residual > 100.0 * (implied + rounding) + 1e-9) {
        note += std::string(note.empty() ? "" : "; ") + "Liouville residual " +
                short_text(residual) +
                " far above the error estimate: the exponents are not resolved; increase `steps`";
      }
    } else if (steps < 2) {
      note = "no error estimate with 1 step; increase `steps`";
    }
    int below = 0;
    for (const FloquetExponent& e : out.floquet.exponents) below += e.zeta < zeta_floor ? 1 : 0;
    if (below > 0) {
      note += std::string(note.empty() ? "" : "; ") + std::to_string(below) +
              " exponent(s) below the rounding floor of the transition matrix (zeta < " +
              short_text(zeta_floor) + " per rev): their zeta is only known to be below that bound";
    }
    if (!equilibrium_note.empty()) {
      note += std::string(note.empty() ? "" : "; ") + equilibrium_note;
    }
    if (!note.empty()) {
      out.status = Status::Warning;
      out.message = note + (out.message.empty() ? "" : "; " + out.message);
    }
    return out;
  }

  FloquetFunction function(std::shared_ptr<Continuation> c = nullptr) const {
    if (!c) c = std::make_shared<Continuation>();
    return [this, c](double mu, double tol) { return floquet(mu, tol, c.get()); };
  }

  // A sweep or track in stretches (Analysis::sweep).  The periodic equilibria of one Analysis
  // share a cache of starts, so their stretches run in order.
  SweepResult track(const std::vector<double>& mus, double step, int threads,
                    const std::atomic<bool>* cancel = nullptr,
                    const ProgressFunction& progress = {}) const {
    if (auto p = threads_problem(threads)) throw *p;
    const int used = builder.params().periodic_linearization ? 1 : threads;
    if (cancel == nullptr && !progress)
      return track_exponents(
          hover_modes, [this] { return function(); }, mus, step, options.zeta_tolerance, used);
    // Every function of the stretches counts its evaluations into one ticker.
    auto ticker = std::make_shared<internal::Ticker>(mus, step, cancel, progress);
    auto make = [this, ticker] { return internal::ticking(function(), ticker); };
    return track_exponents(hover_modes, make, mus, step, options.zeta_tolerance, used);
  }

  // The periodic equilibrium at mu, continued from the nearest cached one below mu (the
  // continuation from hover is the expensive part of a scan).  Converged equilibria are
  // cached; the cache only shortens the continuation along the same branch.
  PeriodicEquilibrium equilibrium(double mu) const {
    std::optional<PeriodicEquilibrium> start;
    {
      std::lock_guard<std::mutex> lock(cache_mutex);
      auto it = cache.upper_bound(mu);
      if (it != cache.begin()) start = std::prev(it)->second;
    }
    PeriodicEquilibrium eq =
        flaplag::periodic_equilibrium(builder, mu, equilibrium_options, start ? &*start : nullptr);
    if (eq.status != Status::Failed) {
      std::lock_guard<std::mutex> lock(cache_mutex);
      if (cache.size() > 4096) cache.clear();
      PeriodicEquilibrium stored = eq;
      stored.linearization = PeriodicSystem{};
      cache.emplace(mu, std::move(stored));
    }
    return eq;
  }

  TransitionOptions options;
  detail::SystemBuilder builder;
  // (psi, harmonic_basis(h, psi) for every h) at the azimuths of automatic_start that do not
  // depend on mu: the eight fixed ones and the sector's middle (3 pi / 2).
  std::vector<std::pair<double, std::vector<double>>> start_basis;
  mutable std::mutex cache_mutex;
  mutable std::map<double, PeriodicEquilibrium> cache;
  // The harmonic balance behind periodic_linearization (stability comes from the analysis).
  PeriodicEquilibriumOptions equilibrium_options = internal::equilibrium_options();
  HoverResult hover;
  HoverModes hover_modes;
  std::string validity;  // rotor/validity.h: "" inside the envelope

  // Outside the validity envelope every result is a Warning that says so.
  void outside_envelope(CriticalResult& r) const {
    if (validity.empty() || r.status == Status::Failed) return;
    internal::combine(&r.status, &r.message, Status::Warning, validity);
  }
  void outside_envelope(SweepResult& r) const {
    if (validity.empty()) return;
    for (PointResult& p : r.points)
      if (p.status != Status::Failed)
        internal::combine(&p.status, &p.message, Status::Warning, validity);
    if (r.status == Status::Ok) {
      r.status = Status::Warning;
      r.message = validity;
    }
  }
};

Analysis::Analysis(const RotorParameters& params, const TransitionOptions& options)
    : impl_(std::make_unique<Impl>(params, options)) {}
Analysis::Analysis(const RotorParameters& params, const TransitionOptions& options, double inflow)
    : impl_(std::make_unique<Impl>(params, options, inflow)) {}
Analysis::~Analysis() = default;
Analysis::Analysis(Analysis&&) noexcept = default;
Analysis& Analysis::operator=(Analysis&&) noexcept = default;

const RotorParameters& Analysis::parameters() const { return impl_->builder.params(); }
const TransitionOptions& Analysis::options() const { return impl_->options; }
const model::ModelDescriptor& Analysis::model() const { return impl_->builder.model(); }
const ModeSet& Analysis::modes() const { return impl_->builder.modes(); }
const HoverResult& Analysis::hover() const { return impl_->hover; }
const std::string& Analysis::validity() const { return impl_->validity; }

PeriodicSystem Analysis::system(double mu) const {
  check_mu(mu, "mu");
  return impl_->builder.system(mu);
}

PeriodicEquilibrium Analysis::periodic_equilibrium(
    double mu, const PeriodicEquilibriumOptions& options) const {
  check_mu(mu, "mu");
  options.Check();
  return flaplag::periodic_equilibrium(impl_->builder, mu, options);
}

FloquetSample Analysis::floquet(const PeriodicEquilibrium& equilibrium,
                                double zeta_tolerance) const {
  if (!(std::isfinite(zeta_tolerance) && zeta_tolerance > 0.0))
    throw InvalidInput("zeta_tolerance", round_trip_text(zeta_tolerance), "must be > 0");
  if (equilibrium.status == Status::Failed ||
      equilibrium.linearization.n != impl_->builder.state_size()) {
    throw InvalidInput("equilibrium", round_trip_text(equilibrium.mu),
                       "is not a periodic equilibrium of this blade (failed, or another model)");
  }
  return impl_->floquet_of(equilibrium.linearization, zeta_tolerance, equilibrium.message);
}

FloquetSample Analysis::floquet(double mu, double zeta_tolerance) const {
  check_mu(mu, "mu");
  if (!(std::isfinite(zeta_tolerance) && zeta_tolerance > 0.0))
    throw InvalidInput("zeta_tolerance", round_trip_text(zeta_tolerance), "must be > 0");
  return impl_->floquet(mu, zeta_tolerance);
}

ForcedResponse Analysis::response(double mu, const ResponseOptions& options) const {
  check_mu(mu, "mu");
  require_hover_linearization(parameters(), "the periodic forced response");
  options.Check();
  ForcedResponse out;
  out.mu = mu;
  out.periodic = periodic_response(impl_->builder.system(mu), options);
  out.status = out.periodic.status;
  out.message = out.periodic.message;
  if (out.status == Status::Failed) return out;
  const int M = model().flap_modes, N = model().lag_modes;
  for (const Eigen::VectorXd& y : out.periodic.y) {
    const internal::TipDeflection t =
        internal::tip_deflection(impl_->builder.modes(), M, N, y, &impl_->hover.q0);
    out.flap_tip.push_back(t.flap);
    out.lag_tip.push_back(t.lag);
  }
  // Discrete Fourier coefficients over the equally spaced samples.
  auto harmonics = [&](const std::vector<double>& s) {
    const double n = static_cast<double>(s.size());
    std::vector<double> c(11, 0.0);
    for (std::size_t i = 0; i < s.size(); ++i) {
      const double psi = out.periodic.psi[i];
      c[0] += s[i] / n;
      for (int h = 1; h <= 5; ++h) {
        c[2 * h - 1] += 2.0 / n * s[i] * std::cos(h * psi);
        c[2 * h] += 2.0 / n * s[i] * std::sin(h * psi);
      }
    }
    return c;
  };
  out.flap_harmonics = harmonics(out.flap_tip);
  out.lag_harmonics = harmonics(out.lag_tip);
  return out;
}

TipSimulation Analysis::simulate(double mu, const Eigen::VectorXd& y0, bool forced,
                                 const SimulationOptions& options) const {
  check_mu(mu, "mu");
  if (options.nonlinear) return simulate_nonlinear(mu, y0, forced, options);
  require_hover_linearization(parameters(), "the time-domain simulation");
  TipSimulation out;
  out.mu = mu;
  out.simulation = flaplag::simulate(impl_->builder.system(mu), y0, forced, options);
  const Simulation& s = out.simulation;
  const int M = model().flap_modes, N = model().lag_modes;
  for (const Eigen::VectorXd& y : s.y) {
    const internal::TipDeflection t = internal::tip_deflection(impl_->builder.modes(), M, N, y);
    out.flap_tip.push_back(t.flap);
    out.lag_tip.push_back(t.lag);
  }
  // The first quarter holds the transient of the other modes.
  out.flap_growth_rate = envelope_growth_rate(s.psi, out.flap_tip, 0.25 * options.revolutions);
  out.lag_growth_rate = envelope_growth_rate(s.psi, out.lag_tip, 0.25 * options.revolutions);
  out.status = s.status;
  out.message = s.message;
  return out;
}

TipSimulation Analysis::simulate_nonlinear(double mu, const Eigen::VectorXd& y0, bool forced,
                                           const SimulationOptions& options) const {
  const model::ModelDescriptor& m = model();
  if (m.nonlinear == nullptr) {
    throw InvalidInput("nonlinear", "true",
                       "the model " + std::string(m.name) +
                           " has no nonlinear loads (its spec does not set [emit] nonlinear); "
                           "use a model that emits them, e.g. paper-nonlinear");
  }
  if (forced) {
    throw InvalidInput("forced", "true",
                       "the nonlinear equations always carry their loads (f is part of them): "
                       "leave `forced` off with `nonlinear`");
  }
  options.Check();
  const int n = state_size();
  if (y0.size() != n || !y0.allFinite())
    throw InvalidInput("y0", std::to_string(y0.size()) + " values",
                       "must be " + std::to_string(n) + " finite values");
  const NonlinearSystem sys(impl_->builder, mu);  // refuses exact_reversed_flow by name
  TipSimulation out;
  out.mu = mu;
  out.nonlinear = true;
  // The reference: the periodic equilibrium on the branch from hover (at mu = 0 the hover
  // equilibrium itself), or hover where that branch has ended (a fold below mu).
  const PeriodicEquilibrium eq = impl_->equilibrium(mu);
  const bool periodic = eq.status != Status::Failed;
  const int M = m.flap_modes, N = m.lag_modes;
  Eigen::VectorXd hover_state = Eigen::VectorXd::Zero(n);
  for (int j = 0; j < M + N; ++j)
    hover_state(model::displacement_index(j, M, N)) = impl_->hover.q0(j);
  auto reference = [&](double psi) { return periodic ? eq.state(psi) : hover_state; };
  out.reference = periodic ? "periodic equilibrium" : "hover equilibrium";
  // The grid and the automatic steps from the linearization about the reference.
  const PeriodicSystem grid = periodic ? eq.linearization : sys.sector();
  const NonlinearRhs rhs = [&sys](double psi, bool reversed, const Eigen::VectorXd& y,
                                  Eigen::VectorXd& F) {
    sys.evaluate(psi, reversed, y, &F, nullptr);
  };
  out.simulation = flaplag::simulate_nonlinear(grid, rhs, reference(0.0) + y0, options);
  const Simulation& s = out.simulation;
  for (std::size_t k = 0; k < s.y.size(); ++k) {
    const Eigen::VectorXd ref = reference(s.psi[k]);
    const internal::TipDeflection d =
        internal::tip_deflection(impl_->builder.modes(), M, N, s.y[k] - ref);
    const internal::TipDeflection t =
        internal::tip_deflection(impl_->builder.modes(), M, N, s.y[k]);
    out.flap_tip.push_back(d.flap);
    out.lag_tip.push_back(d.lag);
    out.flap_total.push_back(t.flap);
    out.lag_total.push_back(t.lag);
  }
  out.flap_growth_rate = envelope_growth_rate(s.psi, out.flap_tip, 0.25 * options.revolutions);
  out.lag_growth_rate = envelope_growth_rate(s.psi, out.lag_tip, 0.25 * options.revolutions);
  out.status = s.status;
  out.message = s.message;
  if (out.status != Status::Failed && eq.status != Status::Ok) {
    out.status = Status::Warning;
    out.message += std::string(out.message.empty() ? "" : "; ") +
                   (periodic ? "the reference periodic equilibrium: " + eq.message
                             : eq.message +
                                   "; the simulation starts from and is measured against the "
                                   "hover equilibrium");
  }
  return out;
}

int Analysis::state_size() const { return impl_->builder.state_size(); }

SystemSnapshot Analysis::snapshot(double mu, double psi) const {
  check_mu(mu, "mu");
  require_hover_linearization(parameters(), "the system snapshot");
  if (!std::isfinite(psi)) throw InvalidInput("psi", round_trip_text(psi), "must be finite");
  SystemSnapshot s;
  s.mu = mu;
  s.psi = psi;
  const PeriodicSystem sys = impl_->builder.system(mu);
  const bool exact = sys.in_varying(psi);
  const bool reversed = exact || (sys.has_sector && sys.in_sector(psi));
  s.region = reversed ? "reversed" : "normal";
  s.A = sys.A(psi);
  s.f = sys.f(psi);
  const auto& m = impl_->builder.model();
  const auto& normal = impl_->builder.normal_integrals();
  const std::vector<double> region = exact      ? impl_->builder.exact_integrals(mu, psi)
                                     : reversed ? impl_->builder.reversed_integrals(mu)
                                                : normal;
  for (int j = 0; j < m.n_aero; ++j) {
    s.aero_integrals.emplace_back(m.aero[j].name, normal[j]);
    s.aero_integrals_region.emplace_back(m.aero[j].name, region[j]);
  }
  const auto& st = impl_->builder.structural_values();
  for (int j = 0; j < m.n_structural; ++j) {
    s.structural_integrals.emplace_back(m.structural[j].name, st[j]);
  }
  return s;
}

PointResult Analysis::point(double mu, double scan_step) const {
  check_mu(mu, "mu");
  if (!(scan_step > 0.0) || !std::isfinite(scan_step)) {
    throw InvalidInput("scan_step", round_trip_text(scan_step), "must be finite and > 0");
  }
  if (mu / scan_step > static_cast<double>(kMaxContinuationSteps)) {
    throw InvalidInput("scan_step", round_trip_text(scan_step),
                       "too small: at most " + std::to_string(kMaxContinuationSteps) +
                           " continuation steps from hover");
  }
  SweepResult sw = sweep_exponents(impl_->hover_modes, impl_->function(), mu, mu, scan_step,
                                   impl_->options.zeta_tolerance);
  PointResult r;
  r.mu = mu;
  if (sw.points.empty()) {
    r.status = Status::Failed;
    r.message = sw.message.empty() ? "continuation from hover failed" : sw.message;
    return r;
  }
  r = std::move(sw.points.back());
  r.mu = mu;
  if (r.status != Status::Failed) {
    // A problem on the way (identification) matters for the point too.
    if (sw.status > r.status) {
      r.status = sw.status;
      r.message = r.message.empty() ? sw.message : r.message + "; " + sw.message;
    }
  } else if (r.message.empty()) {
    r.message = sw.message;
  }
  if (r.status != Status::Failed)
    internal::combine(&r.status, &r.message, impl_->validity.empty() ? Status::Ok : Status::Warning,
                      impl_->validity);
  sort_for_output(r.exponents);
  return r;
}

SweepResult Analysis::sweep(double mu0, double mu1, double step, int threads) const {
  return sweep(mu0, mu1, step, threads, nullptr, {});
}

SweepResult Analysis::sweep(double mu0, double mu1, double step, int threads,
                            const std::atomic<bool>* cancel,
                            const ProgressFunction& progress) const {
  check_mu(mu0, "mu0");
  check_mu(mu1, "mu1");
  if (!(step > 0.0) || !std::isfinite(step)) {
    throw InvalidInput("step", round_trip_text(step), "must be finite and > 0");
  }
  if (!(mu1 > mu0)) {
    throw InvalidInput("mu1", round_trip_text(mu1),
                       "empty or reversed range (must exceed mu0 = " + round_trip_text(mu0) + ")");
  }
  if (mu1 / step > static_cast<double>(kMaxContinuationSteps)) {
    throw InvalidInput(
        "step", round_trip_text(step),
        "too small: at most " + std::to_string(kMaxContinuationSteps) + " continuation steps");
  }
  SweepResult r = impl_->track(sweep_grid(mu0, mu1, step), step, threads, cancel, progress);
  for (PointResult& p : r.points) {
    // mu0 + k step accumulates rounding (0.7999999999999999); report the decimal grid value.
    p.mu = snap12(p.mu);
    sort_for_output(p.exponents);
  }
  impl_->outside_envelope(r);
  return r;
}

SweepResult Analysis::track(const std::vector<double>& mus, double scan_step, int threads) const {
  return track(mus, scan_step, threads, nullptr, {});
}

SweepResult Analysis::track(const std::vector<double>& mus, double scan_step, int threads,
                            const std::atomic<bool>* cancel,
                            const ProgressFunction& progress) const {
  // The advance ratios themselves first: too many of them is their fault, not the step's.
  if (mus.size() > static_cast<std::size_t>(kMaxContinuationSteps)) {
    throw InvalidInput("mu", std::to_string(mus.size()) + " advance ratios",
                       "at most " + std::to_string(kMaxContinuationSteps) + " advance ratios");
  }
  for (double mu : mus) check_mu(mu, "mu");
  if (!(scan_step > 0.0) || !std::isfinite(scan_step)) {
    throw InvalidInput("scan_step", round_trip_text(scan_step), "must be finite and > 0");
  }
  if (!mus.empty() && mus.back() / scan_step + static_cast<double>(mus.size()) >
                          static_cast<double>(kMaxContinuationSteps)) {
    throw InvalidInput("scan_step", round_trip_text(scan_step),
                       "too small for " + std::to_string(mus.size()) +
                           " advance ratios up to mu = " + round_trip_text(mus.back()) +
                           ": at most " + std::to_string(kMaxContinuationSteps) +
                           " continuation steps in all");
  }
  SweepResult r = impl_->track(mus, scan_step, threads, cancel, progress);
  for (PointResult& p : r.points) sort_for_output(p.exponents);
  impl_->outside_envelope(r);
  return r;
}

CriticalResult Analysis::critical(const CriticalOptions& opt) const {
  opt.Check();
  CriticalOptions o = opt;
  o.scan_zeta_tolerance = std::min(opt.scan_zeta_tolerance, impl_->options.zeta_tolerance);
  if (!parameters().periodic_linearization) {
    CriticalResult r = find_critical(impl_->hover_modes, impl_->function(), o);
    sort_for_output(r.exponents);
    impl_->outside_envelope(r);
    return r;
  }
  // About the periodic equilibrium the search can end at a fold of its branch (fold.h).
  const internal::FoldWatch watch;
  const auto continuation = std::make_shared<Impl::Continuation>();
  CriticalResult r =
      find_critical(impl_->hover_modes, watch.wrap(impl_->function(continuation)), o);
  std::optional<PeriodicEquilibrium> last;
  const internal::EquilibriumProbe probe = [&](double mu, PeriodicSystem* lin, double* reached) {
    PeriodicEquilibrium eq = flaplag::periodic_equilibrium(
        impl_->builder, mu, impl_->equilibrium_options, last ? &*last : nullptr);
    if (eq.status == Status::Failed) {
      // the continuation converged up to continued_to: its last solution is a start there
      if (last && eq.continued_to > last->mu && eq.continued_to < mu &&
          eq.coefficients.allFinite()) {
        *reached = eq.continued_to;
        eq.mu = eq.continued_to;
        eq.status = Status::Warning;
        last = std::move(eq);
      }
      return false;
    }
    *lin = eq.linearization;
    last = std::move(eq);
    return true;
  };
  internal::report_fold(r, watch, probe, o);
  sort_for_output(r.exponents);
  // mu_c (and every interval end) is no better than the periodic equilibrium there.
  if (r.status != Status::Failed) {
    for (const InstabilityInterval& iv : r.intervals) {
      for (const std::optional<double>& at : {std::optional<double>(iv.onset), iv.end}) {
        if (!at) continue;
        const auto it = continuation->unclean_equilibria.find(*at);
        if (it == continuation->unclean_equilibria.end()) continue;
        internal::combine(&r.status, &r.message, Status::Warning,
                          "the periodic equilibrium at mu = " + round_trip_text(*at) +
                              ", where the result is found: " + it->second);
      }
    }
  }
  impl_->outside_envelope(r);
  return r;
}

}  // namespace flaplag
