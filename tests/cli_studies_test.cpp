// The study-level commands of the CLI, run as a user would: study, map, run (case files and
// JSON round trips), --plot, response and simulate.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "process.h"

namespace {

using Json = nlohmann::json;

using flaplag::testing::Outcome;
using flaplag::testing::slurp;
using flaplag::testing::TempDir;

// `path_env` replaces PATH when not empty.
Outcome run(const std::vector<std::string>& args, const std::string& path_env = "") {
  return flaplag::testing::run_process(FLAPLAG_EXE, args, std::chrono::seconds(300), path_env);
}

bool gnuplot_available() { return std::system("command -v gnuplot > /dev/null 2>&1") == 0; }

TEST(CliStudy, RowsWithIntervalsIdenticalForOneAndTwoThreads) {
  const std::vector<std::string> base = {
      "--modes", "exact", "study", "--vary", "omega-lag=1.3,1.45", "--mu-max", "1.5", "--json"};
  std::vector<std::string> one = base, two = base;
  one.insert(one.end(), {"--threads", "1"});
  two.insert(two.end(), {"--threads", "2"});
  const Outcome a = run(one), b = run(two);
  ASSERT_EQ(0, a.exit_code) << a.err;
  ASSERT_EQ(0, b.exit_code) << b.err;
  const Json ja = Json::parse(a.out), jb = Json::parse(b.out);
  // Identical results; only the case (which records --threads) differs.
  EXPECT_EQ(ja["rows"], jb["rows"]);
  ASSERT_EQ(2u, ja["rows"].size());
  const Json& r = ja["rows"][1];  // omega_L1 = 1.45: unstable, re-stabilizes, unstable again
  EXPECT_EQ(1.45, r["value"].get<double>());
  ASSERT_GE(r["intervals"].size(), 2u) << r;
  EXPECT_TRUE(r["intervals"][0][1].is_number());
  EXPECT_EQ(r["mu_c"], r["intervals"][0][0]);
  EXPECT_EQ("lag", r["mode"]);
  EXPECT_FALSE(r["hover_unstable"].get<bool>());
  EXPECT_EQ("omega-lag", ja["vary"]);
}

TEST(CliMap, IdenticalBytesForOneAndTwoThreads) {
  const std::vector<std::string> base = {
      "map", "--x", "mu=0:1:0.1", "--y", "omega-lag=0.8,1.2,1.6", "--json"};
  std::vector<std::string> one = base, two = base;
  one.insert(one.end(), {"--threads", "1"});
  two.insert(two.end(), {"--threads", "2"});
  const Outcome a = run(one), b = run(two);
  ASSERT_EQ(0, a.exit_code) << a.err;
  Json ja = Json::parse(a.out), jb = Json::parse(b.out);
  ja.erase("case");
  jb.erase("case");
  EXPECT_EQ(ja.dump(), jb.dump());
  ASSERT_EQ(3u, ja["max_zeta"].size());
  EXPECT_EQ(11u, ja["max_zeta"][0].size());
  EXPECT_EQ("mu", ja["x"]["name"]);
}

TEST(CliRun, CaseFileAndJsonRoundTripReproduceTheBytes) {
  TempDir d;
  const std::string toml = d.file("case.toml");
  std::ofstream(toml) << "# Fig 12, three points\ncommand = \"study\"\n[parameters]\n"
                         "modes = \"exact\"\n[study]\nvary = \"damping-lag=0,0.01\"\n"
                         "[output]\njson = true\n";
  const Outcome first = run({"run", toml});
  ASSERT_EQ(0, first.exit_code) << first.err;
  const std::string json = d.file("first.json");
  std::ofstream(json) << first.out;
  const Outcome second = run({"run", json});
  ASSERT_EQ(0, second.exit_code) << second.err;
  EXPECT_EQ(first.out, second.out);
  // The same study typed on the command line gives the same result.
  const Outcome typed =
      run({"--modes", "exact", "study", "--vary", "damping-lag=0,0.01", "--json"});
  EXPECT_EQ(first.out, typed.out);
  // Command-line options after the file override it.
  const Outcome over = run({"run", toml, "--mu-max", "1.0"});
  ASSERT_EQ(0, over.exit_code) << over.err;
  const Json j = Json::parse(over.out);
  EXPECT_EQ(1.0, j["mu_max"].get<double>());
  EXPECT_TRUE(j["rows"][1]["mu_c"].is_null());  // eta_SL = 0.01: mu_c = 1.317 > 1
}

struct BadCase {
  const char* name;
  const char* text;
  const char* expected;  // regex of the whole stderr line after "flaplag: error: "
};

class CliBadCase : public ::testing::TestWithParam<BadCase> {};

TEST_P(CliBadCase, NamesFileLineKeyAndValue) {
  TempDir d;
  const std::string file = d.file("bad.toml");
  std::ofstream(file) << GetParam().text;
  const std::string out = d.file("out.json");
  const Outcome r = run({"run", file, "-o", out});
  EXPECT_EQ(2, r.exit_code);
  EXPECT_TRUE(r.out.empty());
  const std::regex line("flaplag: error: " +
                        std::regex_replace(GetParam().expected, std::regex("FILE"), file) + "\n");
  EXPECT_TRUE(std::regex_match(r.err, line)) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

INSTANTIATE_TEST_SUITE_P(
    Table, CliBadCase,
    ::testing::Values(
        BadCase{"UnknownKey", "thetaa = 0.1\n", "FILE:1: thetaa = 0.1: unknown key.*"},
        BadCase{"NotANumber", "\n\ntheta = \"abc\"\n", "FILE:3: theta = abc: not a number"},
        BadCase{"OutOfRange", "gamma = -1.0\n", "FILE:1: gamma = -1: must be in .*"},
        BadCase{"WrongType", "modes = [1, 2]\n", "FILE:1: modes = \\[array\\]: must be .*"},
        BadCase{"UnknownTable", "[bogus]\ntheta = 0.1\n", "FILE:1: bogus = \\[table\\]: .*"},
        BadCase{"FlagWithValue", "json = \"yes\"\n", "FILE:1: json = yes: must be true or false"},
        BadCase{"UnknownCommand", "command = \"fly\"\n", "FILE:1: command = fly: not a subcommand"},
        BadCase{"Malformed", "theta = = 1\n", "FILE:1 = \\(TOML\\): .*"},
        BadCase{"BasisOutOfRange", "basis = 13\n", "FILE:1: basis = 13: must be in 1\\.\\.12"},
        BadCase{"BasisNotWhole", "basis = 2.5\n", "FILE:1: basis = 2.5: not a whole number"},
        BadCase{"BasisBelowModes",
                "command = \"critical\"\nmodes = \"exact\"\nflap-modes = 2\nbasis = 1\n",
                "FILE:4: basis = 1: model 'paper-2x1' has 2 flap x 1 lag modes; .*"}),
    [](const auto& tp) { return std::string(tp.param.name); });

// Issue 9 item 3: --basis reaches the analysis from a case file, appears in the JSON
// parameters and round-trips; with it Fig 15's left end (exact modes, omega_L1 = 0.2), refused
// with the default five functions, has a resolved answer.
TEST(CliRun, BasisFromACaseFileReachesTheExactModes) {
  TempDir d;
  const std::string toml = d.file("fig15-left.toml");
  std::ofstream(toml) << "command = \"critical\"\n[parameters]\nmodes = \"exact\"\n"
                         "omega-lag = 0.2\nbasis = 12\n[critical]\nmu-max = 1.5\n"
                         "[output]\njson = true\n";
  const Outcome first = run({"run", toml});
  ASSERT_EQ(0, first.exit_code) << first.err;
  const Json j = Json::parse(first.out);
  EXPECT_EQ(12, j["parameters"]["basis"].get<int>());
  EXPECT_EQ("ok", j["status"]) << j["message"];
  EXPECT_TRUE(j["mu_c"].is_number());
  EXPECT_TRUE(j["mu_c_error"].is_number());
  const std::string json = d.file("first.json");
  std::ofstream(json) << first.out;
  const Outcome again = run({"run", json});
  EXPECT_EQ(first.out, again.out);
  // The default basis refuses the frequency, and the message says what to change.
  const Outcome five = run({"run", toml, "--basis", "5"});
  EXPECT_EQ(2, five.exit_code);
  EXPECT_NE(std::string::npos, five.err.find(":4: omega-lag = 0.2: ")) << five.err;
  EXPECT_NE(std::string::npos, five.err.find("a larger --basis lowers the limit")) << five.err;
  // A smaller basis changes the answer (the modes are rebuilt from it).
  const Outcome ten = run({"run", toml, "--basis", "10"});
  ASSERT_EQ(0, ten.exit_code) << ten.err;
  const Json k = Json::parse(ten.out);
  EXPECT_EQ(10, k["parameters"]["basis"].get<int>());
  EXPECT_NE(j["mu_c"].get<double>(), k["mu_c"].get<double>());
}

TEST(CliRun, MissingOrUnreadableCaseFile) {
  const Outcome a = run({"run"});
  EXPECT_EQ(2, a.exit_code);
  EXPECT_NE(std::string::npos, a.err.find("flaplag: error: argument = (missing): ")) << a.err;
  const Outcome b = run({"run", "/nonexistent/case.toml"});
  EXPECT_EQ(2, b.exit_code);
  EXPECT_NE(std::string::npos, b.err.find("argument = /nonexistent/case.toml: case file")) << b.err;
}

TEST(CliPlot, FilesAreWrittenAndAMissingRendererIsOneWarning) {
  TempDir d;
  const std::string svg = d.file("study.svg"), png = d.file("map.png");
  if (gnuplot_available()) {
    const Outcome s = run({"study", "--vary", "omega-lag=1.0,1.3", "--plot", svg});
    ASSERT_EQ(0, s.exit_code) << s.err;
    EXPECT_GT(std::filesystem::file_size(svg), 1000u);
    EXPECT_NE(std::string::npos, slurp(svg).find("<svg"));
    const Outcome m = run({"map", "--x", "mu=0:1:0.25", "--y", "omega-lag=1,1.3", "--plot", png});
    ASSERT_EQ(0, m.exit_code) << m.err;
    EXPECT_EQ("\x89PNG", slurp(png).substr(0, 4));
  }
  // No gnuplot on PATH: the data is written, the plot is not, one warning line.
  const std::string missing = d.file("missing.svg");
  const Outcome n = run({"study", "--vary", "omega-lag=1.0", "--plot", missing}, "/nonexistent");
  EXPECT_EQ(0, n.exit_code);
  EXPECT_NE(std::string::npos, n.out.find("mu_c"));
  EXPECT_TRUE(std::regex_match(n.err, std::regex("flaplag: warning: gnuplot is not installed.*\n")))
      << n.err;
  EXPECT_FALSE(std::filesystem::exists(missing));
  // A plot path that is not .svg or .png is bad input.
  const Outcome bad = run({"study", "--vary", "omega-lag=1.0", "--plot", d.file("x.pdf")});
  EXPECT_EQ(2, bad.exit_code);
}

TEST(CliResponse, PeriodicTipResponseAndSimulatedGrowth) {
  const Outcome r = run({"response", "--mu", "0.3", "--json"});
  ASSERT_EQ(0, r.exit_code) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ("ok", j["status"]);
  EXPECT_LT(j["closure"].get<double>(), 1e-10);
  EXPECT_EQ(72u, j["flap_tip"].size());
  EXPECT_GT(std::hypot(j["flap_harmonics"]["cos psi"].get<double>(),
                       j["flap_harmonics"]["sin psi"].get<double>()),
            1e-3);
  // The free response grows at the largest zeta (point at mu = 0.9, lag flutter).
  const Json p = Json::parse(run({"point", "--mu", "0.9", "--json"}).out);
  double zeta = -1e9;
  for (const Json& e : p["exponents"])
    if (e["zeta"].is_number()) zeta = std::max(zeta, e["zeta"].get<double>());
  const Json s = Json::parse(run({"simulate", "--mu", "0.9", "--revs", "80", "--json"}).out);
  ASSERT_TRUE(s["lag_growth_rate"].is_number()) << s;
  EXPECT_NEAR(zeta, s["lag_growth_rate"].get<double>(), 0.01 * std::abs(zeta));
  // No unique periodic response / bad input are statuses and errors, never NaN.
  const Outcome bad = run({"response", "--mu", "-1"});
  EXPECT_EQ(2, bad.exit_code);
  EXPECT_TRUE(std::regex_match(bad.err, std::regex("flaplag: error: --mu = -1: .*\n"))) << bad.err;
}

}  // namespace
