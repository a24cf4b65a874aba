#include "flaplag/analysis.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

#include "flaplag/blade/imported_modes.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/core/parallel.h"
#include "flaplag/numerics/continuation.h"
#include "flaplag/numerics/floquet_evaluator.h"
#include "flaplag/rotor/system_builder.h"
#include "flaplag/rotor/validity.h"
#include "fold.h"
#include "internal.h"
#include "trimmed.h"

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

namespace {

// Names of the models that one family per spec replaced: every model now has cyclic pitch, the
// rotor thrust and the nonlinear loads.
const char* replaced_model(const std::string& name) {
  if (name == "paper-cyclic" || name == "paper-nonlinear" || name == "paper-cyclic-nonlinear")
    return "paper";
  if (name == "paper-cyclic-2x2") return "paper-2x2";
  return nullptr;
}

const model::ModelFamily* find_family(const std::string& name) {
  for (const model::ModelFamily* f : model::registered_families())
    if (name == f->name) return f;
  return nullptr;
}

std::string family_names() {
  std::string known;
  for (const model::ModelFamily* f : model::registered_families())
    known += (known.empty() ? "" : ", ") + std::string(f->name);
  return known;
}

// "<family>-<M>x<N>" with one- or two-digit counts: the family and the counts, or nullptr.
const model::ModelFamily* sized_name(const std::string& name, int* M, int* N) {
  const auto dash = name.rfind('-');
  if (dash == std::string::npos) return nullptr;
  const std::string size = name.substr(dash + 1);
  const auto x = size.find('x');
  if (x == std::string::npos || x == 0 || x > 2 || size.size() - x - 1 < 1 ||
      size.size() - x - 1 > 2 || size.find_first_not_of("0123456789x") != std::string::npos ||
      size.find('x', x + 1) != std::string::npos)
    return nullptr;
  *M = std::stoi(size.substr(0, x));
  *N = std::stoi(size.substr(x + 1));
  return find_family(name.substr(0, dash));
}

}  // namespace

const model::ModelDescriptor& find_model(const std::string& name) {
  if (const char* now = replaced_model(name)) return find_model(now);
  if (const model::ModelFamily* f = find_family(name))
    return model::instantiate(*f, f->default_flap_modes, f->default_lag_modes);
  int M = 0, N = 0;
  if (const model::ModelFamily* f = sized_name(name, &M, &N)) return find_model(f->name, M, N);
  throw InvalidInput("model", name,
                     "unknown model (models: " + family_names() +
                         "; each also as <model>-<M>x<N> for M flap x N lag modes, 1.." +
                         std::to_string(model::kMaxModes) + ")");
}

const model::ModelDescriptor& find_model(const std::string& base, int flap_modes, int lag_modes) {
  const model::ModelFamily* f = find_family(base);
  if (!f) throw InvalidInput("model", base, "unknown model (models: " + family_names() + ")");
  for (const int m : {flap_modes, lag_modes}) {
    if (m < 1 || m > model::kMaxModes) {
      throw InvalidInput(m == flap_modes ? "flap modes" : "lag modes", std::to_string(m),
                         "must be 1.." + std::to_string(model::kMaxModes) +
                             " (the Galerkin basis of the exact rotating modes)");
    }
  }
  return model::instantiate(*f, flap_modes, lag_modes);
}

namespace {

using internal::check_mu;
using internal::sort_for_output;

// response, simulate and snapshot are of the hover-linearized system: about the periodic
// equilibrium they would silently answer another question than the one asked.
void require_hover_linearization(const OperatingCondition& c, const char* what) {
  if (!c.periodic()) return;
  throw InvalidInput("linearization", enum_name(c.linearization),
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

}  // namespace

struct Analysis::Impl {
  Impl(const RotorParameters& p, const TransitionOptions& o, const OperatingCondition& c,
       bool with_reference = true)
      : options(o),
        given_options(o),
        given_params(p),
        condition(checked(c)),
        trim_in_hover(c.trimmed() ? std::optional<TrimResult>(
                                        internal::hover_trim(p, o, c.trim, c.linearization))
                                  : std::nullopt),
        builder(trim_in_hover ? trim_in_hover->parameters : p, find_model(p.model),
                trim_in_hover ? InflowModel::Given(trim_in_hover->inflow) : c.inflow),
        // q° has the sector form only: refused after the parameters' own checks (the builder's)
        // and before the options'.
        evaluator((internal::require_sector(builder.params(), c.linearization),
                   FloquetEvaluator::Create(o, builder.state_size()))) {
    options = evaluator->options();  // an automatic method resolved for this model's size
    hover = builder.hover();
    const auto& m = builder.model();
    hover_modes = label_hover_modes(hover.A0, m.flap_modes, m.lag_modes);
    hover.eigenvalues = hover_modes.eigenvalues;
    hover.labels = hover_modes.labels;
    if (hover_modes.status != Status::Ok && hover.status == Status::Ok) {
      hover.status = hover_modes.status;
      hover.message = hover_modes.message;
    }
    for (const model::DirectionBlock& b : model::direction_blocks(m.flap_modes, m.lag_modes))
      for (int k = 0; k < b.modes && b.first_coordinate + k < hover.q0.size(); ++k)
        hover.equilibrium.emplace_back(std::string(b.coordinate) + "0_" + std::to_string(k + 1),
                                       hover.q0(b.first_coordinate + k));
    check_finite(hover);
    validity = internal::validity_of(builder);
    if (trim_in_hover)
      trimmed = std::make_shared<const internal::TrimmedContinuation>(p, o, c.trim, c.linearization,
                                                                      *trim_in_hover, hover_modes);
    if (with_reference) basis = internal::basis_check(p, m.flap_modes, m.lag_modes);
    if (p.mode_shapes) {
      const double defect = mass_orthogonality_defect(builder.modes());
      if (defect > kMassOrthogonalityWarning) {
        modes_note =
            "the imported mode shapes (" + p.mode_shapes->source +
            ") are not mass-orthogonal: the largest normalised generalized mass "
            "between two shapes of one direction is " +
            short_text(defect) + " (above " + short_text(kMassOrthogonalityWarning) +
            "), so they are not modes of one blade with the mass distribution of the model";
      }
    }
  }

  // The same blade with the neighbouring basis of the exact modes (internal::BasisCheck),
  // built at its first use: an Analysis that only evaluates Floquet samples (a trim's, at every
  // evaluation) never builds it.  Null without one (basis.problem then says why).
  const Analysis* reference() const {
    std::call_once(reference_once, [this] {
      if (basis.reference == 0) return;
      try {
        reference_analysis = std::unique_ptr<Analysis>(new Analysis(std::make_unique<Impl>(
            basis.reference_parameters(given_params), given_options, condition, false)));
      } catch (const InvalidInput& e) {
        basis.problem =
            "with " + std::to_string(basis.reference) + " cantilever functions: " + e.what();
        basis.reference = 0;
      }
    });
    return reference_analysis.get();
  }

  // With exact modes: r's basis error, from the same result with the reference basis
  // (compute(reference)), folded into r (internal::BasisCheck::fold) at `tolerance`.
  template <class Result, class Compute>
  void fold_basis(Result& r, double tolerance, const Compute& compute) const {
    if (basis.basis == 0) return;
    fold_reference(r, tolerance, reference_result(compute));
  }

  // The result of compute with the reference basis, none without a reference.
  template <class Compute>
  auto reference_result(const Compute& compute) const {
    using Result = decltype(compute(*reference()));
    const Analysis* ref = reference();
    return ref ? std::optional<Result>(compute(*ref)) : std::nullopt;
  }

  template <class Result>
  void fold_reference(Result& r, double tolerance, const std::optional<Result>& other) const {
    internal::BasisCheck c = basis;
    c.tolerance_ = tolerance;
    c.fold(r, other ? &*other : nullptr);
  }

  // fold_basis for a result computed with `self` (this Impl's Analysis) by compute: the
  // reference's computation runs on a thread of its own while this one runs when `threads`
  // (core/parallel.h) gives two or more.  The results are the same either way.
  template <class Compute>
  auto with_basis_error(const Analysis& self, double tolerance, int threads,
                        const Compute& compute) const {
    using Result = decltype(compute(self));
    if (basis.basis == 0 || thread_count(threads) < 2) {
      Result r = compute(self);
      fold_basis(r, tolerance, compute);
      return r;
    }
    std::future<std::optional<Result>> beside =
        std::async(std::launch::async, [&] { return reference_result(compute); });
    Result r = compute(self);
    fold_reference(r, tolerance, beside.get());
    return r;
  }

  // The passes over a sweep or track: 2 when the reference basis is computed too (their
  // progress counts both, internal::pass_progress).
  int passes() const { return basis.basis != 0 && reference() != nullptr ? 2 : 1; }

  // About the periodic equilibrium: q° at every mu evaluated (the last one there, without its
  // linearization; Failed where there is none), for the results to carry.  Shared by the
  // stretches of a sweep or track.
  struct Equilibria {
    std::mutex mutex;
    std::map<double, PeriodicEquilibrium> by_mu;
    void add(double mu, const PeriodicEquilibrium& eq) {
      const std::lock_guard<std::mutex> lock(mutex);
      by_mu[mu] = internal::without_linearization(eq);
    }
    std::optional<PeriodicEquilibrium> at(double mu) {
      const std::lock_guard<std::mutex> lock(mutex);
      const auto it = by_mu.find(mu);
      return it == by_mu.end() ? std::nullopt : std::optional<PeriodicEquilibrium>(it->second);
    }
  };
  std::shared_ptr<Equilibria> recorder() const {
    return condition.periodic() ? std::make_shared<Equilibria>() : nullptr;
  }

  // What one continuation's evaluations carry from one mu to the next (function()).
  struct Continuation {
    StepsHint hint;
    PeriodicSystem system;  // storage reused at every mu
    // About the periodic equilibrium: the equilibria that were not clean (status Warning), by
    // mu, with their message (what a result at that mu rests on).
    std::map<double, std::string> unclean_equilibria;
    std::shared_ptr<Equilibria> equilibria;  // null: q° not recorded
  };

  FloquetSample floquet(double mu, double zeta_tolerance, Continuation* c = nullptr) const {
    StepsHint* hint = c != nullptr ? &c->hint : nullptr;
    // The linear system about hover (the paper) or about the periodic equilibrium.
    if (condition.periodic()) {
      PeriodicEquilibrium eq = equilibrium(mu);
      if (c != nullptr && c->equilibria) c->equilibria->add(mu, eq);
      if (eq.status == Status::Failed) {
        FloquetSample out;
        out.status = Status::Failed;
        out.message = eq.message;
        return out;
      }
      if (c != nullptr && eq.status != Status::Ok && c->unclean_equilibria.size() < 4096)
        c->unclean_equilibria[mu] = eq.message;
      return evaluator->evaluate(eq.linearization, zeta_tolerance, hint, eq.message);
    }
    if (c == nullptr) return evaluator->evaluate(builder.system(mu), zeta_tolerance, hint);
    builder.system(mu, &c->system);
    return evaluator->evaluate(c->system, zeta_tolerance, hint);
  }

  FloquetFunction function(std::shared_ptr<Continuation> c = nullptr,
                           std::shared_ptr<Equilibria> record = nullptr) const {
    if (!c) c = std::make_shared<Continuation>();
    if (record) c->equilibria = std::move(record);
    return [this, c](double mu, double tol) { return floquet(mu, tol, c.get()); };
  }

  // A sweep or track in stretches (Analysis::sweep).  The periodic equilibria of one Analysis
  // share a cache of starts, so their stretches run in order.
  // About the periodic equilibrium the q° of the points are in *equilibria (one per point, in
  // order).
  SweepResult track(const std::vector<double>& mus, double step, int threads,
                    const std::atomic<bool>* cancel, const ProgressFunction& progress,
                    std::vector<PeriodicEquilibrium>* equilibria) const {
    if (auto p = threads_problem(threads)) throw *p;
    const int used = condition.periodic() ? 1 : threads;
    const std::shared_ptr<Equilibria> record = recorder();
    SweepResult r;
    if (cancel == nullptr && !progress) {
      r = track_exponents(
          hover_modes, [this, record] { return function(nullptr, record); }, mus, step,
          options.zeta_tolerance, used);
    } else {
      // Every function of the stretches counts its evaluations into one ticker.
      auto ticker = std::make_shared<internal::Ticker>(mus, step, cancel, progress);
      auto make = [this, ticker, record] {
        return internal::ticking(function(nullptr, record), ticker);
      };
      r = track_exponents(hover_modes, make, mus, step, options.zeta_tolerance, used);
    }
    if (record) {
      for (const PointResult& p : r.points) equilibria->push_back(equilibrium_at(*record, p.mu));
    }
    return r;
  }

  // The recorded q° at mu, or a Failed one saying that there is none.
  static PeriodicEquilibrium equilibrium_at(Equilibria& record, double mu) {
    if (std::optional<PeriodicEquilibrium> eq = record.at(mu)) return std::move(*eq);
    PeriodicEquilibrium none;
    none.mu = mu;
    none.status = Status::Failed;
    none.message = "no periodic equilibrium was evaluated at mu = " + round_trip_text(mu);
    return none;
  }

  // A point with fixed controls: continued from hover, no better than the validity envelope.
  RotorPoint point(double mu, double scan_step) const {
    const std::shared_ptr<Equilibria> record = recorder();
    RotorPoint r =
        internal::point_at_end(sweep_exponents(hover_modes, function(nullptr, record), mu, mu,
                                               scan_step, options.zeta_tolerance),
                               mu);
    if (record) r.equilibrium = record->at(mu);
    if (r.status != Status::Failed)
      r.Worsen(validity.empty() ? Status::Ok : Status::Warning, validity);
    sort_for_output(r.exponents);
    return r;
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

  static const OperatingCondition& checked(const OperatingCondition& c) {
    ThrowIfInvalid(c.Validate());
    return c;
  }

  TransitionOptions options;
  TransitionOptions given_options;  // as given (options: the automatic method resolved)
  RotorParameters given_params;     // as given (trimmed: the builder's are the hover trim's)
  OperatingCondition condition;
  std::optional<TrimResult> trim_in_hover;  // trimmed: the trim at mu = 0
  // The rotor at the trim in hover when trimmed (its modes label the exponents), else as given.
  detail::SystemBuilder builder;
  // The method and its step control (Create checks the options, after the parameters).
  std::unique_ptr<const FloquetEvaluator> evaluator;
  mutable std::mutex cache_mutex;
  mutable std::map<double, PeriodicEquilibrium> cache;
  // The harmonic balance behind the periodic linearization (stability from the analysis).
  PeriodicEquilibriumOptions equilibrium_options = internal::equilibrium_options();
  HoverResult hover;
  HoverModes hover_modes;
  std::string validity;  // rotor/validity.h: "" inside the envelope
  // Exact modes: the basis and the one compared with (reference() may find it cannot be built).
  mutable internal::BasisCheck basis;
  mutable std::once_flag reference_once;
  mutable std::unique_ptr<Analysis> reference_analysis;  // the blade with that basis, or null

  // Trimmed: the continuation that trims at every mu; null with fixed controls.
  std::shared_ptr<const internal::TrimmedContinuation> trimmed;

  // Imported mode shapes that are not mass-orthogonal: a note on every result ("": none).
  std::string modes_note;
  void note_modes(Outcome& r) const {
    if (!modes_note.empty()) r.Note(modes_note);
  }

  // Outside the validity envelope every result is a Warning that says so.
  void outside_envelope(CriticalResult& r) const {
    if (validity.empty() || r.status == Status::Failed) return;
    r.Worsen(Status::Warning, validity);
  }
  void outside_envelope(SweepResult& r) const {
    if (validity.empty()) return;
    for (PointResult& p : r.points)
      if (p.status != Status::Failed) p.Worsen(Status::Warning, validity);
    if (r.status == Status::Ok) {
      r.status = Status::Warning;
      r.message = validity;
    }
  }
};

const TipMotion& tip_motion(const std::vector<TipMotion>& tips, const std::string& direction) {
  for (const TipMotion& t : tips)
    if (t.direction == direction) return t;
  throw InvalidInput("direction", direction, "is not a direction of this result");
}

const PeriodicEquilibrium* RotorPoint::periodic_equilibrium() const {
  if (equilibrium) return &*equilibrium;
  if (trim && trim->linearization == Linearization::PeriodicEquilibrium) return &trim->equilibrium;
  return nullptr;
}

const PeriodicEquilibrium* RotorCritical::periodic_equilibrium() const {
  if (equilibrium) return &*equilibrium;
  if (trim && trim->linearization == Linearization::PeriodicEquilibrium) return &trim->equilibrium;
  return nullptr;
}

std::optional<InvalidInput> OperatingCondition::Validate() const {
  if (trimmed() && inflow.kind != InflowKind::Uniform) {
    return InvalidInput("inflow", enum_name(inflow.kind),
                        "given with a trim: each trim has its own eq 2.25 inflow");
  }
  if (trimmed()) return trim.Validate();
  return inflow.Validate();
}

Analysis::Analysis(const RotorParameters& params, const TransitionOptions& options,
                   const OperatingCondition& condition)
    : impl_(std::make_unique<Impl>(params, options, condition)) {}
Analysis::Analysis(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Analysis::~Analysis() = default;
Analysis::Analysis(Analysis&&) noexcept = default;
Analysis& Analysis::operator=(Analysis&&) noexcept = default;

const RotorParameters& Analysis::parameters() const { return impl_->builder.params(); }
const TransitionOptions& Analysis::options() const { return impl_->options; }
const OperatingCondition& Analysis::condition() const { return impl_->condition; }

void Analysis::require_fixed_controls(const char* what) const {
  if (!impl_->trimmed) return;
  throw InvalidInput("trim", trim_kind_name(impl_->condition.trim.kind),
                     std::string(what) +
                         " is of fixed controls: use an Analysis at the trim's controls "
                         "(OperatingCondition::At)");
}
const model::ModelDescriptor& Analysis::model() const { return impl_->builder.model(); }
const ModeSet& Analysis::modes() const { return impl_->builder.modes(); }
const HoverResult& Analysis::hover() const { return impl_->hover; }
const std::string& Analysis::validity() const { return impl_->validity; }

PeriodicSystem Analysis::system(double mu) const {
  require_fixed_controls("the periodic system");
  check_mu(mu, "mu");
  return impl_->builder.system(mu);
}

PeriodicEquilibrium Analysis::periodic_equilibrium(
    double mu, const PeriodicEquilibriumOptions& options) const {
  require_fixed_controls("the periodic equilibrium");
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
  return impl_->evaluator->evaluate(equilibrium.linearization, zeta_tolerance, nullptr,
                                    equilibrium.message);
}

FloquetSample Analysis::floquet(double mu, double zeta_tolerance) const {
  require_fixed_controls("a single Floquet evaluation");
  check_mu(mu, "mu");
  if (!(std::isfinite(zeta_tolerance) && zeta_tolerance > 0.0))
    throw InvalidInput("zeta_tolerance", round_trip_text(zeta_tolerance), "must be > 0");
  return impl_->floquet(mu, zeta_tolerance);
}

ForcedResponse Analysis::response(double mu, const ResponseOptions& options) const {
  require_fixed_controls("the periodic forced response");
  check_mu(mu, "mu");
  require_hover_linearization(impl_->condition, "the periodic forced response");
  options.Check();
  ForcedResponse out;
  out.mu = mu;
  out.periodic = periodic_response(impl_->builder.system(mu), options);
  out.status = out.periodic.status;
  out.message = out.periodic.message;
  const int M = model().flap_modes, N = model().lag_modes;
  out.tips = internal::tip_motions(M, N);  // empty motions when failed
  if (out.status == Status::Failed) return out;
  for (const Eigen::VectorXd& y : out.periodic.y)
    internal::append_deflections(
        out.tips, internal::tip_deflections(impl_->builder.modes(), M, N, y, &impl_->hover.q0));
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
  for (TipMotion& t : out.tips) t.harmonics = harmonics(t.deflection);
  return out;
}

TipSimulation Analysis::simulate(double mu, const Eigen::VectorXd& y0, bool forced,
                                 const SimulationOptions& options) const {
  require_fixed_controls("the simulation");
  check_mu(mu, "mu");
  if (options.nonlinear) return simulate_nonlinear(mu, y0, forced, options);
  require_hover_linearization(impl_->condition, "the time-domain simulation");
  TipSimulation out;
  out.mu = mu;
  out.simulation = flaplag::simulate(impl_->builder.system(mu), y0, forced, options);
  const Simulation& s = out.simulation;
  const int M = model().flap_modes, N = model().lag_modes;
  out.tips = internal::tip_motions(M, N);
  for (const Eigen::VectorXd& y : s.y)
    internal::append_deflections(out.tips,
                                 internal::tip_deflections(impl_->builder.modes(), M, N, y));
  // The first quarter holds the transient of the other modes.
  for (TipMotion& t : out.tips)
    t.growth_rate = envelope_growth_rate(s.psi, t.deflection, 0.25 * options.revolutions);
  out.status = s.status;
  out.message = s.message;
  return out;
}

TipSimulation Analysis::simulate_nonlinear(double mu, const Eigen::VectorXd& y0, bool forced,
                                           const SimulationOptions& options) const {
  const model::ModelDescriptor& m = model();
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
  out.tips = internal::tip_motions(M, N);
  for (std::size_t k = 0; k < s.y.size(); ++k) {
    const Eigen::VectorXd ref = reference(s.psi[k]);
    internal::append_deflections(
        out.tips, internal::tip_deflections(impl_->builder.modes(), M, N, s.y[k] - ref));
    const std::vector<double> total =
        internal::tip_deflections(impl_->builder.modes(), M, N, s.y[k]);
    for (std::size_t i = 0; i < out.tips.size(); ++i) out.tips[i].total.push_back(total[i]);
  }
  for (TipMotion& t : out.tips)
    t.growth_rate = envelope_growth_rate(s.psi, t.deflection, 0.25 * options.revolutions);
  out.Merge(s);
  if (out.IsUsable() && eq.status != Status::Ok) {
    out.Worsen(Status::Warning, periodic ? "the reference periodic equilibrium: " + eq.message
                                         : eq.message +
                                               "; the simulation starts from and is measured "
                                               "against the hover equilibrium");
  }
  return out;
}

int Analysis::state_size() const { return impl_->builder.state_size(); }

std::vector<double> Analysis::tip_deflections(const Eigen::VectorXd& y) const {
  if (y.size() != state_size())
    throw InvalidInput("y", std::to_string(y.size()) + " values",
                       "must be " + std::to_string(state_size()) + " values");
  return internal::tip_deflections(modes(), model().flap_modes, model().lag_modes, y);
}

std::vector<TipMotion> Analysis::tip_motions() const {
  return internal::tip_motions(model().flap_modes, model().lag_modes);
}

SystemSnapshot Analysis::snapshot(double mu, double psi) const {
  require_fixed_controls("the system snapshot");
  check_mu(mu, "mu");
  require_hover_linearization(impl_->condition, "the system snapshot");
  if (!std::isfinite(psi)) throw InvalidInput("psi", round_trip_text(psi), "must be finite");
  SystemSnapshot s;
  s.mu = mu;
  s.psi = psi;
  const PeriodicSystem sys = impl_->builder.system(mu);
  const int set = sys.pieces[static_cast<std::size_t>(sys.piece_at(psi))].set;
  const bool exact = set < 0;
  const bool reversed = set != 0;
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
    s.aero_paper_names.push_back(m.aero[j].paper_name);
  }
  const auto& st = impl_->builder.structural_values();
  for (int j = 0; j < m.n_structural; ++j) {
    s.structural_integrals.emplace_back(m.structural[j].name, st[j]);
    s.structural_paper_names.push_back(m.structural[j].paper_name);
  }
  for (Eigen::Index col = 0; col < s.A.cols(); ++col)
    s.states.push_back(model::state_name(static_cast<int>(col), m.flap_modes, m.lag_modes));
  if (!s.A.allFinite() || !s.f.allFinite())
    s.Worsen(Status::Failed, "non-finite entries of A(psi) or f(psi) (not shown)");
  bool integrals_ok = true;
  for (const auto* v : {&s.aero_integrals, &s.aero_integrals_region, &s.structural_integrals})
    for (const auto& [name, value] : *v) integrals_ok = integrals_ok && std::isfinite(value);
  if (!integrals_ok) s.Worsen(Status::Failed, "non-finite spanwise integrals (not shown)");
  return s;
}

std::vector<AeroIntegral> snapshot_aero_integrals(const SystemSnapshot& s) {
  std::vector<AeroIntegral> out;
  for (std::size_t i = 0; i < s.aero_integrals.size(); ++i) {
    out.push_back({s.aero_integrals[i].first,
                   i < s.aero_paper_names.size() ? s.aero_paper_names[i] : "",
                   s.aero_integrals[i].second, std::nullopt});
    if (i < s.aero_integrals_region.size()) out.back().at_psi = s.aero_integrals_region[i].second;
  }
  return out;
}

std::vector<StructuralIntegral> snapshot_structural_integrals(const SystemSnapshot& s) {
  std::vector<StructuralIntegral> out;
  for (std::size_t i = 0; i < s.structural_integrals.size(); ++i)
    out.push_back({s.structural_integrals[i].first,
                   i < s.structural_paper_names.size() ? s.structural_paper_names[i] : "",
                   s.structural_integrals[i].second});
  return out;
}

RotorPoint Analysis::point(double mu, double scan_step) const {
  check_mu(mu, "mu");
  if (!(scan_step > 0.0) || !std::isfinite(scan_step)) {
    throw InvalidInput("scan_step", round_trip_text(scan_step), "must be finite and > 0");
  }
  if (mu / scan_step > static_cast<double>(kMaxContinuationSteps)) {
    throw InvalidInput("scan_step", round_trip_text(scan_step),
                       "too small: at most " + std::to_string(kMaxContinuationSteps) +
                           " continuation steps from hover");
  }
  RotorPoint r =
      impl_->trimmed ? impl_->trimmed->point(mu, scan_step) : impl_->point(mu, scan_step);
  impl_->fold_basis(r, impl_->options.zeta_tolerance,
                    [&](const Analysis& ref) { return ref.point(mu, scan_step); });
  impl_->note_modes(r);
  return r;
}

RotorSweep Analysis::sweep(double mu0, double mu1, double step, int threads) const {
  return sweep(mu0, mu1, step, threads, nullptr, {});
}

RotorSweep Analysis::sweep(double mu0, double mu1, double step, int threads,
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
  const int passes = impl_->passes();
  const ProgressFunction first = internal::pass_progress(progress, 0, passes);
  RotorSweep r;
  if (impl_->trimmed) {
    r = impl_->trimmed->sweep(mu0, mu1, step, cancel, first);
  } else {
    static_cast<SweepResult&>(r) =
        impl_->track(sweep_grid(mu0, mu1, step), step, threads, cancel, first, &r.equilibria);
    for (PointResult& p : r.points) {
      // mu0 + k step accumulates rounding (0.7999999999999999); report the decimal grid value.
      p.mu = snap12(p.mu);
      sort_for_output(p.exponents);
    }
    impl_->outside_envelope(r);
  }
  impl_->fold_basis(r, impl_->options.zeta_tolerance, [&](const Analysis& ref) {
    return ref.sweep(mu0, mu1, step, threads, cancel, internal::pass_progress(progress, 1, passes));
  });
  impl_->note_modes(r);
  return r;
}

RotorSweep Analysis::track(const std::vector<double>& mus, double scan_step, int threads) const {
  return track(mus, scan_step, threads, nullptr, {});
}

RotorSweep Analysis::track(const std::vector<double>& mus, double scan_step, int threads,
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
  const int passes = impl_->passes();
  const ProgressFunction first = internal::pass_progress(progress, 0, passes);
  RotorSweep r;
  if (impl_->trimmed) {
    r = impl_->trimmed->track(mus, scan_step, cancel, first);
  } else {
    static_cast<SweepResult&>(r) =
        impl_->track(mus, scan_step, threads, cancel, first, &r.equilibria);
    for (PointResult& p : r.points) sort_for_output(p.exponents);
    impl_->outside_envelope(r);
  }
  impl_->fold_basis(r, impl_->options.zeta_tolerance, [&](const Analysis& ref) {
    return ref.track(mus, scan_step, threads, cancel, internal::pass_progress(progress, 1, passes));
  });
  impl_->note_modes(r);
  return r;
}

RotorCritical Analysis::critical(const CriticalOptions& opt, int threads) const {
  if (const std::optional<InvalidInput> problem = threads_problem(threads)) throw *problem;
  opt.Check();
  RotorCritical r = impl_->with_basis_error(*this, opt.tolerance, threads, [&](const Analysis& an) {
    return an.critical_with_this_basis(opt);
  });
  impl_->note_modes(r);
  return r;
}

RotorCritical Analysis::critical_with_this_basis(const CriticalOptions& opt) const {
  if (impl_->trimmed) return impl_->trimmed->critical(opt);
  opt.Check();
  CriticalOptions o = opt;
  o.scan_zeta_tolerance = std::min(opt.scan_zeta_tolerance, impl_->options.zeta_tolerance);
  RotorCritical r;
  if (!impl_->condition.periodic()) {
    static_cast<CriticalResult&>(r) = find_critical(impl_->hover_modes, impl_->function(), o);
    sort_for_output(r.exponents);
    impl_->outside_envelope(r);
    return r;
  }
  // About the periodic equilibrium the search can end at a fold of its branch (fold.h).
  const internal::FoldWatch watch;
  const auto continuation = std::make_shared<Impl::Continuation>();
  continuation->equilibria = std::make_shared<Impl::Equilibria>();
  static_cast<CriticalResult&>(r) =
      find_critical(impl_->hover_modes, watch.wrap(impl_->function(continuation)), o);
  std::optional<PeriodicEquilibrium> last;
  std::map<double, PeriodicEquilibrium> found;  // the probes' q°, where it exists
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
    found[mu] = internal::without_linearization(eq);
    last = std::move(eq);
    return true;
  };
  internal::report_fold(r, watch, probe, o);
  sort_for_output(r.exponents);
  // The q° at mu_c: the search's; at a fold (beyond which there is none) the last one found
  // below it, at the lower end of the fold's bracket.
  if (r.mu_c) {
    r.equilibrium = continuation->equilibria->at(*r.mu_c);
    const auto below = found.upper_bound(*r.mu_c);
    if ((!r.equilibrium || r.equilibrium->status == Status::Failed) && below != found.begin())
      r.equilibrium = std::prev(below)->second;
  }
  // mu_c (and every interval end) is no better than the periodic equilibrium there.
  if (r.status != Status::Failed) {
    for (const InstabilityInterval& iv : r.intervals) {
      for (const std::optional<double>& at : {std::optional<double>(iv.onset), iv.end}) {
        if (!at) continue;
        const auto it = continuation->unclean_equilibria.find(*at);
        if (it == continuation->unclean_equilibria.end()) continue;
        r.Worsen(Status::Warning, "the periodic equilibrium at mu = " + round_trip_text(*at) +
                                      ", where the result is found: " + it->second);
      }
    }
  }
  impl_->outside_envelope(r);
  return r;
}

}  // namespace flaplag
