// Rotor thrust and trim: see trim.h for what is computed and at which order.
#include "flaplag/trim.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>

#include "flaplag/analysis.h"
#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/numerics/brent.h"
#include "flaplag/numerics/continuation.h"
#include "flaplag/rotor/hover.h"
#include "flaplag/rotor/periodic_equilibrium.h"
#include "flaplag/rotor/system_builder.h"
#include "internal.h"

namespace flaplag {

namespace {

void check_mu(double mu) { internal::check_mu(mu, "mu"); }
using internal::sort_for_output;

// Value of one region's thrust at psi for state y.
double thrust_at(const detail::ThrustHarmonics& t, double psi, const Eigen::VectorXd& y) {
  double v = 0.0;
  for (std::size_t h = 0; h < t.t.size(); ++h) {
    v += harmonic_basis(static_cast<int>(h), psi) * (t.t[h] + t.tau[h].dot(y));
  }
  return v;
}

// (1/2 pi) int_0^2pi T(psi, y(psi)) dpsi along the periodic solution from y0 (numerics'
// periodic_mean: RK4 on [y; int T] on the grid of the periodic response).
double mean_thrust(const PeriodicSystem& sys, const detail::ThrustSystem& ts,
                   const Eigen::VectorXd& y0, int steps) {
  return periodic_mean(sys, y0, steps, [&](double psi, bool reversed, const Eigen::VectorXd& y) {
    return thrust_at(reversed ? ts.reversed : ts.normal, psi, y);
  });
}

// About the periodic equilibrium (Linearization::PeriodicEquilibrium): thrust and first flap
// harmonic of the nonlinear periodic equilibrium q°(psi) (the harmonic balance of Analysis,
// continued in mu from hover on the branch through the hover equilibrium). `warm` (in/out, may be
// null): a previous evaluation's equilibrium to continue from (a nearby pitch or mu), replaced by
// this one's when it succeeds.
ThrustResult evaluate_periodic(const RotorParameters& p, const model::ModelDescriptor& m, double mu,
                               double inflow, PeriodicEquilibrium* warm) {
  ThrustResult out;
  out.mu = mu;
  const detail::SystemBuilder builder(p, m, InflowModel::Given(inflow));
  internal::require_sector(p, Linearization::PeriodicEquilibrium);
  out.inflow = builder.inflow();
  if (builder.hover().status == Status::Failed) {
    out.status = Status::Failed;
    out.message = builder.hover().message;
    return out;
  }
  const bool has_start = warm != nullptr && warm->coefficients.size() > 0;
  PeriodicEquilibrium eq = periodic_equilibrium(builder, mu, internal::equilibrium_options(),
                                                has_start ? warm : nullptr);
  if (eq.status == Status::Failed) {
    out.status = Status::Failed;
    out.message = eq.message;
    return out;
  }
  out.thrust_coefficient = 0.5 * p.sigma * p.lift_slope * eq.mean_thrust;
  // First harmonic of the flap tip deflection of q°: its cos psi and sin psi coefficients.
  for (int k = 0; k < m.flap_modes; ++k) {
    const double tip = builder.modes().shapes(model::Direction::Flap)[k]->value(0, 1.0);
    out.flap_1c += tip * eq.coefficients(k, 1);
    out.flap_1s += tip * eq.coefficients(k, 2);
  }
  if (!std::isfinite(out.thrust_coefficient)) {
    out.status = Status::Failed;
    out.message = "the thrust overflowed at mu = " + round_trip_text(mu);
  } else if (eq.status == Status::Warning) {
    out.status = Status::Warning;
    out.message = eq.message;
  }
  if (warm != nullptr && out.status != Status::Failed) *warm = std::move(eq);
  return out;
}

// One evaluation: thrust and first flap harmonic at (p's pitch, inflow), about hover or along
// q° (periodic).  response.steps is updated to the steps used, so that later evaluations use
// the same grid.
ThrustResult evaluate(const RotorParameters& p, const model::ModelDescriptor& m, double mu,
                      double inflow, ResponseOptions& response, bool periodic,
                      PeriodicEquilibrium* warm = nullptr) {
  if (periodic) return evaluate_periodic(p, m, mu, inflow, warm);
  // The emitted thrust has a normal and a sector form only (ModelDescriptor::thrust); with the
  // exact circle the thrust and A(psi) would model different reversed regions.
  if (p.exact_reversed_flow) {
    throw InvalidInput("exact_reversed_flow", "true",
                       "the trim's rotor thrust is integrated with the Appendix D sector: trim "
                       "with the sector (`exact_reversed_flow` = false)");
  }
  ThrustResult out;
  out.mu = mu;
  const detail::SystemBuilder builder(p, m, InflowModel::Given(inflow));
  out.inflow = builder.inflow();
  if (builder.hover().status == Status::Failed) {
    out.status = Status::Failed;
    out.message = builder.hover().message;
    return out;
  }
  const PeriodicSystem sys = builder.system(mu);
  const PeriodicResponse r = periodic_response(sys, response);
  if (r.status == Status::Failed) {
    out.status = Status::Failed;
    out.message = "no periodic response at mu = " + round_trip_text(mu) + ": " + r.message;
    return out;
  }
  response.steps = r.steps;
  const detail::ThrustSystem ts = builder.thrust(mu);
  const double sigma_a_2 = 0.5 * p.sigma * p.lift_slope;
  out.thrust_coefficient = sigma_a_2 * mean_thrust(sys, ts, r.y0, std::max(r.steps, 256));
  // First harmonic of the flap tip deflection (hover equilibrium: constant only).
  const int M = m.flap_modes, N = m.lag_modes;
  const double n = static_cast<double>(r.y.size());
  for (std::size_t i = 0; i < r.y.size(); ++i) {
    const double w = internal::tip_deflections(builder.modes(), M, N, r.y[i])[0];  // flap
    out.flap_1c += 2.0 / n * w * std::cos(r.psi[i]);
    out.flap_1s += 2.0 / n * w * std::sin(r.psi[i]);
  }
  if (!std::isfinite(out.thrust_coefficient)) {
    out.status = Status::Failed;
    out.message = "the thrust overflowed at mu = " + round_trip_text(mu);
  } else if (r.status == Status::Warning) {
    out.status = Status::Warning;
    out.message = r.message;
  }
  return out;
}

}  // namespace

const char* trim_kind_name(TrimKind k) {
  switch (k) {
    case TrimKind::None:
      return "none";
    case TrimKind::Thrust:
      return "thrust";
    case TrimKind::Moment:
      return "moment";
  }
  return "none";
}

bool trim_kind_from_name(std::string_view name, TrimKind* kind) {
  for (TrimKind k : {TrimKind::None, TrimKind::Thrust, TrimKind::Moment}) {
    if (name == trim_kind_name(k)) {
      *kind = k;
      return true;
    }
  }
  return false;
}

std::optional<InvalidInput> TrimOptions::Validate() const {
  return Requirements().InRanges(*this).Include(response.Validate()).Result();
}

ThrustResult rotor_thrust(const RotorParameters& p, double mu, double inflow,
                          const ResponseOptions& response, Linearization about) {
  check_mu(mu);
  response.Check();
  if (std::isnan(inflow)) validate(p);
  validate_except_inflow(p);
  const model::ModelDescriptor& m = find_model(p.model);
  ResponseOptions r = response;
  return evaluate(p, m, mu, std::isnan(inflow) ? hover_inflow(p) : inflow, r,
                  about == Linearization::PeriodicEquilibrium);
}

ThrustResult rotor_thrust_momentum(const RotorParameters& p, double mu, double shaft_angle,
                                   const ResponseOptions& response, Linearization about) {
  check_mu(mu);
  response.Check();
  validate(p);
  if (!(std::isfinite(shaft_angle) && std::abs(shaft_angle) < kHalfPi)) {
    throw InvalidInput("shaft_angle", round_trip_text(shaft_angle), "must be in (-pi/2, pi/2)");
  }
  const model::ModelDescriptor& m = find_model(p.model);
  ResponseOptions r = response;
  // Fixed point C_T = thrust(lambda(C_T)): secant iteration on g(lambda) = lambda -
  // lambda_2.25(thrust(lambda)), from eq 2.24's lambda.
  ThrustResult last;
  auto g = [&](double lam) {
    last = evaluate(p, m, mu, lam, r, about == Linearization::PeriodicEquilibrium);
    if (last.status == Status::Failed) return std::numeric_limits<double>::quiet_NaN();
    if (!(last.thrust_coefficient > 0.0)) return std::numeric_limits<double>::quiet_NaN();
    return lam - momentum_inflow(last.thrust_coefficient, mu, shaft_angle);
  };
  double l0 = hover_inflow(p), l1 = l0 * 0.95;
  double g0 = g(l0), g1 = g(l1);
  for (int it = 0; it < 60 && std::isfinite(g1) && g1 != 0.0; ++it) {
    const double d = (g1 - g0);
    if (d == 0.0) break;
    const double l2 = l1 - g1 * (l1 - l0) / d;
    l0 = l1;
    g0 = g1;
    l1 = l2;
    g1 = g(l1);
    if (std::abs(l1 - l0) <= 1e-16 * std::max(1.0, std::abs(l1))) break;
  }
  if (!std::isfinite(g1)) {
    last.status = Status::Failed;
    if (last.message.empty())
      last.message = "no positive thrust with the inflow of eq 2.25 at this pitch";
    return last;
  }
  if (std::abs(g1) > 1e-12 * std::max(1e-3, std::abs(l1))) {
    last.status = Status::Warning;
    last.message = "inflow of eq 2.25 not converged (residual " + round_trip_text(g1) + ")";
  }
  return last;
}

namespace {
// One trim() call: what it trims (about the periodic equilibrium: q° itself) and the thrust
// evaluations it has made, against TrimOptions::max_evaluations.
struct TrimBudget {
  bool periodic = false;
  int used = 0;
};

// One trim at mu (Newton from the start's or the blade-element controls); trim() adds the
// continuation in mu about the periodic equilibrium.
TrimResult trim_once(const RotorParameters& p, const model::ModelDescriptor& m, double mu,
                     const TrimOptions& o, const TrimResult* start, TrimBudget& budget);

TrimResult trim_continued(const RotorParameters& p, const model::ModelDescriptor& m, double mu,
                          const TrimOptions& o, const TrimResult* start, TrimBudget& budget);
}  // namespace

TrimResult trim(const RotorParameters& p, double mu, const TrimOptions& o, const TrimResult* start,
                Linearization about) {
  o.Check();
  check_mu(mu);
  validate_except_inflow(p);
  if (o.kind == TrimKind::None) {
    throw InvalidInput("trim", "none", "nothing to trim: use thrust or moment");
  }
  const model::ModelDescriptor& m = find_model(p.model);
  TrimBudget budget;
  budget.periodic = about == Linearization::PeriodicEquilibrium;
  TrimResult out = trim_continued(p, m, mu, o, start, budget);
  out.evaluations = budget.used;
  out.linearization = about;
  // The trimmed operating point against the validity envelope (rotor/validity.h).
  out.validity.clear();
  if (out.status != Status::Failed) {
    const detail::SystemBuilder builder(out.parameters, m, InflowModel::Given(out.inflow));
    out.validity = internal::validity_of(builder);
    out.Worsen(out.validity.empty() ? Status::Ok : Status::Warning, out.validity);
  }
  return out;
}

std::string trim_problem(const TrimResult& t) {
  if (t.status == Status::Failed || !t.converged) return t.message;
  return t.validity;
}

namespace {

// The result of a trim whose budget is spent: failed, with the controls of the last trim the
// continuation settled (`last`, at another mu) or none.
TrimResult out_of_budget(const RotorParameters& p, double mu, const TrimOptions& o,
                         const TrimResult* last) {
  TrimResult out;
  if (last != nullptr) out = *last;
  out.mu = mu;
  out.kind = o.kind;
  out.target = o.thrust_coefficient;
  if (last == nullptr) out.parameters = p;
  out.converged = false;
  out.status = Status::Failed;
  out.message = "no trim at mu = " + round_trip_text(mu) + " within " +
                std::to_string(o.max_evaluations) + " thrust evaluations (`max_evaluations`)";
  if (last != nullptr && last->status != Status::Failed && last->converged)
    out.message +=
        "; the continuation in mu had reached a trim at mu = " + round_trip_text(last->mu) +
        " (the trimmed branch may end or turn between the two)";
  return out;
}

TrimResult trim_continued(const RotorParameters& p, const model::ModelDescriptor& m, double mu,
                          const TrimOptions& o, const TrimResult* start, TrimBudget& budget) {
  if (budget.used >= o.max_evaluations) return out_of_budget(p, mu, o, start);
  // About the periodic equilibrium without a start of its own: the trim continued in mu from
  // hover (steps of kPeriodicTrimStep, each from the previous trim and its q°), since q° at
  // fixed controls, continued from hover, may fold before the trimmed branch does.
  constexpr double kPeriodicTrimStep = 0.1;
  if (budget.periodic && mu > kPeriodicTrimStep &&
      (start == nullptr || start->equilibrium.coefficients.size() == 0 ||
       start->status == Status::Failed)) {
    TrimResult chain = trim_continued(p, m, 0.0, o, nullptr, budget);
    for (int i = 1; chain.status != Status::Failed && i * kPeriodicTrimStep < mu; ++i)
      chain = trim_continued(p, m, i * kPeriodicTrimStep, o, &chain, budget);
    if (chain.status == Status::Failed) {
      chain.mu = mu;
      chain.message =
          "the trim continued from hover failed on the way to mu = " + round_trip_text(mu) + ": " +
          chain.message;
      return chain;
    }
    return trim_continued(p, m, mu, o, &chain, budget);
  }
  // From a start at another mu: Newton from the start's controls may fail far from it (about
  // hover: the moment trim from mu = 0.7 to 0.8 of the typical case; about the periodic
  // equilibrium: q° of the start's controls, continued to mu, may fold before the trimmed
  // branch does); then the trim is continued in halved steps of mu (down to 1e-3) from the
  // last converged trim.
  auto settled = [](const TrimResult& t) { return t.status != Status::Failed && t.converged; };
  if (start != nullptr && settled(*start) && start->kind == o.kind &&
      (!budget.periodic || start->equilibrium.coefficients.size() > 0) &&
      std::abs(mu - start->mu) > 1e-3) {
    TrimResult direct = trim_once(p, m, mu, o, start, budget);
    if (settled(direct)) return direct;
    const TrimResult half = trim_continued(p, m, 0.5 * (start->mu + mu), o, start, budget);
    if (!settled(half)) return direct;
    return trim_continued(p, m, mu, o, &half, budget);
  }
  // About hover without a start (the thrust trim of a study, from the blade-element controls):
  // when that fails, the same continuation from the hover trim.
  if (!budget.periodic && start == nullptr && mu > 1e-3) {
    TrimResult direct = trim_once(p, m, mu, o, nullptr, budget);
    if (settled(direct)) return direct;
    const TrimResult hover = trim_once(p, m, 0.0, o, nullptr, budget);
    if (!settled(hover)) return direct;
    TrimResult chained = trim_continued(p, m, mu, o, &hover, budget);
    return settled(chained) ? chained : direct;
  }
  return trim_once(p, m, mu, o, start, budget);
}

// One trim at mu: Newton on the controls x (theta0 for a thrust trim; theta0, theta1c, theta1s
// for a moment trim) with a Jacobian that is updated by Broyden's rule after each step and
// evaluated by finite differences only at the start (unless a warm start brings one) and when
// a step fails; each step is halved until the residual decreases (the thrust is strongly
// nonlinear in theta0 near the stability boundary, where the response is large).
class TrimNewton {
 public:
  TrimNewton(const RotorParameters& p, const model::ModelDescriptor& m, double mu,
             const TrimOptions& o, const TrimResult* start, TrimBudget& budget)
      : p_(p),
        m_(m),
        mu_(mu),
        o_(o),
        start_(start),
        budget_(budget),
        ropt_(o.response),
        moment_(o.kind == TrimKind::Moment),
        nx_(moment_ ? 3 : 1) {
    out_.mu = mu;
    out_.kind = o.kind;
    out_.target = o.thrust_coefficient;
    out_.inflow = momentum_inflow(o.thrust_coefficient, mu, o.shaft_angle);
    out_.parameters = p;
    // About the periodic equilibrium: each evaluation continues from the previous one's q°
    // (a start's, then this trim's), not from hover.
    if (start != nullptr && budget.periodic) warm_ = start->equilibrium;
  }

  TrimResult run() {
    x_ = starting_controls();
    if (!residual(x_, &r_)) {
      return finish(Status::Failed, last_.message.empty()
                                        ? "the starting pitch is outside (-pi/2, pi/2)"
                                        : last_.message);
    }
    Eigen::MatrixXd J;
    bool fresh = false;  // J is a finite-difference Jacobian at x_
    if (start_ != nullptr && start_->jacobian.rows() == nx_ && start_->jacobian.cols() == nx_ &&
        start_->kind == o_.kind) {
      J = start_->jacobian;
    } else {
      if (!jacobian(&J)) {
        return finish(Status::Failed, "the trim Jacobian could not be evaluated: " + last_.message);
      }
      fresh = true;
    }
    out_.iterations = 0;
    while (!converged(r_)) {
      if (out_.iterations >= o_.max_iterations) {
        out_.jacobian = J;
        return finish(Status::Warning, "trim not converged in " + std::to_string(out_.iterations) +
                                           " iterations (`max_iterations`): |residual| = " +
                                           round_trip_text(r_.cwiseAbs().maxCoeff()));
      }
      Eigen::VectorXd trial, rt;
      if (!damped_step(J, fresh, trial, rt)) {
        residual(x_, &r_);
        if (fresh) {
          out_.jacobian = J;
          return finish(Status::Failed,
                        "the trim Newton step does not reduce the residual (|r| = " +
                            round_trip_text(r_.norm()) + "; singular or unreachable)" +
                            (last_.message.empty() ? std::string() : ": " + last_.message));
        }
        if (!jacobian(&J)) {
          return finish(Status::Failed,
                        "the trim Jacobian could not be evaluated: " + last_.message);
        }
        fresh = true;
        continue;
      }
      ++out_.iterations;
      const Eigen::VectorXd step = trial - x_;
      J += ((rt - r_) - J * step) * step.transpose() / step.squaredNorm();  // Broyden
      fresh = false;
      x_ = trial;
      r_ = rt;
    }
    out_.jacobian = J;
    out_.converged = true;
    return finish(last_.status, last_.message);
  }

 private:
  // The start's controls, or blade-element theory for a uniform rigid blade without tip loss,
  // C_T = (sigma a/2) [theta0 (1/3 + mu^2/2) + theta1s mu/2 - lambda/2] (the model's thrust at
  // y = 0 and q0 = 0), clipped: Newton then corrects for the real blade.
  Eigen::VectorXd starting_controls() const {
    Eigen::VectorXd x(nx_);
    if (start_ != nullptr && start_->kind == o_.kind && start_->status != Status::Failed) {
      x(0) = start_->theta0;
      if (moment_) {
        x(1) = start_->theta1c;
        x(2) = start_->theta1s;
      }
      return x;
    }
    const double sa2 = 0.5 * p_.sigma * p_.lift_slope;
    const double guess =
        (o_.thrust_coefficient / sa2 + 0.5 * out_.inflow - 0.5 * mu_ * p_.theta1s) /
        (1.0 / 3.0 + 0.5 * mu_ * mu_);
    x(0) = std::isfinite(guess) ? std::clamp(guess, -1.0, 1.0) : p_.theta;
    if (moment_) {
      x(1) = p_.theta1c;
      x(2) = p_.theta1s;
    }
    return x;
  }

  RotorParameters params_of(const Eigen::VectorXd& v) const {
    RotorParameters q = p_;
    q.theta = v(0);
    if (moment_) {
      q.theta1c = v(1);
      q.theta1s = v(2);
    }
    return q;
  }

  // Residual at v: [C_T - target (relative to target), flap 1c, flap 1s]; false when the
  // pitch leaves (-pi/2, pi/2), the budget is spent or the evaluation fails (last_ says why).
  bool residual(const Eigen::VectorXd& v, Eigen::VectorXd* r) {
    for (int j = 0; j < nx_; ++j) {
      if (!(std::abs(v(j)) < kHalfPi)) return false;
    }
    if (budget_.used >= o_.max_evaluations) {
      last_.status = Status::Failed;
      last_.message = "gave up after " + std::to_string(o_.max_evaluations) +
                      " thrust evaluations (`max_evaluations`)";
      return false;
    }
    ++budget_.used;
    last_ = evaluate(params_of(v), m_, mu_, out_.inflow, ropt_, budget_.periodic, &warm_);
    if (last_.status == Status::Failed) return false;
    r->resize(nx_);
    (*r)(0) = (last_.thrust_coefficient - o_.thrust_coefficient) / o_.thrust_coefficient;
    if (moment_) {
      (*r)(1) = last_.flap_1c;
      (*r)(2) = last_.flap_1s;
    }
    return true;
  }

  bool converged(const Eigen::VectorXd& res) const {
    for (int j = 0; j < nx_; ++j) {
      if (!(std::abs(res(j)) <= o_.tolerance)) return false;
    }
    return true;
  }

  // Forward-difference Jacobian at x_ (the residual is nearly linear in the pitch).  The
  // evaluation at x_ (last_, and its q° in warm_) is kept and put back afterwards rather than
  // recomputed: the same solve again (about hover bit for bit: the response's grid is fixed
  // after the first evaluation).
  bool jacobian(Eigen::MatrixXd* J) {
    J->resize(nx_, nx_);
    const ThrustResult at_x = last_;
    const PeriodicEquilibrium warm_at_x = budget_.periodic ? warm_ : PeriodicEquilibrium{};
    for (int j = 0; j < nx_; ++j) {
      const double h = 1e-6;
      Eigen::VectorXd xp = x_, rp;
      xp(j) += h;
      if (!residual(xp, &rp)) return false;
      J->col(j) = (rp - r_) / h;
    }
    last_ = at_x;
    if (budget_.periodic) warm_ = warm_at_x;
    return true;
  }

  // The Newton step from x_ by J, halved (up to 30 times with a fresh J, else not) until the
  // residual decreases: the accepted controls and their residual, or false.
  bool damped_step(const Eigen::MatrixXd& J, bool fresh, Eigen::VectorXd& trial,
                   Eigen::VectorXd& rt) {
    Eigen::FullPivLU<Eigen::MatrixXd> lu(J);
    if (!lu.isInvertible()) return false;
    Eigen::VectorXd dx = lu.solve(r_);
    const double norm0 = r_.norm();
    for (int half = 0; half < (fresh ? 30 : 1); ++half, dx *= 0.5) {
      trial = x_ - dx;
      if (residual(trial, &rt) && (rt.norm() < norm0 || converged(rt))) return true;
    }
    return false;
  }

  // The result at the controls x_.
  TrimResult finish(Status s, std::string msg) {
    out_.parameters = params_of(x_);
    out_.theta0 = out_.parameters.theta;
    out_.theta1c = out_.parameters.theta1c;
    out_.theta1s = out_.parameters.theta1s;
    out_.thrust_coefficient = last_.thrust_coefficient;
    out_.flap_1c = last_.flap_1c;
    out_.flap_1s = last_.flap_1s;
    if (budget_.periodic) out_.equilibrium = warm_;
    out_.status = s;
    out_.message = std::move(msg);
    return out_;
  }

  const RotorParameters& p_;
  const model::ModelDescriptor& m_;
  const double mu_;
  const TrimOptions& o_;
  const TrimResult* start_;
  TrimBudget& budget_;
  TrimResult out_;
  ResponseOptions ropt_;
  PeriodicEquilibrium warm_;
  const bool moment_;
  const int nx_;
  Eigen::VectorXd x_, r_;  // the controls and their residual
  ThrustResult last_;      // the last evaluation
};

TrimResult trim_once(const RotorParameters& p, const model::ModelDescriptor& m, double mu,
                     const TrimOptions& o, const TrimResult* start, TrimBudget& budget) {
  return TrimNewton(p, m, mu, o, start, budget).run();
}

}  // namespace

}  // namespace flaplag
