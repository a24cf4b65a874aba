// The spec keys that say which terms an equation keeps: per-equation radial flow
// ([terms.flap], [terms.lag] radial_flow), only the damping among the O(eps^kept) terms
// (top_order = "damping"), the order of mu ([orders] mu) and exclusions by Appendix B name
// ([exclude] terms).  Each key removes exactly the terms it names, from the linear slots, the
// hover equilibrium, the thrust and the nonlinear loads alike; bad values are one line naming
// file, key and value; the example specs of examples/specs derive the shipped variants.
#include "flaplag_derive/spec.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "flaplag/model_api.h"
#include "flaplag_derive/derive.h"
#include "flaplag_derive/emit.h"
#include "flaplag_derive/generic.h"
#include "flaplag_derive/paper_names.h"

namespace spec_test {

namespace fd = flaplag::derive;
namespace fm = flaplag::model;

namespace {

const std::string kShipped = FLAPLAG_SPEC_DIR;
const std::string kExamples = FLAPLAG_EXAMPLE_SPEC_DIR;

// A spec with every derivation switch the compiled families have, at M x N modes.
fd::OrderingSpec full(fd::OrderingSpec s, int M = 1, int N = 1) {
  s.flap_modes = M;
  s.lag_modes = N;
  s.cyclic_pitch = true;
  s.nonlinear = true;
  return s;
}

fd::OrderingSpec shipped(const std::string& name, int M = 1, int N = 1) {
  return full(fd::load_spec(kShipped + "/" + name + ".toml"), M, N);
}

// Spec text as if it were a file of the shipped directory (so `base = "paper"` resolves there).
fd::OrderingSpec text_spec(const std::string& text, int M = 1, int N = 1) {
  return full(fd::parse_spec(text, kShipped + "/scratch.toml"), M, N);
}

// One term of a derived model with where it sits: kind (mass, force, forcing, S, c, thrust,
// thrust-forcing, nonlinear, nonlinear-thrust), harmonic, equation (M + N = the thrust), state
// column (-1: none) or, for the nonlinear loads, the state powers.
struct Row {
  std::string kind;
  int harmonic = 0, eq = 0, col = -1;
  std::vector<int> powers;
  fd::Term term;
  std::string integral;  // by name: integrals are numbered per model
  bool aero() const { return term.ref == fd::IntegralRef::Aero; }
  int power_of(const fd::DerivedModel& m, const std::string& scalar) const {
    for (const auto& [idx, p] : term.scalars)
      if (m.scalars[idx].name == scalar) return p;
    return 0;
  }
};

std::vector<Row> rows(const fd::DerivedModel& m) {
  const int n = m.n(), ns = 2 * n;
  std::vector<Row> out;
  auto add = [&](const fd::Slot& s, const std::string& kind, int h, int eq, int col,
                 std::vector<int> powers = {}) {
    for (const auto& t : s.terms) {
      Row r;
      r.kind = kind;
      r.harmonic = h;
      r.eq = eq;
      r.col = col;
      r.powers = powers;
      r.term = t;
      r.integral = t.ref == fd::IntegralRef::Aero         ? m.aero[t.integral].name
                   : t.ref == fd::IntegralRef::Structural ? m.structural[t.integral].name
                                                          : "-";
      out.push_back(r);
    }
  };
  for (int eq = 0; eq < n; ++eq) {
    for (int c = 0; c < n; ++c) add(m.mass[eq * n + c], "mass", 0, eq, c);
    for (int c = 0; c < n; ++c) add(m.S[eq * n + c], "S", 0, eq, c);
    add(m.c[eq], "c", 0, eq, -1);
    for (int h = 0; h < m.H; ++h) {
      add(m.forcing[h * n + eq], "forcing", h, eq, -1);
      for (int c = 0; c < ns; ++c) add(m.force[(h * n + eq) * ns + c], "force", h, eq, c);
    }
  }
  for (int h = 0; h < m.H && !m.thrust_forcing.empty(); ++h) {
    add(m.thrust_forcing[h], "thrust-forcing", h, n, -1);
    for (int c = 0; c < ns; ++c) add(m.thrust_force[h * ns + c], "thrust", h, n, c);
  }
  for (const auto& s : m.nonlinear) add(s.slot, "nonlinear", s.harmonic, s.equation, -1, s.powers);
  for (const auto& s : m.nonlinear_thrust)
    add(s.slot, "nonlinear-thrust", s.harmonic, s.equation, -1, s.powers);
  return out;
}

// eps_shift: a row's eps order is compared as eps - eps_shift(row) (the mu test).
std::string text(const fd::DerivedModel& m, const Row& r, int eps_shift = 0) {
  std::ostringstream os;
  os << r.kind << "|" << r.harmonic << "|" << r.eq << "|" << r.col << "|";
  for (int p : r.powers) os << p;
  os << "|" << r.integral << "|" << r.term.coef << "|" << r.term.origin << "|" << r.term.radial_flow
     << "|" << r.term.eps_order - eps_shift << "|" << r.term.paper_name;
  for (const auto& [idx, p] : r.term.scalars) os << "|" << m.scalars[idx].name << "^" << p;
  return os.str();
}

std::multiset<std::string> texts(const fd::DerivedModel& m,
                                 const std::function<bool(const Row&)>& keep = nullptr,
                                 const std::function<int(const Row&)>& shift = nullptr) {
  std::multiset<std::string> s;
  for (const auto& r : rows(m)) {
    if (keep && !keep(r)) continue;
    s.insert(text(m, r, shift ? shift(r) : 0));
  }
  return s;
}

bool is_flap(const fd::DerivedModel& m, const Row& r) { return r.eq < m.M || r.eq == m.n(); }
bool is_lag(const fd::DerivedModel& m, const Row& r) { return r.eq >= m.M && r.eq < m.n(); }

// Multiplies a state rate: a rate column of the linear slots or a rate power of the nonlinear.
bool has_rate(const fd::DerivedModel& m, const Row& r) {
  if (!r.powers.empty()) {
    for (size_t c = 0; c < r.powers.size(); ++c)
      if (r.powers[c] > 0 && fm::state_ref(static_cast<int>(c), m.M, m.N).rate) return true;
    return false;
  }
  return r.col >= 0 && (r.kind == "force" || r.kind == "thrust") &&
         fm::state_ref(r.col, m.M, m.N).rate;
}

// The terms of `full_model` without those `drop` selects equal the terms of `reduced`, and the
// key dropped something.
void expect_drops_exactly(const fd::DerivedModel& full_model, const fd::DerivedModel& reduced,
                          const std::function<bool(const Row&)>& drop) {
  const auto all = texts(full_model);
  const auto kept = texts(full_model, [&](const Row& r) { return !drop(r); });
  ASSERT_LT(kept.size(), all.size()) << "nothing to drop";
  EXPECT_EQ(texts(reduced), kept);
}

// A scratch directory of spec files, removed at the end of the test.
class SpecDir {
 public:
  explicit SpecDir(const std::string& tag)
      : dir_(std::filesystem::temp_directory_path() / ("flaplag_spec_test_" + tag)) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  ~SpecDir() { std::filesystem::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& body) const {
    const auto p = dir_ / (name + ".toml");
    std::ofstream(p) << body;
    return p.string();
  }
  const std::filesystem::path& path() const { return dir_; }

 private:
  std::filesystem::path dir_;
};

}  // namespace

// ---------------------------------------------------------------- defaults

// At their defaults the new keys are not written: the canonical text (recorded in the
// generated code, checked byte for byte by generated_golden_test) of every shipped spec has
// none of them, and giving the defaults explicitly changes nothing.
TEST(SpecTermKeys, DefaultsLeaveTheCanonicalTextAlone) {
  for (const char* name : {"paper", "no-radial-flow", "lag-order-2"}) {
    const std::string t =
        fd::load_spec(kShipped + "/" + std::string(name) + ".toml").canonical_text();
    EXPECT_EQ(t.find("mu ="), std::string::npos) << t;
    EXPECT_EQ(t.find("[terms.flap]"), std::string::npos) << t;
    EXPECT_EQ(t.find("[terms.lag]"), std::string::npos) << t;
    EXPECT_EQ(t.find("top_order"), std::string::npos) << t;
    EXPECT_EQ(t.find("[exclude]"), std::string::npos) << t;
  }
  const auto paper = fd::load_spec(kShipped + "/paper.toml");
  const auto explicit_defaults = fd::parse_spec(
      "base = \"paper\"\n[orders]\nmu = 0\n[terms.flap]\nradial_flow = true\ntop_order = "
      "\"all\"\n[terms.lag]\nradial_flow = true\ntop_order = \"all\"\n[exclude]\nterms = []\n",
      kShipped + "/scratch.toml");
  EXPECT_EQ(explicit_defaults.family, "paper") << "same physics as its base";
  EXPECT_EQ(explicit_defaults.summary().substr(explicit_defaults.name.size()),
            paper.summary().substr(paper.name.size()));
}

// Every new key is written into the canonical text when set, and the text reads back as the
// same spec.
TEST(SpecTermKeys, CanonicalTextRoundTrips) {
  const auto s = fd::parse_spec(
      "base = \"paper\"\n[orders]\nmu = 1\n[terms.flap]\nradial_flow = false\n[terms.lag]\n"
      "top_order = \"damping\"\n[exclude]\nterms = [\"L13\", \"F23\", \"L13\"]\n",
      kShipped + "/scratch.toml");
  const std::string t = s.canonical_text();
  EXPECT_NE(t.find("[orders]"), std::string::npos);
  EXPECT_NE(t.find("mu = 1\n"), std::string::npos) << t;
  EXPECT_NE(t.find("[terms.flap]\nradial_flow = false\n[terms.lag]\ntop_order = \"damping\"\n"),
            std::string::npos)
      << t;
  // paper order, each once
  EXPECT_NE(t.find("[exclude]\nterms = [\"F23\", \"L13\"]\n"), std::string::npos) << t;
  EXPECT_EQ(s.family, "scratch");
  const auto back = fd::parse_spec(t, "/nonexistent/back.toml");
  EXPECT_EQ(back.canonical_text().substr(back.canonical_text().find("description")),
            t.substr(t.find("description")));
  EXPECT_EQ(s.summary(),
            "scratch: 1 flap x 1 lag modes; flap loads to O(eps^2), lag loads to O(eps^3); radial "
            "flow on (lag equation only); mu of O(eps^1); lag O(eps^3) terms: damping only; "
            "excluded F23 L13");
}

// ---------------------------------------------------------------- per-equation radial flow

// Radial flow off in the flap equation only removes exactly the radial-tagged terms of the flap
// equations and of the thrust (which integrates the flap load); the lag equations keep theirs.
TEST(SpecTermKeys, RadialFlowOffInTheFlapEquationOnly) {
  for (const auto& [M, N] : {std::pair{1, 1}, std::pair{2, 2}}) {
    const auto paper = fd::derive_model(shipped("paper", M, N));
    const auto lag_only = fd::derive_model(
        full(fd::load_spec(kExamples + "/fig06-07-radial-flow-lag-only.toml"), M, N));
    expect_drops_exactly(paper, lag_only,
                         [&](const Row& r) { return r.term.radial_flow && is_flap(paper, r); });
    bool lag_radial = false;
    for (const auto& r : rows(lag_only)) lag_radial = lag_radial || r.term.radial_flow;
    EXPECT_TRUE(lag_radial) << "the lag equation keeps its radial-flow terms";
  }
}

TEST(SpecTermKeys, RadialFlowOffInTheLagEquationOnly) {
  const auto paper = fd::derive_model(shipped("paper", 2, 1));
  const auto flap_only =
      fd::derive_model(text_spec("base = \"paper\"\n[terms.lag]\nradial_flow = false\n", 2, 1));
  expect_drops_exactly(paper, flap_only,
                       [&](const Row& r) { return r.term.radial_flow && is_lag(paper, r); });
}

// Both equations off is the spec-wide switch, term for term (integrals, harmonics included).
TEST(SpecTermKeys, RadialFlowOffInBothEquationsIsTheSpecWideSwitch) {
  const auto a = fd::derive_model(shipped("no-radial-flow", 2, 2));
  const auto b =
      fd::derive_model(full(fd::load_spec(kExamples + "/fig06-07-no-radial-flow.toml"), 2, 2));
  EXPECT_EQ(texts(a), texts(b));
  EXPECT_EQ(a.H, b.H);
  EXPECT_EQ(a.H_nonlinear, b.H_nonlinear);
  ASSERT_EQ(a.aero.size(), b.aero.size());
  for (size_t j = 0; j < a.aero.size(); ++j) EXPECT_EQ(a.aero[j].name, b.aero[j].name);
}

// ---------------------------------------------------------------- damping only at top order

// Of the lag equation's O(eps^3) aerodynamic terms only those multiplying a state rate stay;
// the forcing, the displacement coefficients, their hover-equilibrium parts and the nonlinear
// terms without a rate go; the flap equation and the thrust are untouched.
TEST(SpecTermKeys, LagDampingOnlyAtTheTopOrder) {
  for (const auto& [M, N] : {std::pair{1, 1}, std::pair{1, 2}}) {
    const auto paper = fd::derive_model(shipped("paper", M, N));
    const auto damping =
        fd::derive_model(full(fd::load_spec(kExamples + "/fig08-lag-damping-only.toml"), M, N));
    auto top_lag = [&](const Row& r) {
      return r.aero() && is_lag(paper, r) && r.term.eps_order >= 3;
    };
    expect_drops_exactly(paper, damping,
                         [&](const Row& r) { return top_lag(r) && !has_rate(paper, r); });
    // what stays of the O(eps^3) lag terms: the damping, among it the profile drag L14 and
    // the induced drag L13 of the paper's A33
    std::set<std::string> kept_names;
    for (const auto& r : rows(damping)) {
      if (!top_lag(r)) continue;
      EXPECT_TRUE(has_rate(damping, r)) << text(damping, r);
      kept_names.insert(fd::paper_base_name(r.term.paper_name));
    }
    EXPECT_EQ(kept_names.count("L13"), 1u);
    EXPECT_EQ(kept_names.count("L14"), 1u);
    // and it is lag-order-2 plus those damping terms
    EXPECT_EQ(texts(fd::derive_model(shipped("lag-order-2", M, N))),
              texts(damping, [&](const Row& r) { return !top_lag(r); }));
  }
}

// Damping only in the flap equation also applies to the thrust (the flap load).
TEST(SpecTermKeys, FlapDampingOnlyAppliesToTheThrust) {
  const auto paper = fd::derive_model(shipped("paper"));
  const auto damping =
      fd::derive_model(text_spec("base = \"paper\"\n[terms.flap]\ntop_order = \"damping\"\n"));
  expect_drops_exactly(paper, damping, [&](const Row& r) {
    return r.aero() && is_flap(paper, r) && r.term.eps_order >= 2 && !has_rate(paper, r);
  });
}

// ---------------------------------------------------------------- order of mu

// mu = 1 makes every term with mu^p p orders smaller: the model is the paper's with each
// aerodynamic term's order raised by its power of mu and the terms above the kept order gone.
TEST(SpecTermKeys, MuOfOrderOneTruncatesItsTerms) {
  for (const auto& [M, N] : {std::pair{1, 1}, std::pair{2, 1}}) {
    const auto paper = fd::derive_model(shipped("paper", M, N));
    const auto small_mu = fd::derive_model(text_spec("base = \"paper\"\n[orders]\nmu = 1\n", M, N));
    auto mu_power = [&](const Row& r) { return r.power_of(paper, "mu"); };
    const auto expected = texts(
        paper,
        [&](const Row& r) {
          const int kept = is_flap(paper, r) ? 2 : 3;
          return !r.aero() || r.term.eps_order + mu_power(r) <= kept;
        },
        [&](const Row& r) { return -mu_power(r); });
    ASSERT_LT(expected.size(), texts(paper).size());
    EXPECT_EQ(texts(small_mu), expected);
    // still mu terms, at least one order up
    bool mu_term = false;
    for (const auto& r : rows(small_mu)) {
      if (r.power_of(small_mu, "mu") == 0) continue;
      mu_term = true;
      EXPECT_GE(r.term.eps_order, r.power_of(small_mu, "mu")) << text(small_mu, r);
    }
    EXPECT_TRUE(mu_term);
  }
}

// ---------------------------------------------------------------- exclusions

// [exclude] terms drops every term with those Appendix B names, in every slot and at every
// mode index, lists each dropped term of the linear model with its reason, and shows them in the
// audit report.
TEST(SpecTermKeys, ExclusionDropsExactlyTheNamedTerms) {
  for (const auto& [M, N] : {std::pair{1, 1}, std::pair{2, 2}}) {
    const auto paper = fd::derive_model(shipped("paper", M, N));
    const auto excl = fd::derive_model(
        text_spec("base = \"paper\"\n[exclude]\nterms = [\"F23\", \"L13\"]\n", M, N));
    auto named = [&](const Row& r) {
      const std::string b = fd::paper_base_name(r.term.paper_name);
      return r.aero() && (b == "F23" || b == "L13");
    };
    expect_drops_exactly(paper, excl, named);
    // the record: one entry per dropped term of force, forcing and thrust (S and c are the
    // forcing's hover part, the nonlinear loads a second pass)
    size_t linear = 0;
    for (const auto& r : rows(paper)) {
      if (named(r) && (r.kind == "force" || r.kind == "forcing")) ++linear;
    }
    EXPECT_EQ(excl.dropped.size(), linear);
    std::set<std::string> reasons;
    for (const auto& d : excl.dropped) reasons.insert(d.reason);
    EXPECT_EQ(reasons, (std::set<std::string>{"excluded: F23", "excluded: L13"}));
    const std::string report = fd::emit_report(excl);
    EXPECT_NE(report.find("## Terms dropped by the spec"), std::string::npos);
    EXPECT_NE(report.find("| F23_1"), std::string::npos);
    EXPECT_NE(report.find("| excluded: L13 |"), std::string::npos);
    EXPECT_EQ(fd::emit_report(paper).find("Terms dropped"), std::string::npos);
  }
}

TEST(SpecTermKeys, ExclusionExampleDropsTheL13Terms) {
  const auto paper = fd::derive_model(shipped("paper"));
  const auto excl =
      fd::derive_model(full(fd::load_spec(kExamples + "/no-induced-lag-damping.toml")));
  expect_drops_exactly(paper, excl, [&](const Row& r) {
    return r.aero() && fd::paper_base_name(r.term.paper_name) == "L13";
  });
}

// Every valid name is accepted; the list is the derivation's names.
TEST(SpecTermKeys, EveryPaperNameCanBeExcluded) {
  const auto& names = fd::paper_aero_names();
  ASSERT_GE(names.size(), 30u);
  EXPECT_EQ(names.front(), "F1");
  EXPECT_EQ(names.back(), "L24");
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "\"" : ", \"") + n + "\"";
  const auto s = fd::parse_spec("[exclude]\nterms = [" + list + "]\n", "dir/all.toml");
  EXPECT_EQ(s.excluded, names);
}

// ---------------------------------------------------------------- bad values

namespace {

struct BadKey {
  const char* name;
  const char* text;
  std::vector<std::string> must_contain;
};

class BadTermKeyTest : public ::testing::TestWithParam<BadKey> {};

}  // namespace

TEST_P(BadTermKeyTest, RejectedWithOneLineNamingFileKeyAndValue) {
  const BadKey& b = GetParam();
  try {
    fd::parse_spec(b.text, "dir/bad.toml");
    FAIL() << "accepted: " << b.text;
  } catch (const fd::SpecError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("bad.toml: ", 0), 0u) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one line: " << what;
    for (const auto& s : b.must_contain) EXPECT_NE(what.find(s), std::string::npos) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Specs, BadTermKeyTest,
    ::testing::Values(
        BadKey{"UnknownPaperName",
               "[exclude]\nterms = [\"F23\", \"F99\"]\n",
               {"exclude.terms = \"F99\"", "no term of the derivation", "F1, F2", "L24"}},
        BadKey{"PaperNameWithSubscripts",
               "[exclude]\nterms = [\"F23_111\"]\n",
               {"exclude.terms = \"F23_111\"", "expected F1"}},
        BadKey{"PaperNameLowerCase", "[exclude]\nterms = [\"l13\"]\n", {"exclude.terms = \"l13\""}},
        BadKey{"ExcludeNotAList",
               "[exclude]\nterms = \"F23\"\n",
               {"exclude.terms = \"F23\"", "list of strings"}},
        BadKey{"ExcludeNumber", "[exclude]\nterms = [23]\n", {"exclude.terms = 23", "string"}},
        BadKey{"ExcludeUnknownKey",
               "[exclude]\nnames = [\"F23\"]\n",
               {"exclude.names = (array)", "unknown key (expected terms)"}},
        BadKey{"ExcludeNotATable", "exclude = [\"F23\"]\n", {"exclude = (array)", "table"}},
        BadKey{"TopOrderUnknown",
               "[terms.lag]\ntop_order = \"dampin\"\n",
               {"terms.lag.top_order = \"dampin\"", "one of \"all\", \"damping\""}},
        BadKey{"TopOrderNotText", "[terms.flap]\ntop_order = 3\n", {"terms.flap.top_order = 3"}},
        BadKey{"EquationRadialNotBool",
               "[terms.lag]\nradial_flow = \"no\"\n",
               {"terms.lag.radial_flow = \"no\"", "true or false"}},
        BadKey{"UnknownEquationTermClass",
               "[terms.lag]\nstall = true\n",
               {"terms.lag.stall = true", "unknown term class (expected radial_flow, top_order)"}},
        BadKey{"UnknownEquation",
               "[terms.rotor]\nradial_flow = false\n",
               {"terms.rotor = (table)", "expected radial_flow, flap, lag"}},
        BadKey{"EquationNotATable", "[terms]\nflap = false\n", {"terms.flap = false", "table"}},
        BadKey{"NegativeMuOrder", "[orders]\nmu = -1\n", {"orders.mu = -1", ">= 0"}},
        BadKey{"NonIntegerMuOrder", "[orders]\nmu = 0.5\n", {"orders.mu = 0.5", "integer"}}),
    [](const auto& tp) { return std::string(tp.param.name); });

// ---------------------------------------------------------------- base resolution

// A spec outside generator/orderings finds a shipped base; a spec of its own directory with the
// same name comes first; a base found nowhere names both places.
TEST(SpecBase, FoundNextToTheSpecThenAmongTheShippedSpecs) {
  SpecDir d("base");
  const auto a = fd::load_spec(d.write("mine", "base = \"paper\"\n[kept]\nflap = 3\n"));
  EXPECT_EQ(a.base, "paper");
  EXPECT_EQ(a.kept_flap, 3);
  EXPECT_EQ(a.kept_lag, 3);  // from the shipped paper.toml
  EXPECT_EQ(a.description, fd::load_spec(kShipped + "/paper.toml").description);
  d.write("paper", "description = \"local paper\"\n[kept]\nlag = 1\n");
  const auto b = fd::load_spec((d.path() / "mine.toml").string());
  EXPECT_EQ(b.description, "local paper");
  EXPECT_EQ(b.kept_lag, 1);
  try {
    fd::load_spec(d.write("lost", "base = \"nowhere\"\n"));
    FAIL();
  } catch (const fd::SpecError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("lost.toml: base = \"nowhere\": no spec file"), std::string::npos) << what;
    EXPECT_NE(what.find((d.path() / "nowhere.toml").string()), std::string::npos) << what;
    EXPECT_NE(what.find(kShipped + "/nowhere.toml"), std::string::npos) << what;
  }
}

// ---------------------------------------------------------------- examples

// The example specs written with the per-equation keys derive exactly the shipped variants
// (every slot, the thrust, the nonlinear loads, at 1 x 1 and 2 x 2), and the generic family
// extracted from them is the same.
TEST(ExampleSpecs, ReproduceTheShippedVariants) {
  for (const auto& [example, variant] : {std::pair{"fig06-07-no-radial-flow", "no-radial-flow"},
                                         std::pair{"fig08-lag-order-2", "lag-order-2"}}) {
    const auto ex = fd::load_spec(kExamples + "/" + example + ".toml");
    EXPECT_EQ(ex.base, "paper");
    for (const auto& [M, N] : {std::pair{1, 1}, std::pair{2, 2}}) {
      const auto a = fd::derive_model(full(ex, M, N));
      const auto b = fd::derive_model(shipped(variant, M, N));
      EXPECT_EQ(fd::concrete_terms(a), fd::concrete_terms(b)) << example << " " << M << "x" << N;
      EXPECT_EQ(texts(a), texts(b)) << example;
    }
    EXPECT_EQ(fd::expand_generic(fd::extract_generic(ex), 3, 2),
              fd::expand_generic(
                  fd::extract_generic(fd::load_spec(kShipped + "/" + variant + ".toml")), 3, 2))
        << example;
  }
}

// Every example spec loads and derives.
TEST(ExampleSpecs, EveryExampleLoads) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kExamples)) {
    if (entry.path().extension() != ".toml") continue;
    const auto s = fd::load_spec(entry.path().string());
    EXPECT_EQ(s.base, "paper") << s.name;
    EXPECT_FALSE(fd::derive_model(full(s)).force.empty()) << s.name;
    ++count;
  }
  EXPECT_EQ(count, 5);
}

}  // namespace spec_test
