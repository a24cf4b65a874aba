// The derivation and its emitted code: compiled coefficients equal GiNaC's own evaluation,
// output is deterministic, truncation respects the spec, term classes drop exactly, and bad
// specs are rejected with file, key and value.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <string>

#include "flaplag/model_api.h"
#include "flaplag_derive/derive.h"
#include "flaplag_derive/emit.h"
#include "flaplag_derive/spec.h"

namespace fd = flaplag::derive;
namespace fm = flaplag::model;

namespace {

const fm::ModelDescriptor* compiled(const std::string& name) {
  for (const auto* m : fm::registered_models()) {
    if (name == m->name) return m;
  }
  return nullptr;
}

std::vector<std::string> compiled_names() {
  std::vector<std::string> v;
  for (const auto* m : fm::registered_models()) v.emplace_back(m->name);
  return v;
}

fd::OrderingSpec spec_of(const std::string& name) {
  return fd::load_spec(std::string(FLAPLAG_SPEC_DIR) + "/" + name + ".toml");
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

  fm::CoefficientInputs inputs() const {
    fm::CoefficientInputs in{};
    in.lock = value.at("lock");
    in.lr = value.at("lr");
    in.theta = value.at("theta");
    in.inflow = value.at("inflow");
    in.precone = value.at("precone");
    in.droop = value.at("droop");
    in.cdo_a = value.at("cdo_a");
    in.mu = value.at("mu");
    in.g0 = g0.data();
    in.h0 = h0.data();
    in.omega_flap = wf.data();
    in.omega_lag = wl.data();
    in.damping_flap = zf.data();
    in.damping_lag = zl.data();
    in.es_flap = esf.data();
    in.es_lag = esl.data();
    in.ecs_flap_lag = ecsfl.data();
    in.ecs_lag_flap = ecslf.data();
    in.aero = aero.data();
    in.structural = structural.data();
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
  ASSERT_EQ(static_cast<size_t>(cm->n_aero), dm.aero.size());
  ASSERT_EQ(static_cast<size_t>(cm->n_structural), dm.structural.size());
  const int n = dm.n();
  for (unsigned seed : {1u, 2u, 3u}) {
    RandomInputs r(dm, seed);
    std::vector<double> mass(n * n), force(dm.H * n * 2 * n), forcing(dm.H * n), S(n * n), c(n);
    cm->coefficients(r.inputs(), {mass.data(), force.data(), forcing.data()});
    cm->equilibrium(r.inputs(), {S.data(), c.data()});
    const auto sub = r.substitution(dm);
    expect_slots(dm.mass, mass, sub, "mass");
    expect_slots(dm.force, force, sub, "force");
    expect_slots(dm.forcing, forcing, sub, "forcing");
    expect_slots(dm.S, S, sub, "S");
    expect_slots(dm.c, c, sub, "c");
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

std::multiset<std::string> signatures(const fd::DerivedModel& m, bool keep_radial) {
  std::multiset<std::string> s;
  auto add = [&](const std::vector<fd::Slot>& slots, const std::string& kind) {
    for (size_t j = 0; j < slots.size(); ++j) {
      for (const auto& t : slots[j].terms) {
        if (!keep_radial && t.radial_flow) continue;
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
        BadSpec{"UnknownTermClass", "[terms]\nstall = true\n", {"terms.stall"}},
        BadSpec{"ZeroOrderCoordinate", "[orders]\ng = 0\n", {"orders.g", "0"}}),
    [](const auto& tp) { return std::string(tp.param.name); });

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
