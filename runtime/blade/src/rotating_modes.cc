// flaplag — exact rotating modes by Galerkin's method on nonrotating cantilever functions
// (paper 4.1(b); orthogonality relations A.1-A.4 are the Galerkin equations used here).
#include "flaplag/blade/rotating_modes.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "first_frequency.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"

namespace flaplag {

ModalCombination::ModalCombination(std::vector<std::shared_ptr<const ModeShape>> basis,
                                   Eigen::VectorXd coefficients)
    : basis_(std::move(basis)), coefficients_(std::move(coefficients)) {
  if (static_cast<Eigen::Index>(basis_.size()) != coefficients_.size()) {
    throw InvalidInput(
        "coefficients", std::to_string(coefficients_.size()),
        "must have one coefficient per basis shape (" + std::to_string(basis_.size()) + ")");
  }
}

double ModalCombination::value(int d, double x0) const {
  double v = 0.0;
  for (std::size_t j = 0; j < basis_.size(); ++j) {
    v += coefficients_[static_cast<Eigen::Index>(j)] * basis_[j]->value(d, x0);
  }
  return v;
}

namespace {

constexpr int kMaxBasis = kMaxBasisFunctions;

// The Galerkin matrices divided by mbar, so that lambda = wbar^2 are the eigenvalues of
//   flap: kappa B + G,   lag: kappa B + G - I,   kappa = k / mbar,
// with B = diag(beta_j^4) and G_ij = int phi_i' phi_j' t, t = (1 - x^2)/2 + e (1 - x) = T/mbar
// (the basis is orthonormal, so M / mbar = I and int phi_i'' phi_j'' = beta_j^4 delta_ij hold
// exactly; only G needs quadrature).
struct Galerkin {
  int n = 0;
  std::vector<std::shared_ptr<const ModeShape>> basis;
  Eigen::VectorXd beta4;
  Eigen::MatrixXd g;
  double beta1 = 0.0;

  Galerkin(int n_basis, double e1_over_l) : n(n_basis), beta4(n_basis), g(n_basis, n_basis) {
    for (int j = 1; j <= n; ++j) {
      basis.push_back(cantilever_mode(j));
      const double b = cantilever_root(j);
      beta4[j - 1] = b * b * b * b;
    }
    beta1 = cantilever_root(1);
    const SpanRule rule = span_rule(0.0, 1.0);
    const Eigen::Index nq = static_cast<Eigen::Index>(rule.x0.size());
    Eigen::MatrixXd slope(nq, n);
    Eigen::VectorXd wt(nq);
    for (Eigen::Index q = 0; q < nq; ++q) {
      const double x = rule.x0[q];
      wt[q] = rule.weight[q] * (0.5 * (1.0 - x * x) + e1_over_l * (1.0 - x));
      for (int j = 0; j < n; ++j) slope(q, j) = basis[j]->value(1, x);
    }
    g = slope.transpose() * wt.asDiagonal() * slope;
    g = 0.5 * (g + g.transpose()).eval();
  }

  Eigen::MatrixXd centrifugal(BendingDirection dir) const {
    Eigen::MatrixXd c = g;
    if (dir == BendingDirection::Lag) c -= Eigen::MatrixXd::Identity(n, n);
    return c;
  }

  // Eigenpairs for kappa, ascending; eigenvalues replaced by the Rayleigh quotients of the
  // eigenvectors, evaluated as kappa sum beta^4 c^2 + c'Cc: the stiffness part is a sum of
  // positive terms, so small eigenvalues keep full relative accuracy however large beta_n^4 is.
  std::pair<Eigen::VectorXd, Eigen::MatrixXd> solve(BendingDirection dir, double kappa) const {
    const Eigen::MatrixXd c = centrifugal(dir);
    Eigen::MatrixXd a = c;
    a.diagonal() += kappa * beta4;
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(a);
    Eigen::MatrixXd v = es.eigenvectors();
    Eigen::VectorXd lambda(n);
    for (int i = 0; i < n; ++i) {
      const Eigen::VectorXd vi = v.col(i);
      lambda[i] =
          (kappa * (beta4.array() * vi.array().square()).sum() + vi.dot(c * vi)) / vi.squaredNorm();
    }
    return {lambda, v};
  }

  double first_eigenvalue(BendingDirection dir, double kappa) const {
    return solve(dir, kappa).first[0];
  }
};

// The Galerkin matrices of a nonuniform blade (blade_properties.h) on the same basis:
//   M_ij = int mbar phi_i phi_j + tip phi_i(1) phi_j(1),   B_ij = int kshape phi_i'' phi_j'',
//   G_ij = int T phi_i' phi_j',   T(x) = int_x^1 mbar (x1 + e) dx1 + tip (1 + e),
//   flap: [s B + G] c = w^2 M c,   lag: [s B + G - M] c = w^2 M c   (the -m Omega^2 v term),
// with s the scale of the table's stiffness column (1 when the column is absolute).  The
// quadrature panels end at the table's stations, where the distributions have corners.
struct BladeGalerkin {
  int n = 0;
  std::vector<std::shared_ptr<const ModeShape>> basis;
  Eigen::MatrixXd m, b_flap, b_lag, g;
  Eigen::VectorXd tip_values;

  BladeGalerkin(int n_basis, double e, const BladeProperties& blade)
      : n(n_basis),
        m(Eigen::MatrixXd::Zero(n_basis, n_basis)),
        b_flap(m),
        b_lag(m),
        g(m),
        tip_values(n_basis) {
    for (int j = 1; j <= n; ++j) basis.push_back(cantilever_mode(j));
    const SpanRule rule = span_rule(0.0, 1.0, blade.corners());
    const Eigen::Index nq = static_cast<Eigen::Index>(rule.x0.size());
    Eigen::MatrixXd value(nq, n), slope(nq, n), curvature(nq, n);
    Eigen::VectorXd wm(nq), wt(nq), wf(nq), wl(nq);
    for (Eigen::Index q = 0; q < nq; ++q) {
      const double x = rule.x0[q], w = rule.weight[q];
      wm[q] = w * blade.mass_at(x);
      wt[q] = w * tension(blade, e, x);
      wf[q] = w * blade.at(blade.stiffness_flap, x);
      wl[q] = w * blade.at(blade.stiffness_lag, x);
      for (int j = 0; j < n; ++j) {
        value(q, j) = basis[j]->value(0, x);
        slope(q, j) = basis[j]->value(1, x);
        curvature(q, j) = basis[j]->value(2, x);
      }
    }
    for (int j = 0; j < n; ++j) tip_values[j] = basis[j]->value(0, 1.0);
    m = value.transpose() * wm.asDiagonal() * value +
        blade.tip_mass * tip_values * tip_values.transpose();
    g = slope.transpose() * wt.asDiagonal() * slope;
    b_flap = curvature.transpose() * wf.asDiagonal() * curvature;
    b_lag = curvature.transpose() * wl.asDiagonal() * curvature;
    for (Eigen::MatrixXd* a : {&m, &g, &b_flap, &b_lag}) *a = 0.5 * (*a + a->transpose()).eval();
  }

  // T(x): the exact integral of the piecewise-quadratic mbar (x1 + e) from x to the tip, plus
  // the tip mass's pull.
  static double tension(const BladeProperties& b, double e, double x) {
    double t = b.tip_mass * (1.0 + e);
    for (std::size_t i = 0; i + 1 < b.x0.size(); ++i) {
      const double lo = std::max(b.x0[i], x), hi = b.x0[i + 1];
      if (!(hi > lo)) continue;
      const double mid = 0.5 * (lo + hi);
      auto f = [&](double s) { return b.mass_at(s) * (s + e); };
      t += (hi - lo) / 6.0 * (f(lo) + 4.0 * f(mid) + f(hi));  // Simpson: exact for a quadratic
    }
    return t;
  }

  const Eigen::MatrixXd& stiffness(BendingDirection dir) const {
    return dir == BendingDirection::Flap ? b_flap : b_lag;
  }
  Eigen::MatrixXd centrifugal(BendingDirection dir) const {
    return dir == BendingDirection::Lag ? Eigen::MatrixXd(g - m) : g;
  }

  // Eigenpairs for stiffness scale s, ascending, the eigenvalues as Rayleigh quotients of the
  // eigenvectors (as Galerkin::solve).
  std::pair<Eigen::VectorXd, Eigen::MatrixXd> solve(BendingDirection dir, double s) const {
    const Eigen::MatrixXd c = centrifugal(dir);
    const Eigen::MatrixXd& b = stiffness(dir);
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(s * b + c, m);
    Eigen::MatrixXd v = es.eigenvectors();
    Eigen::VectorXd lambda(n);
    for (int i = 0; i < n; ++i) {
      const Eigen::VectorXd vi = v.col(i);
      lambda[i] = (s * vi.dot(b * vi) + vi.dot(c * vi)) / vi.dot(m * vi);
    }
    return {lambda, v};
  }
  // d lambda_1 / d s at s (Hellmann-Feynman): c'Bc / c'Mc.
  double slope(BendingDirection dir, const Eigen::VectorXd& c) const {
    return c.dot(stiffness(dir) * c) / c.dot(m * c);
  }
  // The nonrotating first frequency squared at scale s: the first eigenvalue of (s B, M).
  double nonrotating(BendingDirection dir, double s) const { return nonrotating_all(dir, s)[0]; }
  // All n nonrotating eigenvalues (frequencies squared) at scale s, ascending.
  Eigen::VectorXd nonrotating_all(BendingDirection dir, double s) const {
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(s * stiffness(dir), m,
                                                                 Eigen::EigenvaluesOnly);
    return es.eigenvalues();
  }
};

// The Galerkin matrices of options.blade, after checking the blade (validate).
BladeGalerkin blade_galerkin(const ExactModeOptions& o) {
  validate(*o.blade);
  return BladeGalerkin(o.n_basis, o.e1_over_l, *o.blade);
}

void check_options(const ExactModeOptions& o) {
  if (o.n_basis < 1 || o.n_basis > kMaxBasis) {
    throw InvalidInput("n_basis", std::to_string(o.n_basis),
                       "number of cantilever functions must be 1.." + std::to_string(kMaxBasis));
  }
  if (o.flap_modes < 1 || o.flap_modes > o.n_basis) {
    throw InvalidInput("flap_modes", std::to_string(o.flap_modes),
                       "must be 1..n_basis = " + std::to_string(o.n_basis));
  }
  if (o.lag_modes < 1 || o.lag_modes > o.n_basis) {
    throw InvalidInput("lag_modes", std::to_string(o.lag_modes),
                       "must be 1..n_basis = " + std::to_string(o.n_basis));
  }
  if (!std::isfinite(o.e1_over_l) || o.e1_over_l < 0.0) {
    throw InvalidInput("e1_over_l", round_trip_text(o.e1_over_l), "must be finite and >= 0");
  }
  if (!std::isfinite(o.mbar) || o.mbar <= 0.0) {
    throw InvalidInput("mbar", round_trip_text(o.mbar), "must be finite and positive");
  }
}

using internal::solve_concave;

// kappa = k/mbar with lambda_1(kappa) = target: solve_concave with the derivative c'Bc
// (Hellmann-Feynman; B > 0).
double solve_kappa(const Galerkin& gal, BendingDirection dir, double omega) {
  internal::check_first_frequency(dir, omega);
  const double target = omega * omega;
  const double lambda0 = gal.first_eigenvalue(dir, 0.0);
  internal::check_above_limit(dir, omega, lambda0,
                              "the " + std::to_string(gal.n) +
                                  "-function cantilever basis (a larger `n_basis` lowers the "
                                  "limit)");
  // Southwell-type start: lambda_1 ~ kappa beta_1^4 + lambda_1(0).
  return solve_concave(
      [&](double kappa) {
        auto [lambda, v] = gal.solve(dir, kappa);
        const Eigen::VectorXd c = v.col(0);
        return std::pair{lambda[0],
                         (gal.beta4.array() * c.array().square()).sum() / c.squaredNorm()};
      },
      target, (target - lambda0) / gal.beta4[0], 2.0);
}

// The stiffness scale s of a blade table with lambda_1(s) = omega^2: as solve_kappa (lambda_1
// is increasing and concave in s).
double solve_scale(const BladeGalerkin& gal, BendingDirection dir, double omega) {
  internal::check_first_frequency(dir, omega);
  const double target = omega * omega;
  const double lambda0 = gal.solve(dir, 0.0).first[0];
  internal::check_above_limit(dir, omega, lambda0, "this blade");
  return solve_concave(
      [&](double scale) {
        auto [lambda, v] = gal.solve(dir, scale);
        return std::pair{lambda[0], gal.slope(dir, v.col(0))};
      },
      target, (target - lambda0) / gal.nonrotating(dir, 1.0), 4.0);
}

// A stiffness (or, with a blade table, a scale) argument: finite and >= 0.
void check_stiffness(BendingDirection dir, double stiffness) {
  if (!std::isfinite(stiffness) || stiffness < 0.0) {
    throw InvalidInput(dir == BendingDirection::Flap ? "stiffness_flap" : "stiffness_lag",
                       round_trip_text(stiffness), "must be finite and >= 0");
  }
}

// Frequencies from eigenvalues (a rounding-negative one as 0).
std::vector<double> frequencies(const Eigen::VectorXd& lambda) {
  std::vector<double> w(static_cast<std::size_t>(lambda.size()));
  for (Eigen::Index i = 0; i < lambda.size(); ++i) w[i] = std::sqrt(std::max(lambda[i], 0.0));
  return w;
}

// A nonrotating first frequency argument: finite and >= 0.
void check_nonrotating(BendingDirection dir, double omega_nonrotating) {
  if (!std::isfinite(omega_nonrotating) || omega_nonrotating < 0.0) {
    throw InvalidInput(
        dir == BendingDirection::Flap ? "omega_flap_nonrotating" : "omega_lag_nonrotating",
        round_trip_text(omega_nonrotating), "must be finite and >= 0");
  }
}

// The first rotating frequency of a blade table whose first nonrotating frequency is wn: the
// nonrotating eigenvalues are linear in the scale, wn^2 = s lambda_N1(1), so s = wn^2 /
// lambda_N1(1).
double table_rotating_first(const BladeGalerkin& gal, BendingDirection dir, double unit_nr,
                            double wn) {
  const double s = wn * wn / unit_nr;
  return std::sqrt(std::max(gal.solve(dir, s).first[0], 0.0));
}

// Shape coefficients scaled to tip value +1: eta(1) = sum c_j phi_j(1), phi_j(1) = 2(-1)^(j+1).
Eigen::VectorXd tip_normalised(Eigen::VectorXd c, bool paper_1974) {
  const Eigen::Index n = c.size();
  if (paper_1974) {
    // The 1974 slip: coefficients computed for phi_j used with tip-(+2) functions.
    for (Eigen::Index j = 1; j < n; j += 2) c[j] = -c[j];
  }
  double tip = 0.0;
  for (Eigen::Index j = 0; j < n; ++j) tip += c[j] * ((j % 2 == 0) ? 2.0 : -2.0);
  return c / tip;
}

}  // namespace

std::vector<double> rotating_frequencies(BendingDirection direction, double stiffness,
                                         const ExactModeOptions& options) {
  check_options(options);
  check_stiffness(direction, stiffness);
  if (options.blade) return frequencies(blade_galerkin(options).solve(direction, stiffness).first);
  const Galerkin gal(options.n_basis, options.e1_over_l);
  const Eigen::VectorXd lambda = gal.solve(direction, stiffness / options.mbar).first;
  std::vector<double> w(static_cast<std::size_t>(gal.n));
  for (int i = 0; i < gal.n; ++i) w[i] = std::sqrt(std::max(lambda[i], 0.0));
  return w;
}

double centrifugal_limit(BendingDirection direction, const ExactModeOptions& options) {
  check_options(options);
  if (options.blade) {
    return std::sqrt(std::max(blade_galerkin(options).solve(direction, 0.0).first[0], 0.0));
  }
  const Galerkin gal(options.n_basis, options.e1_over_l);
  return std::sqrt(std::max(gal.first_eigenvalue(direction, 0.0), 0.0));
}

double stiffness_for_frequency(BendingDirection direction, double omega_rotating,
                               const ExactModeOptions& options) {
  check_options(options);
  if (options.blade) return solve_scale(blade_galerkin(options), direction, omega_rotating);
  const Galerkin gal(options.n_basis, options.e1_over_l);
  return options.mbar * solve_kappa(gal, direction, omega_rotating);
}

namespace {

// The modes of a blade table: stiffness scales solved for the first frequencies, or 1 for
// absolute stiffness columns (omega_* NaN).
ExactModes blade_table_modes(double omega_flap, double omega_lag, const ExactModeOptions& options) {
  validate(*options.blade);
  const BladeGalerkin gal(options.n_basis, options.e1_over_l, *options.blade);
  ExactModes r;
  r.modes.kind = "exact";
  r.modes.blade = options.blade;
  const double first[model::kDirectionCount] = {omega_flap, omega_lag};
  for (const BendingDirection dir : model::kDirections) {
    const double omega = first[model::index(dir)];
    const int count = options.modes(dir);
    DirectionModes& out = r.modes[dir];
    ExactDirection& all = r[dir];
    const double scale = std::isnan(omega) ? 1.0 : solve_scale(gal, dir, omega);
    auto [lambda, v] = gal.solve(dir, scale);
    all.omega_all.resize(static_cast<std::size_t>(gal.n));
    for (int i = 0; i < gal.n; ++i) all.omega_all[i] = std::sqrt(std::max(lambda[i], 0.0));
    out.omega.assign(all.omega_all.begin(), all.omega_all.begin() + count);
    all.coefficients.resize(gal.n, count);
    for (int i = 0; i < count; ++i) {
      all.coefficients.col(i) = tip_normalised(v.col(i), options.paper_1974_shapes);
      out.shapes.push_back(std::make_shared<ModalCombination>(gal.basis, all.coefficients.col(i)));
    }
    all.omega_nonrotating = std::sqrt(std::max(gal.nonrotating(dir, scale), 0.0));
    out.stiffness = scale;
  }
  return r;
}

}  // namespace

ExactModes blade_stiffness_modes(const ExactModeOptions& options) {
  check_options(options);
  if (!options.blade) {
    throw InvalidInput("blade", "none", "modes from the stiffness need a blade table");
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return blade_table_modes(nan, nan, options);
}

ExactModes exact_rotating_modes(double omega_flap, double omega_lag,
                                const ExactModeOptions& options) {
  check_options(options);
  if (options.blade) {
    // NaN would mean "absolute stiffness" inside; here a frequency is required.
    internal::check_first_frequencies(omega_flap, omega_lag);
    return blade_table_modes(omega_flap, omega_lag, options);
  }
  const Galerkin gal(options.n_basis, options.e1_over_l);
  ExactModes r;
  r.modes.kind = "exact";

  const double first[model::kDirectionCount] = {omega_flap, omega_lag};
  for (const BendingDirection dir : model::kDirections) {
    const int count = options.modes(dir);
    DirectionModes& out = r.modes[dir];
    ExactDirection& all = r[dir];
    const double kappa = solve_kappa(gal, dir, first[model::index(dir)]);
    auto [lambda, v] = gal.solve(dir, kappa);
    all.omega_all.resize(static_cast<std::size_t>(gal.n));
    for (int i = 0; i < gal.n; ++i) all.omega_all[i] = std::sqrt(std::max(lambda[i], 0.0));
    out.omega.assign(all.omega_all.begin(), all.omega_all.begin() + count);
    all.coefficients.resize(gal.n, count);
    for (int i = 0; i < count; ++i) {
      all.coefficients.col(i) = tip_normalised(v.col(i), options.paper_1974_shapes);
      out.shapes.push_back(std::make_shared<ModalCombination>(gal.basis, all.coefficients.col(i)));
    }
    out.stiffness = kappa * options.mbar;
    all.omega_nonrotating = std::sqrt(out.stiffness / options.mbar) * gal.beta1 * gal.beta1;
  }
  return r;
}

ModeSet exact_modes(double omega_flap, double omega_lag, const ExactModeOptions& options) {
  return exact_rotating_modes(omega_flap, omega_lag, options).modes;
}

std::vector<double> nonrotating_frequencies(BendingDirection direction, double stiffness,
                                            const ExactModeOptions& options) {
  check_options(options);
  check_stiffness(direction, stiffness);
  if (options.blade) {
    return frequencies(blade_galerkin(options).nonrotating_all(direction, stiffness));
  }
  std::vector<double> w;
  for (int j = 1; j <= options.n_basis; ++j) {
    const double beta = cantilever_root(j);
    w.push_back(std::sqrt(stiffness / options.mbar) * beta * beta);
  }
  return w;
}

double nonrotating_frequency(BendingDirection direction, double omega_rotating,
                             const ExactModeOptions& options) {
  if (options.blade) {
    check_options(options);
    const BladeGalerkin gal = blade_galerkin(options);
    const double s = solve_scale(gal, direction, omega_rotating);
    return std::sqrt(std::max(gal.nonrotating(direction, s), 0.0));
  }
  const double k = stiffness_for_frequency(direction, omega_rotating, options);
  const double b1 = cantilever_root(1);
  return std::sqrt(k / options.mbar) * b1 * b1;
}

double rotating_frequency(BendingDirection direction, double omega_nonrotating,
                          const ExactModeOptions& options) {
  check_options(options);
  check_nonrotating(direction, omega_nonrotating);
  if (options.blade) {
    const BladeGalerkin gal = blade_galerkin(options);
    return table_rotating_first(gal, direction, gal.nonrotating(direction, 1.0), omega_nonrotating);
  }
  const Galerkin gal(options.n_basis, options.e1_over_l);
  const double r = omega_nonrotating / (gal.beta1 * gal.beta1);
  return std::sqrt(std::max(gal.first_eigenvalue(direction, r * r), 0.0));
}

std::vector<FrequencyPair> fig9_table(BendingDirection direction, double omega_nonrotating_lo,
                                      double omega_nonrotating_hi, int n_points,
                                      const ExactModeOptions& options) {
  check_options(options);
  if (n_points < 2) {
    throw InvalidInput("n_points", std::to_string(n_points), "must be >= 2");
  }
  if (!std::isfinite(omega_nonrotating_lo) || omega_nonrotating_lo < 0.0) {
    throw InvalidInput("omega_nonrotating_lo", round_trip_text(omega_nonrotating_lo),
                       "must be finite and >= 0");
  }
  if (!std::isfinite(omega_nonrotating_hi) || omega_nonrotating_hi < omega_nonrotating_lo) {
    throw InvalidInput(
        "omega_nonrotating_hi", round_trip_text(omega_nonrotating_hi),
        "must be finite and >= omega_nonrotating_lo = " + round_trip_text(omega_nonrotating_lo));
  }
  std::vector<FrequencyPair> table;
  table.reserve(static_cast<std::size_t>(n_points));
  if (options.blade) {
    const BladeGalerkin gal = blade_galerkin(options);
    const double unit = gal.nonrotating(direction, 1.0);
    for (int i = 0; i < n_points; ++i) {
      const double t = static_cast<double>(i) / (n_points - 1);
      const double wn = omega_nonrotating_lo + t * (omega_nonrotating_hi - omega_nonrotating_lo);
      table.push_back({wn, table_rotating_first(gal, direction, unit, wn)});
    }
    return table;
  }
  const Galerkin gal(options.n_basis, options.e1_over_l);
  const double b12 = gal.beta1 * gal.beta1;
  for (int i = 0; i < n_points; ++i) {
    const double t = static_cast<double>(i) / (n_points - 1);
    const double wn = omega_nonrotating_lo + t * (omega_nonrotating_hi - omega_nonrotating_lo);
    const double r = wn / b12;
    const double lambda = gal.first_eigenvalue(direction, r * r);
    table.push_back({wn, std::sqrt(std::max(lambda, 0.0))});
  }
  return table;
}

namespace {

// sqrt of the Rayleigh quotient [scale int k w''^2 + int T w'^2] / [int mbar w^2 + tip w(1)^2]
// (lag: minus 1, eq A.4, the -m Omega^2 v term on the whole mass) by quadrature on `rule`, with
// k, T and mbar given at each node.
template <typename Stiffness, typename Tension, typename Mass>
double rayleigh_root(BendingDirection direction, const ModeShape& shape, double scale,
                     const SpanRule& rule, Stiffness k, Tension t, Mass mbar, double tip_mass) {
  double strain = 0.0;
  double tension = 0.0;
  double mass = 0.0;
  for (std::size_t q = 0; q < rule.x0.size(); ++q) {
    const double x = rule.x0[q];
    const double w = rule.weight[q];
    const double d0 = shape.value(0, x);
    const double d1 = shape.value(1, x);
    const double d2 = shape.value(2, x);
    strain += w * k(x) * d2 * d2;
    tension += w * d1 * d1 * t(x);
    mass += w * mbar(x) * d0 * d0;
  }
  const double tip = shape.value(0, 1.0);
  mass += tip_mass * tip * tip;
  double r = (scale * strain + tension) / mass;
  if (direction == BendingDirection::Lag) r -= 1.0;
  return std::sqrt(std::max(r, 0.0));
}

void check_rayleigh(double stiffness, double e1_over_l) {
  if (!std::isfinite(stiffness) || stiffness < 0.0) {
    throw InvalidInput("stiffness", round_trip_text(stiffness), "must be finite and >= 0");
  }
  if (!std::isfinite(e1_over_l) || e1_over_l < 0.0) {
    throw InvalidInput("e1_over_l", round_trip_text(e1_over_l), "must be finite and >= 0");
  }
}

}  // namespace

double rayleigh_frequency(BendingDirection direction, const ModeShape& shape, double stiffness,
                          double e1_over_l, double mbar) {
  check_rayleigh(stiffness, e1_over_l);
  if (!std::isfinite(mbar) || mbar <= 0.0) {
    throw InvalidInput("mbar", round_trip_text(mbar), "must be finite and positive");
  }
  return rayleigh_root(
      direction, shape, stiffness, span_rule(0.0, 1.0), [](double) { return 1.0; },
      [&](double x) { return mbar * (0.5 * (1.0 - x * x) + e1_over_l * (1.0 - x)); },
      [&](double) { return mbar; }, 0.0);
}

double rayleigh_frequency(BendingDirection direction, const ModeShape& shape, double scale,
                          double e1_over_l, const BladeProperties& blade) {
  check_rayleigh(scale, e1_over_l);
  validate(blade);
  const std::vector<double>& column =
      direction == BendingDirection::Flap ? blade.stiffness_flap : blade.stiffness_lag;
  return rayleigh_root(
      direction, shape, scale, span_rule(0.0, 1.0, blade.corners()),
      [&](double x) { return blade.at(column, x); },
      [&](double x) { return BladeGalerkin::tension(blade, e1_over_l, x); },
      [&](double x) { return blade.mass_at(x); }, blade.tip_mass);
}

}  // namespace flaplag
