#include "flaplag/core/constants.h"
#include "flaplag/analysis.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "flaplag/numerics/continuation.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/rotor/system_builder.h"

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
  throw InvalidInput("--model", name, "unknown model (compiled: " + known + ")");
}

namespace {

void check_mu(double mu, const char* name) {
  if (!std::isfinite(mu) || mu < 0.0) {
    throw InvalidInput(name, round_trip_text(mu), "advance ratio must be finite and >= 0");
  }
}

std::string snap12(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.12g", v);
  return buf;
}

std::vector<ModeExponent> to_modes(const std::vector<LabelledExponent>& v) {
  std::vector<ModeExponent> out;
  for (const auto& e : v) out.push_back({e.label, e.zeta, e.omega, e.multiplier});
  std::stable_sort(out.begin(), out.end(), [](const ModeExponent& a, const ModeExponent& b) {
    return a.label != b.label ? a.label < b.label : a.omega > b.omega;
  });
  return out;
}

}  // namespace

struct Analysis::Impl {
  Impl(const RotorParameters& p, const TransitionOptions& o)
      : options(o), builder(p, find_model(p.model)) {
    if (o.steps < 1) throw InvalidInput("--steps", std::to_string(o.steps), "must be >= 1");
    if (o.terms < 1) throw InvalidInput("--terms", std::to_string(o.terms), "must be >= 1");
    hover = builder.hover();
    const auto& m = builder.model();
    hover_modes = label_hover_modes(hover.A0, m.flap_modes, m.lag_modes);
    hover.eigenvalues = hover_modes.eigenvalues;
    hover.labels = hover_modes.labels;
    if (hover_modes.status != Status::Ok && hover.status == Status::Ok) {
      hover.status = hover_modes.status;
      hover.message = hover_modes.message;
    }
    // Fixed-step methods resolve a mode only when |lambda| * step is well inside their
    // stability region; a stiff blade (high frequencies) needs more steps.
    double rho = 0.0;
    for (const auto& lam : hover.eigenvalues) rho = std::max(rho, std::abs(lam));
    const double h = kTwoPi / o.steps;
    if (o.method != TransitionMethod::Magnus4 && rho * h > 1.0) {
      resolution_warning =
          "step too coarse for the fastest hover mode (|lambda| = " + round_trip_text(rho) +
          " per rev, |lambda| * step = " + round_trip_text(rho * h) + " > 1): increase --steps";
    }
  }

  // Adds the resolution warning to a result's status and message.
  template <class R>
  void flag(R& r) const {
    if (resolution_warning.empty()) return;
    if (r.status == Status::Ok) r.status = Status::Warning;
    r.message = r.message.empty() ? resolution_warning : r.message + "; " + resolution_warning;
  }

  // The reference method refines itself: the Magnus steps double until the Richardson error
  // estimate of Phi is below kReferenceTolerance (or kMaxReferenceSteps is reached), so that
  // "reference" means converged, whatever --steps asked for.
  static constexpr double kReferenceTolerance = 1e-12;
  static constexpr int kMaxReferenceSteps = 12800;

  TransitionResult transition(const PeriodicSystem& sys) const {
    TransitionResult tr = transition_matrix(sys, options);
    if (options.method != TransitionMethod::Magnus4) return tr;
    TransitionOptions o = options;
    while (tr.error_estimate > kReferenceTolerance && o.steps * 2 <= kMaxReferenceSteps) {
      o.steps *= 2;
      tr = transition_matrix(sys, o);
    }
    return tr;
  }

  FloquetResult floquet(double mu) const {
    const PeriodicSystem sys = builder.system(mu);
    return floquet_exponents(transition(sys).phi, sys.trace_integral());
  }

  FloquetFunction function() const {
    return [this](double mu) { return floquet(mu); };
  }

  TransitionOptions options;
  detail::SystemBuilder builder;
  HoverResult hover;
  HoverModes hover_modes;
  std::string resolution_warning;
};

Analysis::Analysis(const RotorParameters& params, const TransitionOptions& options)
    : impl_(std::make_unique<Impl>(params, options)) {}
Analysis::~Analysis() = default;
Analysis::Analysis(Analysis&&) noexcept = default;
Analysis& Analysis::operator=(Analysis&&) noexcept = default;

const RotorParameters& Analysis::parameters() const { return impl_->builder.params(); }
const TransitionOptions& Analysis::options() const { return impl_->options; }
const model::ModelDescriptor& Analysis::model() const { return impl_->builder.model(); }
const ModeSet& Analysis::modes() const { return impl_->builder.modes(); }
const HoverResult& Analysis::hover() const { return impl_->hover; }

PeriodicSystem Analysis::system(double mu) const {
  check_mu(mu, "--mu");
  return impl_->builder.system(mu);
}

SystemSnapshot Analysis::snapshot(double mu, double psi) const {
  check_mu(mu, "--mu");
  if (!std::isfinite(psi)) throw InvalidInput("--psi", round_trip_text(psi), "must be finite");
  SystemSnapshot s;
  s.mu = mu;
  s.psi = psi;
  const PeriodicSystem sys = impl_->builder.system(mu);
  const bool reversed = sys.has_sector && sys.in_sector(psi);
  s.region = reversed ? "reversed" : "normal";
  s.A = sys.A(psi);
  s.f = sys.f(psi);
  const auto& m = impl_->builder.model();
  const auto& normal = impl_->builder.normal_integrals();
  const std::vector<double> region = reversed ? impl_->builder.reversed_integrals(mu) : normal;
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
  check_mu(mu, "--mu");
  if (!(scan_step > 0.0) || !std::isfinite(scan_step)) {
    throw InvalidInput("--step", round_trip_text(scan_step), "must be finite and > 0");
  }
  const ExponentSweep sw =
      sweep_exponents(impl_->hover_modes, impl_->function(), mu, mu, scan_step);
  PointResult r;
  r.mu = mu;
  r.status = sw.status;
  r.message = sw.message;
  if (sw.points.empty()) {
    r.status = Status::Failed;
    if (r.message.empty()) r.message = "continuation from hover failed";
    return r;
  }
  const SweepPoint& p = sw.points.back();
  r.exponents = to_modes(p.exponents);
  r.liouville_residual = p.liouville_residual;
  r.stable = p.stable;
  if (impl_->options.method == TransitionMethod::Magnus4) {
    r.error_estimate = impl_->transition(impl_->builder.system(mu)).error_estimate;
  }
  impl_->flag(r);
  return r;
}

SweepResult Analysis::sweep(double mu0, double mu1, double step) const {
  check_mu(mu0, "--mu (start)");
  check_mu(mu1, "--mu (end)");
  if (!(step > 0.0) || !std::isfinite(step)) {
    throw InvalidInput("--mu (step)", round_trip_text(step), "step must be finite and > 0");
  }
  if (!(mu1 > mu0)) {
    throw InvalidInput("--mu", round_trip_text(mu0) + ":" + round_trip_text(mu1),
                       "empty or reversed range (end must exceed start)");
  }
  const ExponentSweep sw = sweep_exponents(impl_->hover_modes, impl_->function(), mu0, mu1, step);
  SweepResult r;
  r.status = sw.status;
  r.message = sw.message;
  for (const auto& p : sw.points) {
    PointResult q;
    // mu0 + k step accumulates rounding (0.7999999999999999); report the decimal grid value.
    q.mu = std::stod(snap12(p.mu));
    q.exponents = to_modes(p.exponents);
    q.liouville_residual = p.liouville_residual;
    q.stable = p.stable;
    q.status = p.status;
    q.message = p.message;
    r.points.push_back(std::move(q));
  }
  impl_->flag(r);
  return r;
}

CriticalResult Analysis::critical(const CriticalOptions& opt) const {
  if (!(opt.mu_max > 0.0) || !std::isfinite(opt.mu_max)) {
    throw InvalidInput("--mu-max", round_trip_text(opt.mu_max), "must be finite and > 0");
  }
  if (!(opt.scan_step > 0.0) || !std::isfinite(opt.scan_step)) {
    throw InvalidInput("--scan-step", round_trip_text(opt.scan_step), "must be finite and > 0");
  }
  if (!(opt.tolerance > 0.0) || !std::isfinite(opt.tolerance)) {
    throw InvalidInput("--tolerance", round_trip_text(opt.tolerance), "must be finite and > 0");
  }
  CriticalSearchOptions o;
  o.mu_max = opt.mu_max;
  o.step = opt.scan_step;
  o.tolerance = opt.tolerance;
  const CriticalSearchResult c = find_critical(impl_->hover_modes, impl_->function(), o);
  CriticalResult r;
  r.found = c.found;
  r.mu_c = c.mu_c;
  r.mode = c.label;
  // A conjugate pair crosses together; report the member with omega >= 0.
  r.omega = std::abs(c.omega);
  r.kind = c.kind;
  r.mu_max = c.mu_max;
  r.status = c.status;
  r.message = c.message;
  impl_->flag(r);
  return r;
}

}  // namespace flaplag
