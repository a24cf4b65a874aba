// flaplag — spanwise integrals: aerodynamic coefficients (Appendix B, split for reversed flow as
// in Appendix D), structural generalized masses (Appendix B) and elastic coupling (Appendix E).
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "flaplag/blade/blade.h"
#include "flaplag/blade/blade_properties.h"
#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"

namespace flaplag {
namespace {

using model::Direction;
using model::Factor;
using model::FactorRef;

constexpr int kGaussPoints = 20;
constexpr int kPanels = 8;

struct GaussRule {
  std::array<double, kGaussPoints> t{};  // nodes on [-1, 1]
  std::array<double, kGaussPoints> w{};
};

// Gauss-Legendre nodes by Newton iteration on P_n (three-term recurrence); converges to full
// double precision from the Tricomi initial guess.
GaussRule make_gauss_rule() {
  GaussRule r;
  const int n = kGaussPoints;
  for (int i = 0; i < n; ++i) {
    double t = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0;
      double p1 = t;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * t * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (t * p1 - p0) / (t * t - 1.0);
      const double step = p1 / dp;
      t -= step;
      if (std::abs(step) < 1e-17) break;
    }
    r.t[i] = t;
    r.w[i] = 2.0 / ((1.0 - t * t) * dp * dp);
  }
  return r;
}

const GaussRule& gauss_rule() {
  static const GaussRule rule = make_gauss_rule();
  return rule;
}

// Gauss nodes of one interval [a, b] appended to (x, w).
void append_interval(double a, double b, std::vector<double>& x, std::vector<double>& w) {
  const GaussRule& g = gauss_rule();
  const double half = 0.5 * (b - a);
  const double mid = 0.5 * (a + b);
  const std::size_t at = x.size();
  x.resize(at + kGaussPoints);
  w.resize(at + kGaussPoints);
  for (std::size_t i = 0; i < static_cast<std::size_t>(kGaussPoints); ++i) {
    x[at + i] = mid + half * g.t[i];
    w[at + i] = half * g.w[i];
  }
}

const char* factor_name(Factor f) {
  switch (f) {
    case Factor::Eta:
      return "eta";
    case Factor::EtaPrime:
      return "eta'";
    case Factor::Gamma:
      return "gamma";
    case Factor::GammaPrime:
      return "gamma'";
    case Factor::X0:
      return "x0";
    case Factor::Arm:
      return "arm";
    case Factor::Twist:
      return "tw";
  }
  return "?";
}

// Values of spanwise factors at a fixed list of stations, each distinct (kind, mode) evaluated
// once: a model has tens of integrals over the same few mode shapes, and exact modes cost a few
// transcendental functions per basis function and station.
class FactorTable {
 public:
  FactorTable(const ModeSet& modes, std::vector<double> x0, double arm_offset)
      : modes_(modes), x0_(std::move(x0)), arm_offset_(arm_offset) {}

  std::size_t size() const { return x0_.size(); }

  const std::vector<double>& values(const FactorRef& f, const char* integral) {
    const int kind = static_cast<int>(f.kind);
    const int mode = model::has_mode(f.kind) ? f.mode : 0;
    const auto key = std::make_pair(kind, mode);
    auto it = cache_.find(key);
    if (it != cache_.end()) return it->second;

    std::vector<double> v(x0_.size());
    if (f.kind == Factor::Twist) {
      // Built-in twist theta_tw(x0); the paper's uniform blade (no table) is untwisted.
      for (std::size_t q = 0; q < x0_.size(); ++q)
        v[q] = modes_.blade ? modes_.blade->twist_at(x0_[q]) : 0.0;
    } else if (f.kind == Factor::X0 || f.kind == Factor::Arm) {
      const double off = f.kind == Factor::Arm ? arm_offset_ : 0.0;
      for (std::size_t q = 0; q < x0_.size(); ++q) v[q] = x0_[q] + off;
    } else {
      const bool flap = f.kind == Factor::Eta || f.kind == Factor::EtaPrime;
      const auto& shapes = modes_.shapes(flap ? Direction::Flap : Direction::Lag);
      if (mode < 0 || mode >= static_cast<int>(shapes.size())) {
        throw InvalidInput(
            std::string("mode index of ") + factor_name(f.kind) + " in \"" + integral + "\"",
            std::to_string(mode),
            "the mode set has " + std::to_string(shapes.size()) + (flap ? " flap" : " lag") +
                " modes");
      }
      const int d = (f.kind == Factor::EtaPrime || f.kind == Factor::GammaPrime) ? 1 : 0;
      const ModeShape& shape = *shapes[mode];
      for (std::size_t q = 0; q < x0_.size(); ++q) v[q] = shape.value(d, x0_[q]);
    }
    return cache_.emplace(key, std::move(v)).first->second;
  }

  // prod(factors) at every station, times scale.
  std::vector<double> product(const FactorRef* factors, int n_factors, double scale,
                              const char* integral) {
    if (n_factors < 0 || n_factors > 4) {
      throw InvalidInput(std::string("factor count of \"") + integral + "\"",
                         std::to_string(n_factors), "must be 0..4");
    }
    std::vector<double> p(x0_.size(), scale);
    for (int i = 0; i < n_factors; ++i) {
      const std::vector<double>& v = values(factors[i], integral);
      for (std::size_t q = 0; q < p.size(); ++q) p[q] *= v[q];
    }
    return p;
  }

 private:
  const ModeSet& modes_;
  std::vector<double> x0_;
  double arm_offset_;
  std::map<std::pair<int, int>, std::vector<double>> cache_;
};

}  // namespace

void validate(const SpanGeometry& g) {
  if (!std::isfinite(g.e1) || g.e1 < 0.0) {
    throw InvalidInput("e1", round_trip_text(g.e1), "hinge offset by R must be finite and >= 0");
  }
  if (!std::isfinite(g.lr) || g.lr <= 0.0) {
    throw InvalidInput("lr", round_trip_text(g.lr), "l/R must be finite and positive");
  }
  if (!std::isfinite(g.tip_loss_a) || !std::isfinite(g.tip_loss_b) || g.tip_loss_a > g.tip_loss_b) {
    throw InvalidInput(
        "tip_loss_a", round_trip_text(g.tip_loss_a),
        "tip-loss limits must be finite with A <= B = " + round_trip_text(g.tip_loss_b));
  }
}

std::vector<std::vector<double>> aero_integrands(const model::ModelDescriptor& m,
                                                 const ModeSet& modes, const SpanGeometry& g,
                                                 const std::vector<double>& x0) {
  validate(g);
  FactorTable table(modes, x0, g.e1 / g.lr);
  std::vector<std::vector<double>> out(static_cast<std::size_t>(m.n_aero));
  for (int j = 0; j < m.n_aero; ++j) {
    const model::AeroIntegral& spec = m.aero[j];
    std::vector<double> v = table.product(spec.factors, spec.n_factors, 1.0, spec.name);
    for (std::size_t q = 0; q < x0.size(); ++q) v[q] *= std::pow(g.e1 + g.lr * x0[q], spec.x_power);
    // Every aerodynamic load is proportional to the local chord (eqs 2.18-2.19 per unit span).
    if (modes.blade)
      for (std::size_t q = 0; q < x0.size(); ++q) v[q] *= modes.blade->chord_at(x0[q]);
    out[j] = std::move(v);
  }
  return out;
}

namespace {

// One flow region [lo, hi] of the aerodynamic span: stations, weights and factor values.
class AeroRegion {
 public:
  AeroRegion(const ModeSet& modes, const SpanGeometry& g, double lo, double hi)
      : rule_(span_rule(lo, hi, blade_corners(modes))), table_(modes, rule_.x0, g.e1 / g.lr) {
    x_.resize(rule_.x0.size());
    for (std::size_t q = 0; q < x_.size(); ++q) x_[q] = g.e1 + g.lr * rule_.x0[q];
    chord_.assign(rule_.x0.size(), 1.0);
    if (modes.blade)
      for (std::size_t q = 0; q < x_.size(); ++q) chord_[q] = modes.blade->chord_at(rule_.x0[q]);
  }

  double integral(const model::AeroIntegral& spec) {
    if (spec.x_power < 0) {
      throw InvalidInput(std::string("x power of \"") + spec.name + "\"",
                         std::to_string(spec.x_power), "must be >= 0");
    }
    const std::vector<double> p = table_.product(spec.factors, spec.n_factors, 1.0, spec.name);
    double sum = 0.0;
    for (std::size_t q = 0; q < p.size(); ++q) {
      double xp = 1.0;
      for (int k = 0; k < spec.x_power; ++k) xp *= x_[q];
      sum += rule_.weight[q] * xp * p[q] * chord_[q];
    }
    return sum;
  }

 private:
  SpanRule rule_;
  FactorTable table_;
  std::vector<double> x_, chord_;
};

// Stations for int_0^1 F(x) J(x) dx with J a tail (int_x^1) or head (int_0^x) integral.
// Outer: the composite rule on [0, 1] (panels ending at the blade's corners).  For each outer
// station x in panel [a, b], J is the Gauss integral over the partial panel [x, b] (tail) or
// [a, x] (head) plus the whole-panel Gauss sums of the other panels, so J is as accurate as a
// single integral and exact for polynomials.  A blade's mass mbar(x) weights the integrands
// station by station, and its tip mass adds the point terms at x0 = 1 (blade_properties.h).
class NestedGrid {
 public:
  NestedGrid(const ModeSet& modes, double e1_over_l)
      : blade_(modes.blade.get()),
        edges_(panel_edges(0.0, 1.0, blade_corners(modes))),
        outer_rule_(span_rule(0.0, 1.0, blade_corners(modes))),
        outer_(modes, outer_rule_.x0, e1_over_l),
        tail_(modes, partial_points(true, tail_w_, tail_x_), e1_over_l),
        head_(modes, partial_points(false, head_w_, head_x_), e1_over_l),
        tip_(modes, std::vector<double>{1.0}, e1_over_l) {}

  double integral(const model::StructuralIntegral& spec, double mbar) {
    const int panels = static_cast<int>(edges_.size()) - 1;
    const bool has_tip = blade_ != nullptr && blade_->tip_mass > 0.0;
    if (has_tip &&
        (spec.outer_mass > 1 || spec.inner_mass > 1 ||
         (spec.inner != model::Inner::None && spec.outer_mass > 0 && spec.inner_mass > 0))) {
      throw InvalidInput(std::string("structural integral \"") + spec.name + "\"", "tip mass",
                         "a point mass has no value for this power of the mass");
    }
    std::vector<double> f =
        outer_.product(spec.outer, spec.n_outer, mass_scale(spec.outer_mass, mbar), spec.name);
    weigh(f, outer_rule_.x0, spec.outer_mass);
    const std::size_t n = f.size();
    std::vector<double> j(n, 1.0);
    // The tip mass's share of the inner integral: all of it for a tail (x < 1), none for a head.
    double inner_tip = 0.0;
    if (spec.inner != model::Inner::None) {
      const bool tail = spec.inner == model::Inner::Tail;
      const double inner_scale = mass_scale(spec.inner_mass, mbar);
      // Whole-panel integrals of the inner integrand, on the outer stations.
      std::vector<double> g_outer =
          outer_.product(spec.inner_factors, spec.n_inner, inner_scale, spec.name);
      weigh(g_outer, outer_rule_.x0, spec.inner_mass);
      std::vector<double> panel(static_cast<std::size_t>(panels), 0.0);
      for (int p = 0; p < panels; ++p) {
        for (int i = 0; i < kGaussPoints; ++i) {
          const std::size_t q = static_cast<std::size_t>(p * kGaussPoints + i);
          panel[p] += outer_rule_.weight[q] * g_outer[q];
        }
      }
      FactorTable& partial = tail ? tail_ : head_;
      const std::vector<double>& pw = tail ? tail_w_ : head_w_;
      std::vector<double> g_part =
          partial.product(spec.inner_factors, spec.n_inner, inner_scale, spec.name);
      weigh(g_part, tail ? tail_x_ : head_x_, spec.inner_mass);
      if (has_tip && tail && spec.inner_mass == 1)
        inner_tip =
            blade_->tip_mass * tip_.product(spec.inner_factors, spec.n_inner, 1.0, spec.name)[0];
      for (int p = 0; p < panels; ++p) {
        double others = 0.0;
        if (tail) {
          for (int r = p + 1; r < panels; ++r) others += panel[r];
        } else {
          for (int r = 0; r < p; ++r) others += panel[r];
        }
        for (int i = 0; i < kGaussPoints; ++i) {
          const std::size_t q = static_cast<std::size_t>(p * kGaussPoints + i);
          double part = 0.0;
          for (int k = 0; k < kGaussPoints; ++k) {
            const std::size_t s = q * kGaussPoints + static_cast<std::size_t>(k);
            part += pw[s] * g_part[s];
          }
          j[q] = others + part + inner_tip;
        }
      }
    }
    double sum = 0.0;
    for (std::size_t q = 0; q < n; ++q) sum += outer_rule_.weight[q] * f[q] * j[q];
    if (has_tip && spec.outer_mass == 1) {
      // The point mass's own term: the outer integrand at the tip times the inner integral
      // there (a head integral over the whole span; a tail one has no mass outboard).
      double j_tip = 1.0;
      if (spec.inner == model::Inner::Tail) {
        j_tip = 0.0;
      } else if (spec.inner == model::Inner::Head) {
        j_tip = 0.0;
        std::vector<double> g = outer_.product(spec.inner_factors, spec.n_inner, 1.0, spec.name);
        weigh(g, outer_rule_.x0, spec.inner_mass);
        for (std::size_t q = 0; q < n; ++q) j_tip += outer_rule_.weight[q] * g[q];
      }
      sum += blade_->tip_mass * tip_.product(spec.outer, spec.n_outer, 1.0, spec.name)[0] * j_tip;
    }
    return sum;
  }

 private:
  // The constant factor of a mass power: mbar^power for the uniform blade; 1 for a blade table,
  // whose mass is weighed station by station.
  double mass_scale(int power, double mbar) const {
    return blade_ != nullptr ? 1.0 : std::pow(mbar, power);
  }
  void weigh(std::vector<double>& v, const std::vector<double>& x0, int power) const {
    if (blade_ == nullptr || power == 0) return;
    for (std::size_t q = 0; q < v.size(); ++q) v[q] *= std::pow(blade_->mass_at(x0[q]), power);
  }

  std::vector<double> partial_points(bool tail, std::vector<double>& w,
                                     std::vector<double>& x) const {
    const int panels = static_cast<int>(edges_.size()) - 1;
    const std::size_t nodes = static_cast<std::size_t>(panels * kGaussPoints * kGaussPoints);
    x.reserve(nodes);
    w.reserve(nodes);
    for (int p = 0; p < panels; ++p) {
      const double a = edges_[p];
      const double b = edges_[p + 1];
      for (int i = 0; i < kGaussPoints; ++i) {
        const double xq = outer_rule_.x0[static_cast<std::size_t>(p * kGaussPoints + i)];
        if (tail) {
          append_interval(xq, b, x, w);
        } else {
          append_interval(a, xq, x, w);
        }
      }
    }
    return x;
  }

  const BladeProperties* blade_;
  std::vector<double> edges_;
  SpanRule outer_rule_;
  FactorTable outer_;
  std::vector<double> tail_w_, tail_x_;
  std::vector<double> head_w_, head_x_;
  FactorTable tail_;
  FactorTable head_;
  FactorTable tip_;
};

void check_structural(double e1_over_l, double mbar) {
  if (!std::isfinite(e1_over_l) || e1_over_l < 0.0) {
    throw InvalidInput("e1_over_l", round_trip_text(e1_over_l), "must be finite and >= 0");
  }
  if (!std::isfinite(mbar) || mbar <= 0.0) {
    throw InvalidInput("mbar", round_trip_text(mbar), "mass per length m l^3/I_b must be positive");
  }
}

// int_0^1 weight(x0) f_i'' g_k'' dx0 for all pairs (weight 1 when it is null).
template <typename Weight>
Eigen::MatrixXd curvature_products(const std::vector<std::shared_ptr<const ModeShape>>& f,
                                   const std::vector<std::shared_ptr<const ModeShape>>& g,
                                   const std::vector<double>& corners, Weight weight) {
  const SpanRule rule = span_rule(0.0, 1.0, corners);
  const Eigen::Index nq = static_cast<Eigen::Index>(rule.x0.size());
  auto curvatures = [&](const std::vector<std::shared_ptr<const ModeShape>>& s) {
    Eigen::MatrixXd c(nq, static_cast<Eigen::Index>(s.size()));
    for (Eigen::Index k = 0; k < c.cols(); ++k) {
      for (Eigen::Index q = 0; q < nq; ++q) c(q, k) = s[k]->value(2, rule.x0[q]);
    }
    return c;
  };
  const Eigen::MatrixXd cf = curvatures(f);
  const Eigen::MatrixXd cg = curvatures(g);
  Eigen::VectorXd w = Eigen::Map<const Eigen::VectorXd>(rule.weight.data(), nq);
  for (Eigen::Index q = 0; q < nq; ++q) w[q] *= weight(rule.x0[q]);
  return cf.transpose() * w.asDiagonal() * cg;
}
Eigen::MatrixXd curvature_products(const std::vector<std::shared_ptr<const ModeShape>>& f,
                                   const std::vector<std::shared_ptr<const ModeShape>>& g,
                                   const std::vector<double>& corners) {
  return curvature_products(f, g, corners, [](double) { return 1.0; });
}

}  // namespace

SpanRule span_rule(double a, double b) { return span_rule(a, b, {}); }

SpanRule span_rule(double a, double b, const std::vector<double>& corners) {
  SpanRule r;
  const std::vector<double> edges = panel_edges(a, b, corners);
  r.x0.reserve((edges.size() - 1) * kGaussPoints);
  r.weight.reserve((edges.size() - 1) * kGaussPoints);
  for (std::size_t p = 0; p + 1 < edges.size(); ++p)
    append_interval(edges[p], edges[p + 1], r.x0, r.weight);
  return r;
}

std::vector<double> panel_edges(double a, double b, const std::vector<double>& corners) {
  const double h = (b - a) / kPanels;
  std::vector<double> edges;
  for (int p = 0; p < kPanels; ++p) edges.push_back(a + p * h);
  edges.push_back(b);
  // A corner splits its panel, unless it (nearly) is an edge already: a sliver panel would
  // add nothing but rounding.
  const double tiny = 1e-9 * std::max(b - a, 0.0);
  for (double c : corners) {
    if (!(c > a + tiny && c < b - tiny)) continue;
    bool near = false;
    for (double e : edges) near = near || std::abs(e - c) <= tiny;
    if (!near) edges.push_back(c);
  }
  std::sort(edges.begin(), edges.end());
  return edges;
}

std::vector<double> blade_corners(const ModeSet& modes) {
  std::vector<double> c = modes.blade ? modes.blade->corners() : std::vector<double>{};
  if (modes.mesh.empty()) return c;
  c.insert(c.end(), modes.mesh.begin(), modes.mesh.end());
  std::sort(c.begin(), c.end());
  c.erase(std::unique(c.begin(), c.end()), c.end());
  return c;
}

double aero_integral(const model::AeroIntegral& spec, const ModeSet& modes, const SpanGeometry& g,
                     double x0_lo, double x0_hi) {
  validate(g);
  AeroRegion region(modes, g, x0_lo, x0_hi);
  return region.integral(spec);
}

double structural_integral(const model::StructuralIntegral& spec, const ModeSet& modes,
                           double e1_over_l, double mbar) {
  check_structural(e1_over_l, mbar);
  NestedGrid grid(modes, e1_over_l);
  return grid.integral(spec, mbar);
}

std::vector<double> structural_integrals(const model::ModelDescriptor& m, const ModeSet& modes,
                                         double e1_over_l, double mbar) {
  check_structural(e1_over_l, mbar);
  NestedGrid grid(modes, e1_over_l);
  std::vector<double> v(static_cast<std::size_t>(m.n_structural));
  for (int i = 0; i < m.n_structural; ++i) v[i] = grid.integral(m.structural[i], mbar);
  return v;
}

ElasticCoupling no_elastic_coupling(const ModeSet& modes) {
  ElasticCoupling e;
  for (const Direction row : model::kDirections)
    for (const Direction col : model::kDirections)
      e.blocks[model::index(row)][model::index(col)] =
          Eigen::MatrixXd::Zero(modes[row].count(), modes[col].count());
  return e;
}

namespace {

// The blocks of eqs E.3-E.8 from the curvature products of each pair of directions: products(row,
// col, diagonal) for a block on (diagonal) or off the diagonal.  The blocks below the diagonal
// are the transposes of those above (Ecs_LF = Ecs_FL^T, exactly).
template <class Products>
ElasticCoupling coupling_blocks(const ModeSet& modes, const Products& products) {
  ElasticCoupling e = no_elastic_coupling(modes);
  for (int r = 0; r < model::kDirectionCount; ++r) {
    for (int c = r; c < model::kDirectionCount; ++c) {
      e.blocks[r][c] = products(model::kDirections[r], model::kDirections[c], r == c);
      if (c != r) e.blocks[c][r] = e.blocks[r][c].transpose();
    }
  }
  return e;
}

}  // namespace

ElasticCoupling elastic_coupling(const ModeSet& modes, double theta) {
  if (!std::isfinite(theta)) {
    throw InvalidInput("theta", round_trip_text(theta), "collective pitch must be finite");
  }
  const DirectionModes& flap = modes[Direction::Flap];
  const DirectionModes& lag = modes[Direction::Lag];
  if (flap.stiffness == 0.0 && lag.stiffness == 0.0) return no_elastic_coupling(modes);
  const std::vector<double> corners = blade_corners(modes);
  if (modes.blade) {
    // Eqs E.3-E.8 with the stiffnesses and the pitch theta + theta_tw(x0) of each station.
    const BladeProperties& b = *modes.blade;
    auto dk = [&](double x) {
      return lag.stiffness * b.at(b.stiffness_lag, x) - flap.stiffness * b.at(b.stiffness_flap, x);
    };
    auto s2 = [&](double x) {
      const double s = std::sin(theta + b.twist_at(x));
      return dk(x) * s * s;
    };
    auto sc = [&](double x) {
      const double t = theta + b.twist_at(x);
      return dk(x) * std::sin(t) * std::cos(t);
    };
    return coupling_blocks(modes, [&](Direction row, Direction col, bool diagonal) {
      return diagonal ? curvature_products(modes.shapes(row), modes.shapes(col), corners, s2)
                      : curvature_products(modes.shapes(row), modes.shapes(col), corners, sc);
    });
  }
  // Eqs E.3-E.8 divided by Omega^2 I_b / l: (EI_z - EI_y)/(Omega^2 l I_b) = k_z - k_y.
  const double dk = lag.stiffness - flap.stiffness;
  const double s = std::sin(theta);
  const double c = std::cos(theta);
  return coupling_blocks(modes, [&](Direction row, Direction col, bool diagonal) {
    const Eigen::MatrixXd products =
        curvature_products(modes.shapes(row), modes.shapes(col), corners);
    return Eigen::MatrixXd((diagonal ? dk * s * s : dk * s * c) * products);
  });
}

}  // namespace flaplag
