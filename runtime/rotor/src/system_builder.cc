#include "flaplag/core/constants.h"
#include "flaplag/rotor/system_builder.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/blade/rotating_modes.h"

namespace flaplag::detail {

double reversed_flow_sector_width(double mu) {
  if (mu < 1.0) return kPi / 2.0;  // eq D.1
  const double s = std::asin(1.0 / mu);
  return kPi - 2.0 * s + mu * mu * s - std::sqrt(mu * mu - 1.0);  // eq D.2
}

SystemBuilder::SystemBuilder(const RotorParameters& p, const model::ModelDescriptor& m)
    : p_(p), model_(&m), M_(m.flap_modes), N_(m.lag_modes), n_(M_ + N_), H_(m.n_harmonics) {
  validate(p_);
  if (p_.periodic_linearization && m.nonlinear == nullptr) {
    throw InvalidInput("periodic_linearization", "true",
                       std::string("model '") + m.name +
                           "' has no nonlinear loads (its spec does not set [emit] nonlinear); "
                           "use a model that has them, e.g. paper-nonlinear");
  }
  if (p_.modes == ModeKind::Assumed) {
    if (M_ != 1 || N_ != 1) {
      throw InvalidInput("modes", "assumed",
                         std::string("model '") + m.name + "' has " + std::to_string(M_) +
                             " flap x " + std::to_string(N_) +
                             " lag modes; the assumed mode (eq 4.1) gives one of each: use "
                             "`modes` = exact");
    }
    modes_ = assumed_modes(p_.omega_flap, p_.omega_lag);
  } else {
    ExactModeOptions opt;
    opt.flap_modes = M_;
    opt.lag_modes = N_;
    opt.e1_over_l = p_.root_offset / p_.length_ratio;
    opt.paper_1974_shapes = p_.paper_1974_shapes;
    modes_ = exact_modes(p_.omega_flap, p_.omega_lag, opt);
  }
  geometry_.e1 = p_.root_offset;
  geometry_.lr = p_.length_ratio;
  geometry_.tip_loss_a = p_.tip_loss_a;
  geometry_.tip_loss_b = p_.tip_loss_b;
  inflow_ = hover_inflow(p_);
  // Structural damping ratios apply to every mode of a direction.
  damping_flap_.assign(M_, p_.damping_flap);
  damping_lag_.assign(N_, p_.damping_lag);
  cdo_a_ = p_.cdo / p_.lift_slope;

  // Appendix E: only with exact modes (paper 4.1(a): neglected with the assumed mode).
  coupling_ = (p_.modes == ModeKind::Exact && p_.elastic_coupling)
                  ? elastic_coupling(modes_, p_.theta)
                  : no_elastic_coupling(modes_);
  auto flat = [](const Eigen::MatrixXd& a) {
    std::vector<double> v(static_cast<size_t>(a.size()));
    for (Eigen::Index i = 0; i < a.rows(); ++i)
      for (Eigen::Index j = 0; j < a.cols(); ++j) v[i * a.cols() + j] = a(i, j);
    return v;
  };
  es_flap_ = flat(coupling_.es_flap);
  es_lag_ = flat(coupling_.es_lag);
  ecs_flap_lag_ = flat(coupling_.ecs_flap_lag);
  ecs_lag_flap_ = flat(coupling_.ecs_lag_flap);

  structural_ = structural_integrals(m, modes_, p_.root_offset / p_.length_ratio);
  aero_ = AeroIntegrals(m, modes_, geometry_);

  // Hover equilibrium (2.29-2.32): S q0 = c with mu = 0.
  g0_.assign(M_, 0.0);
  h0_.assign(N_, 0.0);
  std::vector<double> S(n_ * n_), c(n_);
  m.equilibrium(inputs(0.0, aero_.normal().data()), {S.data(), c.data()});
  Eigen::MatrixXd Sm(n_, n_);
  Eigen::VectorXd cv(n_);
  for (int i = 0; i < n_; ++i) {
    cv(i) = c[i];
    for (int j = 0; j < n_; ++j) Sm(i, j) = S[i * n_ + j];
  }
  Eigen::FullPivLU<Eigen::MatrixXd> lu(Sm);
  hover_.inflow = inflow_;
  if (!lu.isInvertible()) {
    hover_.status = Status::Failed;
    hover_.message = "hover equilibrium matrix S (eq 2.32) is singular";
    hover_.q0 = Eigen::VectorXd::Zero(n_);
  } else {
    hover_.q0 = lu.solve(cv);
  }
  for (int k = 0; k < M_; ++k) g0_[k] = hover_.q0(k);
  for (int r = 0; r < N_; ++r) h0_[r] = hover_.q0(M_ + r);

  // The generalized mass depends on the structural integrals only (model_api.h): factor it once.
  {
    std::vector<double> mass(n_ * n_);
    m.mass(inputs(0.0, aero_.normal().data()), mass.data());
    Eigen::MatrixXd Mm(n_, n_);
    for (int i = 0; i < n_; ++i)
      for (int j = 0; j < n_; ++j) Mm(i, j) = mass[i * n_ + j];
    mass_inverse_ = Mm.inverse();
  }

  // Forcing at the hover equilibrium (balances to ~0 when S q0 = c) and the constant A0.
  HarmonicSet h0set;
  hover_forcing_ = Eigen::VectorXd::Zero(2 * n_);
  assemble(0.0, aero_.normal(), h0set);
  hover_forcing_ = h0set.f[0];
  hover_.A0 = h0set.A[0];
  Eigen::EigenSolver<Eigen::MatrixXd> es(hover_.A0);
  hover_.stable = true;
  for (Eigen::Index k = 0; k < es.eigenvalues().size(); ++k) {
    const auto lam = es.eigenvalues()(k);
    hover_.eigenvalues.push_back(lam);
    if (lam.real() > 0.0) hover_.stable = false;
  }
  if (!hover_.stable && hover_.status == Status::Ok) {
    hover_.status = Status::Warning;
    hover_.message =
        "the hover equilibrium itself is unstable (an eigenvalue of A0 has a "
        "positive real part); forward-flight results start from an unstable state";
  }
}

model::CoefficientInputs SystemBuilder::inputs(double mu, const double* aero) const {
  model::CoefficientInputs in{};
  in.lock = p_.gamma;
  in.lr = p_.length_ratio;
  in.theta = p_.theta;
  in.inflow = inflow_;
  in.precone = p_.precone;
  in.droop = p_.droop;
  in.cdo_a = cdo_a_;
  in.mu = mu;
  in.g0 = g0_.data();
  in.h0 = h0_.data();
  in.omega_flap = modes_.omega_flap.data();
  in.omega_lag = modes_.omega_lag.data();
  in.damping_flap = damping_flap_.data();
  in.damping_lag = damping_lag_.data();
  in.es_flap = es_flap_.data();
  in.es_lag = es_lag_.data();
  in.ecs_flap_lag = ecs_flap_lag_.data();
  in.ecs_lag_flap = ecs_lag_flap_.data();
  in.aero = aero;
  in.structural = structural_.data();
  return in;
}

// A rows: velocity rows get mass^-1 * generalized force; displacement rows the identity.
void SystemBuilder::assemble(double mu, const std::vector<double>& aero, HarmonicSet& out) const {
  const int n = n_, ns = 2 * n_;
  std::vector<double> buffer(H_ * n * ns + H_ * n);
  double* force = buffer.data();
  double* forcing = force + H_ * n * ns;
  model_->coefficients(inputs(mu, aero.data()), {force, forcing});
  // state column of the rate / displacement of coordinate j
  auto rate_col = [&](int j) { return model::rate_index(j, M_, N_); };
  auto disp_col = [&](int j) { return model::displacement_index(j, M_, N_); };
  out.A.assign(H_, Eigen::MatrixXd::Zero(ns, ns));
  out.f.assign(H_, Eigen::VectorXd::Zero(ns));
  for (int h = 0; h < H_; ++h) {
    Eigen::MatrixXd& A = out.A[h];
    Eigen::VectorXd& f = out.f[h];
    for (int i = 0; i < n; ++i) {
      const int row = rate_col(i);
      for (int j = 0; j < n; ++j) {
        const double mij = mass_inverse_(i, j);
        if (mij == 0.0) continue;
        const double* q = force + (h * n + j) * ns;
        for (int c = 0; c < ns; ++c) A(row, c) += mij * q[c];
        f(row) += mij * forcing[h * n + j];
      }
    }
  }
  for (int j = 0; j < n; ++j) out.A[0](disp_col(j), rate_col(j)) = 1.0;
  // Perturbation forcing: the hover balance is subtracted (it is exactly zero at mu = 0).
  if (hover_forcing_.size() == ns) out.f[0] -= hover_forcing_;
}

void SystemBuilder::nonlinear_loads(double mu, const std::vector<double>& aero, const double* y,
                                    double* force, double* jacobian) const {
  if (model_->nonlinear == nullptr) {
    throw std::logic_error(std::string("model '") + model_->name + "' has no nonlinear loads");
  }
  model_->nonlinear(inputs(mu, aero.data()), y, {force, jacobian});
}

std::vector<double> SystemBuilder::reversed_integrals(double mu) const {
  return aero_.reversed(mu);
}

PeriodicSystem SystemBuilder::system(double mu) const {
  if (!(mu >= 0.0) || !std::isfinite(mu)) {
    throw InvalidInput("mu", round_trip_text(mu), "advance ratio must be finite and >= 0");
  }
  PeriodicSystem sys;
  sys.n = 2 * n_;
  assemble(mu, aero_.normal(), sys.normal);
  if (p_.reversed_flow && mu > 0.0) {
    const double alpha = reversed_flow_sector_width(mu);
    sys.has_sector = true;
    sys.sector_begin = 1.5 * kPi - 0.5 * alpha;
    sys.sector_end = 1.5 * kPi + 0.5 * alpha;
    assemble(mu, reversed_integrals(mu), sys.reversed);
  }
  return sys;
}

}  // namespace flaplag::detail
