// The study-level commands of the CLI, run as a user would: study, map, run (case files and
// JSON round trips), --plot, response and simulate.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "process.h"

namespace cli_studies_test {

namespace {

using Json = nlohmann::json;

using flaplag::testing::Outcome;
using flaplag::testing::slurp;
using flaplag::testing::TempDir;

// `path_env` replaces PATH when not empty.
Outcome run(const std::vector<std::string>& args, const std::string& path_env = "") {
  return flaplag::testing::run_process(FLAPLAG_EXE, args, std::chrono::seconds(300), path_env);
}

// The same command with --threads 1 and with --threads 2.
std::pair<Outcome, Outcome> run_on_one_and_two_threads(const std::vector<std::string>& base) {
  std::vector<std::string> one = base, two = base;
  one.insert(one.end(), {"--threads", "1"});
  two.insert(two.end(), {"--threads", "2"});
  return {run(one), run(two)};
}

bool gnuplot_available() { return std::system("command -v gnuplot > /dev/null 2>&1") == 0; }

// The texts of an SVG picture of gnuplot, each <text> element's content without its tags (an
// enhanced-text subscript is a <tspan> of its own: "η<tspan ...>1</tspan>" reads "η1"), one a
// line.
std::string svg_texts(const std::string& svg) {
  std::string out;
  for (std::size_t at = svg.find("<text"); at != std::string::npos;
       at = svg.find("<text", at + 1)) {
    const std::size_t open = svg.find('>', at), close = svg.find("</text>", at);
    if (open == std::string::npos || close == std::string::npos) break;
    out += std::regex_replace(svg.substr(open + 1, close - open - 1), std::regex("<[^>]*>"), "") +
           "\n";
  }
  return out;
}

// A fake gnuplot first on PATH that keeps the script it is given and answers with an image:
// the script of a picture, whether or not gnuplot is installed.
class ScriptKeeper {
 public:
  ScriptKeeper() {
    const std::string exe = dir_.file("gnuplot");
    std::ofstream(exe) << "#!/bin/sh\ncat > '" << dir_.file("script.gp")
                       << "'\nprintf '<svg></svg>'\n";
    std::filesystem::permissions(exe, std::filesystem::perms::owner_all);
  }
  std::string path() const {
    const char* p = std::getenv("PATH");
    return dir_.path() + ":" + (p != nullptr ? p : "/usr/bin:/bin");
  }
  std::string script() const { return slurp(dir_.file("script.gp")); }

 private:
  TempDir dir_;
};

// The points of the curve (or markers) titled `title` in a gnuplot script: the rows of the data
// block it draws ("NaN": a gap).  Empty when no curve has that title or it draws no block.
// `occurrence`: the curve of that title in the order of the script (0: the first).
std::vector<std::pair<double, double>> curve_points(const std::string& script,
                                                    const std::string& title, int occurrence = 0) {
  std::vector<std::pair<double, double>> points;
  std::size_t at = script.find("title '" + title + "'");
  for (int k = 0; k < occurrence && at != std::string::npos; ++k)
    at = script.find("title '" + title + "'", at + 1);
  if (at == std::string::npos) return points;
  const std::size_t name = script.rfind("$d", at);
  if (name == std::string::npos || script.find(',', name) < at) return points;
  const std::string block = script.substr(name, script.find(' ', name) - name);
  std::istringstream in(script.substr(script.find(block + " << EOD\n") + block.size() + 8));
  std::string x, y;
  while (in >> x && x != "EOD" && in >> y) points.emplace_back(std::stod(x), std::stod(y));
  return points;
}

TEST(CliStudy, RowsWithIntervalsIdenticalForOneAndTwoThreads) {
  const std::vector<std::string> base = {
      "--modes", "exact", "study", "--vary", "omega-lag=1.3,1.45", "--mu-max", "1.5", "--json"};
  const auto [a, b] = run_on_one_and_two_threads(base);
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

// study --damping-criterion: each row's crossings are those of the sweep of that row's rotor
// over 0..mu-max in steps of --scan-step (the same continuation), and the text and picture show
// them; rows without the option keep their keys.
TEST(CliStudy, DampingCriterionCrossingsAreThoseOfTheRowsSweep) {
  const std::vector<std::string> fast = {"--method", "hsu"};
  std::vector<std::string> study = {
      "study",       "--vary", "theta=0.1,0.15",      "--mu-max", "1",
      "--scan-step", "0.05",   "--damping-criterion", "0.0005",   "--json"};
  study.insert(study.end(), fast.begin(), fast.end());
  const Outcome a = run(study);
  ASSERT_EQ(0, a.exit_code) << a.err;
  const Json j = Json::parse(a.out);
  EXPECT_EQ(j["damping_criterion"].get<double>(), 0.0005);
  ASSERT_EQ(j["rows"].size(), 2u);
  for (const Json& row : j["rows"]) {
    std::vector<std::string> sweep = {
        "sweep",  "--mu",  "0:1:0.05", "--theta", row["value"].dump(), "--damping-criterion",
        "0.0005", "--json"};
    sweep.insert(sweep.end(), fast.begin(), fast.end());
    const Outcome s = run(sweep);
    ASSERT_EQ(0, s.exit_code) << s.err;
    const Json sj = Json::parse(s.out);
    EXPECT_EQ(row["damping_crossings"], sj["damping_crossings"]) << row;
    ASSERT_EQ(row["damping_crossings"].size(), 2u) << row;
  }
  // The text table has the column; without the option no row has the key.
  std::vector<std::string> text = study;
  text.erase(std::find(text.begin(), text.end(), "--json"));
  const Outcome t = run(text);
  ASSERT_EQ(0, t.exit_code) << t.err;
  EXPECT_NE(t.out.find("damping < 0.05 % from mu"), std::string::npos) << t.out;
  std::vector<std::string> plain = {"study", "--vary", "theta=0.1", "--mu-max", "0.5", "--json"};
  plain.insert(plain.end(), fast.begin(), fast.end());
  const Outcome n = run(plain);
  ASSERT_EQ(0, n.exit_code) << n.err;
  const Json nj = Json::parse(n.out);
  EXPECT_FALSE(nj.contains("damping_criterion"));
  EXPECT_FALSE(nj["rows"][0].contains("damping_crossings"));
}

TEST(CliMap, IdenticalBytesForOneAndTwoThreads) {
  const std::vector<std::string> base = {
      "map", "--x", "mu=0:1:0.1", "--y", "omega-lag=0.8,1.2,1.6", "--json"};
  const auto [a, b] = run_on_one_and_two_threads(base);
  ASSERT_EQ(0, a.exit_code) << a.err;
  Json ja = Json::parse(a.out), jb = Json::parse(b.out);
  ja.erase("case");
  jb.erase("case");
  EXPECT_EQ(ja.dump(), jb.dump());
  ASSERT_EQ(3u, ja["max_zeta"].size());
  EXPECT_EQ(11u, ja["max_zeta"][0].size());
  EXPECT_EQ("mu", ja["x"]["name"]);
}

// A sweep in stretches (Analysis::sweep) on one and two threads: the same rows, bit for bit.
TEST(CliSweep, IdenticalRowsForOneAndTwoThreads) {
  const std::vector<std::string> base = {"sweep", "--mu", "0:1.2:0.01", "--json"};
  const auto [a, b] = run_on_one_and_two_threads(base);
  ASSERT_EQ(0, a.exit_code) << a.err;
  ASSERT_EQ(0, b.exit_code) << b.err;
  Json ja = Json::parse(a.out), jb = Json::parse(b.out);
  EXPECT_EQ("1", ja["case"]["threads"]);  // the case records what was given
  ja.erase("case");
  jb.erase("case");
  EXPECT_EQ(ja.dump(), jb.dump());
  EXPECT_EQ(121u, ja["rows"].size());
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

// study --trim (issue 12 item 3): each row with mu_c carries the trim at mu_c under the names
// of `flaplag trim` (that trim, bit for bit), a row without mu_c a null trim; the text table
// adds theta0, theta1c, theta1s, lambda; `flaplag run` of the JSON reproduces it, and so does
// flaplag merge of its --shard parts.
TEST(CliStudy, TrimmedRowsCarryTheTrimAtMuC) {
  // The typical C_T: at omega_L1 = 0.5 a periodic lag instability near mu = 1.02, none at 0.45.
  // (The study is computed three times below: a coarse scan, two steps to just past mu_c, keeps
  // it cheap; each trim is a full one at its mu either way.)
  const std::vector<std::string> base = {
      "study",  "--vary", "omega-lag=0.45,0.5",   "--mu-max", "1.05", "--scan-step", "0.525",
      "--trim", "thrust", "--thrust-coefficient", "0.0042384"};
  std::vector<std::string> args = base;
  args.push_back("--json");
  const Outcome s = run(args);
  ASSERT_EQ(0, s.exit_code) << s.err;
  const Json j = Json::parse(s.out);
  ASSERT_EQ(2u, j["rows"].size());
  EXPECT_TRUE(j["rows"][0]["mu_c"].is_null());
  EXPECT_TRUE(j["rows"][0]["trim"].is_null());
  const Json& row = j["rows"][1];
  ASSERT_TRUE(row["mu_c"].is_number()) << row;
  const Json& t = row["trim"];
  ASSERT_TRUE(t.is_object()) << row;
  EXPECT_EQ(row["mu_c"], t["mu"]);
  EXPECT_EQ("thrust", t["kind"]);
  EXPECT_TRUE(t["converged"].get<bool>());
  EXPECT_LE(std::abs(t["thrust_coefficient"].get<double>() - 0.0042384), 1e-10 * 0.0042384);
  // The same trim as `flaplag trim` of that rotor at that mu, and the same keys.
  TempDir d;
  const Outcome one = run({"--omega-lag", "0.5", "trim", "--mu", t["mu"].dump(),
                           "--thrust-coefficient", "0.0042384", "--json"});
  ASSERT_EQ(0, one.exit_code) << one.err;
  const Json o = Json::parse(one.out);
  for (const auto& [key, value] : t.items()) EXPECT_EQ(o[key], value) << key;
  // The text table: the controls at mu_c ("-" without mu_c: a cheap row).
  const Outcome text = run({"study", "--vary", "omega-lag=0.45", "--mu-max", "0.3", "--scan-step",
                            "0.1", "--trim", "thrust", "--thrust-coefficient", "0.0042384"});
  ASSERT_EQ(0, text.exit_code) << text.err;
  EXPECT_TRUE(std::regex_search(text.out, std::regex("theta0 +theta1c +theta1s +lambda +status\n")))
      << text.out;
  EXPECT_TRUE(std::regex_search(text.out, std::regex("\n +0\\.45 .* - +- +- +- +ok\n")))
      << text.out;
  // Sharded and merged: the same file.
  std::vector<std::string> merge = {"merge"};
  for (const char* part : {"2/2", "1/2"}) {
    std::vector<std::string> a = args;
    const std::string f = d.file(std::string("part") + part[0] + ".json");
    a.insert(a.end(), {"--shard", part, "-o", f});
    ASSERT_EQ(0, run(a).exit_code) << part;
    merge.push_back(f);
  }
  const Outcome merged = run(merge);
  ASSERT_EQ(0, merged.exit_code) << merged.err;
  EXPECT_EQ(s.out, merged.out);
  // The JSON as a case reproduces itself; an untrimmed study has no trim at all.
  const std::string file = d.file("study.json");
  std::ofstream(file) << s.out;
  const Outcome again = run({"run", file});
  ASSERT_EQ(0, again.exit_code) << again.err;
  EXPECT_EQ(s.out, again.out);
  const Outcome plain = run({"study", "--vary", "omega-lag=1.0", "--mu-max", "0.2", "--json"});
  ASSERT_EQ(0, plain.exit_code) << plain.err;
  EXPECT_FALSE(Json::parse(plain.out)["rows"][0].contains("trim"));
  EXPECT_EQ(std::string::npos,
            run({"study", "--vary", "omega-lag=1.0", "--mu-max", "0.2"}).out.find("theta0"));
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
        BadCase{"BasisOutOfRange", "basis = 13\n",
                "FILE:1: basis = 13: must be converged, paper, elements or 1\\.\\.12"},
        BadCase{"BasisNotWhole", "basis = 2.5\n", "FILE:1: basis = 2.5: not a whole number"},
        BadCase{"BasisBelowModes",
                "command = \"critical\"\nmodes = \"exact\"\nflap-modes = 2\nbasis = 1\n",
                "FILE:4: basis = 1: model 'paper-2x1' has 2 flap x 1 lag modes; .*"}),
    [](const auto& tp) { return std::string(tp.param.name); });

// --basis reaches the analysis from a case file, appears in the JSON parameters and
// round-trips; with it Fig 15's left end (exact modes, omega_L1 = 0.2), refused with the paper's
// five functions, has an answer resolved in the Floquet analysis, whose basis error (12 against
// 11 functions, above 10 tolerances here) is in mu_c_error and makes it a warning that says so.
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
  EXPECT_EQ(12, j["basis"].get<int>());
  EXPECT_EQ("warning", j["status"]) << j["message"];
  const std::string message = j["message"].get<std::string>();
  EXPECT_NE(std::string::npos, message.find("not resolved in their basis")) << message;
  EXPECT_EQ(std::string::npos, message.find("not resolved to")) << message;
  EXPECT_TRUE(j["mu_c"].is_number());
  ASSERT_TRUE(j["mu_c_error"].is_number());
  ASSERT_TRUE(j["basis_error"].is_number());
  EXPECT_GE(j["mu_c_error"].get<double>(), j["basis_error"].get<double>());
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

// A study's rows with exact modes carry the basis's part of their mu_c_error, equal to the
// change of mu_c with the neighbouring basis (a critical run of each basis here); the assumed
// mode's rows have no such key.
TEST(CliRun, StudyRowsCarryTheBasisError) {
  const Json s = Json::parse(
      run({"study", "--vary", "theta=0.15", "--modes", "exact", "--basis", "paper", "--json"}).out);
  ASSERT_EQ(1u, s["rows"].size()) << s;
  const Json& row = s["rows"][0];
  ASSERT_TRUE(row["mu_c"].is_number()) << row;
  ASSERT_TRUE(row["basis_error"].is_number()) << row;
  EXPECT_GE(row["mu_c_error"].get<double>(), row["basis_error"].get<double>()) << row;
  double mu_c[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const Json c = Json::parse(run({"critical", "--modes", "exact", "--basis", k == 0 ? "5" : "6",
                                    "--theta", "0.15", "--json"})
                                   .out);
    ASSERT_TRUE(c["mu_c"].is_number()) << c;
    mu_c[k] = c["mu_c"].get<double>();
  }
  EXPECT_EQ(row["mu_c"].get<double>(), mu_c[0]);
  EXPECT_NEAR(row["basis_error"].get<double>(), std::abs(mu_c[1] - mu_c[0]), 1e-12);
  EXPECT_GT(row["basis_error"].get<double>(), 10 * 1e-5);  // the paper's 5 against 6
  EXPECT_EQ(row["status"], "warning") << row;
  const Json a = Json::parse(run({"study", "--vary", "theta=0.15", "--json"}).out);
  EXPECT_FALSE(a["rows"][0].contains("basis_error")) << a;
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

// ---- --shard and merge (issue 9 item 4) --------------------------------------------------------

struct ShardCase {
  const char* name;
  std::vector<std::string> args;  // a --json command line
  int parts;
  std::vector<std::size_t> sizes;  // the expected number of lines of each part
};

class CliShard : public ::testing::TestWithParam<ShardCase> {};

// The parts of a job merged (given in reverse order) are byte for byte the file one run writes.
TEST_P(CliShard, MergedPartsEqualOneRunByteForByte) {
  const ShardCase& c = GetParam();
  TempDir d;
  std::vector<std::string> files;
  for (int i = c.parts; i >= 1; --i) {
    std::vector<std::string> a = c.args;
    const std::string file = d.file("part" + std::to_string(i) + ".json");
    a.insert(a.end(), {"--shard", std::to_string(i) + "/" + std::to_string(c.parts), "-o", file});
    const Outcome r = run(a);
    ASSERT_EQ(0, r.exit_code) << r.err;
    const Json j = Json::parse(slurp(file));
    EXPECT_EQ(i, j["shard"]["index"].get<int>());
    const std::string axis = j["shard"]["axis"];
    const std::size_t lines =
        axis == "vary" ? j["rows"].size() : j[axis]["values"].get<std::vector<double>>().size();
    EXPECT_EQ(c.sizes[static_cast<std::size_t>(i - 1)], lines) << "part " << i;
    files.push_back(file);
  }
  const Outcome whole = run(c.args);
  ASSERT_EQ(0, whole.exit_code) << whole.err;
  std::vector<std::string> merge = {"merge"};
  merge.insert(merge.end(), files.begin(), files.end());
  const std::string out = d.file("merged.json");
  merge.insert(merge.end(), {"-o", out});
  const Outcome m = run(merge);
  ASSERT_EQ(0, m.exit_code) << m.err;
  EXPECT_TRUE(m.err.empty()) << m.err;
  EXPECT_EQ(whole.out, slurp(out));
}

const std::vector<std::string> kMapRows = {
    "map", "--x", "mu=0:1:0.25", "--y", "omega-lag=0.8,1.2,1.6,2.0", "--json"};
// y = mu: the lines are the columns (each a continuation in mu, never split).
const std::vector<std::string> kMapColumns = {
    "map", "--y", "mu=0:0.8:0.2", "--x", "omega-lag=0.8,1.2,1.6,2.0", "--json"};
// Failed lines (omega_L1 <= 0 is refused per row): the status and message of the whole map are
// those of its first failed line.
const std::vector<std::string> kMapFailedRows = {
    "map", "--x", "mu=0:1:0.5", "--y", "omega-lag=0.8,-2,1.6,-1", "--json"};
const std::vector<std::string> kMapFailedColumns = {
    "map", "--y", "mu=0:1:0.5", "--x", "omega-lag=0.8,1.2,-2,-1", "--json"};
const std::vector<std::string> kStudy = {"study",    "--vary", "omega-lag=1.0,1.3,1.45",
                                         "--mu-max", "1.2",    "--json"};

INSTANTIATE_TEST_SUITE_P(
    Jobs, CliShard,
    ::testing::Values(ShardCase{"MapRowsUneven", kMapRows, 3, {1, 1, 2}},
                      ShardCase{"MapRowsMorePartsThanRows", kMapRows, 6, {0, 1, 1, 0, 1, 1}},
                      ShardCase{"MapColumns", kMapColumns, 3, {1, 1, 2}},
                      ShardCase{"MapFailedRows", kMapFailedRows, 3, {1, 1, 2}},
                      ShardCase{"MapFailedColumns", kMapFailedColumns, 4, {1, 1, 1, 1}},
                      ShardCase{"StudyMorePartsThanValues", kStudy, 5, {0, 1, 0, 1, 1}},
                      ShardCase{"OnePart", kStudy, 1, {3}}),
    [](const auto& tp) { return std::string(tp.param.name); });

TEST(CliMerge, RefusesPartsThatDoNotMakeOneRun) {
  TempDir d;
  auto part = [&](const std::string& name, int i, int n, std::vector<std::string> args) {
    args.insert(args.end(),
                {"--shard", std::to_string(i) + "/" + std::to_string(n), "-o", d.file(name)});
    const Outcome r = run(args);
    EXPECT_EQ(0, r.exit_code) << r.err;
    return d.file(name);
  };
  const std::string a1 = part("a1.json", 1, 2, kMapRows), a2 = part("a2.json", 2, 2, kMapRows);
  std::vector<std::string> theta = kMapRows;
  theta.insert(theta.end(), {"--theta", "0.1"});
  const std::string b2 = part("b2.json", 2, 2, theta);
  const std::string c2 = part("c2.json", 2, 3, kMapRows);
  const std::string s2 = part("s2.json", 2, 2, kStudy);
  const std::string whole = d.file("whole.json"), text = d.file("text.txt");
  ASSERT_EQ(
      0, run({"map", "--x", "mu=0:1:0.5", "--y", "omega-lag=1", "--json", "-o", whole}).exit_code);
  std::ofstream(text) << "mu zeta\n0 -0.1\n";
  Json cancelled = Json::parse(slurp(a2));
  cancelled["status"] = "cancelled";
  const std::string x2 = d.file("x2.json");
  std::ofstream(x2) << cancelled.dump(2) << "\n";
  struct Refusal {
    std::vector<std::string> parts;
    std::string line;  // regex after "flaplag: error: "
  };
  const std::vector<Refusal> refusals = {
      {{a1}, "argument = \\(missing\\): part 2/2 missing \\(given: " + a1 + " = 1/2\\)"},
      {{a1, a2, a2}, "argument = " + a2 + ": part 2/2 again \\(also " + a2 + "\\)"},
      {{a1, b2},
       "argument = " + b2 + ": not a part of the same case as " + a1 +
           " \\(parameters.theta differs\\)"},
      {{a1, c2}, "argument = " + c2 + ": part 2/3, but " + a1 + " is a part of 2"},
      {{a1, s2}, "argument = " + s2 + ": .*study.*"},
      {{whole}, "argument = " + whole + ": a whole flaplag map result .*"},
      {{text}, "argument = " + text + ": not JSON .*"},
      {{a1, x2}, "argument = " + x2 + ": an interrupted part .*"},
      {{d.file("none.json")}, "argument = " + d.file("none.json") + ": cannot be read"},
  };
  for (const Refusal& f : refusals) {
    std::vector<std::string> args = {"merge"};
    args.insert(args.end(), f.parts.begin(), f.parts.end());
    const std::string out = d.file("out.json");
    args.insert(args.end(), {"-o", out});
    const Outcome r = run(args);
    EXPECT_EQ(2, r.exit_code) << f.line;
    EXPECT_TRUE(std::regex_match(r.err, std::regex("flaplag: error: " + f.line + "\n")))
        << r.err << "expected: " << f.line;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
  // A part must be JSON: --shard without --json is refused before anything runs.
  std::vector<std::string> no_json(kMapRows.begin(), kMapRows.end() - 1);
  no_json.insert(no_json.end(), {"--shard", "1/2"});
  const Outcome r = run(no_json);
  EXPECT_EQ(2, r.exit_code);
  EXPECT_TRUE(
      std::regex_match(r.err, std::regex("flaplag: error: --shard = 1/2: needs --json.*\n")))
      << r.err;
  for (const char* bad : {"0/2", "3/2", "1/0", "2", "a/b", "1/2/3", ""}) {
    std::vector<std::string> a = kMapRows;
    a.insert(a.end(), {"--shard", bad});
    EXPECT_EQ(2, run(a).exit_code) << bad;
  }
}

// ---- Ctrl-C (issue 9 item 4) -------------------------------------------------------------------

// SIGINT during a long map: exit 130, one stderr line, and a valid file holding the rows
// finished, which are the first rows of the full map.
TEST(CliInterrupt, SigintLeavesAParseablePrefixOfTheMap) {
  TempDir d;
  const std::string out = d.file("partial.json");
  // 4001 rows: about 25 s of work on one core, interrupted after one second.
  const std::vector<std::string> args = {
      "map",    "--x",       "mu=0:1:0.25", "--y", "omega-lag=0.5:2.5:0.0005",
      "--json", "--threads", "2",           "-o",  out};
  const Outcome r = flaplag::testing::run_process(FLAPLAG_EXE, args, std::chrono::seconds(300), "",
                                                  std::chrono::milliseconds(1000));
  ASSERT_EQ(130, r.exit_code) << r.err;
  EXPECT_TRUE(std::regex_match(
      r.err, std::regex("flaplag: interrupted: [0-9]+ of 4001 rows \\(omega-lag\\) finished.*\n")))
      << r.err;
  const Json j = Json::parse(slurp(out));  // throws (fails) if not parseable
  EXPECT_EQ("cancelled", j["status"]);
  EXPECT_NE(std::string::npos, j["message"].get<std::string>().find("interrupted"));
  const std::vector<double> y = j["y"]["values"];
  ASSERT_LT(y.size(), 4001u);
  ASSERT_EQ(y.size(), j["max_zeta"].size());
  ASSERT_EQ(y.size(), j["mode"].size());
  EXPECT_EQ(5u, j["x"]["values"].size());
  if (y.empty()) return;  // a very slow machine: nothing finished, still a valid file
  EXPECT_EQ(0.5, y.front());
  // The rows are those of the full map: the same map over (up to 20 of) the finished y values.
  std::string list;
  const std::size_t n = std::min<std::size_t>(y.size(), 20);
  for (std::size_t i = 0; i < n; ++i) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", y[i]);
    list += (i ? "," : "") + std::string(buf);
  }
  const Outcome full = run({"map", "--x", "mu=0:1:0.25", "--y", "omega-lag=" + list, "--json"});
  ASSERT_EQ(0, full.exit_code) << full.err;
  const Json f = Json::parse(full.out);
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(f["max_zeta"][i], j["max_zeta"][i]) << "row " << i;
    EXPECT_EQ(f["mode"][i], j["mode"][i]) << "row " << i;
    EXPECT_EQ(f["kind"][i], j["kind"][i]) << "row " << i;
  }
}

TEST(CliInterrupt, SigintDuringAStudyKeepsTheValuesFinished) {
  TempDir d;
  const std::string out = d.file("partial.json");
  const std::vector<std::string> args = {
      "study", "--vary", "omega-lag=0.5:2.5:0.001", "--json", "--threads", "2", "-o", out};
  const Outcome r = flaplag::testing::run_process(FLAPLAG_EXE, args, std::chrono::seconds(300), "",
                                                  std::chrono::milliseconds(1000));
  ASSERT_EQ(130, r.exit_code) << r.err;
  const Json j = Json::parse(slurp(out));
  EXPECT_EQ("cancelled", j["status"]);
  ASSERT_LT(j["rows"].size(), 2001u);
  for (std::size_t i = 0; i < j["rows"].size(); ++i)
    EXPECT_NEAR(0.5 + 0.001 * static_cast<double>(i), j["rows"][i]["value"].get<double>(), 1e-12);
}

// ---- the progress bar (issue 9 item 4) ----------------------------------------------------------

// On a terminal, a run longer than a second shows a bar on stderr, erased before anything else
// is written there; --quiet shows none; the output never holds any of it.  (A stderr that is
// not a terminal never gets a bar: every other test here sees an empty stderr.)
TEST(CliProgress, BarOnATerminalOnlyAndNeverInTheOutput) {
  const std::vector<std::string> map = {
      "map", "--x", "mu=0:1:0.25", "--y", "omega-lag=0.5:2.5:0.0005", "--json", "--threads", "2"};
  // Interrupted once the bar is on the terminal (at least 2 s in): the job is running and its
  // handler installed, however slowly a loaded or instrumented build starts.
  const Outcome bar =
      flaplag::testing::run_process_on_terminal(FLAPLAG_EXE, map, std::chrono::seconds(300),
                                                std::chrono::milliseconds(2000), "flaplag map [");
  ASSERT_EQ(130, bar.exit_code) << bar.err;
  EXPECT_TRUE(std::regex_search(
      bar.err, std::regex("\rflaplag map \\[#*\\.*\\] +[0-9]+%  [0-9]+/4001 rows  [0-9]+ s")))
      << bar.err;
  // Erased ("\r", erase to the end of the line) before the message line.
  EXPECT_NE(std::string::npos, bar.err.find("\r\033[Kflaplag: interrupted: ")) << bar.err;
  EXPECT_EQ(std::string::npos, bar.out.find('\r'));
  EXPECT_EQ("cancelled", Json::parse(bar.out)["status"]);
  std::vector<std::string> quiet = map;
  quiet.push_back("--quiet");
  // Nothing on the terminal to wait for: interrupted as late as the bar run was, plus a margin.
  const auto late = std::max(std::chrono::milliseconds(1500),
                             bar.interrupted_at + std::chrono::milliseconds(500));
  const Outcome q = flaplag::testing::run_process_on_terminal(FLAPLAG_EXE, quiet,
                                                              std::chrono::seconds(300), late);
  ASSERT_EQ(130, q.exit_code) << q.err;
  EXPECT_TRUE(std::regex_match(q.err, std::regex("flaplag: interrupted: [^\r\n]*\r?\n"))) << q.err;
}

// ---- flaplag plot DATA.json (issue 9 item 5) -------------------------------------------------

TEST(CliPlot, PlotOfTheDataIsThePictureOfPlotOption) {
  TempDir d;
  const std::string data = d.file("map.json"), first = d.file("first.svg"),
                    again = d.file("again.svg");
  const Outcome m = run({"map", "--x", "mu=0:1:0.25", "--y", "omega-lag=1,1.3", "--json", "-o",
                         data, "--plot", first});
  ASSERT_EQ(0, m.exit_code) << m.err;
  const Outcome sweep = run({"sweep", "--mu", "0:0.6:0.2", "--json", "-o", d.file("sweep.json")});
  ASSERT_EQ(0, sweep.exit_code);
  if (gnuplot_available()) {
    const Outcome p = run({"plot", data, "--plot", again});
    ASSERT_EQ(0, p.exit_code) << p.err;
    EXPECT_TRUE(p.out.empty() && p.err.empty()) << p.out << p.err;
    EXPECT_GT(std::filesystem::file_size(again), 1000u);
    EXPECT_EQ(slurp(first), slurp(again));  // the same script, so the same picture
    const std::string png = d.file("sweep.png");
    ASSERT_EQ(0, run({"plot", d.file("sweep.json"), "--plot", png}).exit_code);
    EXPECT_EQ("\x89PNG", slurp(png).substr(0, 4));
  }
  // No gnuplot: one line, exit 3, nothing written.
  const std::string missing = d.file("missing.svg");
  const Outcome n = run({"plot", data, "--plot", missing}, "/nonexistent");
  EXPECT_EQ(3, n.exit_code);
  EXPECT_TRUE(std::regex_match(n.err, std::regex("flaplag: error: gnuplot is not installed.*\n")))
      << n.err;
  EXPECT_FALSE(std::filesystem::exists(missing));
  // Bad data: one line naming the file, exit 2.
  const std::string text = d.file("notes.txt"), point = d.file("point.json");
  std::ofstream(text) << "not json\n";
  ASSERT_EQ(0, run({"point", "--mu", "0.3", "--json", "-o", point}).exit_code);
  const std::string damaged = d.file("damaged.json");
  Json broken = Json::parse(slurp(data));
  broken.erase("max_zeta");
  std::ofstream(damaged) << broken.dump();
  for (const auto& [file, reason] :
       std::vector<std::pair<std::string, std::string>>{{text, "not JSON.*"},
                                                        {point, "a flaplag point result has no.*"},
                                                        {damaged, "a damaged flaplag map result.*"},
                                                        {d.file("none.json"), "cannot be read"}}) {
    const Outcome b = run({"plot", file, "--plot", d.file("x.svg")});
    EXPECT_EQ(2, b.exit_code) << file;
    EXPECT_TRUE(std::regex_match(
        b.err, std::regex("flaplag: error: argument = " + file + ": " + reason + "\n")))
        << b.err;
    EXPECT_FALSE(std::filesystem::exists(d.file("x.svg")));
  }
  EXPECT_EQ(2, run({"plot", data}).exit_code);  // --plot is required
  EXPECT_EQ(2, run({"plot", "--plot", d.file("x.svg")}).exit_code);
}

// modes --plot: the flap and lag shapes and slopes of every mode, the same picture again from
// the --json output; a damaged modes file is refused naming it.
TEST(CliPlot, ModeShapes) {
  TempDir d;
  const std::string data = d.file("modes.json"), first = d.file("first.svg"),
                    again = d.file("again.svg");
  const Outcome m = run({"modes", "--flap-modes", "2", "--lag-modes", "3", "--points", "21",
                         "--json", "-o", data, "--plot", first});
  ASSERT_EQ(0, m.exit_code) << m.err;
  if (gnuplot_available()) {
    const std::string svg = slurp(first), texts = svg_texts(svg);
    for (const char* name : {"\nη1\n", "\nη2\n", "\nγ1\n", "\nγ3\n", "slopes", "1.28303"})
      EXPECT_NE(std::string::npos, texts.find(name)) << name << " in\n" << texts;
    EXPECT_EQ(std::string::npos, texts.find("\nη3\n"));
    ASSERT_EQ(0, run({"plot", data, "--plot", again}).exit_code);
    EXPECT_EQ(svg, slurp(again));
  }
  Json broken = Json::parse(slurp(data));
  broken["flap"]["modes"][0].erase("d1");
  const std::string damaged = d.file("damaged.json");
  std::ofstream(damaged) << broken.dump();
  const Outcome b = run({"plot", damaged, "--plot", d.file("x.svg")});
  EXPECT_EQ(2, b.exit_code);
  EXPECT_TRUE(std::regex_match(b.err, std::regex("flaplag: error: argument = " + damaged +
                                                 ": a damaged flaplag modes result.*\n")))
      << b.err;
  EXPECT_FALSE(std::filesystem::exists(d.file("x.svg")));
}

// ---- campbell --------------------------------------------------------------------------------

// The Campbell diagram from the command line, a case file and a received result: the speeds
// asked for, a crossing of the soft-in-plane lag mode with 1/rev below the nominal speed, the
// same picture again from the JSON, and bad input named as typed.
TEST(CliCampbell, TableJsonCaseFileAndPicture) {
  TempDir d;
  const std::string data = d.file("campbell.json"), first = d.file("first.svg"),
                    again = d.file("again.svg");
  const Outcome m = run({"campbell", "--omega-lag", "0.7", "--speed-max", "1.2", "--speeds", "13",
                         "--harmonics", "3", "--json", "-o", data, "--plot", first});
  ASSERT_EQ(0, m.exit_code) << m.err;
  const Json j = Json::parse(slurp(data));
  EXPECT_EQ(j["command"], "campbell");
  EXPECT_EQ(j["status"], "ok") << j["message"];
  ASSERT_EQ(j["points"].size(), 13u);
  EXPECT_EQ(j["points"][12]["speed"].get<double>(), 1.2);
  EXPECT_EQ(j["labels"], (Json{"flap", "lag"}));
  EXPECT_TRUE(j["points"][0]["modes"][0]["damping_ratio"].is_null());  // at rest
  bool lag_one_per_rev = false;
  for (const Json& x : j["crossings"]) {
    EXPECT_LE(x["harmonic"].get<int>(), 3);
    if (x["label"] == "lag" && x["harmonic"] == 1) {
      lag_one_per_rev = true;
      EXPECT_LT(x["speed"].get<double>(), 1.0);
    }
  }
  EXPECT_TRUE(lag_one_per_rev);
  // The table says the same, and a case file runs it.
  const Outcome text = run({"campbell", "--omega-lag", "0.7", "--speeds", "4"});
  ASSERT_EQ(0, text.exit_code) << text.err;
  EXPECT_NE(std::string::npos, text.out.find("Campbell diagram at mu = 0")) << text.out;
  EXPECT_NE(std::string::npos, text.out.find("note: Omega = 0")) << text.out;
  const std::string toml = d.file("campbell.toml");
  std::ofstream(toml) << "command = \"campbell\"\n[parameters]\nomega-lag = 0.7\n"
                         "[campbell]\nspeeds = 4\n";
  const Outcome c = run({"run", toml});
  ASSERT_EQ(0, c.exit_code) << c.err;
  EXPECT_EQ(text.out, c.out);
  if (gnuplot_available()) {
    ASSERT_EQ(0, run({"plot", data, "--plot", again}).exit_code);
    EXPECT_EQ(slurp(first), slurp(again));
  }
  // A received file cannot ask for a billion per-rev lines.
  Json big = j;
  big["harmonics"] = 1000000000;
  const std::string damaged = d.file("damaged.json");
  std::ofstream(damaged) << big.dump();
  const Outcome b = run({"plot", damaged, "--plot", d.file("x.svg")});
  EXPECT_EQ(2, b.exit_code);
  EXPECT_NE(std::string::npos, b.err.find("key harmonics = 1000000000: must be an integer 1..100"))
      << b.err;
  EXPECT_FALSE(std::filesystem::exists(d.file("x.svg")));
  for (const auto& [option, value, reason] :
       std::vector<std::tuple<std::string, std::string, std::string>>{
           {"--speeds", "1", "must be"},
           {"--speed-max", "0", "must be in (0, 10]"},
           {"--speed-max", "11", "must be in (0, 10]"},
           {"--harmonics", "101", "must be"},
           {"--mu", "-0.5", "must be"}}) {
    const Outcome e = run({"campbell", option, value, "-o", d.file("never.txt")});
    EXPECT_EQ(2, e.exit_code) << option << " " << value;
    const std::string line = "flaplag: error: " + option + " = " + value + ": " + reason;
    EXPECT_EQ(e.err.rfind(line, 0), 0u) << e.err;
    EXPECT_EQ(std::count(e.err.begin(), e.err.end(), '\n'), 1) << e.err;
    EXPECT_FALSE(std::filesystem::exists(d.file("never.txt")));
  }
}

// flaplag plot A.json B.json: several sweeps in one picture, each curve labelled by its file's
// case or by --label; --mode and --max-zeta select curves; one file is the single-file picture;
// mixing kinds is refused naming the file.
TEST(CliPlot, SweepsOverlaidInOnePicture) {
  TempDir d;
  const std::string a = d.file("a.json"), b = d.file("b.json"), one = d.file("one.svg");
  ASSERT_EQ(0, run({"sweep", "--mu", "0:0.4:0.2", "--json", "-o", a, "--plot", one}).exit_code);
  ASSERT_EQ(0,
            run({"sweep", "--mu", "0:0.4:0.2", "--trim", "thrust", "--json", "-o", b}).exit_code);
  const std::string study = d.file("study.json");
  ASSERT_EQ(0, run({"study", "--vary", "omega-lag=1.0", "--mu-max", "0.2", "--json", "-o", study})
                   .exit_code);
  if (gnuplot_available()) {
    // One file: byte for byte the picture of sweep --plot.
    const std::string again = d.file("again.svg");
    ASSERT_EQ(0, run({"plot", a, "--plot", again}).exit_code);
    EXPECT_EQ(slurp(one), slurp(again));
    // The curves' titles appear in gnuplot's SVG as text: count each.
    auto count = [](const std::string& svg, const std::string& title) {
      std::size_t n = 0;
      for (std::size_t at = svg.find(">" + title + "<"); at != std::string::npos;
           at = svg.find(">" + title + "<", at + 1))
        ++n;
      return n;
    };
    const std::string both = d.file("both.svg");
    const Outcome o = run({"plot", a, b, "--plot", both});
    ASSERT_EQ(0, o.exit_code) << o.err;
    const std::string svg = slurp(both);
    for (const char* title :
         {"paper: flap", "paper: lag", "paper, thrust trim: flap", "paper, thrust trim: lag"})
      EXPECT_GT(count(svg, title), 0u) << title;
    const std::string lag = d.file("lag.svg");
    ASSERT_EQ(0, run({"plot", a, b, "--mode", "lag", "--label", "fixed theta", "--label", "trimmed",
                      "--plot", lag})
                     .exit_code);
    const std::string l = slurp(lag);
    EXPECT_GT(count(l, "fixed theta: lag"), 0u);
    EXPECT_GT(count(l, "trimmed: lag"), 0u);
    EXPECT_EQ(0u, count(l, "fixed theta: flap") + count(l, "paper: lag"));
    const std::string largest = d.file("largest.svg");
    ASSERT_EQ(0, run({"plot", a, b, "--max-zeta", "--plot", largest}).exit_code);
    const std::string m = slurp(largest);
    EXPECT_GT(count(m, "paper"), 0u);
    EXPECT_GT(count(m, "paper, thrust trim"), 0u);
    EXPECT_EQ(0u, count(m, "frequency omega"));  // one zeta panel
  }
  // Refused, one line naming the file or option as typed, exit 2, nothing written.
  const std::string x = d.file("x.svg");
  for (const auto& [args, reason] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"plot", a, study, "--plot", x},
            "argument = " + study + ": a flaplag study result, not a sweep like " + a + ": .*"},
           {{"plot", study, study, "--plot", x}, "argument = " + study + ": a flaplag study .*"},
           {{"plot", a, b, "--label", "one", "--plot", x},
            "--label = one: 1 given for 2 data files.*"},
           {{"plot", a, b, "--mode", "pitch", "--plot", x}, "--mode = pitch: not a mode of .*"}}) {
    const Outcome r = run(args);
    EXPECT_EQ(2, r.exit_code) << reason;
    EXPECT_TRUE(std::regex_match(r.err, std::regex("flaplag: error: " + reason + "\n"))) << r.err;
    EXPECT_FALSE(std::filesystem::exists(x));
  }
}

// The pictures a reviewer reads: axis labels with the symbols and units of the parameter table,
// a title naming the model and the linearization, rows not ok marked in the key, a study row
// stable to mu_max drawn at mu_max, a locked frequency drawn modulo 1 with its own marker.  The
// A heavily damped flap mode (57 %) no longer flattens a lag mode near a 1 % criterion: the damping
// ratio's axis ends at four times the least damped mode's largest ratio (at least 2 % and the
// criterion), and the title says how high the mode that leaves the panel goes.
TEST(CliPlot, DampingRatioPanelZoomsToTheLightlyDampedModes) {
  TempDir d;
  ScriptKeeper keeper;
  const std::string example = std::string(FLAPLAG_SOURCE_DIR) + "/examples/damping-criterion.toml";
  const Outcome r = run({"run", example, "--json", "--plot", d.file("x.svg")}, keeper.path());
  ASSERT_EQ(0, r.exit_code) << r.err;
  const Json j = Json::parse(r.out);
  double lag = -INFINITY, flap = -INFINITY;
  for (const Json& row : j["rows"]) {
    lag = std::max(lag, 100.0 * row["lag"]["damping_ratio"].get<double>());
    flap = std::max(flap, 100.0 * row["flap"]["damping_ratio"].get<double>());
  }
  const double top = 4.0 * std::max({lag, 2.0, 100.0 * j["damping_criterion"].get<double>()});
  ASSERT_GT(flap, 2.0 * top);
  const std::string s = keeper.script();
  std::smatch m;
  ASSERT_TRUE(std::regex_search(s, m, std::regex("set yrange \\[([^:]+):([^\\]]+)\\]"))) << s;
  EXPECT_NEAR(top, std::stod(m[2]), 1e-9 * top);
  EXPECT_LT(std::stod(m[1]), 0.0);
  char reach[64];
  std::snprintf(reach, sizeof reach, "flap up to %.6g %%", flap);
  EXPECT_NE(std::string::npos, s.find("zoomed to the lightly damped modes (" + std::string(reach)))
      << s;
  // The exponent zeta keeps its autoscaled axis.
  ASSERT_EQ(0, run({"run", example, "--plot-quantity", "zeta", "-o", "/dev/null", "--plot",
                    d.file("z.svg")},
                   keeper.path())
                   .exit_code);
  EXPECT_EQ(std::string::npos, keeper.script().find("zoomed")) << keeper.script();
}

// scripts are read through a fake gnuplot (the picture of `flaplag plot` is the one of --plot).
TEST(CliPlot, SymbolsTitlesAndMarksOfThePictures) {
  TempDir d;
  ScriptKeeper keeper;
  const std::string sweep = d.file("sweep.json"), x = d.file("x.svg");
  // (The typical flap locks to 1 per rev at mu = 0.32: below it, no frequency is locked.)
  ASSERT_EQ(0, run({"sweep", "--mu", "0:0.28:0.07", "--json", "-o", sweep}).exit_code);
  ASSERT_EQ(0, run({"plot", sweep, "--plot", x}, keeper.path()).exit_code);
  std::string s = keeper.script();
  EXPECT_NE(std::string::npos,
            s.find("title 'paper model, linearized about hover: γ = 10, θ = 0.15"))
      << s;
  EXPECT_NE(std::string::npos, s.find("set xlabel 'advance ratio μ'")) << s;
  EXPECT_NE(std::string::npos, s.find("set ylabel 'damping ratio −ζ/|λ| [% of critical]'")) << s;
  EXPECT_EQ(std::string::npos, s.find("warning at")) << s;  // all rows ok: no such entry
  EXPECT_EQ(std::string::npos, s.find("locked")) << s;

  // Rows not ok, a locked frequency (the flap's -1 per rev of the exact modes, 3/2, ~0), a
  // trimmed case about the periodic equilibrium: edited into the result.
  Json j = Json::parse(slurp(sweep));
  j["rows"][1]["status"] = "warning";
  j["rows"][3]["status"] = "failed";
  j["rows"][3]["flap"] = nullptr;
  j["rows"][3]["lag"] = nullptr;
  j["rows"][2]["flap"]["omega"] = -1.0002;
  j["rows"][4]["flap"]["omega"] = 1.5004;
  j["rows"][0]["lag"]["omega"] = 0.0003;
  j["case"]["trim"] = "moment";
  j["parameters"]["periodic-linearization"] = true;
  j["trim"] = Json::array({Json{{"target", 0.005}}});
  const std::string edited = d.file("edited.json");
  std::ofstream(edited) << j.dump();
  ASSERT_EQ(0, run({"plot", edited, "--plot", x}, keeper.path()).exit_code);
  s = keeper.script();
  EXPECT_NE(std::string::npos,
            s.find("title 'paper model, moment trim, linearized about the periodic equilibrium: "
                   "C_T = 0.005, γ = 10, ω̄_{F1} = 1.175"))
      << s;
  EXPECT_EQ(std::string::npos, s.find("θ = ")) << s;  // trimmed: the collective is not fixed
  const auto warning = curve_points(s, "warning at this μ (see the row message in the result)");
  ASSERT_EQ(2u, warning.size()) << s;  // on the flap and the lag curve
  for (const auto& [mu, y] : warning) {
    EXPECT_EQ(j["rows"][1]["mu"].get<double>(), mu);
    const double ratio =
        100.0 *
        (y > 10.0 ? j["rows"][1]["flap"] : j["rows"][1]["lag"])["damping_ratio"].get<double>();
    EXPECT_NEAR(ratio, y, 1e-9 * std::abs(ratio));
  }
  const auto failed = curve_points(s, "failed at this μ (no exponents; drawn at 0)");
  ASSERT_EQ(1u, failed.size()) << s;
  EXPECT_EQ(std::make_pair(j["rows"][3]["mu"].get<double>(), 0.0), failed[0]);
  // The locked frequencies: markers in [0, 1] (their key entry once), gaps in the lines.
  EXPECT_NE(std::string::npos,
            s.find("NaN with points pt 6 ps 0.8 lc rgb '#000000' title 'locked to 0, 1/2 or 1 "
                   "per rev (drawn as ω mod 1)'"))
      << s;
  std::vector<std::pair<double, double>> locked;
  std::istringstream lines(s);
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (std::regex_match(line, m, std::regex("([0-9.e-]+) ([0-9.e-]+)"))) {
      const double w = std::stod(m[2]);
      if (std::abs(w - 1.0002) < 1e-12 || std::abs(w - 0.5004) < 1e-12 ||
          std::abs(w - 0.0003) < 1e-12)
        locked.emplace_back(std::stod(m[1]), w);
    }
  }
  auto mu = [&](int row) { return j["rows"][row]["mu"].get<double>(); };
  // (the flap's markers first, then the lag's)
  EXPECT_EQ(
      (std::vector<std::pair<double, double>>{{mu(2), 1.0002}, {mu(4), 0.5004}, {mu(0), 0.0003}}),
      locked)
      << s;
  for (const char* raw : {"-1.0002", "1.5004"})
    EXPECT_EQ(std::string::npos, s.find(std::string(" ") + raw + "\n")) << raw << "\n" << s;
  // The frequency panel's lines (drawn in the colours of the flap and lag curves of the first
  // panel) have gaps there.
  auto colour_of = [&](const std::string& title) {
    const std::size_t at = s.find("title '" + title + "'");
    const std::size_t c = s.rfind("lc rgb '", at);
    return s.substr(c, s.find('\'', c + 8) - c + 1);
  };
  auto frequency_line = [&](const std::string& colour) {
    const std::size_t panel = s.find("set title 'frequency");
    const std::size_t at = s.find("with lines lw 1.5 " + colour, panel);
    const std::size_t name = s.rfind("$d", at);
    const std::string block = s.substr(name, s.find(' ', name) - name);
    std::vector<std::pair<double, double>> points;
    std::istringstream in(s.substr(s.find(block + " << EOD\n") + block.size() + 8));
    std::string a, b;
    while (in >> a && a != "EOD" && in >> b) points.emplace_back(std::stod(a), std::stod(b));
    return points;
  };
  const auto flap = frequency_line(colour_of("flap")), lag = frequency_line(colour_of("lag"));
  ASSERT_EQ(5u, flap.size()) << s;
  ASSERT_EQ(5u, lag.size()) << s;
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(i == 2 || i == 3 || i == 4, std::isnan(flap[i].second)) << i;
    EXPECT_EQ(i == 0 || i == 3, std::isnan(lag[i].second)) << i;
  }

  // A study: the axis of --vary omega-lag from the parameter table's symbol and units, a row
  // stable up to mu_max drawn there, a row with a warning ringed.
  const std::string study = d.file("study.json");
  ASSERT_EQ(0, run({"study", "--vary", "omega-lag=1,1.2", "--mu-max", "0.2", "--json", "-o", study,
                    "--plot", x},
                   keeper.path())
                   .exit_code);
  s = keeper.script();
  EXPECT_NE(std::string::npos, s.find("set xlabel 'first rotating lag frequency ω̄_{L1} [per rev]'"))
      << s;
  const std::string title =
      "title 'paper model, linearized about hover: γ = 10, θ = 0.15, ω̄_{F1} = 1.175'";
  EXPECT_NE(std::string::npos, s.find(title)) << s;  // the varied value is not in the title
  EXPECT_EQ((std::vector<std::pair<double, double>>{{1.0, 0.2}, {1.2, 0.2}}),
            curve_points(s, "stable up to μ_{max} = 0.2"))
      << s;
  Json st = Json::parse(slurp(study));
  st["rows"][1]["status"] = "warning";
  std::ofstream(edited) << st.dump();
  ASSERT_EQ(0, run({"plot", edited, "--plot", x}, keeper.path()).exit_code);
  EXPECT_EQ((std::vector<std::pair<double, double>>{{1.2, 0.2}}),
            curve_points(keeper.script(), "warning (see the row message in the result)"))
      << keeper.script();
}

// One label scheme for every model: "lag" is the first lag mode of the 1 x 1 and of the 3 x 3
// model, and selects both.  "lag1", the label of M x N results written before the one scheme,
// names the same mode: a 3 x 3 file with the old labels overlays the same way.
TEST(CliPlot, OverlayOfAOneByOneAndAThreeByThreeSweepWithOneModeName) {
  TempDir d;
  const std::string one = d.file("one.json"), three = d.file("three.json");
  ASSERT_EQ(0, run({"sweep", "--mu", "0:0.2:0.1", "--json", "-o", one}).exit_code);
  ASSERT_EQ(0, run({"sweep", "--modes", "exact", "--flap-modes", "3", "--lag-modes", "3", "--mu",
                    "0:0.2:0.1", "--json", "-o", three})
                   .exit_code);
  ASSERT_EQ(Json::parse(slurp(one))["labels"], (Json{"flap", "lag"}));
  std::vector<std::string> labels = Json::parse(slurp(three))["labels"];  // in hover order
  std::sort(labels.begin(), labels.end());
  ASSERT_EQ(labels, (std::vector<std::string>{"flap", "flap2", "flap3", "lag", "lag2", "lag3"}));
  // The same result as an older flaplag wrote it: flap1, lag1 for the first modes.
  const std::string old = d.file("old.json");
  {
    std::string text = slurp(three);
    for (const char* dir : {"flap", "lag"}) {
      const std::string from = std::string("\"") + dir + "\"", to = std::string("\"") + dir + "1\"";
      for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at))
        text.replace(at, from.size(), to);
    }
    std::ofstream(old) << text;
  }
  for (const std::string& file : {three, old}) {
    const std::string first = file == three ? "lag" : "lag1";
    for (const char* mode : {"lag", "lag1"}) {
      ScriptKeeper keeper;
      const Outcome o =
          run({"plot", one, file, "--mode", mode, "--plot", d.file("x.svg")}, keeper.path());
      ASSERT_EQ(0, o.exit_code) << mode << ": " << o.err;
      const std::string s = keeper.script();
      EXPECT_EQ(3u, curve_points(s, "paper: lag").size()) << s;  // mu = 0, 0.1, 0.2
      EXPECT_EQ(3u, curve_points(s, "paper-3x3: " + first).size()) << s;
      for (const char* other : {"paper: flap", "paper-3x3: lag2", "paper-3x3: flap"})
        EXPECT_EQ(std::string::npos, s.find(std::string("'") + other + "'")) << other;
    }
  }
  if (gnuplot_available()) {
    const std::string svg = d.file("both.svg");
    ASSERT_EQ(0, run({"plot", one, three, "--mode", "lag", "--plot", svg}).exit_code);
    const std::string texts = svg_texts(slurp(svg));
    EXPECT_NE(std::string::npos, texts.find("paper: lag\n")) << texts;
    EXPECT_NE(std::string::npos, texts.find("paper-3x3: lag\n")) << texts;
  }
}

// simulate --nonlinear: the nonlinear equations from the periodic equilibrium; the tip deviation
// from it decays at the largest zeta of `point --periodic-linearization` (within 1 %), and the
// JSON carries the totals and the reference.
TEST(CliSimulate, NonlinearDecaysAtTheZetaAboutThePeriodicEquilibrium) {
  const Json p =
      Json::parse(run({"point", "--mu", "0.3", "--periodic-linearization", "--json"}).out);
  double zeta = -1e9;
  for (const Json& e : p["exponents"])
    if (e["zeta"].is_number()) zeta = std::max(zeta, e["zeta"].get<double>());
  const Outcome r = run({"simulate", "--mu", "0.3", "--nonlinear", "--revs", "40", "--perturbation",
                         "0.001", "--samples", "180", "--json"});
  ASSERT_EQ(0, r.exit_code) << r.err;
  const Json s = Json::parse(r.out);
  EXPECT_EQ("ok", s["status"]);
  EXPECT_EQ(true, s["nonlinear"]);
  EXPECT_EQ("periodic equilibrium", s["reference"]);
  ASSERT_EQ(s["psi"].size(), s["flap_total"].size());
  EXPECT_DOUBLE_EQ(0.001, s["flap_tip"][0].get<double>());
  EXPECT_GT(std::abs(s["flap_total"][0].get<double>()), 0.01);  // the equilibrium included
  ASSERT_TRUE(s["lag_growth_rate"].is_number()) << s;
  EXPECT_NEAR(zeta, s["lag_growth_rate"].get<double>(), 0.01 * std::abs(zeta));
  // the linear simulation has no totals
  const Json lin = Json::parse(run({"simulate", "--mu", "0.3", "--revs", "1", "--json"}).out);
  EXPECT_EQ(false, lin["nonlinear"]);
  EXPECT_FALSE(lin.contains("flap_total"));
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

}  // namespace cli_studies_test
