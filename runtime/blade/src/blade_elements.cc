// flaplag — rotating modes by cubic Hermite finite elements (blade_elements.h).
#include "flaplag/blade/blade_elements.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "first_frequency.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"

namespace flaplag {

namespace {

// The Hermite cubics on xi in [0, 1] for an element of length h, derivative order d in 0..3 by
// x: deflection and slope at the left node, deflection and slope at the right node.
std::array<double, 4> hermite(int d, double t, double h) {
  switch (d) {
    case 0:
      return {1.0 - t * t * (3.0 - 2.0 * t), h * t * (1.0 - t) * (1.0 - t), t * t * (3.0 - 2.0 * t),
              h * t * t * (t - 1.0)};
    case 1:
      return {6.0 * t * (t - 1.0) / h, (1.0 - t) * (1.0 - 3.0 * t), 6.0 * t * (1.0 - t) / h,
              t * (3.0 * t - 2.0)};
    case 2:
      return {(12.0 * t - 6.0) / (h * h), (6.0 * t - 4.0) / h, (6.0 - 12.0 * t) / (h * h),
              (6.0 * t - 2.0) / h};
    default:
      return {12.0 / (h * h * h), 6.0 / (h * h), -12.0 / (h * h * h), 6.0 / (h * h)};
  }
}

// An iterated eigenvalue has settled when it changes by less than this, relative: its rounding
// (a few eps) would otherwise keep the iterations going to their limit.
constexpr double kSettled = 16.0 * std::numeric_limits<double>::epsilon();

// 5-point Gauss-Legendre on [0, 1]: exact for degree 9 (the element integrands reach 7).
constexpr std::array<double, 5> kGaussT = {0.04691007703066800, 0.23076534494715845, 0.5,
                                           0.76923465505284155, 0.95308992296933200};
constexpr std::array<double, 5> kGaussW = {0.11846344252809454, 0.23931433524968324,
                                           0.28444444444444444, 0.23931433524968324,
                                           0.11846344252809454};

// The blade's distributions as the elements see them: the table, or the uniform blade of mass
// mbar and unit stiffness shape.
struct Distributions {
  const BladeProperties* table = nullptr;
  double mbar = 3.0;
  double e = 0.0;  // e1 / l

  double mass(double x) const { return table ? table->mass_at(x) : mbar; }
  double tip() const { return table ? table->tip_mass : 0.0; }
  double stiffness(BendingDirection dir, double x) const {
    if (!table) return 1.0;
    return table->at(dir == BendingDirection::Flap ? table->stiffness_flap : table->stiffness_lag,
                     x);
  }
  // T(x) = int_x^1 mbar (x1 + e) dx1 + tip (1 + e): Simpson on each interval (exact for the
  // quadratic integrand).
  double tension(double x) const {
    auto f = [&](double s) { return mass(s) * (s + e); };
    auto simpson = [&](double lo, double hi) {
      return (hi - lo) / 6.0 * (f(lo) + 4.0 * f(0.5 * (lo + hi)) + f(hi));
    };
    double t = tip() * (1.0 + e);
    if (!table) return t + simpson(x, 1.0);
    for (std::size_t i = 0; i + 1 < table->x0.size(); ++i) {
      const double lo = std::max(table->x0[i], x), hi = table->x0[i + 1];
      if (hi > lo) t += simpson(lo, hi);
    }
    return t;
  }
};

// The assembled matrices on the clamped mesh: unknowns (w_i, w_i') of nodes 1..n.  Each Gauss
// point keeps the deflection, slope and curvature of its element's four shape functions (the
// matrices are sums of their weighted products), so that a Rayleigh quotient costs one pass
// over the points.
struct Elements {
  struct Point {
    Eigen::Index first;                // the unknown of the element's first shape; < 0: clamped
    std::array<double, 4> n0, n1, n2;  // deflection, slope, curvature of the four shapes
    double wm, wt, wk_f, wk_l;         // weight times mbar, T, k shape (flap, lag)
  };
  std::vector<double> nodes;
  std::vector<Point> points;
  double tip = 0.0;
  Eigen::MatrixXd m, b_flap, b_lag, g;

  Elements(const Distributions& dist, std::vector<double> mesh) : nodes(std::move(mesh)) {
    const Eigen::Index n = 2 * static_cast<Eigen::Index>(nodes.size() - 1);
    m = Eigen::MatrixXd::Zero(n, n);
    b_flap = m;
    b_lag = m;
    g = m;
    for (std::size_t el = 0; el + 1 < nodes.size(); ++el) {
      const double x0 = nodes[el], h = nodes[el + 1] - x0;
      for (int q = 0; q < 5; ++q) {
        const double t = kGaussT[q], w = kGaussW[q] * h, x = x0 + t * h;
        Point p{2 * static_cast<Eigen::Index>(el) - 2,
                hermite(0, t, h),
                hermite(1, t, h),
                hermite(2, t, h),
                w * dist.mass(x),
                w * dist.tension(x),
                w * dist.stiffness(BendingDirection::Flap, x),
                w * dist.stiffness(BendingDirection::Lag, x)};
        for (int i = 0; i < 4; ++i) {
          if (p.first + i < 0) continue;
          for (int j = 0; j < 4; ++j) {
            if (p.first + j < 0) continue;
            const Eigen::Index r = p.first + i, c = p.first + j;
            m(r, c) += p.wm * p.n0[i] * p.n0[j];
            g(r, c) += p.wt * p.n1[i] * p.n1[j];
            b_flap(r, c) += p.wk_f * p.n2[i] * p.n2[j];
            b_lag(r, c) += p.wk_l * p.n2[i] * p.n2[j];
          }
        }
        points.push_back(p);
      }
    }
    tip = dist.tip();
    m(n - 2, n - 2) += tip;
  }

  Eigen::Index size() const { return m.rows(); }
  const Eigen::MatrixXd& stiffness(BendingDirection dir) const {
    return dir == BendingDirection::Flap ? b_flap : b_lag;
  }
  // The stiffness matrix at scale s: s B + G (flap), s B + G - M (lag, the -m Omega^2 v term);
  // without rotation s B.
  Eigen::MatrixXd k(BendingDirection dir, double s, bool rotating = true) const {
    if (!rotating) return s * stiffness(dir);
    Eigen::MatrixXd a = s * stiffness(dir) + g;
    if (dir == BendingDirection::Lag) a -= m;
    return a;
  }

  // The Rayleigh quotient of v as sums of positive terms: v'Kv computed as a product carries the
  // rounding of the largest element stiffness (~1/h^4 times a low mode's energy); its slope
  // in s, v'Bv / v'Mv, likewise.
  std::pair<double, double> quotient(BendingDirection dir, double s, const Eigen::VectorXd& v,
                                     bool rotating = true) const {
    const bool flap = dir == BendingDirection::Flap;
    double bend = 0.0, tension = 0.0, mass = tip * v[size() - 2] * v[size() - 2];
    for (const Point& p : points) {
      double w = 0.0, slope = 0.0, curvature = 0.0;
      for (int i = 0; i < 4; ++i) {
        if (p.first + i < 0) continue;
        const double vi = v[p.first + i];
        w += p.n0[i] * vi;
        slope += p.n1[i] * vi;
        curvature += p.n2[i] * vi;
      }
      bend += (flap ? p.wk_f : p.wk_l) * curvature * curvature;
      tension += p.wt * slope * slope;
      mass += p.wm * w * w;
    }
    double num = s * bend;
    if (rotating) {
      num += tension;
      if (dir == BendingDirection::Lag) num -= mass;
    }
    return {num / mass, bend / mass};
  }

  // The first eigenpair of (K, M) by inverse iteration on K + M (positive definite: s B + G >= 0,
  // M > 0) from `v`: the eigenvalue and its slope in s as quotients of the iterate.
  struct Pair {
    double lambda, slope;
    Eigen::VectorXd v;
  };
  Pair first(BendingDirection dir, double s, Eigen::VectorXd v, bool rotating = true) const {
    const Eigen::LLT<Eigen::MatrixXd> llt(k(dir, s, rotating) + m);
    double lambda = quotient(dir, s, v, rotating).first;
    for (int it = 0; it < 500; ++it) {
      v = llt.solve(m * v);
      v /= v.cwiseAbs().maxCoeff();
      const double next = quotient(dir, s, v, rotating).first;
      const bool done = std::abs(next - lambda) <= kSettled * std::max(std::abs(next), 1.0);
      lambda = next;
      if (done) break;
    }
    const auto [l, slope] = quotient(dir, s, v, rotating);
    return {l, slope, v};
  }

  // The lowest `count` eigenpairs of (K(s), M), ascending.  A dense solver's small eigenvalues
  // carry the rounding of the largest (1e-9 relative at 96 elements), so its vectors only start
  // a subspace iteration on (K + M)^-1 M with Rayleigh-Ritz steps; the eigenvalues are the
  // quotients of the converged vectors.
  std::pair<Eigen::VectorXd, Eigen::MatrixXd> lowest(BendingDirection dir, double s,
                                                     int count) const {
    const Eigen::MatrixXd a = k(dir, s);
    const Eigen::Index p = std::min<Eigen::Index>(size(), count + 4);
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(a, m);
    Eigen::MatrixXd x = es.eigenvectors().leftCols(p);
    const Eigen::LLT<Eigen::MatrixXd> llt(a + m);
    Eigen::VectorXd lambda = Eigen::VectorXd::Constant(p, std::numeric_limits<double>::infinity());
    for (int it = 0; it < 200; ++it) {
      x = llt.solve(m * x);
      const Eigen::MatrixXd ar = x.transpose() * a * x, mr = x.transpose() * m * x;
      Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> small(0.5 * (ar + ar.transpose()),
                                                                      0.5 * (mr + mr.transpose()));
      x = (x * small.eigenvectors()).eval();
      bool done = true;
      for (Eigen::Index i = 0; i < p; ++i) {
        x.col(i) /= x.col(i).cwiseAbs().maxCoeff();
        const double next = quotient(dir, s, x.col(i)).first;
        if (i < count && !(std::abs(next - lambda[i]) <= kSettled * std::max(std::abs(next), 1.0)))
          done = false;
        lambda[i] = next;
      }
      if (done) break;
    }
    return {lambda.head(count), x.leftCols(count)};
  }

  // The tip-normalised shape of eigenvector q.
  std::shared_ptr<const ModeShape> shape(const Eigen::VectorXd& q) const {
    const Eigen::Index n = size();
    const double at_tip = q[n - 2];
    std::vector<double> w(nodes.size(), 0.0), dw(nodes.size(), 0.0);
    for (std::size_t i = 1; i < nodes.size(); ++i) {
      w[i] = q[2 * static_cast<Eigen::Index>(i) - 2] / at_tip;
      dw[i] = q[2 * static_cast<Eigen::Index>(i) - 1] / at_tip;
    }
    return std::make_shared<ElementModeShape>(nodes, std::move(w), std::move(dw));
  }
};

// The scale s with first eigenvalue omega^2, as rotating_modes.cc solves it for the Galerkin
// basis (lambda_1 increasing and concave in s; slope q'Bq / q'Mq).
double solve_scale(const Elements& el, BendingDirection dir, double omega) {
  internal::check_first_frequency(dir, omega);
  const double target = omega * omega;
  Eigen::VectorXd v = Eigen::VectorXd::Ones(el.size());
  const double lambda0 = el.first(dir, 0.0, v).lambda;
  internal::check_above_limit(dir, omega, lambda0, "this blade");
  // Newton starts from lambda_1 ~ s lambda_N + lambda_0, lambda_N the nonrotating first
  // eigenvalue at s = 1.
  const double nonrotating = el.first(dir, 1.0, v, false).lambda;
  return internal::solve_concave(
      [&](double s) {
        Elements::Pair p = el.first(dir, s, v);
        v = p.v;
        return std::pair{p.lambda, p.slope};
      },
      target, (target - lambda0) / nonrotating, 4.0);
}

ExactModes element_modes(double omega_flap, double omega_lag, const ExactModeOptions& options) {
  if (options.paper_1974_shapes) {
    throw InvalidInput("paper_1974_shapes", "true",
                       "the 1974 sign slip is a property of the Galerkin basis, not of finite "
                       "elements");
  }
  if (options.blade) validate(*options.blade);
  if (!std::isfinite(options.e1_over_l) || options.e1_over_l < 0.0) {
    throw InvalidInput("e1_over_l", round_trip_text(options.e1_over_l), "must be finite and >= 0");
  }
  if (!std::isfinite(options.mbar) || options.mbar <= 0.0) {
    throw InvalidInput("mbar", round_trip_text(options.mbar), "must be finite and positive");
  }
  for (const auto& [name, count] :
       {std::pair{"flap_modes", options.flap_modes}, std::pair{"lag_modes", options.lag_modes}}) {
    if (count < 1 || count > kMaxBasisFunctions) {
      throw InvalidInput(name, std::to_string(count),
                         "must be 1.." + std::to_string(kMaxBasisFunctions));
    }
  }
  const Distributions dist{options.blade.get(), options.mbar, options.e1_over_l};
  const Elements el(dist, element_nodes(options.blade.get()));
  ExactModes r;
  r.modes.kind = "exact";
  r.modes.blade = options.blade;
  r.modes.mesh.assign(el.nodes.begin() + 1, el.nodes.end() - 1);
  const double first[model::kDirectionCount] = {omega_flap, omega_lag};
  for (const BendingDirection dir : model::kDirections) {
    const double omega = first[model::index(dir)];
    const int count = options.modes(dir);
    DirectionModes& out = r.modes[dir];
    ExactDirection& all = r[dir];
    const double scale = std::isnan(omega) ? 1.0 : solve_scale(el, dir, omega);
    const int n = std::min<int>(kMaxBasisFunctions, static_cast<int>(el.size()));
    auto [lambda, v] = el.lowest(dir, scale, n);
    all.omega_all.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) all.omega_all[i] = std::sqrt(std::max(lambda[i], 0.0));
    out.omega.assign(all.omega_all.begin(), all.omega_all.begin() + count);
    for (int i = 0; i < count; ++i) out.shapes.push_back(el.shape(v.col(i)));
    const double nr = el.first(dir, scale, v.col(0), false).lambda;
    all.omega_nonrotating = std::sqrt(std::max(nr, 0.0));
    out.stiffness = scale;
  }
  // The uniform blade's stiffness column is 1 (mbar is in M and T): its scale is k itself.
  return r;
}

}  // namespace

ElementModeShape::ElementModeShape(std::vector<double> nodes, std::vector<double> deflection,
                                   std::vector<double> slope)
    : nodes_(std::move(nodes)), w_(std::move(deflection)), dw_(std::move(slope)) {}

double ElementModeShape::value(int d, double x0) const {
  if (d < 0 || d > 3) {
    throw InvalidInput("derivative order", std::to_string(d), "must be 0..3");
  }
  const double x = std::clamp(x0, nodes_.front(), nodes_.back());
  const auto it = std::upper_bound(nodes_.begin(), nodes_.end(), x);
  std::size_t i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - nodes_.begin() - 1, 0));
  i = std::min(i, nodes_.size() - 2);
  const double h = nodes_[i + 1] - nodes_[i];
  const auto n = hermite(d, (x - nodes_[i]) / h, h);
  return n[0] * w_[i] + n[1] * dw_[i] + n[2] * w_[i + 1] + n[3] * dw_[i + 1];
}

std::vector<double> element_nodes(const BladeProperties* blade) {
  const std::vector<double> stations =
      blade != nullptr && blade->x0.size() >= 2 ? blade->x0 : std::vector<double>{0.0, 1.0};
  std::vector<double> nodes = {stations.front()};
  for (std::size_t i = 0; i + 1 < stations.size(); ++i) {
    const double lo = stations[i], hi = stations[i + 1];
    const int n = std::max(1, static_cast<int>(std::ceil((hi - lo) * kElementsPerSpan - 1e-9)));
    for (int k = 1; k < n; ++k) nodes.push_back(lo + (hi - lo) * k / n);
    nodes.push_back(hi);
  }
  return nodes;
}

ExactModes element_rotating_modes(double omega_flap, double omega_lag,
                                  const ExactModeOptions& options) {
  internal::check_first_frequencies(omega_flap, omega_lag);
  return element_modes(omega_flap, omega_lag, options);
}

ExactModes element_stiffness_modes(const ExactModeOptions& options) {
  if (!options.blade) {
    throw InvalidInput("blade", "none", "modes from the stiffness need a blade table");
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return element_modes(nan, nan, options);
}

}  // namespace flaplag
