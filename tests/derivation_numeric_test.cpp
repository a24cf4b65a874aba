// Independent numeric check of the derivation: the generalized aerodynamic loads computed by
// direct spanwise quadrature of the *full nonlinear* L_z, L_y (eqs 2.18-2.23, written out here
// by hand), linearized by central finite differences, against the derived coefficients.
//   - untruncated spec: agreement to ~1e-8 (finite-difference accuracy);
//   - the paper's spec: the difference shrinks like s^kept (coefficients of A) and s^(kept+1)
//     (forcing) when every small quantity is scaled by s.
// The same for cyclic pitch (theta(psi) = theta + theta1c cos psi + theta1s sin psi in the
// section pitch of eqs 2.20-2.21; the droop slope keeps the collective theta), for the built-in
// twist (section pitch theta + theta_tw(x0), a linearly twisted blade table) and for the rotor
// thrust T = lr int L_z dx0 that the cyclic-pitch models emit for the trim.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <string>

#include "flaplag/blade/blade.h"
#include "flaplag/core/constants.h"
#include "flaplag/model_api.h"
#include "flaplag_derive/derive.h"
#include "flaplag_derive/spec.h"

namespace derivation_numeric_test {

namespace fd = flaplag::derive;
namespace fm = flaplag::model;
// The directions' places in the per-direction model inputs.
constexpr int kF = fm::index(fm::Direction::Flap), kL = fm::index(fm::Direction::Lag);

namespace {

// Eq 4.1 and its slope, coded independently of the runtime.
double eta(double x) { return -(1.0 / 3.0) * (1.0 - 4.0 * x - std::pow(1.0 - x, 4)); }
double eta_p(double x) { return -(1.0 / 3.0) * (-4.0 + 4.0 * std::pow(1.0 - x, 3)); }

struct Operating {
  double lock = 10.0, lr = 0.9, e1 = 0.05, theta = 0.15, inflow = 0.05, precone = 0.02,
         droop = 0.03, cdo_a = 0.0016, mu = 0.8;
  double g0 = 0.09, h0 = 0.006;
  double theta1c = 0.0, theta1s = 0.0;       // cyclic pitch
  double twist_root = 0.0, twist_tip = 0.0;  // built-in twist, linear in x0 (a blade table)

  double twist(double x0) const { return twist_root + (twist_tip - twist_root) * x0; }

  Operating scaled(double s) const {
    Operating o = *this;
    o.theta *= s;
    o.theta1c *= s;
    o.theta1s *= s;
    o.twist_root *= s;
    o.twist_tip *= s;
    o.inflow *= s;
    o.precone *= s;
    o.droop *= s;
    o.cdo_a *= s * s;
    o.g0 *= s;
    o.h0 *= s;
    return o;
  }
};

// State q = [g, h, g', h'] (not the runtime ordering: plain for the finite differences).
using Q4 = std::array<double, 4>;

// A_F, A_L of eqs 2.18-2.19 from the full nonlinear loads, by Gauss quadrature over x0 in [0,1].
// Third entry: the rotor thrust of one blade, lr int L_z dx0 (L_z as in A_F, unweighted).
std::array<double, 3> full_loads(const Operating& o, double psi, const Q4& q) {
  const double g = q[0], h = q[1], gd = q[2], hd = q[3];
  const double c = std::cos(psi), s = std::sin(psi);
  const double cyclic = o.theta + o.theta1c * c + o.theta1s * s;  // theta(psi)
  const auto rule = flaplag::span_rule(0.0, 1.0);
  double af = 0.0, al = 0.0, thrust = 0.0;
  for (size_t k = 0; k < rule.x0.size(); ++k) {
    const double x0 = rule.x0[k], w = rule.weight[k];
    const double x = o.e1 + o.lr * x0;
    const double pitch = cyclic + o.twist(x0);  // section pitch theta(psi) + theta_tw(x0)
    const double v_slope = -(eta_p(x0) * h + o.droop * o.theta);                // dv/dx0, eq 2.14
    const double w_slope = (o.precone + o.droop) + eta_p(x0) * g;               // dw/dx0, eq 2.15
    const double uT = x + o.mu * s + o.mu * c * v_slope - o.lr * eta(x0) * hd;  // eq 2.23
    const double uP = o.inflow + o.mu * c * w_slope + o.lr * eta(x0) * gd;      // eq 2.22
    af += w * uT * (uT * pitch - uP) * eta(x0);
    al += w * (uP * (uT * pitch - uP) + o.cdo_a * uT * uT) * eta(x0);
    thrust += w * uT * (uT * pitch - uP);
  }
  const double scale = o.lock / 2.0 * o.lr * o.lr;
  return {scale * af, scale * al, o.lr * thrust};
}

// Jacobian d[A_F, A_L, T]/d[g', g, h', h] (runtime state ordering) at (g0, h0, 0, 0).
std::array<std::array<double, 4>, 3> fd_jacobian(const Operating& o, double psi) {
  const double step = 1e-5;
  const int to_q[4] = {2, 0, 3, 1};  // state column -> index in Q4
  std::array<std::array<double, 4>, 3> J{};
  for (int col = 0; col < 4; ++col) {
    Q4 qp = {o.g0, o.h0, 0.0, 0.0}, qm = qp;
    qp[to_q[col]] += step;
    qm[to_q[col]] -= step;
    const auto fp = full_loads(o, psi, qp), fm2 = full_loads(o, psi, qm);
    for (int r = 0; r < 3; ++r) J[r][col] = (fp[r] - fm2[r]) / (2.0 * step);
  }
  return J;
}

double basis(int h, double psi) {
  if (h == 0) return 1.0;
  const int k = (h + 1) / 2;
  return h % 2 == 1 ? std::cos(k * psi) : std::sin(k * psi);
}

// Aerodynamic integrals of a model for the assumed mode over [0, 1], via the runtime (whose
// quadrature is tested on its own); with the operating point's twist as a blade table.
std::vector<double> integrals(const std::vector<fm::AeroIntegral>& list, const Operating& o) {
  auto modes = flaplag::assumed_modes(1.0, 1.0);
  if (o.twist_root != 0.0 || o.twist_tip != 0.0) {
    auto blade = std::make_shared<flaplag::BladeProperties>(flaplag::uniform_blade());
    blade->twist = {o.twist_root, o.twist_tip};
    modes.blade = blade;
  }
  flaplag::SpanGeometry g;
  g.e1 = o.e1;
  g.lr = o.lr;
  std::vector<double> v;
  for (const auto& a : list) v.push_back(flaplag::aero_integral(a, modes, g, 0.0, 1.0));
  return v;
}

// Descriptors of a derived model in the runtime's form.
std::vector<fm::AeroIntegral> descriptors(const fd::DerivedModel& m) {
  std::vector<fm::AeroIntegral> v;
  for (const auto& k : m.aero_keys) {
    fm::AeroIntegral a{};
    a.name = "";
    a.ident = "";
    a.paper_name = "";
    a.x_power = k.x_power;
    a.n_factors = static_cast<int>(k.factors.size());
    for (size_t j = 0; j < k.factors.size(); ++j) {
      a.factors[j] = {static_cast<fm::Factor>(k.factors[j].kind), k.factors[j].mode};
    }
    v.push_back(a);
  }
  return v;
}

// Rows 0, 1: flap and lag generalized loads; row 2: the thrust (cyclic-pitch models only).
struct LinearAero {
  std::array<std::array<double, 4>, 3> J{};
  std::array<double, 3> F{};
};

// The derived model's aerodynamic part at psi: structural inputs zeroed, GiNaC evaluation.
LinearAero derived_aero(const fd::DerivedModel& m, const Operating& o, double psi) {
  const auto vals = integrals(descriptors(m), o);
  GiNaC::exmap sub;
  for (const auto& s : m.scalars) sub[s.sym] = GiNaC::numeric(0);
  auto set = [&](const std::string& name, double v) {
    for (const auto& s : m.scalars) {
      if (s.name == name) sub[s.sym] = GiNaC::numeric(v);
    }
  };
  set("lock", o.lock);
  set("lr", o.lr);
  set("theta", o.theta);
  set("inflow", o.inflow);
  set("precone", o.precone);
  set("droop", o.droop);
  set("cdo_a", o.cdo_a);
  set("mu", o.mu);
  set("g0_1", o.g0);
  set("h0_1", o.h0);
  set("theta1c", o.theta1c);
  set("theta1s", o.theta1s);
  for (size_t j = 0; j < m.aero_syms.size(); ++j) sub[m.aero_syms[j]] = GiNaC::numeric(vals[j]);
  for (const auto& s : m.structural_syms) sub[s] = GiNaC::numeric(0);
  LinearAero r;
  for (int h = 0; h < m.H; ++h) {
    const double b = basis(h, psi);
    for (int i = 0; i < 2; ++i) {
      for (int col = 0; col < 4; ++col) {
        const GiNaC::ex v = GiNaC::evalf(m.force[(h * 2 + i) * 4 + col].value.subs(sub));
        r.J[i][col] += b * GiNaC::ex_to<GiNaC::numeric>(v).to_double();
      }
      const GiNaC::ex f = GiNaC::evalf(m.forcing[h * 2 + i].value.subs(sub));
      r.F[i] += b * GiNaC::ex_to<GiNaC::numeric>(f).to_double();
    }
    if (m.thrust_forcing.empty()) continue;
    for (int col = 0; col < 4; ++col) {
      const GiNaC::ex v = GiNaC::evalf(m.thrust_force[h * 4 + col].value.subs(sub));
      r.J[2][col] += b * GiNaC::ex_to<GiNaC::numeric>(v).to_double();
    }
    const GiNaC::ex f = GiNaC::evalf(m.thrust_forcing[h].value.subs(sub));
    r.F[2] += b * GiNaC::ex_to<GiNaC::numeric>(f).to_double();
  }
  return r;
}

// The compiled model's aerodynamic part (structural inputs zeroed).
LinearAero compiled_aero(const fm::ModelDescriptor& m, const Operating& o, double psi) {
  std::vector<fm::AeroIntegral> list(m.aero, m.aero + m.n_aero);
  const auto vals = integrals(list, o);
  const std::vector<double> zeros(64, 0.0), structural(m.n_structural, 0.0);
  const double g0[1] = {o.g0}, h0[1] = {o.h0};
  fm::CoefficientInputs in{};
  in.modes[kF] = m.flap_modes;
  in.modes[kL] = m.lag_modes;
  in.lock = o.lock;
  in.lr = o.lr;
  in.theta = o.theta;
  in.inflow = o.inflow;
  in.precone = o.precone;
  in.droop = o.droop;
  in.cdo_a = o.cdo_a;
  in.mu = o.mu;
  in.q0[kF] = g0;
  in.q0[kL] = h0;
  in.omega[kF] = in.omega[kL] = in.damping[kF] = in.damping[kL] = zeros.data();
  for (auto& row : in.elastic)
    for (const double*& block : row) block = zeros.data();
  in.aero = vals.data();
  in.structural = structural.data();
  in.theta1c = o.theta1c;
  in.theta1s = o.theta1s;
  std::vector<double> force(m.n_harmonics * 2 * 4), forcing(m.n_harmonics * 2);
  m.coefficients(in, {force.data(), forcing.data()});
  std::vector<double> tforce(m.n_harmonics * 4), tforcing(m.n_harmonics);
  if (m.thrust != nullptr) m.thrust(in, {tforce.data(), tforcing.data()});
  LinearAero r;
  for (int h = 0; h < m.n_harmonics; ++h) {
    const double b = basis(h, psi);
    for (int i = 0; i < 2; ++i) {
      for (int col = 0; col < 4; ++col) r.J[i][col] += b * force[(h * 2 + i) * 4 + col];
      r.F[i] += b * forcing[h * 2 + i];
    }
    for (int col = 0; col < 4; ++col) r.J[2][col] += b * tforce[h * 4 + col];
    r.F[2] += b * tforcing[h];
  }
  return r;
}

const fm::ModelDescriptor& compiled(const std::string& name) {
  for (const auto* f : fm::registered_families()) {
    if (name == f->name) return fm::instantiate(*f, 1, 1);
  }
  throw std::runtime_error("model not compiled: " + name);
}

}  // namespace

TEST(DerivationVsQuadrature, UntruncatedSpecMatchesFullNonlinearLoadsToFiniteDifferenceAccuracy) {
  const auto spec = fd::load_spec(std::string(FLAPLAG_TEST_SPEC_DIR) + "/untruncated.toml");
  const auto m = fd::derive_model(spec);
  const Operating o;
  for (double psi : {0.3, 1.7, 2.9, 4.4, 5.8}) {
    const auto J = fd_jacobian(o, psi);
    const auto d = derived_aero(m, o, psi);
    const auto F = full_loads(o, psi, {o.g0, o.h0, 0.0, 0.0});
    for (int i = 0; i < 2; ++i) {
      for (int col = 0; col < 4; ++col) {
        EXPECT_NEAR(d.J[i][col], J[i][col], 1e-8 * std::max(1.0, std::abs(J[i][col])))
            << "psi " << psi << " row " << i << " col " << col;
      }
      EXPECT_NEAR(d.F[i], F[i], 1e-12 * std::max(1.0, std::abs(F[i]))) << "psi " << psi;
    }
  }
}

// The untruncated spec with cyclic pitch: flap and lag loads and the thrust equal the full
// nonlinear ones (pitch theta + theta1c cos psi + theta1s sin psi) and their linearization.
TEST(DerivationVsQuadrature, UntruncatedCyclicPitchMatchesFullNonlinearLoadsAndThrust) {
  auto spec = fd::load_spec(std::string(FLAPLAG_TEST_SPEC_DIR) + "/untruncated.toml");
  spec.cyclic_pitch = true;
  const auto m = fd::derive_model(spec);
  ASSERT_FALSE(m.thrust_forcing.empty());
  Operating o;
  o.theta1c = 0.04;
  o.theta1s = -0.07;
  for (double psi : {0.3, 1.7, 2.9, 4.4, 5.8}) {
    const auto J = fd_jacobian(o, psi);
    const auto d = derived_aero(m, o, psi);
    const auto F = full_loads(o, psi, {o.g0, o.h0, 0.0, 0.0});
    for (int i = 0; i < 3; ++i) {
      for (int col = 0; col < 4; ++col) {
        EXPECT_NEAR(d.J[i][col], J[i][col], 1e-8 * std::max(1.0, std::abs(J[i][col])))
            << "psi " << psi << " row " << i << " col " << col;
      }
      EXPECT_NEAR(d.F[i], F[i], 1e-12 * std::max(1.0, std::abs(F[i])))
          << "psi " << psi << " row " << i;
    }
  }
  // The cyclic terms are really there: without them the forcing differs at O(theta1).
  Operating o0 = o;
  o0.theta1c = o0.theta1s = 0.0;
  const auto F0 = full_loads(o0, 0.3, {o.g0, o.h0, 0.0, 0.0});
  EXPECT_GT(std::abs(derived_aero(m, o, 0.3).F[2] - F0[2]), 1e-3);
}

// The untruncated spec on a twisted blade (with cyclic pitch, for the thrust): the tw terms
// make the loads, their linearization and the thrust those of the section pitch
// theta + theta_tw(x0) + theta1c cos psi + theta1s sin psi.
TEST(DerivationVsQuadrature, UntruncatedTwistMatchesFullNonlinearLoadsAndThrust) {
  auto spec = fd::load_spec(std::string(FLAPLAG_TEST_SPEC_DIR) + "/untruncated.toml");
  spec.cyclic_pitch = true;
  const auto m = fd::derive_model(spec);
  Operating o;
  o.theta1c = 0.04;
  o.theta1s = -0.07;
  o.twist_root = 0.05;
  o.twist_tip = -0.13;
  for (double psi : {0.3, 1.7, 2.9, 4.4, 5.8}) {
    const auto J = fd_jacobian(o, psi);
    const auto d = derived_aero(m, o, psi);
    const auto F = full_loads(o, psi, {o.g0, o.h0, 0.0, 0.0});
    for (int i = 0; i < 3; ++i) {
      for (int col = 0; col < 4; ++col) {
        EXPECT_NEAR(d.J[i][col], J[i][col], 1e-8 * std::max(1.0, std::abs(J[i][col])))
            << "psi " << psi << " row " << i << " col " << col;
      }
      EXPECT_NEAR(d.F[i], F[i], 1e-12 * std::max(1.0, std::abs(F[i])))
          << "psi " << psi << " row " << i;
    }
  }
  // The twist terms are really there: the untwisted blade's loads differ at O(theta_tw).
  Operating o0 = o;
  o0.twist_root = o0.twist_tip = 0.0;
  const auto F = full_loads(o, 0.3, {o.g0, o.h0, 0.0, 0.0});
  const auto F0 = full_loads(o0, 0.3, {o.g0, o.h0, 0.0, 0.0});
  for (int i = 0; i < 3; ++i) EXPECT_GT(std::abs(F[i] - F0[i]), 1e-3) << "row " << i;
}

// Max |difference| over psi samples for one equation (row; 2 = thrust): Jacobian and forcing
// separately.
std::array<double, 2> truncation_error(const fm::ModelDescriptor& m, const Operating& o, int row) {
  double ej = 0.0, ef = 0.0;
  for (double psi = 0.1; psi < flaplag::kTwoPi; psi += 0.37) {
    const auto J = fd_jacobian(o, psi);
    const auto F = full_loads(o, psi, {o.g0, o.h0, 0.0, 0.0});
    const auto c = compiled_aero(m, o, psi);
    for (int col = 0; col < 4; ++col) ej = std::max(ej, std::abs(c.J[row][col] - J[row][col]));
    ef = std::max(ef, std::abs(c.F[row] - F[row]));
  }
  return {ej, ef};
}

struct OrderCase {
  const char* model;
  int row;  // 0 flap, 1 lag, 2 thrust
  int kept;
  bool cyclic = false;  // with cyclic pitch
  bool twist = false;   // on a twisted blade
};

// The twist of the order cases: small like theta (scaled with it), root and tip apart.
void twist_blade(Operating& o) {
  o.twist_root = 0.04;
  o.twist_tip = -0.1;
}

class TruncationOrder : public ::testing::TestWithParam<OrderCase> {};

const char* row_name(int row) { return row == 0 ? "_flap" : row == 1 ? "_lag" : "_thrust"; }

TEST_P(TruncationOrder, DifferenceShrinksLikeTheFirstDroppedOrder) {
  const auto& c = GetParam();
  const auto& m = compiled(c.model);
  Operating base;
  if (c.cyclic) {
    base.theta1c = 0.04;
    base.theta1s = -0.07;
  }
  if (c.twist) twist_blade(base);
  const auto e1 = truncation_error(m, base.scaled(0.2), c.row);
  const auto e2 = truncation_error(m, base.scaled(0.1), c.row);
  const double order_j = std::log2(e1[0] / e2[0]);
  const double order_f = std::log2(e1[1] / e2[1]);
  EXPECT_NEAR(order_j, c.kept, 0.35) << "A coefficients: errors " << e1[0] << " -> " << e2[0];
  EXPECT_NEAR(order_f, c.kept + 1, 0.35) << "forcing: errors " << e1[1] << " -> " << e2[1];
}

INSTANTIATE_TEST_SUITE_P(
    Models, TruncationOrder,
    ::testing::Values(OrderCase{"paper", 0, 2}, OrderCase{"paper", 1, 3},
                      OrderCase{"lag-order-2", 1, 2}, OrderCase{"paper", 0, 2, true},
                      OrderCase{"paper", 1, 3, true}, OrderCase{"paper", 2, 2, true},
                      OrderCase{"paper", 0, 2, true, true}, OrderCase{"paper", 1, 3, true, true},
                      OrderCase{"paper", 2, 2, true, true}),
    [](const auto& tp) {
      std::string s = std::string(tp.param.model) + (tp.param.cyclic ? "_cyclic" : "") +
                      (tp.param.twist ? "_twist" : "") + row_name(tp.param.row);
      for (char& ch : s) {
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      }
      return s;
    });

// ----- the nonlinear loads (spec [emit] nonlinear) at a full state ---------------------------

namespace {

// State columns [g', g, h', h] of the runtime ordering from Q4 = [g, h, g', h'].
std::array<double, 4> runtime_state(const Q4& q) { return {q[2], q[0], q[3], q[1]}; }

double monomial(const std::vector<int>& powers, const std::array<double, 4>& y) {
  double v = 1.0;
  for (size_t c = 0; c < powers.size(); ++c) v *= std::pow(y[c], powers[c]);
  return v;
}

// The derived nonlinear loads' aerodynamic part at (psi, q): GiNaC evaluation of every slot with
// the structural inputs zeroed.
std::array<double, 2> derived_nonlinear_aero(const fd::DerivedModel& m, const Operating& o,
                                             double psi, const Q4& q) {
  const auto vals = integrals(descriptors(m), o);
  GiNaC::exmap sub;
  for (const auto& s : m.scalars) sub[s.sym] = GiNaC::numeric(0);
  const std::map<std::string, double> named = {
      {"lock", o.lock},       {"lr", o.lr},       {"theta", o.theta}, {"inflow", o.inflow},
      {"precone", o.precone}, {"droop", o.droop}, {"cdo_a", o.cdo_a}, {"mu", o.mu}};
  for (const auto& s : m.scalars) {
    auto it = named.find(s.name);
    if (it != named.end()) sub[s.sym] = GiNaC::numeric(it->second);
  }
  for (size_t j = 0; j < m.aero_syms.size(); ++j) sub[m.aero_syms[j]] = GiNaC::numeric(vals[j]);
  for (const auto& s : m.structural_syms) sub[s] = GiNaC::numeric(0);
  std::array<double, 2> r{};
  const auto y = runtime_state(q);
  for (const auto& s : m.nonlinear) {
    const double c = GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(s.slot.value.subs(sub))).to_double();
    r[s.equation] += c * basis(s.harmonic, psi) * monomial(s.powers, y);
  }
  return r;
}

// The compiled nonlinear loads' aerodynamic part (structural inputs zeroed) and their Jacobian.
struct NonlinearAero {
  std::array<double, 2> F{};
  std::array<std::array<double, 4>, 2> J{};
};

NonlinearAero compiled_nonlinear_aero(const fm::ModelDescriptor& m, const Operating& o, double psi,
                                      const Q4& q) {
  std::vector<fm::AeroIntegral> list(m.aero, m.aero + m.n_aero);
  const auto vals = integrals(list, o);
  const std::vector<double> zeros(64, 0.0), structural(m.n_structural, 0.0);
  const double nan[1] = {std::nan("")};  // the nonlinear loads must not read g0, h0
  fm::CoefficientInputs in{};
  in.modes[kF] = m.flap_modes;
  in.modes[kL] = m.lag_modes;
  in.lock = o.lock;
  in.lr = o.lr;
  in.theta = o.theta;
  in.inflow = o.inflow;
  in.precone = o.precone;
  in.droop = o.droop;
  in.cdo_a = o.cdo_a;
  in.mu = o.mu;
  in.q0[kF] = in.q0[kL] = nan;
  in.omega[kF] = in.omega[kL] = in.damping[kF] = in.damping[kL] = zeros.data();
  for (auto& row : in.elastic)
    for (const double*& block : row) block = zeros.data();
  in.aero = vals.data();
  in.structural = structural.data();
  const int H = m.n_nonlinear_harmonics;
  std::vector<double> force(H * 2), jac(H * 2 * 4);
  const auto y = runtime_state(q);
  m.nonlinear(in, y.data(), {force.data(), jac.data()});
  NonlinearAero r;
  for (int h = 0; h < H; ++h) {
    for (int i = 0; i < 2; ++i) {
      r.F[i] += basis(h, psi) * force[h * 2 + i];
      for (int c = 0; c < 4; ++c) r.J[i][c] += basis(h, psi) * jac[(h * 2 + i) * 4 + c];
    }
  }
  return r;
}

// States far from hover (flap up to ~0.2, lag rates of either sign), in [g, h, g', h'].
const Q4 kStates[] = {
    {0.12, 0.01, 0.03, -0.02}, {-0.05, 0.04, -0.06, 0.015}, {0.2, -0.03, 0.08, 0.05}};

}  // namespace

// Without truncation the nonlinear loads are the full loads at any state: a polynomial identity.
TEST(NonlinearLoadsVsQuadrature, UntruncatedSpecEqualsFullNonlinearLoadsAtAnyState) {
  auto spec = fd::load_spec(std::string(FLAPLAG_TEST_SPEC_DIR) + "/untruncated.toml");
  spec.nonlinear = true;
  const auto m = fd::derive_model(spec);
  Operating twisted;
  twist_blade(twisted);
  for (const Operating& o : {Operating{}, twisted}) {
    for (double psi : {0.3, 2.9, 4.4}) {
      for (const auto& q : kStates) {
        const auto d = derived_nonlinear_aero(m, o, psi, q);
        const auto F = full_loads(o, psi, q);
        for (int i = 0; i < 2; ++i) {
          EXPECT_NEAR(d[i], F[i], 1e-12 * std::max(1.0, std::abs(F[i])))
              << "psi " << psi << " row " << i << " q " << q[0] << " " << q[1] << " twist "
              << o.twist_tip;
        }
      }
    }
  }
}

// The compiled paper model's nonlinear loads and their Jacobian against the full loads and their
// central differences at states away from hover: the difference shrinks like s^(kept+1) when
// every small quantity, the state included, is scaled by s (the first dropped eps order).
class NonlinearTruncationOrder : public ::testing::TestWithParam<OrderCase> {};

TEST_P(NonlinearTruncationOrder, DifferenceShrinksLikeTheFirstDroppedOrder) {
  const auto& c = GetParam();
  const auto& m = compiled(c.model);
  Operating base;
  if (c.twist) twist_blade(base);
  auto error = [&](double s) {
    const Operating o = base.scaled(s);
    double ef = 0.0, ej = 0.0;
    for (double psi = 0.1; psi < flaplag::kTwoPi; psi += 0.71) {
      for (const auto& q0 : kStates) {
        const Q4 q = {s * q0[0], s * q0[1], s * q0[2], s * q0[3]};
        const auto d = compiled_nonlinear_aero(m, o, psi, q);
        ef = std::max(ef, std::abs(d.F[c.row] - full_loads(o, psi, q)[c.row]));
        const int to_q[4] = {2, 0, 3, 1};
        for (int col = 0; col < 4; ++col) {
          Q4 qp = q, qm = q;
          const double step = 1e-6;
          qp[to_q[col]] += step;
          qm[to_q[col]] -= step;
          const double fdj =
              (full_loads(o, psi, qp)[c.row] - full_loads(o, psi, qm)[c.row]) / (2 * step);
          ej = std::max(ej, std::abs(d.J[c.row][col] - fdj));
        }
      }
    }
    return std::array<double, 2>{ef, ej};
  };
  const auto e1 = error(0.2), e2 = error(0.1);
  EXPECT_NEAR(std::log2(e1[0] / e2[0]), c.kept + 1, 0.35)
      << "loads: errors " << e1[0] << " -> " << e2[0];
  EXPECT_NEAR(std::log2(e1[1] / e2[1]), c.kept, 0.35)
      << "Jacobian: errors " << e1[1] << " -> " << e2[1];
}

INSTANTIATE_TEST_SUITE_P(Models, NonlinearTruncationOrder,
                         ::testing::Values(OrderCase{"paper", 0, 2}, OrderCase{"paper", 1, 3},
                                           OrderCase{"paper", 0, 2, false, true},
                                           OrderCase{"paper", 1, 3, false, true}),
                         [](const auto& tp) {
                           return std::string(tp.param.row == 0 ? "flap" : "lag") +
                                  (tp.param.twist ? "_twist" : "");
                         });

}  // namespace derivation_numeric_test
