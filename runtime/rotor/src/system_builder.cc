#include "flaplag/rotor/system_builder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "flaplag/blade/blade_elements.h"
#include "flaplag/blade/imported_modes.h"
#include "flaplag/blade/rotating_modes.h"
#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/numerics/dense.h"
#include "flaplag/rotor/parameter_table.h"

namespace flaplag::detail {

double reversed_flow_sector_width(double mu) {
  if (mu < 1.0) return kPi / 2.0;  // eq D.1
  const double s = std::asin(1.0 / mu);
  return kPi - 2.0 * s + mu * mu * s - std::sqrt(mu * mu - 1.0);  // eq D.2
}

ExactReversedRegion exact_reversed_region(double mu, const RotorParameters& p) {
  ExactReversedRegion r;
  const double x_a = p.root_offset + p.length_ratio * p.tip_loss_a;  // inner aerodynamic limit
  const double x_b = p.root_offset + p.length_ratio * p.tip_loss_b;  // outer (tip loss) limit
  if (!(mu > x_a)) return r;  // the circle of diameter mu does not reach the aerodynamic span
  const double a = std::asin(x_a / mu);
  r.exists = true;
  r.begin = kPi + a;
  r.end = kTwoPi - a;
  if (mu > x_b) {
    const double b = std::asin(x_b / mu);
    r.breaks = {kPi + b, kTwoPi - b};
  }
  return r;
}

namespace {

// The parameters and inflow the builder accepts (InvalidInput otherwise).
void check_inputs(const RotorParameters& p, const InflowModel& inflow) {
  if (inflow.kind != InflowKind::Uniform) {
    validate_except_inflow(p);  // eq 2.24 is not used
  } else {
    validate(p);
  }
  ThrowIfInvalid(inflow.Validate());
}

// The modes of p.mode_shapes (imported from a table) for model m.  The table gives shapes and
// frequencies, not the bending stiffnesses the elastic coupling (Appendix E) needs: they are
// filled as the exact modes of the uniform blade would have them, stiffness_for_frequency of
// the first imported frequency of each direction with the exact modes' basis and e1 / l.
ModeSet imported_blade_modes(const RotorParameters& p, const model::ModelDescriptor& m) {
  const ImportedModes& table = *p.mode_shapes;
  if (p.modes != ModeKind::Exact) {
    throw InvalidInput("mode_shapes", table.source,
                       "imported mode shapes need `modes` = exact (assumed is the eq 4.1 shape)");
  }
  ModeSet s;
  try {
    s = imported_mode_set(table, m.flap_modes, m.lag_modes);
  } catch (const InvalidInput& e) {
    throw InvalidInput("mode_shapes", table.source, e.reason());
  }
  ExactModeOptions opt;
  opt.n_basis = p.basis == kElementBasis ? kMaxBasisFunctions : galerkin_basis(p);
  opt.e1_over_l = p.root_offset / p.length_ratio;
  s.blade = p.blade;
  if (p.blade) {
    // The blade table's stiffness columns, scaled as its own first modes would need to have
    // the imported first frequencies.
    opt.blade = p.blade;
    const double first_flap = s[model::Direction::Flap].omega[0];
    const double first_lag = s[model::Direction::Lag].omega[0];
    const ModeSet own = p.basis == kElementBasis
                            ? element_rotating_modes(first_flap, first_lag, opt).modes
                            : exact_modes(first_flap, first_lag, opt);
    for (const model::Direction d : model::kDirections) s[d].stiffness = own[d].stiffness;
    return s;
  }
  for (const model::Direction dir : model::kDirections) {
    const double omega = s[dir].omega[0];
    try {
      s[dir].stiffness = stiffness_for_frequency(dir, omega, opt);
    } catch (const InvalidInput& e) {
      throw InvalidInput("mode_shapes", table.source,
                         // the column of the mode table: flap1, lag1
                         std::string(model::kDirectionNames[model::index(dir)]) +
                             "1 omega = " + round_trip_text(omega) +
                             " gives no stiffness of the uniform blade for the elastic "
                             "coupling: " +
                             e.reason());
    }
  }
  return s;
}

// The structural damping ratio of direction d's modes (the parameters eta_SF, eta_SL).
double structural_damping(const RotorParameters& p, model::Direction d) {
  return d == model::Direction::Flap ? p.damping_flap : p.damping_lag;
}

// The rotating modes of the blade: the assumed mode (eq 4.1) or the exact modes (Galerkin).
ModeSet blade_modes(const RotorParameters& p, const model::ModelDescriptor& m) {
  if (p.mode_shapes) return imported_blade_modes(p, m);
  const int M = m.flap_modes, N = m.lag_modes;
  if (p.modes == ModeKind::Assumed) {
    if (M != 1 || N != 1) {
      throw InvalidInput("modes", "assumed",
                         std::string("model '") + m.name + "' has " + std::to_string(M) +
                             " flap x " + std::to_string(N) +
                             " lag modes; the assumed mode (eq 4.1) gives one of each: use "
                             "`modes` = exact");
    }
    return assumed_modes(p.omega_flap, p.omega_lag);
  }
  // Galerkin's method gives at most as many rotating modes per direction as basis functions
  // (the finite elements as many as the largest basis, the most a model has).
  const int basis = p.basis == kElementBasis ? kMaxBasisFunctions : galerkin_basis(p);
  if (M > basis || N > basis) {
    throw InvalidInput("basis", parameter_text(p, *find_parameter("basis")),
                       std::string("model '") + m.name + "' has " + std::to_string(M) + " flap x " +
                           std::to_string(N) + " lag modes; the exact modes need at least " +
                           std::to_string(std::max(M, N)) + " cantilever functions per direction");
  }
  ExactModeOptions opt;
  opt.n_basis = basis;
  opt.flap_modes = M;
  opt.lag_modes = N;
  opt.e1_over_l = p.root_offset / p.length_ratio;
  opt.paper_1974_shapes = p.paper_1974_shapes;
  opt.blade = p.blade;
  try {
    if (p.basis == kElementBasis)
      return element_rotating_modes(p.omega_flap, p.omega_lag, opt).modes;
    return exact_modes(p.omega_flap, p.omega_lag, opt);
  } catch (const InvalidInput& e) {
    // The blade layer calls the basis size `n_basis` (ExactModeOptions); here it is `basis`.
    std::string reason = e.reason();
    for (std::size_t at; (at = reason.find("`n_basis`")) != std::string::npos;)
      reason.replace(at, 9, "`basis`");
    throw InvalidInput(e.name() == "n_basis" ? "basis" : e.name(), e.value(), reason);
  }
}

std::vector<double> row_major(const Eigen::MatrixXd& a) {
  std::vector<double> v(static_cast<size_t>(a.size()));
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index j = 0; j < a.cols(); ++j) v[i * a.cols() + j] = a(i, j);
  return v;
}

Eigen::MatrixXd square_matrix(const std::vector<double>& values, int n) {
  Eigen::MatrixXd a(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) a(i, j) = values[i * n + j];
  return a;
}

// hover.q0 from S q0 = c (S row-major, n x n), Failed when S is singular.
void solve_hover_equilibrium(const std::vector<double>& S, const std::vector<double>& c, int n,
                             HoverResult& hover) {
  const Eigen::MatrixXd Sm = square_matrix(S, n);
  Eigen::VectorXd cv(n);
  for (int i = 0; i < n; ++i) cv(i) = c[i];
  Eigen::FullPivLU<Eigen::MatrixXd> lu(Sm);
  if (!lu.isInvertible()) {
    hover.status = Status::Failed;
    hover.message = "hover equilibrium matrix S (eq 2.32) is singular";
    hover.q0 = Eigen::VectorXd::Zero(n);
  } else {
    hover.q0 = lu.solve(cv);
  }
}

// The eigenvalues of hover.A0, and whether hover is stable, unstable or (within rounding)
// neutral.
void classify_hover(HoverResult& hover) {
  const RealEigenSystem es = real_eigen_system(hover.A0, true, EigenStorage::Dynamic);
  hover.stable = true;
  double largest = -std::numeric_limits<double>::infinity();
  for (Eigen::Index k = 0; k < es.values.size(); ++k) {
    const auto lam = es.values(k);
    hover.eigenvalues.push_back(lam);
    if (lam.real() > 0.0) hover.stable = false;
    largest = std::max(largest, lam.real());
  }
  const double rounding = hover_zeta_rounding(hover.A0);
  hover.neutral = std::abs(largest) <= rounding;
  if (hover.neutral && hover.status == Status::Ok) {
    hover.status = Status::Warning;
    hover.message =
        "the stability of hover is unknown: the largest real part of an eigenvalue "
        "of A0, " +
        short_text(largest) + ", is within the rounding level " + short_text(rounding) +
        " of zero (a neutral blade)";
  } else if (!hover.stable && hover.status == Status::Ok) {
    hover.status = Status::Warning;
    hover.message =
        "the hover equilibrium itself is unstable (an eigenvalue of A0 has a "
        "positive real part); forward-flight results start from an unstable state";
  }
}

}  // namespace

SystemBuilder::SystemBuilder(const RotorParameters& p, const model::ModelDescriptor& m,
                             const InflowModel& inflow)
    : p_(p),
      model_(&m),
      directions_(model::direction_blocks(m.flap_modes, m.lag_modes)),
      n_(m.flap_modes + m.lag_modes),
      H_(m.n_harmonics),
      inflow_model_(inflow) {
  check_inputs(p_, inflow);
  modes_ = blade_modes(p_, m);
  geometry_.e1 = p_.root_offset;
  geometry_.lr = p_.length_ratio;
  geometry_.tip_loss_a = p_.tip_loss_a;
  geometry_.tip_loss_b = p_.tip_loss_b;
  inflow_ = inflow_model_.lambda(p_, 0.0);
  cdo_a_ = p_.cdo / p_.lift_slope;
  for (const model::DirectionBlock& b : directions_) {
    const int d = model::index(b.direction);
    // Structural damping ratios apply to every mode of a direction.
    damping_[d].assign(b.modes, structural_damping(p_, b.direction));
    q0_[d].assign(b.modes, 0.0);
    for (int k = 0; k < b.modes; ++k) {
      rate_col_.push_back(b.rate_index(k));
      displacement_col_.push_back(b.displacement_index(k));
    }
  }

  // Appendix E: only with exact modes (paper 4.1(a): neglected with the assumed mode).
  coupling_ = (p_.modes == ModeKind::Exact && p_.elastic_coupling)
                  ? elastic_coupling(modes_, p_.theta)
                  : no_elastic_coupling(modes_);
  for (const model::Direction r : model::kDirections)
    for (const model::Direction c : model::kDirections)
      elastic_[model::index(r)][model::index(c)] = row_major(coupling_.block(r, c));

  structural_ = structural_integrals(m, modes_, p_.root_offset / p_.length_ratio);
  aero_ = AeroIntegrals(m, modes_, geometry_);

  // Hover equilibrium (2.29-2.32): S q0 = c with mu = 0.
  std::vector<double> S(n_ * n_), c(n_);
  m.equilibrium(inputs(0.0, aero_.normal().data()), {S.data(), c.data()});
  hover_.inflow = inflow_;
  solve_hover_equilibrium(S, c, n_, hover_);
  for (const model::DirectionBlock& b : directions_)
    for (int k = 0; k < b.modes; ++k)
      q0_[model::index(b.direction)][k] = hover_.q0(b.first_coordinate + k);

  // The generalized mass depends on the structural integrals only (model_api.h): factor it once.
  std::vector<double> mass(n_ * n_);
  m.mass(inputs(0.0, aero_.normal().data()), mass.data());
  const Eigen::MatrixXd Mm = square_matrix(mass, n_);
  mass_inverse_ = Mm.inverse();

  // Forcing at the hover equilibrium (balances to ~0 when S q0 = c) and the constant A0.
  HarmonicSet h0set;
  hover_forcing_ = Eigen::VectorXd::Zero(2 * n_);
  assemble(0.0, aero_.normal(), h0set);
  hover_forcing_ = h0set.f[0];
  hover_.A0 = h0set.A[0];
  classify_hover(hover_);
}

model::CoefficientInputs SystemBuilder::inputs(double mu, const double* aero) const {
  model::CoefficientInputs in{};
  in.lock = p_.gamma;
  in.lr = p_.length_ratio;
  in.theta = p_.theta;
  in.inflow = inflow(mu);
  in.precone = p_.precone;
  in.droop = p_.droop;
  in.cdo_a = cdo_a_;
  in.mu = mu;
  for (const model::DirectionBlock& b : directions_) {
    const int d = model::index(b.direction);
    in.q0[d] = q0_[d].data();
    in.omega[d] = modes_[b.direction].omega.data();
    in.damping[d] = damping_[d].data();
    in.modes[d] = b.modes;
    for (int col = 0; col < model::kDirectionCount; ++col)
      in.elastic[d][col] = elastic_[d][col].data();
  }
  in.aero = aero;
  in.structural = structural_.data();
  in.theta1c = p_.theta1c;
  in.theta1s = p_.theta1s;
  in.context = model_->context;
  return in;
}

// A rows: velocity rows get mass^-1 * generalized force; displacement rows the identity.
void SystemBuilder::assemble(double mu, const std::vector<double>& aero, HarmonicSet& out,
                             ZeroTail tail) const {
  const int n = n_, ns = 2 * n_;
  thread_local std::vector<double> buffer;  // scratch of this thread, every entry written below
  buffer.resize(static_cast<std::size_t>(H_ * n * ns + H_ * n));
  double* force = buffer.data();
  double* forcing = force + H_ * n * ns;
  model_->coefficients(inputs(mu, aero.data()), {force, forcing});
  // The harmonics written: harmonic h is exactly zero when its coefficients are.
  int harmonics = H_;
  if (tail == ZeroTail::Drop) {
    auto zero = [](const double* v, int count) {
      return std::all_of(v, v + count, [](double x) { return x == 0.0; });
    };
    while (harmonics > 1 && zero(force + (harmonics - 1) * n * ns, n * ns) &&
           zero(forcing + (harmonics - 1) * n, n))
      --harmonics;
  }
  // state column of the rate / displacement of coordinate j
  auto rate_col = [&](int j) { return rate_col_[static_cast<std::size_t>(j)]; };
  auto disp_col = [&](int j) { return displacement_col_[static_cast<std::size_t>(j)]; };
  // Sized in place: the storage of a reused system is kept.
  out.A.resize(static_cast<std::size_t>(harmonics));
  out.f.resize(static_cast<std::size_t>(harmonics));
  for (Eigen::MatrixXd& a : out.A) a.setZero(ns, ns);
  for (Eigen::VectorXd& v : out.f) v.setZero(ns);
  for (int h = 0; h < harmonics; ++h) {
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

namespace {

// Trailing harmonics that are exactly zero (assemble() drops those whose coefficients are; a
// product can still vanish) would cost every evaluation of A(psi) and add nothing.
void drop_zero_harmonics(HarmonicSet& set) {
  while (set.A.size() > 1 && set.A.back().isZero(0.0) && set.f.back().isZero(0.0)) {
    set.A.pop_back();
    set.f.pop_back();
  }
}

}  // namespace

void SystemBuilder::nonlinear_loads(double mu, const std::vector<double>& aero, const double* y,
                                    double* force, double* jacobian) const {
  model_->nonlinear(inputs(mu, aero.data()), y, {force, jacobian});
}

void SystemBuilder::nonlinear_thrust(double mu, const std::vector<double>& aero, const double* y,
                                     double* thrust, double* jacobian) const {
  std::vector<double> scratch;
  if (jacobian == nullptr) {
    scratch.resize(static_cast<std::size_t>(model_->n_nonlinear_harmonics) * 2 * n_);
    jacobian = scratch.data();
  }
  model_->nonlinear_thrust(inputs(mu, aero.data()), y, {thrust, jacobian});
}

std::vector<double> SystemBuilder::reversed_integrals(double mu) const {
  return aero_.reversed(mu);
}

// A and f of the exact region at one mu as functions of the split station x0 in [A, B] and of
// psi.  The aerodynamic integrals at a split x0 are normal - 2 int_A^{x0}, whose antiderivatives
// are Chebyshev series of degree kDegree + 1 in x0 (aero_integrals.h), and the generated loads
// are affine in the integrals (each term carries one spanwise integral, model_api.h), so every
// harmonic coefficient of A and f is a polynomial of that degree in x0: interpolating it at
// kDegree + 2 Chebyshev-Lobatto points reproduces it to rounding, and one evaluation is a
// Chebyshev sum instead of a call of the generated code.  (tests/system_builder_test.cpp checks
// the result, for every shipped model family, against the loads assembled from Gauss-quadrature
// integrals split at x0(psi).)
class SystemBuilder::ExactTable {
 public:
  ExactTable(const SystemBuilder& b, double mu)
      : mu_(mu),
        e1_(b.p_.root_offset),
        lr_(b.p_.length_ratio),
        a_(b.p_.tip_loss_a),
        b_(b.p_.tip_loss_b),
        ns_(2 * b.n_),
        H_(b.H_) {
    const int n = AeroIntegrals::kDegree + 1;  // polynomial degree in x0
    const Eigen::Index rows = static_cast<Eigen::Index>(ns_) * ns_ + ns_;
    // Harmonics packed as columns [vec(A_h); f_h]; the table holds the change from the normal
    // harmonics, so that entries the reversed flow does not touch (the identity rows of A)
    // stay exact.
    // assemble() drops trailing harmonics that are exactly zero: those columns stay zero.
    auto pack = [&](const HarmonicSet& set) {
      Eigen::MatrixXd v = Eigen::MatrixXd::Zero(rows, H_);
      for (int h = 0; h < static_cast<int>(set.A.size()); ++h) {
        v.col(h).head(static_cast<Eigen::Index>(ns_) * ns_) =
            Eigen::Map<const Eigen::VectorXd>(set.A[h].data(), set.A[h].size());
        v.col(h).tail(ns_) = set.f[h];
      }
      return v;
    };
    const std::vector<double>& normal = b.aero_.normal();
    {
      HarmonicSet set;
      b.assemble(mu, normal, set, ZeroTail::Drop);
      base_ = pack(set);
    }
    std::vector<Eigen::MatrixXd> values(n + 1);
    std::vector<double> partial;
    for (int k = 0; k <= n; ++k) {
      const double x0 = 0.5 * (a_ + b_) + 0.5 * (b_ - a_) * std::cos(kPi * k / n);
      b.aero_.partial(x0, partial);
      std::vector<double> aero(partial.size());
      for (std::size_t j = 0; j < aero.size(); ++j) aero[j] = normal[j] - 2.0 * partial[j];
      HarmonicSet set;
      b.assemble(mu, aero, set, ZeroTail::Drop);
      values[k] = pack(set) - base_;
    }
    // Chebyshev coefficients (discrete cosine transform over the Lobatto nodes).
    coef_.assign(n + 1, Eigen::MatrixXd::Zero(rows, H_));
    for (int i = 0; i <= n; ++i) {
      for (int k = 0; k <= n; ++k) {
        const double w = (k == 0 || k == n) ? 0.5 : 1.0;
        coef_[i] += (w * std::cos(kPi * i * k / n)) * values[k];
      }
      coef_[i] *= 2.0 / n * ((i == 0 || i == n) ? 0.5 : 1.0);
    }
    // Trailing coefficients at the rounding floor of the transform (measured ~2e-15 of the
    // largest harmonic) only cost time: the assumed-mode integrands are polynomials of low degree
    // (13 terms kept for the paper model), the exact-mode ones converge geometrically (~32).
    double big = 0.0;
    for (const Eigen::MatrixXd& c : coef_) big = std::max(big, c.cwiseAbs().maxCoeff());
    big = std::max(big, base_.cwiseAbs().maxCoeff());
    while (coef_.size() > 1 && coef_.back().cwiseAbs().maxCoeff() <= 4e-15 * big) coef_.pop_back();
    // Only the entries the reversed flow changes are summed (the displacement rows of A and
    // the entries without aerodynamic terms have an exactly zero change).
    for (Eigen::Index r = 0; r < rows; ++r) {
      bool changes = false;
      for (const Eigen::MatrixXd& c : coef_) changes = changes || (c.row(r).array() != 0.0).any();
      if (changes) rows_.push_back(r);
    }
    // stack_ column i = vec of coefficient i restricted to those entries (m x H, column-major)
    const Eigen::Index m = static_cast<Eigen::Index>(rows_.size());
    stack_.resize(m * H_, static_cast<Eigen::Index>(coef_.size()));
    for (std::size_t i = 0; i < coef_.size(); ++i)
      for (int h = 0; h < H_; ++h)
        for (Eigen::Index e = 0; e < m; ++e) stack_(h * m + e, i) = coef_[i](rows_[e], h);
    coef_.clear();
  }

  void at(double psi, Eigen::MatrixXd& A, Eigen::VectorXd& f) const {
    const double c1 = std::cos(psi), s1 = std::sin(psi);
    const double x0 = std::clamp((-mu_ * s1 - e1_) / lr_, a_, b_);
    const double t = (2.0 * x0 - a_ - b_) / (b_ - a_);
    // Scratch per thread: the evaluator is const and may run in several threads at once.
    thread_local Eigen::VectorXd phi, v, w, T, sum;
    // the harmonic basis by the rotation recurrence (index convention of periodic_system.h)
    phi.resize(H_);
    phi(0) = 1.0;
    double ck = c1, sk = s1;
    for (int h = 1; h < H_; h += 2) {
      phi(h) = ck;
      if (h + 1 < H_) phi(h + 1) = sk;
      const double cn = ck * c1 - sk * s1;
      sk = sk * c1 + ck * s1;
      ck = cn;
    }
    // the normal harmonics at psi, plus the change (sum_i T_i(t) coef_i) phi; T_i by the
    // three-term recurrence (|t| <= 1 keeps it stable)
    v.noalias() = base_ * phi;
    const Eigen::Index m = static_cast<Eigen::Index>(rows_.size()), terms = stack_.cols();
    T.resize(terms);
    T(0) = 1.0;
    if (terms > 1) T(1) = t;
    for (Eigen::Index i = 2; i < terms; ++i) T(i) = 2.0 * t * T(i - 1) - T(i - 2);
    sum.noalias() = stack_ * T;
    w.noalias() = Eigen::Map<const Eigen::MatrixXd>(sum.data(), m, H_) * phi;
    for (Eigen::Index e = 0; e < m; ++e) v(rows_[e]) += w(e);
    A = Eigen::Map<const Eigen::MatrixXd>(v.data(), ns_, ns_);
    f = v.tail(ns_);
  }

 private:
  double mu_, e1_, lr_, a_, b_;
  int ns_, H_;
  Eigen::MatrixXd base_;               // normal-flow harmonics, (ns^2 + ns) x H
  std::vector<Eigen::Index> rows_;     // the packed entries that the reversed flow changes
  std::vector<Eigen::MatrixXd> coef_;  // [degree + 1] of the change (construction only)
  Eigen::MatrixXd stack_;              // (rows_ x H) x terms: the kept coefficients, stacked
};

std::vector<double> SystemBuilder::exact_integrals(double mu, double psi) const {
  std::vector<double> out;
  // the station (in x0) where the flow reverses at psi; partial() clips it to [A, B]
  aero_.partial((-mu * std::sin(psi) - p_.root_offset) / p_.length_ratio, out);
  const std::vector<double>& normal = aero_.normal();
  for (std::size_t j = 0; j < out.size(); ++j) out[j] = normal[j] - 2.0 * out[j];
  return out;
}

HarmonicSet SystemBuilder::harmonics(double mu, const std::vector<double>& aero) const {
  HarmonicSet set;
  assemble(mu, aero, set);
  return set;
}

ThrustSystem SystemBuilder::thrust(double mu) const {
  const int ns = 2 * n_;
  auto eval = [&](const std::vector<double>& aero) {
    std::vector<double> force(H_ * ns), forcing(H_);
    model_->thrust(inputs(mu, aero.data()), {force.data(), forcing.data()});
    ThrustHarmonics t;
    t.t = forcing;
    for (int h = 0; h < H_; ++h) {
      Eigen::RowVectorXd r(ns);
      for (int c = 0; c < ns; ++c) r(c) = force[h * ns + c];
      t.tau.push_back(r);
    }
    return t;
  };
  ThrustSystem out;
  out.normal = eval(aero_.normal());
  out.reversed = p_.reversed_flow && mu > 0.0 ? eval(reversed_integrals(mu)) : out.normal;
  return out;
}

PeriodicSystem SystemBuilder::system(double mu) const {
  PeriodicSystem sys;
  system(mu, &sys);
  return sys;
}

void SystemBuilder::system(double mu, PeriodicSystem* out) const {
  if (out == nullptr) throw InvalidInput("out", "null", "a PeriodicSystem to fill is required");
  if (!(mu >= 0.0) || !std::isfinite(mu)) {
    throw InvalidInput("mu", round_trip_text(mu), "advance ratio must be finite and >= 0");
  }
  // The system rebuilt in place, its harmonic sets' and pieces' storage kept (a sweep rebuilds
  // one system per mu).
  PeriodicSystem& sys = *out;
  const bool sector = p_.reversed_flow && !p_.exact_reversed_flow && mu > 0.0;
  sys.sets.resize(sector ? 2 : 1);
  assemble(mu, aero_.normal(), sys.sets[0], ZeroTail::Drop);
  drop_zero_harmonics(sys.sets[0]);
  sys.n = 2 * n_;
  sys.reset_pieces();
  if (p_.reversed_flow && p_.exact_reversed_flow && mu > 0.0) {
    const ExactReversedRegion r = exact_reversed_region(mu, p_);
    if (r.exists) {
      // The system may outlive this builder (it is returned by value): the evaluator owns its
      // table.
      auto table = std::make_shared<const ExactTable>(*this, mu);
      sys.add_evaluator_piece(
          r.begin, r.end,
          [table](double psi, Eigen::MatrixXd& A, Eigen::VectorXd& f) { table->at(psi, A, f); },
          r.breaks);
    }
  } else if (sector) {
    // The reversed-flow sector of Appendix D, centred on the retreating blade.
    const double alpha = reversed_flow_sector_width(mu);
    thread_local std::vector<double> reversed;  // scratch of this thread
    // Only the integrals the linear coefficients read (the others NaN, never read).
    const int linear = model_->n_linear_aero > 0 ? model_->n_linear_aero : model_->n_aero;
    aero_.reversed(mu, reversed, linear);
    assemble(mu, reversed, sys.sets[1], ZeroTail::Drop);
    drop_zero_harmonics(sys.sets[1]);
    sys.add_set_piece(1.5 * kPi - 0.5 * alpha, 1.5 * kPi + 0.5 * alpha, 1);
  }
}

}  // namespace flaplag::detail
