// --inflow at the command line: fixed controls at the momentum inflow of eq 2.25 (rotor/inflow.h
// InflowModel::Momentum), checked against the library's own analyses at the inflow ratio that eq
// 2.25 gives (InflowModel::Given of momentum_inflow, solved here), and every refusal of the option.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_run.h"
#include "flaplag/analysis.h"
#include "flaplag/rotor/inflow.h"
#include "process.h"

namespace {

using Json = nlohmann::json;
using flaplag::testing::Outcome;
using flaplag::testing::run;
using flaplag::testing::run_json;

// The exponents of a point document by label: (zeta, omega).
std::map<std::string, std::pair<double, double>> exponents_of(const Json& point) {
  std::map<std::string, std::pair<double, double>> out;
  for (const Json& e : point["exponents"])
    out[e["label"].get<std::string>()] = {e["zeta"].get<double>(), e["omega"].get<double>()};
  return out;
}

std::map<std::string, std::pair<double, double>> exponents_of(const flaplag::PointResult& p) {
  std::map<std::string, std::pair<double, double>> out;
  for (const flaplag::LabelledExponent& e : p.exponents) out[e.label] = {e.zeta, e.omega};
  return out;
}

// The analysis of the typical rotor at fixed controls and one inflow ratio at every mu.
flaplag::Analysis at_lambda(double lambda, bool periodic = false) {
  flaplag::RotorParameters p;
  flaplag::OperatingCondition c;
  c.inflow = flaplag::InflowModel::Given(lambda);
  if (periodic) c.linearization = flaplag::Linearization::PeriodicEquilibrium;
  return flaplag::Analysis(p, {}, c);
}

void expect_same_exponents(const std::map<std::string, std::pair<double, double>>& a,
                           const std::map<std::string, std::pair<double, double>>& b,
                           double tolerance) {
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [label, e] : a) {
    ASSERT_EQ(b.count(label), 1u) << label;
    EXPECT_NEAR(e.first, b.at(label).first, tolerance) << label << " zeta";
    EXPECT_NEAR(e.second, b.at(label).second, tolerance) << label << " omega";
  }
}

constexpr double kThrust = 0.005;

// In hover eq 2.25 is lambda = sqrt(C_T / 2): the hover of --inflow momentum is the rotor at
// that inflow ratio, which the library gives with InflowModel::Given.
TEST(CliInflow, HoverAtTheMomentumInflowIsTheRotorAtSqrtOfHalfTheThrust) {
  const Json j =
      run_json({"point", "--mu", "0", "--inflow", "momentum", "--thrust-coefficient", "0.005"});
  EXPECT_EQ(j["status"], "ok") << j;
  const double lambda = std::sqrt(kThrust / 2.0);  // 0.05
  EXPECT_NEAR(j["hover"]["inflow"].get<double>(), lambda, 1e-15) << j["hover"];
  EXPECT_NEAR(j["inflow"]["lambda"].get<double>(), lambda, 1e-15) << j["inflow"];
  EXPECT_EQ(j["inflow"]["kind"], "momentum");
  EXPECT_EQ(j["inflow"]["thrust_coefficient"], kThrust);
  EXPECT_EQ(j["inflow"]["shaft_angle"], 0.0);
  const flaplag::Analysis given = at_lambda(lambda);
  expect_same_exponents(exponents_of(j), exponents_of(given.point(0.0)), 1e-12);
  // ... and not the paper's eq 2.24 (lambda = 0.04967 for theta = 0.15).
  const Json uniform = run_json({"point", "--mu", "0"});
  EXPECT_GT(std::abs(uniform["hover"]["inflow"].get<double>() - lambda), 1e-4);
}

// At mu = 0.3 the momentum inflow is eq 2.25 at 0.3, below the hover value: the exponents
// differ from the paper's uniform inflow.  About the periodic equilibrium at mu (which does not
// rest on the hover equilibrium) they are those of the rotor held at lambda(0.3).
TEST(CliInflow, MomentumInflowAtAnAdvanceRatioIsEq225There) {
  const double lambda = flaplag::momentum_inflow(kThrust, 0.3, 0.0);
  // Eq 2.25 solved here by fixed-point iteration, independently of the library's root finder.
  double lam = std::sqrt(kThrust / 2.0);
  for (int i = 0; i < 200; ++i) lam = 0.5 * lam + 0.5 * kThrust / (2.0 * std::hypot(0.3, lam));
  ASSERT_NEAR(lambda, lam, 1e-14);
  const Json m = run_json({"point", "--mu", "0.3", "--inflow", "momentum", "--thrust-coefficient",
                           "0.005", "--scan-step", "0.1"});
  const Json u = run_json({"point", "--mu", "0.3", "--scan-step", "0.1"});
  EXPECT_NEAR(m["inflow"]["lambda"].get<double>(), lam, 1e-14) << m["inflow"];
  EXPECT_FALSE(u.contains("inflow")) << "the default document gained a key";
  const auto em = exponents_of(m), eu = exponents_of(u);
  double largest = 0.0;
  for (const auto& [label, e] : em)
    largest = std::max(largest, std::abs(e.first - eu.at(label).first));
  EXPECT_GT(largest, 1e-3) << "the momentum inflow left the exponents at mu = 0.3 unchanged";

  // About hover the equilibrium is the hover's at lambda(0) (docs/trim.md), not lambda(0.3)'s:
  // the rotor held at lambda(0.3) throughout, hover included, is another rotor.
  const auto held = exponents_of(at_lambda(lam).point(0.3, 0.1));
  double apart = 0.0;
  for (const auto& [label, e] : em)
    apart = std::max(apart, std::abs(e.first - held.at(label).first));
  EXPECT_GT(apart, 1e-4) << "the hover equilibrium of the momentum inflow moved to lambda(mu)";

  const Json mp = run_json({"--periodic-linearization", "point", "--mu", "0.3", "--inflow",
                            "momentum", "--thrust-coefficient", "0.005", "--scan-step", "0.1"});
  const flaplag::Analysis given = at_lambda(lam, true);
  expect_same_exponents(exponents_of(mp), exponents_of(given.point(0.3, 0.1)), 1e-11);
}

// A shaft angle enters eq 2.25 as mu tan alpha_R.
TEST(CliInflow, ShaftAngleEntersTheMomentumInflow) {
  const Json j = run_json({"point", "--mu", "0.2", "--inflow", "momentum", "--thrust-coefficient",
                           "0.005", "--shaft-angle", "0.05", "--scan-step", "0.1"});
  const double lambda = j["inflow"]["lambda"].get<double>();
  EXPECT_NEAR(lambda, 0.2 * std::tan(0.05) + kThrust / (2.0 * std::hypot(0.2, lambda)), 1e-14);
  EXPECT_EQ(j["inflow"]["shaft_angle"], 0.05);
}

// The critical search at the momentum inflow converges, and its status is the search's: mu_c is
// a root of the least stable zeta of the rotor at that inflow (checked on the library's analysis
// at the inflow of eq 2.25 around mu_c, the hover equilibrium at lambda(0) as the CLI's).
TEST(CliInflow, CriticalSearchAtTheMomentumInflowConverges) {
  const Json c = run_json({"critical", "--inflow", "momentum", "--thrust-coefficient", "0.005"});
  ASSERT_TRUE(c["mu_c"].is_number()) << c;
  EXPECT_EQ(c["status"], "ok") << c["message"];
  const double mu_c = c["mu_c"].get<double>();
  const Json u = run_json({"critical"});
  EXPECT_GT(std::abs(mu_c - u["mu_c"].get<double>()), 1e-3) << "the inflow changed nothing";
  EXPECT_NEAR(c["inflow"]["lambda_at_mu_c"].get<double>(),
              flaplag::momentum_inflow(kThrust, mu_c, 0.0), 1e-15);
  // Just below mu_c the rotor is stable, just above it is not.
  const flaplag::Analysis an(flaplag::RotorParameters{}, {}, [] {
    flaplag::OperatingCondition o;
    o.inflow = flaplag::InflowModel::Momentum(kThrust, 0.0);
    return o;
  }());
  double max_below = -1e300, max_above = -1e300;
  for (const auto& e : an.point(mu_c - 1e-3).exponents) max_below = std::max(max_below, e.zeta);
  for (const auto& e : an.point(mu_c + 1e-3).exponents) max_above = std::max(max_above, e.zeta);
  EXPECT_LT(max_below, 0.0);
  EXPECT_GT(max_above, 0.0);
}

// The text output says which inflow a result was computed at.
TEST(CliInflow, TextHeaderNamesTheInflow) {
  const Outcome o = run({"point", "--mu", "0.3", "--inflow", "momentum", "--thrust-coefficient",
                         "0.005", "--scan-step", "0.1"});
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_NE(o.out.find("momentum (eq 2.25) at every mu for C_T = 0.005"), std::string::npos)
      << o.out;
  EXPECT_NE(o.out.find("inflow lambda at mu = 0.3"), std::string::npos) << o.out;
  const Outcome u = run({"point", "--mu", "0.3", "--inflow", "uniform", "--scan-step", "0.1"});
  const Outcome d = run({"point", "--mu", "0.3", "--scan-step", "0.1"});
  EXPECT_EQ(u.out, d.out) << "--inflow uniform is the default";
}

// Each refusal: one line, exit 2, naming the option as typed.
struct Refusal {
  std::vector<std::string> args;
  std::string line_start;
};

TEST(CliInflow, EveryRefusalNamesTheOption) {
  const std::vector<Refusal> cases = {
      {{"point", "--mu", "0.3", "--inflow", "momentum"},
       "flaplag: error: --inflow = momentum: needs --thrust-coefficient"},
      {{"critical", "--inflow", "momentum", "--trim", "thrust", "--thrust-coefficient", "0.005"},
       "flaplag: error: --inflow = momentum: not with --trim thrust"},
      {{"sweep", "--mu", "0:0.2:0.1", "--inflow=momentum", "--trim", "moment",
        "--thrust-coefficient", "0.005"},
       "flaplag: error: --inflow = momentum: not with --trim moment"},
      {{"point", "--mu", "0.3", "--inflow", "given"},
       "flaplag: error: --inflow = given: must be one of uniform, momentum"},
      {{"point", "--mu", "0.3", "--inflow", "Momentum"},
       "flaplag: error: --inflow = Momentum: must be one of uniform, momentum"},
      {{"point", "--mu", "0.3", "--inflow", "momentum", "--thrust-coefficient", "0"},
       "flaplag: error: --thrust-coefficient = 0: "},
      {{"point", "--mu", "0.3", "--inflow", "momentum", "--thrust-coefficient", "0.2"},
       "flaplag: error: --thrust-coefficient = 0.2: "},
      {{"system", "--mu", "0.3", "--inflow", "momentum", "--thrust-coefficient", "0.005",
        "--shaft-angle", "2"},
       "flaplag: error: --shaft-angle = 2: "},
      {{"point", "--mu", "0.3", "--thrust-coefficient", "0.005"},
       "flaplag: error: --thrust-coefficient = 0.005: applies only with --trim thrust|moment or "
       "--inflow momentum"},
      {{"point", "--mu", "0.3", "--inflow", "uniform", "--shaft-angle", "0.1"},
       "flaplag: error: --shaft-angle = 0.1: applies only with --trim thrust|moment or --inflow "
       "momentum"},
      {{"response", "--mu", "0.3", "--thrust-coefficient", "0.005"},
       "flaplag: error: --thrust-coefficient = 0.005: applies only with --inflow momentum"},
      // campbell varies the rotor speed at the paper's inflow: it takes no --inflow.
      {{"campbell", "--inflow", "momentum", "--thrust-coefficient", "0.005"},
       "flaplag: error: --inflow"},
      {{"trim", "--mu", "0.3", "--inflow", "momentum"}, "flaplag: error: --inflow"},
  };
  for (const Refusal& c : cases) {
    const Outcome o = run(c.args);
    std::string cmd;
    for (const std::string& a : c.args) cmd += a + " ";
    EXPECT_EQ(o.exit_code, 2) << cmd << o.err;
    EXPECT_EQ(o.err.rfind(c.line_start, 0), 0u) << cmd << "\n" << o.err;
    EXPECT_EQ(o.err.find('\n'), o.err.size() - 1) << cmd << "\n" << o.err;
    EXPECT_TRUE(o.out.empty()) << cmd;
  }
}

// study and map take the inflow through the library's StudyOptions / MapOptions: a study row at
// a value is the critical search of that rotor at the momentum inflow.
TEST(CliInflow, StudyAndMapAtTheMomentumInflow) {
  const Json s = run_json({"study", "--vary", "omega-lag=1.4", "--inflow", "momentum",
                           "--thrust-coefficient", "0.005", "--mu-max", "1.2"});
  const Json c = run_json({"critical", "--omega-lag", "1.4", "--inflow", "momentum",
                           "--thrust-coefficient", "0.005", "--mu-max", "1.2"});
  ASSERT_EQ(s["rows"].size(), 1u) << s;
  EXPECT_EQ(s["inflow"]["kind"], "momentum") << s;
  ASSERT_TRUE(c["mu_c"].is_number()) << c;
  EXPECT_NEAR(s["rows"][0]["mu_c"].get<double>(), c["mu_c"].get<double>(), 1e-9) << s["rows"][0];
  const Json m = run_json({"map", "--x", "mu=0.3", "--y", "theta=0.15", "--inflow", "momentum",
                           "--thrust-coefficient", "0.005"});
  const Json p =
      run_json({"point", "--mu", "0.3", "--inflow", "momentum", "--thrust-coefficient", "0.005"});
  EXPECT_EQ(m["inflow"]["kind"], "momentum") << m;
  double max_zeta = -1e300;
  for (const Json& e : p["exponents"]) max_zeta = std::max(max_zeta, e["zeta"].get<double>());
  EXPECT_NEAR(m["max_zeta"][0][0].get<double>(), max_zeta, 1e-9) << m;
}

// A case file takes the option as the command line does.
TEST(CliInflow, CaseFileTakesTheInflow) {
  const Json j = run_json({"point", "--mu", "0.3", "--inflow", "momentum", "--thrust-coefficient",
                           "0.005", "--scan-step", "0.1"});
  ASSERT_EQ(j["case"]["inflow"], "momentum") << j["case"];
  const std::string path = ::testing::TempDir() + "inflow_case.json";
  {
    FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    const std::string text = j.dump();
    std::fwrite(text.data(), 1, text.size(), f);
    std::fclose(f);
  }
  const Json again = run_json({"run", path});
  EXPECT_EQ(again["exponents"], j["exponents"]);
  EXPECT_EQ(again["inflow"], j["inflow"]);
  const std::string toml = ::testing::TempDir() + "inflow_case.toml";
  {
    FILE* f = std::fopen(toml.c_str(), "w");
    ASSERT_NE(f, nullptr);
    const std::string text =
        "command = \"point\"\nmu = 0.3\nscan-step = 0.1\ninflow = \"momentum\"\n"
        "thrust-coefficient = 0.005\n";
    std::fwrite(text.data(), 1, text.size(), f);
    std::fclose(f);
  }
  const Json from_toml = run_json({"run", toml});
  EXPECT_EQ(from_toml["exponents"], j["exponents"]);
  // Without the C_T the case is refused as the command line is.
  {
    FILE* f = std::fopen(toml.c_str(), "w");
    ASSERT_NE(f, nullptr);
    const std::string text = "command = \"point\"\nmu = 0.3\ninflow = \"momentum\"\n";
    std::fwrite(text.data(), 1, text.size(), f);
    std::fclose(f);
  }
  const Outcome o = run({"run", toml});
  EXPECT_EQ(o.exit_code, 2) << o.err;
  EXPECT_NE(o.err.find("inflow"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("needs --thrust-coefficient"), std::string::npos) << o.err;
}

}  // namespace
