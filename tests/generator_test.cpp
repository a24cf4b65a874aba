// The derivation and its emitted code: compiled coefficients equal GiNaC's own evaluation,
// output is deterministic, truncation respects the spec, term classes drop exactly, and bad
// specs are rejected with file, key and value.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <string>
#include <tuple>

#include "flaplag/blade/blade.h"
#include "flaplag/model_api.h"
#include "flaplag_derive/derive.h"
#include "flaplag_derive/emit.h"
#include "flaplag_derive/operating_point.h"
#include "flaplag_derive/paper_print.h"
#include "flaplag_derive/spec.h"

namespace generator_test {

namespace fd = flaplag::derive;
namespace fm = flaplag::model;
// The directions' places in the per-direction model inputs.
constexpr int kF = fm::index(fm::Direction::Flap), kL = fm::index(fm::Direction::Lag);

namespace {

// "<family>" or "<family>-<M>x<N>": the family and the mode counts (0: the spec's own).
std::string family_of(const std::string& name, int* M, int* N) {
  *M = *N = 0;
  const auto dash = name.rfind('-');
  if (dash != std::string::npos && std::sscanf(name.c_str() + dash + 1, "%dx%d", M, N) == 2)
    return name.substr(0, dash);
  *M = *N = 0;
  return name;
}

// The compiled model of that name: its family instantiated for the mode counts.
const fm::ModelDescriptor* compiled(const std::string& name) {
  int M = 0, N = 0;
  const std::string family = family_of(name, &M, &N);
  for (const auto* f : fm::registered_families()) {
    if (family == f->name)
      return &fm::instantiate(*f, M > 0 ? M : f->default_flap_modes,
                              N > 0 ? N : f->default_lag_modes);
  }
  return nullptr;
}

// Every shipped family at its own mode counts and at a few others.
std::vector<std::string> compiled_names() {
  std::vector<std::string> v;
  for (const auto* f : fm::registered_families()) v.emplace_back(f->name);
  for (const char* sized : {"paper-2x1", "paper-1x2", "paper-2x2", "lag-order-2-2x2"})
    v.emplace_back(sized);
  return v;
}

// The spec of a compiled model, with the derivation switches every model has (cyclic pitch,
// thrust, nonlinear loads) on.
fd::OrderingSpec spec_of(const std::string& name) {
  int M = 0, N = 0;
  auto s = fd::load_spec(std::string(FLAPLAG_SPEC_DIR) + "/" + family_of(name, &M, &N) + ".toml");
  if (M > 0) s.flap_modes = M;
  if (N > 0) s.lag_modes = N;
  s.cyclic_pitch = true;
  s.nonlinear = true;
  return s;
}

// A canonical text of an integral's factors (kind, mode), whatever their order.
std::string factor_key(const fm::FactorRef* f, int n) {
  std::vector<std::pair<int, int>> v;
  for (int j = 0; j < n; ++j) v.emplace_back(static_cast<int>(f[j].kind), f[j].mode);
  std::sort(v.begin(), v.end());
  std::string s;
  for (const auto& [k, m] : v) s += std::to_string(k) + ":" + std::to_string(m) + ",";
  return s;
}
std::string factor_key(const std::vector<fd::ShapeFactor>& f) {
  std::vector<fm::FactorRef> v;
  for (const auto& x : f) v.push_back({static_cast<fm::Factor>(x.kind), x.mode});
  return factor_key(v.data(), static_cast<int>(v.size()));
}
std::string aero_key(const fm::AeroIntegral& a) {
  return std::to_string(a.x_power) + "|" + factor_key(a.factors, a.n_factors);
}
std::string aero_key(const fd::AeroIntegralKey& k) {
  return std::to_string(k.x_power) + "|" + factor_key(k.factors);
}
std::string structural_key(const fm::StructuralIntegral& s) {
  return std::to_string(s.outer_mass) + "|" + factor_key(s.outer, s.n_outer) + "|" +
         std::to_string(static_cast<int>(s.inner)) + "|" + std::to_string(s.inner_mass) + "|" +
         factor_key(s.inner_factors, s.n_inner);
}
std::string structural_key(const fd::StructuralIntegralKey& k) {
  return std::to_string(k.outer_mass) + "|" + factor_key(k.outer) + "|" +
         std::to_string(static_cast<int>(k.inner)) + "|" + std::to_string(k.inner_mass) + "|" +
         factor_key(k.inner_factors);
}

// Random inputs shared by the compiled code and the GiNaC evaluation.
struct RandomInputs {
  RandomInputs(const fd::DerivedModel& m, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (const auto& s : m.scalars) value[s.name] = u(rng);
    value["lock"] = 4.0 + 10.0 * std::abs(u(rng));
    value["mu"] = 1.5 * std::abs(u(rng));
    aero.resize(m.aero.size());
    structural.resize(m.structural.size());
    for (auto& a : aero) a = u(rng);
    for (auto& s : structural) s = 0.5 + std::abs(u(rng));
    const int M = m.M, N = m.N;
    auto arr = [&](const std::string& base, int count) {
      std::vector<double> v(count);
      for (int i = 0; i < count; ++i) v[i] = value.at(base + std::to_string(i + 1));
      return v;
    };
    auto mat = [&](const std::string& base, int r, int c) {
      std::vector<double> v(r * c);
      for (int i = 0; i < r; ++i)
        for (int j = 0; j < c; ++j)
          v[i * c + j] = value.at(base + std::to_string(i + 1) + "_" + std::to_string(j + 1));
      return v;
    };
    g0 = arr("g0_", M);
    h0 = arr("h0_", N);
    wf = arr("omega_flap_", M);
    wl = arr("omega_lag_", N);
    zf = arr("damping_flap_", M);
    zl = arr("damping_lag_", N);
    esf = mat("es_flap_", M, M);
    esl = mat("es_lag_", N, N);
    ecsfl = mat("ecs_flap_lag_", M, N);
    ecslf = mat("ecs_lag_flap_", N, M);
  }

  // The compiled model's integral lists (its family's tensors) get the values of the derived
  // model's integrals of the same integrand; the few it has beyond them, other values.
  void bind(const fm::ModelDescriptor& cm, const fd::DerivedModel& m) {
    std::map<std::string, double> a, s;
    for (size_t j = 0; j < m.aero_keys.size(); ++j) a[aero_key(m.aero_keys[j])] = aero[j];
    for (size_t j = 0; j < m.structural_keys.size(); ++j)
      s[structural_key(m.structural_keys[j])] = structural[j];
    compiled_aero.clear();
    compiled_structural.clear();
    for (int j = 0; j < cm.n_aero; ++j) {
      const auto it = a.find(aero_key(cm.aero[j]));
      compiled_aero.push_back(it != a.end() ? it->second : 0.37 + 0.01 * j);
    }
    for (int j = 0; j < cm.n_structural; ++j) {
      const auto it = s.find(structural_key(cm.structural[j]));
      compiled_structural.push_back(it != s.end() ? it->second : 0.41 + 0.01 * j);
    }
    flap_modes = cm.flap_modes;
    lag_modes = cm.lag_modes;
  }

  fm::CoefficientInputs inputs() const {
    fm::CoefficientInputs in{};
    in.modes[kF] = flap_modes;
    in.modes[kL] = lag_modes;
    in.lock = value.at("lock");
    in.lr = value.at("lr");
    in.theta = value.at("theta");
    in.inflow = value.at("inflow");
    in.precone = value.at("precone");
    in.droop = value.at("droop");
    in.cdo_a = value.at("cdo_a");
    in.mu = value.at("mu");
    in.q0[kF] = g0.data();
    in.q0[kL] = h0.data();
    in.omega[kF] = wf.data();
    in.omega[kL] = wl.data();
    in.damping[kF] = zf.data();
    in.damping[kL] = zl.data();
    in.elastic[kF][kF] = esf.data();
    in.elastic[kL][kL] = esl.data();
    in.elastic[kF][kL] = ecsfl.data();
    in.elastic[kL][kF] = ecslf.data();
    in.aero = compiled_aero.data();
    in.structural = compiled_structural.data();
    if (value.count("theta1c") > 0) in.theta1c = value.at("theta1c");
    if (value.count("theta1s") > 0) in.theta1s = value.at("theta1s");
    return in;
  }

  GiNaC::exmap substitution(const fd::DerivedModel& m) const {
    GiNaC::exmap e;
    for (const auto& s : m.scalars) e[s.sym] = GiNaC::numeric(value.at(s.name));
    for (size_t j = 0; j < m.aero_syms.size(); ++j) e[m.aero_syms[j]] = GiNaC::numeric(aero[j]);
    for (size_t j = 0; j < m.structural_syms.size(); ++j)
      e[m.structural_syms[j]] = GiNaC::numeric(structural[j]);
    return e;
  }

  std::map<std::string, double> value;
  std::vector<double> aero, structural, g0, h0, wf, wl, zf, zl, esf, esl, ecsfl, ecslf;
  std::vector<double> compiled_aero, compiled_structural;
  int flap_modes = 0, lag_modes = 0;
};

double ginac_value(const GiNaC::ex& e, const GiNaC::exmap& sub) {
  const GiNaC::ex v = GiNaC::evalf(e.subs(sub));
  return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
}

void expect_slots(const std::vector<fd::Slot>& slots, const std::vector<double>& compiled_values,
                  const GiNaC::exmap& sub, const std::string& what) {
  ASSERT_EQ(slots.size(), compiled_values.size()) << what;
  for (size_t j = 0; j < slots.size(); ++j) {
    const double expected = ginac_value(slots[j].value, sub);
    const double actual = compiled_values[j];
    EXPECT_NEAR(actual, expected, 1e-12 * std::max(1.0, std::abs(expected)))
        << what << "[" << j << "]: GiNaC " << expected << ", compiled " << actual;
  }
}

class GeneratedModel : public ::testing::TestWithParam<std::string> {};

}  // namespace

// Catches printer bugs: the compiled generated code against GiNaC's numeric evaluation of the
// symbolic slots, at several random parameter sets.
TEST_P(GeneratedModel, CompiledCodeEqualsGiNaCEvaluation) {
  const fm::ModelDescriptor* cm = compiled(GetParam());
  ASSERT_NE(cm, nullptr);
  const fd::DerivedModel dm = fd::derive_model(spec_of(GetParam()));
  ASSERT_EQ(cm->flap_modes, dm.M);
  ASSERT_EQ(cm->lag_modes, dm.N);
  ASSERT_EQ(cm->n_harmonics, dm.H);
  ASSERT_GE(static_cast<size_t>(cm->n_aero), dm.aero.size());
  ASSERT_GE(static_cast<size_t>(cm->n_structural), dm.structural.size());
  const int n = dm.n();
  for (unsigned seed : {1u, 2u, 3u}) {
    RandomInputs r(dm, seed);
    r.bind(*cm, dm);
    std::vector<double> mass(n * n), force(dm.H * n * 2 * n), forcing(dm.H * n), S(n * n), c(n);
    cm->mass(r.inputs(), mass.data());
    cm->coefficients(r.inputs(), {force.data(), forcing.data()});
    cm->equilibrium(r.inputs(), {S.data(), c.data()});
    const auto sub = r.substitution(dm);
    expect_slots(dm.mass, mass, sub, "mass");
    expect_slots(dm.force, force, sub, "force");
    expect_slots(dm.forcing, forcing, sub, "forcing");
    expect_slots(dm.S, S, sub, "S");
    expect_slots(dm.c, c, sub, "c");
    // Every model emits the rotor thrust.
    {
      std::vector<double> tforce(dm.H * 2 * n), tforcing(dm.H);
      cm->thrust(r.inputs(), {tforce.data(), tforcing.data()});
      expect_slots(dm.thrust_force, tforce, sub, "thrust force");
      expect_slots(dm.thrust_forcing, tforcing, sub, "thrust forcing");
    }
    // The mass reads the structural integrals only: the runtime evaluates it once, before the
    // hover state is known.  Every other input is NaN or null here.
    const double nan = std::numeric_limits<double>::quiet_NaN();
    fm::CoefficientInputs only{};
    only.lock = only.lr = only.theta = only.inflow = nan;
    only.precone = only.droop = only.cdo_a = only.mu = nan;
    only.structural = r.compiled_structural.data();
    only.modes[kF] = cm->flap_modes;
    only.modes[kL] = cm->lag_modes;
    std::vector<double> structural_only(n * n);
    cm->mass(only, structural_only.data());
    EXPECT_EQ(structural_only, mass);
  }
}

TEST_P(GeneratedModel, DerivationIsDeterministic) {
  const auto spec = spec_of(GetParam());
  const auto a = fd::derive_model(spec);
  const auto b = fd::derive_model(spec);
  EXPECT_EQ(fd::emit_cpp(a), fd::emit_cpp(b));
  EXPECT_EQ(fd::emit_report(a), fd::emit_report(b));
}

// No retained aerodynamic term exceeds its equation's order.
TEST_P(GeneratedModel, TruncationRespectsKeptOrders) {
  const auto spec = spec_of(GetParam());
  const auto m = fd::derive_model(spec);
  const int n = m.n();
  int max_flap = -1, max_lag = -1;
  for (int h = 0; h < m.H; ++h) {
    for (int i = 0; i < n; ++i) {
      std::vector<const fd::Slot*> slots = {&m.forcing[h * n + i]};
      for (int col = 0; col < 2 * n; ++col) slots.push_back(&m.force[(h * n + i) * 2 * n + col]);
      for (const auto* s : slots) {
        for (const auto& t : s->terms) {
          if (t.ref != fd::IntegralRef::Aero) continue;
          (i < m.M ? max_flap : max_lag) = std::max(i < m.M ? max_flap : max_lag, t.eps_order);
        }
      }
    }
  }
  EXPECT_LE(max_flap, spec.kept_flap);
  EXPECT_LE(max_lag, spec.kept_lag);
  // The kept order is reached (the truncation is not cutting deeper than asked).
  EXPECT_EQ(max_flap, spec.kept_flap);
  EXPECT_EQ(max_lag, spec.kept_lag);
}

// The nonlinear loads (spec [emit] nonlinear): models without the switch carry none; with it,
// the compiled polynomial equals GiNaC's, its Jacobian is its derivative, and about the hover
// state (0, q0) it reproduces the model's own linear coefficients and forcing.
TEST_P(GeneratedModel, NonlinearLoadsLinearizeToTheLinearModel) {
  const fm::ModelDescriptor* cm = compiled(GetParam());
  ASSERT_NE(cm, nullptr);
  const auto spec = spec_of(GetParam());
  const fd::DerivedModel dm = fd::derive_model(spec);
  ASSERT_EQ(cm->n_nonlinear_harmonics, dm.H_nonlinear);
  ASSERT_FALSE(dm.nonlinear.empty());
  const int n = dm.n(), ns = 2 * n, H = dm.H_nonlinear, HL = dm.H;
  ASSERT_GE(H, HL);
  int max_degree = 0;
  for (const auto& s : dm.nonlinear) max_degree = std::max(max_degree, s.degree());
  // Regression: the thrust pseudo-equation (cyclic-pitch models) is no generalized load; it was
  // emitted as equation n, past the end of the loads array.
  for (const auto& s : dm.nonlinear) ASSERT_LT(s.equation, n) << "slot of a pseudo-equation";
  EXPECT_GE(max_degree, 2) << "no product of the coordinates was kept";
  for (unsigned seed : {4u, 5u}) {
    RandomInputs r(dm, seed);
    r.bind(*cm, dm);
    const auto sub = r.substitution(dm);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-0.3, 0.3);
    std::vector<double> y(ns);
    for (auto& v : y) v = u(rng);
    std::vector<double> force(H * n), jac(H * n * ns);
    cm->nonlinear(r.inputs(), y.data(), {force.data(), jac.data()});
    std::vector<double> expected(H * n, 0.0);
    for (const auto& s : dm.nonlinear) {
      double mono = 1.0;
      for (int c = 0; c < ns; ++c) mono *= std::pow(y[c], s.powers[c]);
      expected[s.harmonic * n + s.equation] += ginac_value(s.slot.value, sub) * mono;
    }
    for (int k = 0; k < H * n; ++k) {
      EXPECT_NEAR(force[k], expected[k], 1e-12 * std::max(1.0, std::abs(expected[k]))) << k;
    }
    // Jacobian against central differences of the compiled loads (a polynomial of degree
    // max_degree: the difference quotient is exact up to rounding for degree <= 2).
    const double step = 1e-4;
    for (int c = 0; c < ns; ++c) {
      std::vector<double> yp = y, ym = y, fp(H * n), fm2(H * n), scratch(H * n * ns);
      yp[c] += step;
      ym[c] -= step;
      cm->nonlinear(r.inputs(), yp.data(), {fp.data(), scratch.data()});
      cm->nonlinear(r.inputs(), ym.data(), {fm2.data(), scratch.data()});
      for (int k = 0; k < H * n; ++k) {
        const double d = (fp[k] - fm2[k]) / (2 * step);
        EXPECT_NEAR(jac[k * ns + c], d, 1e-7 * std::max(1.0, std::abs(d))) << k << " col " << c;
      }
    }
    // About the hover state of these inputs: the linear model.
    std::vector<double> yh(ns, 0.0);
    for (int k = 0; k < dm.M; ++k) yh[fm::flap_displacement_index(k, dm.M, dm.N)] = r.g0[k];
    for (int m = 0; m < dm.N; ++m) yh[fm::lag_displacement_index(m, dm.M, dm.N)] = r.h0[m];
    std::vector<double> lin_force(HL * n * ns), lin_forcing(HL * n);
    cm->coefficients(r.inputs(), {lin_force.data(), lin_forcing.data()});
    cm->nonlinear(r.inputs(), yh.data(), {force.data(), jac.data()});
    for (int h = 0; h < H; ++h) {
      for (int i = 0; i < n; ++i) {
        const double f_lin = h < HL ? lin_forcing[h * n + i] : 0.0;
        EXPECT_NEAR(force[h * n + i], f_lin, 1e-12 * std::max(1.0, std::abs(f_lin)))
            << "forcing h " << h << " eq " << i;
        for (int c = 0; c < ns; ++c) {
          const double a_lin = h < HL ? lin_force[(h * n + i) * ns + c] : 0.0;
          EXPECT_NEAR(jac[(h * n + i) * ns + c], a_lin, 1e-12 * std::max(1.0, std::abs(a_lin)))
              << "force h " << h << " eq " << i << " col " << c;
        }
      }
    }
  }
  // Cyclic pitch too: the thrust as a polynomial of the full state equals GiNaC's and
  // linearizes about (0, q0) to the linear thrust (value thrust_forcing, Jacobian thrust_force).
  ASSERT_EQ(cm->nonlinear_thrust != nullptr, spec.cyclic_pitch);
  ASSERT_EQ(dm.nonlinear_thrust.empty(), !spec.cyclic_pitch);
  if (spec.cyclic_pitch) {
    RandomInputs r(dm, 7u);
    r.bind(*cm, dm);
    const auto sub = r.substitution(dm);
    std::mt19937 rng(7u);
    std::uniform_real_distribution<double> u(-0.3, 0.3);
    std::vector<double> y(ns), t(H), tj(H * ns);
    for (auto& v : y) v = u(rng);
    cm->nonlinear_thrust(r.inputs(), y.data(), {t.data(), tj.data()});
    std::vector<double> expected(H, 0.0);
    int max_thrust_degree = 0;
    for (const auto& s : dm.nonlinear_thrust) {
      double mono = 1.0;
      for (int c = 0; c < ns; ++c) mono *= std::pow(y[c], s.powers[c]);
      expected[s.harmonic] += ginac_value(s.slot.value, sub) * mono;
      max_thrust_degree = std::max(max_thrust_degree, s.degree());
    }
    EXPECT_GE(max_thrust_degree, 2) << "the thrust keeps products of the coordinates";
    for (int h = 0; h < H; ++h) {
      EXPECT_NEAR(t[h], expected[h], 1e-12 * std::max(1.0, std::abs(expected[h]))) << h;
    }
    std::vector<double> yh(ns, 0.0);
    for (int k = 0; k < dm.M; ++k) yh[fm::flap_displacement_index(k, dm.M, dm.N)] = r.g0[k];
    for (int m = 0; m < dm.N; ++m) yh[fm::lag_displacement_index(m, dm.M, dm.N)] = r.h0[m];
    std::vector<double> lin_force(HL * ns), lin_forcing(HL);
    cm->thrust(r.inputs(), {lin_force.data(), lin_forcing.data()});
    cm->nonlinear_thrust(r.inputs(), yh.data(), {t.data(), tj.data()});
    for (int h = 0; h < H; ++h) {
      const double f_lin = h < HL ? lin_forcing[h] : 0.0;
      EXPECT_NEAR(t[h], f_lin, 1e-12 * std::max(1.0, std::abs(f_lin))) << "thrust h " << h;
      for (int c = 0; c < ns; ++c) {
        const double a_lin = h < HL ? lin_force[h * ns + c] : 0.0;
        EXPECT_NEAR(tj[h * ns + c], a_lin, 1e-12 * std::max(1.0, std::abs(a_lin)))
            << "thrust h " << h << " col " << c;
      }
    }
    for (const auto& s : dm.nonlinear_thrust)
      for (const auto& term : s.slot.terms) EXPECT_LE(term.eps_order, spec.kept_flap);
  }
  // Every aerodynamic term obeys its equation's kept order.
  for (const auto& s : dm.nonlinear) {
    for (const auto& t : s.slot.terms) {
      if (t.ref != fd::IntegralRef::Aero) continue;
      EXPECT_LE(t.eps_order, s.equation < dm.M ? spec.kept_flap : spec.kept_lag);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllCompiledModels, GeneratedModel, ::testing::ValuesIn(compiled_names()),
                         [](const auto& tp) {
                           std::string s = tp.param;
                           for (char& ch : s) {
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           }
                           return s;
                         });

namespace {

// A term's identity apart from its radial-flow flag.
std::string signature(const std::string& slot, const fd::Term& t) {
  std::ostringstream os;
  os << slot << "|" << static_cast<int>(t.ref) << ":" << t.integral << "|" << t.coef << "|"
     << t.origin;
  for (const auto& [i, p] : t.scalars) os << "|" << i << "^" << p;
  return os.str();
}

// drop_cyclic: leave out the terms that carry theta1c or theta1s.
std::multiset<std::string> signatures(const fd::DerivedModel& m, bool keep_radial,
                                      bool drop_cyclic = false) {
  std::set<int> cyclic;
  for (size_t j = 0; j < m.scalars.size(); ++j) {
    if (m.scalars[j].name == "theta1c" || m.scalars[j].name == "theta1s") {
      cyclic.insert(static_cast<int>(j));
    }
  }
  auto is_cyclic = [&](const fd::Term& t) {
    for (const auto& sp : t.scalars) {
      if (cyclic.count(sp.first) > 0) return true;
    }
    return false;
  };
  std::multiset<std::string> s;
  auto add = [&](const std::vector<fd::Slot>& slots, const std::string& kind) {
    for (size_t j = 0; j < slots.size(); ++j) {
      for (const auto& t : slots[j].terms) {
        if (!keep_radial && t.radial_flow) continue;
        if (drop_cyclic && is_cyclic(t)) continue;
        // integrals are renumbered per model: identify them by name
        std::string id = kind + std::to_string(j) + "|" +
                         (t.ref == fd::IntegralRef::Aero         ? m.aero[t.integral].name
                          : t.ref == fd::IntegralRef::Structural ? m.structural[t.integral].name
                                                                 : std::string("-"));
        fd::Term u = t;
        u.integral = 0;
        s.insert(signature(id, u));
      }
    }
  };
  add(m.mass, "mass");
  add(m.force, "force");
  add(m.forcing, "forcing");
  return s;
}

}  // namespace

// Switching radial_flow off removes exactly the terms tagged radial, nothing else.
TEST(TermClasses, RadialFlowSwitchRemovesExactlyTheTaggedTerms) {
  auto spec = spec_of("paper");
  const auto with = fd::derive_model(spec);
  spec.radial_flow = false;
  const auto without = fd::derive_model(spec);
  const auto all = signatures(with, true);
  const auto non_radial = signatures(with, false);
  ASSERT_LT(non_radial.size(), all.size()) << "the paper model has radial-flow terms";
  EXPECT_EQ(signatures(without, true), non_radial);
}

// The cyclic-pitch derivation switch adds exactly terms in theta1c, theta1s (tagged
// theta_cyclic), the thrust and nothing else: without them the model is the paper's, term by
// term (zero cyclic pitch reproduces the paper).
TEST(TermClasses, CyclicPitchSwitchAddsOnlyCyclicTerms) {
  auto plain = spec_of("paper");
  plain.cyclic_pitch = false;
  plain.nonlinear = false;
  auto with_cyclic = plain;
  with_cyclic.cyclic_pitch = true;
  const auto paper = fd::derive_model(plain);
  const auto cyc = fd::derive_model(with_cyclic);
  ASSERT_TRUE(cyc.spec.cyclic_pitch);
  EXPECT_TRUE(paper.thrust_forcing.empty());
  ASSERT_EQ(cyc.thrust_forcing.size(), static_cast<size_t>(cyc.H));
  // more harmonics (theta1 times the 2/rev terms); compare harmonic by harmonic
  ASSERT_GT(cyc.H, paper.H);
  const auto all = signatures(cyc, true);
  const auto without = signatures(cyc, true, true);
  ASSERT_LT(without.size(), all.size()) << "the cyclic model has cyclic terms";
  EXPECT_EQ(without, signatures(paper, true));
  int c1 = -1, s1 = -1;
  for (size_t j = 0; j < cyc.scalars.size(); ++j) {
    if (cyc.scalars[j].name == "theta1c") c1 = static_cast<int>(j);
    if (cyc.scalars[j].name == "theta1s") s1 = static_cast<int>(j);
  }
  ASSERT_GE(c1, 0);
  ASSERT_GE(s1, 0);
  // every cyclic term comes from a theta_cyclic load product, of the order of theta or above
  for (const auto& slot : cyc.force) {
    for (const auto& t : slot.terms) {
      bool has = false;
      for (const auto& sp : t.scalars) has = has || sp.first == c1 || sp.first == s1;
      if (!has) continue;
      EXPECT_NE(t.origin.find("theta_cyclic"), std::string::npos) << t.origin;
      EXPECT_GE(t.eps_order, cyc.spec.order("theta"));
    }
  }
  // a feature of every model, not a key of the spec
  EXPECT_EQ(cyc.spec.canonical_text().find("cyclic_pitch"), std::string::npos);
}

// Lowering the lag order removes exactly the O(eps^3) lag aerodynamic terms.
TEST(TermClasses, LagOrderTwoRemovesExactlyTheThirdOrderLagTerms) {
  auto spec = spec_of("paper");
  const auto three = fd::derive_model(spec);
  spec.kept_lag = 2;
  const auto two = fd::derive_model(spec);
  std::multiset<std::string> expected;
  auto add = [&](const fd::DerivedModel& m, std::multiset<std::string>& out, bool drop3) {
    const int n = m.n();
    auto visit = [&](const std::vector<fd::Slot>& slots, const std::string& kind, int stride) {
      for (size_t j = 0; j < slots.size(); ++j) {
        const int eq = static_cast<int>((j / stride) % n);
        for (const auto& t : slots[j].terms) {
          if (drop3 && eq >= m.M && t.ref == fd::IntegralRef::Aero && t.eps_order > 2) continue;
          fd::Term u = t;
          const std::string name = t.ref == fd::IntegralRef::Aero ? m.aero[t.integral].name
                                   : t.ref == fd::IntegralRef::Structural
                                       ? m.structural[t.integral].name
                                       : std::string("-");
          u.integral = 0;
          out.insert(signature(kind + std::to_string(j) + "|" + name, u));
        }
      }
    };
    visit(m.force, "force", 2 * n);
    visit(m.forcing, "forcing", 1);
  };
  std::multiset<std::string> got;
  add(three, expected, true);
  add(two, got, false);
  EXPECT_EQ(got, expected);
}

// ---------------------------------------------------------------- state ordering

// The helpers of model_api.h against the layout written out by hand from eq 2.36 generalised:
// y = [dg'_1..dg'_M, dg_1..dg_M, dh'_1..dh'_N, dh_1..dh_N].
// The nonlinear-loads derivation switch leaves the linear part alone (the linear coefficient
// code is the same, term for term) and is no key of the spec.
TEST(NonlinearSwitch, LinearPartIsThePapersAndTheSwitchIsNoSpecKey) {
  auto paper = spec_of("paper");
  paper.nonlinear = false;
  auto nl = paper;
  nl.nonlinear = true;
  EXPECT_EQ(nl.canonical_text().find("nonlinear"), std::string::npos);
  auto body = [](const std::string& cc) {
    const auto a = cc.find("void coefficients("), b = cc.find("// Hover static equilibrium");
    return a == std::string::npos || b == std::string::npos ? std::string() : cc.substr(a, b - a);
  };
  const std::string p = body(fd::emit_cpp(fd::derive_model(paper)));
  ASSERT_FALSE(p.empty());
  EXPECT_EQ(p, body(fd::emit_cpp(fd::derive_model(nl))));
  const std::string report = fd::emit_report(fd::derive_model(nl));
  EXPECT_NE(report.find("## Nonlinear generalized loads"), std::string::npos);
  EXPECT_NE(report.find("| g1 h1' |"), std::string::npos);  // Coriolis tension product
  EXPECT_EQ(fd::emit_report(fd::derive_model(paper)).find("Nonlinear"), std::string::npos);
}

TEST(StateOrdering, HelpersFollowEquation236) {
  const std::vector<std::string> two_by_one = {"dg1'", "dg2'", "dg1", "dg2", "dh1'", "dh1"};
  const std::vector<std::string> one_by_two = {"dg1'", "dg1", "dh1'", "dh2'", "dh1", "dh2"};
  for (const auto& [M, N, names] :
       {std::make_tuple(2, 1, two_by_one), std::make_tuple(1, 2, one_by_two)}) {
    ASSERT_EQ(fm::state_count(M, N), static_cast<int>(names.size()));
    for (int col = 0; col < fm::state_count(M, N); ++col) {
      EXPECT_EQ(fm::state_name(col, M, N), names[col]) << M << "x" << N << " col " << col;
    }
    for (int k = 0; k < M; ++k) {
      EXPECT_EQ(names[fm::flap_rate_index(k, M, N)], "dg" + std::to_string(k + 1) + "'");
      EXPECT_EQ(names[fm::flap_displacement_index(k, M, N)], "dg" + std::to_string(k + 1));
      EXPECT_EQ(fm::rate_index(k, M, N), fm::flap_rate_index(k, M, N));
      EXPECT_EQ(fm::coordinate_of_state(fm::flap_displacement_index(k, M, N), M, N), k);
    }
    for (int m = 0; m < N; ++m) {
      EXPECT_EQ(names[fm::lag_rate_index(m, M, N)], "dh" + std::to_string(m + 1) + "'");
      EXPECT_EQ(names[fm::lag_displacement_index(m, M, N)], "dh" + std::to_string(m + 1));
      EXPECT_EQ(fm::displacement_index(M + m, M, N), fm::lag_displacement_index(m, M, N));
      EXPECT_EQ(fm::coordinate_of_state(fm::lag_rate_index(m, M, N), M, N), M + m);
      EXPECT_EQ(fm::lag_equation_index(m, M), M + m);
    }
  }
  static_assert(fm::lag_displacement_index(0, 1, 1) == 3, "A14 multiplies h (eq 2.36)");
}

// ---------------------------------------------------------------- differences from print

namespace {

fd::Term* term_named(fd::DerivedModel& m, std::vector<fd::Slot>& slots, int slot,
                     const std::string& paper, const std::string& scalar) {
  for (auto& t : slots[slot].terms) {
    if (t.paper_name != paper) continue;
    for (const auto& [idx, p] : t.scalars) {
      if (m.scalars[idx].name == scalar) return &t;
    }
  }
  ADD_FAILURE() << "no term " << paper << " with " << scalar << " in slot " << slot;
  static fd::Term none;
  return &none;
}

int integral_named(const std::vector<fd::IntegralInfo>& list, const std::string& paper) {
  for (size_t j = 0; j < list.size(); ++j) {
    if (list[j].paper_name.find(paper) != std::string::npos) return static_cast<int>(j);
  }
  ADD_FAILURE() << "no integral " << paper;
  return 0;
}

std::map<std::string, fd::PaperCheck> statuses(const fd::DerivedModel& m) {
  std::map<std::string, fd::PaperCheck> s;
  for (const auto& d : fd::paper_differences(m)) s[d.id] = d.status;
  return s;
}

// One deliberate error per entry, each the printed form the entry says is wrong.
struct Alteration {
  const char* id;
  std::function<void(fd::DerivedModel&)> alter;
};

const fd::DerivedModel& paper_model() {
  static const fd::DerivedModel m = fd::derive_model(spec_of("paper"));
  return m;
}

// slot indices of the 1 x 1 paper model
int force_slot(int h, int eq, int col) { return (h * 2 + eq) * 4 + col; }
int forcing_slot(int h, int eq) { return h * 2 + eq; }
constexpr int kConst = 0, kCos = 1, kCos2 = 3, kSin2 = 4, kFlap = 0, kLag = 1;

const std::vector<Alteration>& alterations() {
  using FK = fd::FactorKind;
  static const std::vector<Alteration> a = {
      {"P_ikm",  // the printed moment arm x1 inside the Coriolis tension integral
       [](fd::DerivedModel& m) {
         m.structural_keys[integral_named(m.structural, "P_111")].inner_factors.push_back(
             {FK::X0, 0});
       }},
      {"B8_im",  // printed weight gamma_i instead of its slope
       [](fd::DerivedModel& m) {
         m.structural_keys[integral_named(m.structural, "B8_11")].outer[0].kind = FK::Gamma;
       }},
      {"B10_i",
       [](fd::DerivedModel& m) {
         m.structural_keys[integral_named(m.structural, "B10_1")].outer[0].kind = FK::Gamma;
       }},
      {"F23_ikm",  // printed eta_i eta_k gamma_m' (= F24)
       [](fd::DerivedModel& m) {
         m.aero_keys[integral_named(m.aero, "F23_111")].factors = {
             {FK::Eta, 0}, {FK::Eta, 0}, {FK::GammaPrime, 0}};
       }},
      {"S_imr",  // h0 (2 S + 2 M_gamma): the Coriolis pair would not cancel
       [](fd::DerivedModel& m) {
         auto* t = term_named(m, m.force, force_slot(kConst, kLag, 2), "Mgamma_111", "h0_1");
         t->coef = -t->coef;
       }},
      {"A31",  // the lag row divided by the flap mass
       [](fd::DerivedModel& m) { m.mass[1 * 2 + 1] = m.mass[0]; }},
      {"f1 F22 lambda",
       [](fd::DerivedModel& m) {
         auto* t = term_named(m, m.forcing, forcing_slot(kCos, kFlap), "F22_11", "inflow");
         t->coef = -t->coef;
       }},
      {"f1 F22 theta",
       [](fd::DerivedModel& m) {
         auto* t = term_named(m, m.forcing, forcing_slot(kSin2, kFlap), "F22_11", "theta");
         t->coef = -t->coef;
       }},
      {"f1 F22 beta",
       [](fd::DerivedModel& m) {
         auto* t = term_named(m, m.forcing, forcing_slot(kConst, kFlap), "F22_11", "precone");
         t->coef = -t->coef;
       }},
      {"f3 L2 drag",  // printed (1 + cos 2psi)
       [](fd::DerivedModel& m) {
         auto* t = term_named(m, m.forcing, forcing_slot(kCos2, kLag), "L2_1", "cdo_a");
         t->coef = -t->coef;
       }},
      {"f3 L21",
       [](fd::DerivedModel& m) {
         auto* t = term_named(m, m.forcing, forcing_slot(kConst, kLag), "L21_111", "theta");
         t->coef = -t->coef;
       }},
      {"c L4",  // printed L4 + C_Do/a: a drag term without spanwise integral
       [](fd::DerivedModel& m) {
         fd::Term bare = *term_named(m, m.c, kLag, "L4_1", "cdo_a");
         bare.ref = fd::IntegralRef::None;
         bare.integral = -1;
         bare.paper_name.clear();
         m.c[kLag].terms.push_back(bare);
       }},
      {"eq 2.34 E^cs",
       [](fd::DerivedModel& m) {
         for (auto& t : m.force[force_slot(kConst, kFlap, 3)].terms) {
           if (t.ref == fd::IntegralRef::None) t.coef = -t.coef;
         }
       }},
      {"A_F scale",  // (gamma/2)(l/R)^2 F1 theta printed as gamma (l/R)^2 F1 theta
       [](fd::DerivedModel& m) {
         term_named(m, m.forcing, forcing_slot(kConst, kFlap), "F1_1", "theta")->coef *= 2;
       }},
      {"L_z F6",  // printed eta_k instead of eta_k'
       [](fd::DerivedModel& m) {
         m.aero_keys[integral_named(m.aero, "F6_11")].factors = {{FK::Eta, 0}, {FK::Eta, 0}};
       }},
      {"F15 L18",
       [](fd::DerivedModel& m) { m.aero[integral_named(m.aero, "F9_11")].paper_name = "F15_11"; }},
  };
  return a;
}

}  // namespace

// The paper model reproduces every corrected entry; no shipped model contradicts one.
TEST(PaperDifferences, PaperModelConfirmsEveryEntryAndNoModelContradictsOne) {
  for (const auto& [id, status] : statuses(paper_model())) {
    EXPECT_EQ(status, fd::PaperCheck::Confirmed) << id;
  }
  for (const auto& name : compiled_names()) {
    for (const auto& d : fd::paper_differences(fd::derive_model(spec_of(name)))) {
      EXPECT_NE(d.status, fd::PaperCheck::Contradicted) << name << ": " << d.id;
    }
  }
  // without radial flow the F22 terms do not exist: absent, not confirmed
  const auto nrf = statuses(fd::derive_model(spec_of("no-radial-flow")));
  EXPECT_EQ(nrf.at("f1 F22 lambda"), fd::PaperCheck::Absent);
}

// Every entry tests the derived model: the printed form, put into the model, contradicts it.
TEST(PaperDifferences, EachEntryFailsOnTheMisprintedForm) {
  const auto all = statuses(paper_model());
  ASSERT_EQ(all.size(), alterations().size());
  for (const auto& a : alterations()) {
    ASSERT_EQ(all.count(a.id), 1u) << a.id;
    fd::DerivedModel altered = paper_model();
    a.alter(altered);
    const auto s = statuses(altered);
    EXPECT_EQ(s.at(a.id), fd::PaperCheck::Contradicted) << a.id;
    for (const auto& [id, status] : s) {
      if (id != a.id) {
        EXPECT_EQ(status, fd::PaperCheck::Confirmed) << a.id << " also changes " << id;
      }
    }
  }
  fd::DerivedModel altered = paper_model();
  alterations().front().alter(altered);
  EXPECT_NE(fd::paper_differences_section(altered).find("| CONTRADICTED |"), std::string::npos);
}

// ---------------------------------------------------------------- audit report

// The report's exact assumed-mode integrals against the runtime's Gauss quadrature (blade.h),
// an independent implementation.
TEST(AuditReport, ExactAssumedModeIntegralsAgreeWithTheRuntimeQuadrature) {
  const flaplag::ModeSet modes = flaplag::assumed_modes(1.175, 1.28303);
  const flaplag::SpanGeometry span;  // e1 = 0, l/R = 1, A = 0, B = 1 (paper Sec. 4.1)
  for (const char* name : {"paper", "no-radial-flow", "lag-order-2"}) {
    const fm::ModelDescriptor* cm = compiled(name);
    ASSERT_NE(cm, nullptr);
    const auto dm = fd::derive_model(spec_of(name));
    // every integral of the derivation is one of the compiled model's (its family's tensors)
    std::map<std::string, int> aero, structural;
    for (int j = 0; j < cm->n_aero; ++j) aero.emplace(aero_key(cm->aero[j]), j);
    for (int j = 0; j < cm->n_structural; ++j)
      structural.emplace(structural_key(cm->structural[j]), j);
    for (size_t j = 0; j < dm.aero_keys.size(); ++j) {
      const auto it = aero.find(aero_key(dm.aero_keys[j]));
      ASSERT_NE(it, aero.end()) << name << " " << dm.aero[j].name;
      EXPECT_EQ(dm.aero[j].name, cm->aero[it->second].name);
      const double exact = fd::assumed_mode_integral(dm.aero_keys[j]).to_double();
      const double gauss = flaplag::aero_integral(cm->aero[it->second], modes, span, 0.0, 1.0);
      EXPECT_NEAR(exact, gauss, 1e-13 * std::abs(gauss)) << name << " " << dm.aero[j].name;
    }
    for (size_t j = 0; j < dm.structural_keys.size(); ++j) {
      const auto it = structural.find(structural_key(dm.structural_keys[j]));
      ASSERT_NE(it, structural.end()) << name << " " << dm.structural[j].name;
      EXPECT_EQ(dm.structural[j].name, cm->structural[it->second].name);
      const double exact = fd::assumed_mode_integral(dm.structural_keys[j]).to_double();
      const double gauss = flaplag::structural_integral(cm->structural[it->second], modes, 0.0);
      EXPECT_NEAR(exact, gauss, 1e-13 * std::abs(gauss)) << name << " " << dm.structural[j].name;
    }
  }
}

// The value column: the report's evaluation (exact integrals, symbolic slots) against the
// compiled model fed with the runtime's integrals, at the typical case typed in from the paper.
TEST(AuditReport, ValuesAtTheTypicalCaseAgreeWithTheCompiledModel) {
  const fm::ModelDescriptor* cm = compiled("paper");
  const auto dm = fd::derive_model(spec_of("paper"));
  const fd::PointValues pv = fd::typical_case_values(dm);
  ASSERT_TRUE(pv.available) << pv.reason;
  // Sec. 4.1 and eq 2.24: sigma = 0.05, a = 2 pi, theta = 0.15
  const double a = 2.0 * std::acos(-1.0), sa = 0.05 * a;
  const double lambda = sa / 16.0 * (std::sqrt(1.0 + 24.0 * 0.15 / sa) - 1.0);
  EXPECT_NEAR(lambda, 0.0496715830600, 1e-12);
  const flaplag::ModeSet modes = flaplag::assumed_modes(1.175, 1.28303);
  std::vector<double> aero, structural;
  for (int j = 0; j < cm->n_aero; ++j) {
    aero.push_back(flaplag::aero_integral(cm->aero[j], modes, {}, 0.0, 1.0));
  }
  for (int j = 0; j < cm->n_structural; ++j) {
    structural.push_back(flaplag::structural_integral(cm->structural[j], modes, 0.0));
  }
  const double zero[1] = {0.0}, wf[1] = {1.175}, wl[1] = {1.28303};
  double g0[1] = {0.0}, h0[1] = {0.0};
  fm::CoefficientInputs in{};
  in.modes[kF] = in.modes[kL] = 1;
  in.lock = 10.0;
  in.lr = 1.0;
  in.theta = 0.15;
  in.inflow = lambda;
  in.cdo_a = 0.01 / a;
  in.mu = 0.0;
  in.q0[kF] = g0;
  in.q0[kL] = h0;
  in.omega[kF] = wf;
  in.omega[kL] = wl;
  in.damping[kF] = in.damping[kL] = zero;
  for (auto& row : in.elastic)
    for (const double*& block : row) block = zero;
  in.aero = aero.data();
  in.structural = structural.data();
  double S[4], c[2];
  cm->equilibrium(in, {S, c});
  const double det = S[0] * S[3] - S[1] * S[2];
  g0[0] = (c[0] * S[3] - S[1] * c[1]) / det;
  h0[0] = (S[0] * c[1] - S[2] * c[0]) / det;
  auto scalar = [&](const std::string& n) {
    for (size_t j = 0; j < dm.scalars.size(); ++j) {
      if (dm.scalars[j].name == n) return pv.scalar[j];
    }
    return std::nan("");
  };
  EXPECT_NEAR(scalar("g0_1"), g0[0], 1e-13);
  EXPECT_NEAR(scalar("h0_1"), h0[0], 1e-13);
  in.mu = 0.5;
  double mass[4];
  std::vector<double> force(dm.H * 8), forcing(dm.H * 2);
  cm->mass(in, mass);
  cm->coefficients(in, {force.data(), forcing.data()});
  for (int h = 0; h < dm.H; ++h) {
    for (int eq = 0; eq < 2; ++eq) {
      const double m_report = pv.value(dm.mass[eq * 3]);
      EXPECT_NEAR(m_report, mass[eq * 3], 1e-14);
      for (int col = 0; col < 4; ++col) {
        const int k = (h * 2 + eq) * 4 + col;
        EXPECT_NEAR(pv.value(dm.force[k]) / m_report, force[k] / mass[eq * 3], 1e-12)
            << "harmonic " << h << " eq " << eq << " col " << col;
      }
      EXPECT_NEAR(pv.value(dm.forcing[h * 2 + eq]), forcing[h * 2 + eq], 1e-12);
    }
  }
  EXPECT_FALSE(fd::typical_case_values(fd::derive_model(spec_of("paper-2x2"))).available);
}

// The blocks read like Appendix C.2 and C.3 (transcribed from the paper into the report's names,
// with the corrected signs of the "Differences" section).
TEST(AuditReport, BlocksReadLikeAppendixC) {
  const std::string r = fd::emit_report(paper_model());
  for (const char* line :
       {// A11 = -2 eta_SF1 w_F1 + (1/M_F1)(gamma/2)(l/R)^2 [-F8 l/R - F9 mu l/R sin psi
        //       + F24 mu cos psi l/R h0]
        "`A11 = (1/M_F11) { -2 omega_flap_1 damping_flap_1 M_F11 + (lock/2) lr^2 [ -lr F8_11 "
        "- lr mu sin psi F9_11 + lr mu h0_1 cos psi F24_111 ] }`",
        // A13: 2 P_111 g0 + 2 (beta_P + beta_D) B3_11 + ...
        "2 (precone + droop) B3_11 + 2 g0_1 P_111",
        // A32: -L11 mu^2 (beta_P + beta_D)(1 + cos 2psi)
        "- (precone + droop) mu^2 (1 + cos 2psi) L11_11",
        // f3: -L2 (mu^2/2)(beta_P + beta_D)^2 (1 + cos 2psi) + L2 (mu^2/2)(C_Do/a)(1 - cos 2psi)
        "- 1/2 (precone + droop)^2 mu^2 (1 + cos 2psi) L2_1 + 1/2 cdo_a mu^2 (1 - cos 2psi) L2_1",
        "| A13 | const | 2 (precone + droop) | int eta1' [int_x^1 m gamma1 dx1] | B3_11 |",
        "### f3: lag 1 equation"}) {
    EXPECT_NE(r.find(line), std::string::npos) << line;
  }
}

// beta_P and beta_D are printed as their sum only when the derivation gives them equal factors.
TEST(AuditReport, BetaSumOnlyForEqualFactors) {
  fd::DerivedModel m = paper_model();
  term_named(m, m.force, force_slot(kConst, kFlap, 2), "B3_11", "droop")->coef *= 2;
  const std::string r = fd::emit_report(m);
  EXPECT_EQ(r.find("| A13 | const | 2 (precone + droop) |"), std::string::npos);
  EXPECT_NE(r.find("| A13 | const | 2 precone | int eta1' [int_x^1 m gamma1 dx1] | B3_11 |"),
            std::string::npos);
  EXPECT_NE(r.find("| A13 | const | 4 droop | int eta1' [int_x^1 m gamma1 dx1] | B3_11 |"),
            std::string::npos);
}

// ---------------------------------------------------------------- bad specs

struct BadSpec {
  const char* name;
  const char* text;
  std::vector<std::string> must_contain;
};

class BadSpecTest : public ::testing::TestWithParam<BadSpec> {};

TEST_P(BadSpecTest, RejectedWithFileKeyAndValue) {
  const BadSpec& b = GetParam();
  try {
    fd::parse_spec(b.text, "dir/bad.toml");
    FAIL() << "accepted: " << b.text;
  } catch (const fd::SpecError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bad.toml"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one line: " << what;
    for (const auto& s : b.must_contain) EXPECT_NE(what.find(s), std::string::npos) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Specs, BadSpecTest,
    ::testing::Values(
        BadSpec{"Malformed", "[modes\nflap = 1\n", {"line 1", "malformed"}},
        BadSpec{"UnknownKey", "colour = 1\n", {"colour", "unknown key"}},
        BadSpec{"UnknownSymbol", "[orders]\nzeta = 1\n", {"orders.zeta", "unknown symbol"}},
        BadSpec{"NegativeOrder", "[orders]\ntheta = -1\n", {"orders.theta", "-1"}},
        BadSpec{"NonIntegerOrder", "[orders]\ntheta = 1.5\n", {"orders.theta", "1.5", "integer"}},
        BadSpec{"StringOrder", "[kept]\nflap = \"two\"\n", {"kept.flap", "\"two\""}},
        BadSpec{"NegativeFlapModes", "[modes]\nflap = -2\n", {"modes.flap", "-2"}},
        BadSpec{"ZeroLagModes", "[modes]\nlag = 0\n", {"modes.lag", "0", ">= 1"}},
        BadSpec{"RadialNotBool", "[terms]\nradial_flow = 1\n", {"terms.radial_flow", "1"}},
        BadSpec{"CyclicPitchIsNoSpecKey",
                "[terms]\ncyclic_pitch = true\n",
                {"terms.cyclic_pitch", "true", "no longer a spec key"}},
        BadSpec{"UnknownTermClass", "[terms]\nstall = true\n", {"terms.stall"}},
        BadSpec{"EmitIsNoSpecKey", "[emit]\nnonlinear = true\n", {"emit", "no longer a spec key"}},
        BadSpec{"ZeroOrderCoordinate", "[orders]\ng = 0\n", {"orders.g", "0"}},
        BadSpec{"BaseNotString", "base = 3\n", {"base = 3", "string"}},
        BadSpec{"BaseTable", "[base]\nname = \"paper\"\n", {"base = (table)", "string"}},
        BadSpec{"BaseWithPath", "base = \"../paper\"\n", {"base = \"../paper\"", "no path"}},
        BadSpec{"BaseMissingFile",
                "base = \"no-such-spec\"\n",
                {"base = \"no-such-spec\"", "no spec file", "no-such-spec.toml"}},
        BadSpec{"BaseIsItself", "base = \"bad\"\n", {"base = \"bad\"", "cycle"}}),
    [](const auto& tp) { return std::string(tp.param.name); });

// ---------------------------------------------------------------- spec inheritance

namespace {

// A scratch directory of spec files, removed at the end of the test.
class SpecDir {
 public:
  explicit SpecDir(const std::string& tag)
      : dir_(std::filesystem::temp_directory_path() / ("flaplag_spec_" + tag)) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  ~SpecDir() { std::filesystem::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) const {
    const auto p = dir_ / (name + ".toml");
    std::ofstream(p) << text;
    return p.string();
  }
  const std::filesystem::path& path() const { return dir_; }

 private:
  std::filesystem::path dir_;
};

std::string spec_error(const std::string& path) {
  try {
    fd::load_spec(path);
  } catch (const fd::SpecError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

// A base of a base is resolved; each file overrides only the keys it gives.
TEST(SpecInheritance, ChainOfBasesResolvesKeyByKey) {
  SpecDir d("chain");
  d.write("root", "description = \"root\"\n[orders]\ntheta = 2\n[kept]\nflap = 3\n");
  d.write("mid", "base = \"root\"\n[kept]\nlag = 2\n");
  const auto leaf = fd::load_spec(d.write("leaf", "base = \"mid\"\n[modes]\nlag = 2\n"));
  EXPECT_EQ(leaf.name, "leaf");
  EXPECT_EQ(leaf.base, "mid");
  EXPECT_EQ(leaf.description, "root");  // inherited through two levels
  EXPECT_EQ(leaf.order("theta"), 2);    // from root
  EXPECT_EQ(leaf.order("cdo_a"), 2);    // default
  EXPECT_EQ(leaf.kept_flap, 3);         // from root
  EXPECT_EQ(leaf.kept_lag, 2);          // from mid
  EXPECT_EQ(leaf.flap_modes, 1);
  EXPECT_EQ(leaf.lag_modes, 2);  // its own
  // mid changes the physics of root: a family of its own; leaf changes only its modes.
  EXPECT_EQ(fd::load_spec((d.path() / "root.toml").string()).family, "root");
  EXPECT_EQ(fd::load_spec((d.path() / "mid.toml").string()).family, "mid");
  EXPECT_EQ(leaf.family, "mid");
  EXPECT_NE(leaf.canonical_text().find("base = \"mid\""), std::string::npos);
}

TEST(SpecInheritance, CycleIsAnErrorNamingFileKeyAndValue) {
  SpecDir d("cycle");
  d.write("b", "base = \"c\"\n");
  d.write("c", "base = \"b\"\n");
  const std::string what = spec_error(d.write("a", "base = \"b\"\n"));
  EXPECT_NE(what.find("c.toml: base = \"b\""), std::string::npos) << what;
  EXPECT_NE(what.find("cycle a -> b -> c -> b"), std::string::npos) << what;
  EXPECT_EQ(what.find('\n'), std::string::npos) << what;
}

// An error inside a base file names the base file, not the file that inherits from it.
TEST(SpecInheritance, ErrorInBaseNamesTheBaseFile) {
  SpecDir d("base_error");
  d.write("parent", "[orders]\nzeta = 1\n");
  const std::string what = spec_error(d.write("child", "base = \"parent\"\n"));
  EXPECT_NE(what.find("parent.toml: orders.zeta = 1"), std::string::npos) << what;
}

// The shipped variants differ from their base only where they say so, and (family, M, N) names
// one compiled model, which is how the runtime looks them up.
TEST(SpecInheritance, ShippedSpecsAreOneFamilyEach) {
  // Any M x N comes from the family: one spec per family is shipped, and the compiled families
  // are exactly those specs.
  std::set<std::string> families;
  for (const auto& entry : std::filesystem::directory_iterator(FLAPLAG_SPEC_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    const auto s = fd::load_spec(entry.path().string());
    EXPECT_EQ(s.family, s.name) << "a spec that only changes [modes] of another";
    EXPECT_TRUE(families.insert(s.family).second) << s.family;
  }
  std::set<std::string> compiled_families;
  for (const auto* f : fm::registered_families()) compiled_families.insert(f->name);
  EXPECT_EQ(compiled_families, families);
  // the compiled descriptors carry the family
  for (const char* name : {"paper", "paper-2x2", "no-radial-flow-3x1", "lag-order-2"}) {
    int M = 0, N = 0;
    EXPECT_EQ(std::string(compiled(name)->base), family_of(name, &M, &N)) << name;
  }
}

// The build-time tool: one line on stderr naming file, key and value, exit code 2, and no
// output file; the build fails with that message because the custom command fails.
TEST(DeriveTool, BadSpecFailsWithOneLineAndNoOutput) {
  const auto dir = std::filesystem::temp_directory_path() / "flaplag_generator_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto spec = dir / "broken.toml";
  std::ofstream(spec) << "[orders]\ntheta = -3\n";
  const auto out = dir / "out";
  const std::string cmd = std::string(FLAPLAG_DERIVE_EXE) + " --spec " + spec.string() +
                          " --out-dir " + out.string() + " 2>" + (dir / "err").string();
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  std::ifstream err(dir / "err");
  std::string line, rest;
  std::getline(err, line);
  EXPECT_FALSE(std::getline(err, rest)) << "more than one line: " << rest;
  EXPECT_NE(line.find("broken.toml"), std::string::npos) << line;
  EXPECT_NE(line.find("orders.theta"), std::string::npos) << line;
  EXPECT_NE(line.find("-3"), std::string::npos) << line;
  EXPECT_FALSE(std::filesystem::exists(out / "broken.cc"));
  EXPECT_FALSE(std::filesystem::exists(out / "broken.md"));
  std::filesystem::remove_all(dir);
}

TEST(DeriveTool, MissingSpecFileFails) {
  const std::string cmd =
      std::string(FLAPLAG_DERIVE_EXE) + " --spec /nonexistent/none.toml --out-dir /tmp 2>/dev/null";
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
}

TEST(DeriveTool, BadBaseFailsWithExitCode2) {
  SpecDir d("tool_base");
  const std::string spec = d.write("orphan", "base = \"gone\"\n");
  const auto err = d.path() / "err";
  const std::string cmd = std::string(FLAPLAG_DERIVE_EXE) + " --spec " + spec + " --out-dir " +
                          (d.path() / "out").string() + " 2>" + err.string();
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  std::ifstream in(err);
  std::string line;
  std::getline(in, line);
  EXPECT_NE(line.find("orphan.toml: base = \"gone\""), std::string::npos) << line;
}

}  // namespace generator_test
