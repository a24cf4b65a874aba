// The `flaplag` command run as a user runs it: bad input gives one line on stderr, exit code 2
// and no output file; good input gives complete, parseable output.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#ifndef FLAPLAG_EXE
#error "FLAPLAG_EXE must name the flaplag binary"
#endif

namespace {

using Json = nlohmann::json;

struct Outcome {
  int exit_code = -1;  // -1: did not exit normally (signal)
  std::string out, err;
};

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

bool exists(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0;
}

// A fresh directory per test, removed with its contents afterwards.
class TempDir {
 public:
  TempDir() {
    char tmpl[] = "/tmp/flaplag_cli_test.XXXXXX";
    const char* d = ::mkdtemp(tmpl);
    if (d == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = d;
  }
  ~TempDir() { std::system(("rm -rf '" + path_ + "'").c_str()); }
  const std::string& path() const { return path_; }
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  // Names in the directory (to see that no temporary files are left behind).
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    FILE* p = ::popen(("ls -A '" + path_ + "'").c_str(), "r");
    char line[4096];
    while (p != nullptr && std::fgets(line, sizeof line, p) != nullptr) {
      std::string s(line);
      if (!s.empty() && s.back() == '\n') s.pop_back();
      names.push_back(s);
    }
    if (p != nullptr) ::pclose(p);
    return names;
  }

 private:
  std::string path_;
};

// fork + exec with stdout/stderr captured in files: no shell, so arguments arrive verbatim
// (empty strings, '*', quotes).
Outcome run(const std::vector<std::string>& args) {
  TempDir io;
  const std::string out = io.file("stdout"), err = io.file("stderr");
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fo = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    const int fe = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (fo < 0 || fe < 0 || ::dup2(fo, 1) < 0 || ::dup2(fe, 2) < 0) ::_exit(127);
    std::vector<char*> argv;
    std::string exe = FLAPLAG_EXE;
    argv.push_back(exe.data());
    std::vector<std::string> copy = args;
    for (std::string& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(exe.c_str(), argv.data());
    ::_exit(127);
  }
  Outcome r;
  int status = 0;
  if (pid > 0 && ::waitpid(pid, &status, 0) == pid && WIFEXITED(status)) {
    r.exit_code = WEXITSTATUS(status);
  }
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

std::string joined(const std::vector<std::string>& args) {
  std::string s;
  for (const auto& a : args) s += (s.empty() ? "" : " ") + (a.empty() ? std::string("''") : a);
  return s;
}

// ---- bad input -------------------------------------------------------------------------------

struct BadInput {
  const char* name;
  std::vector<std::string> args;
  std::string option;  // must appear in the error line
  std::string value;   // must appear in the error line ("" when there is none to show)
};

std::ostream& operator<<(std::ostream& os, const BadInput& b) { return os << joined(b.args); }

class CliBadInput : public ::testing::TestWithParam<BadInput> {};

void expect_one_error_line(const Outcome& r, const BadInput& b) {
  EXPECT_EQ(r.exit_code, 2) << joined(b.args) << "\nstderr: " << r.err;
  EXPECT_EQ(r.out, "") << joined(b.args);
  ASSERT_FALSE(r.err.empty()) << joined(b.args);
  EXPECT_EQ(r.err.back(), '\n');
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("flaplag: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(b.option), std::string::npos) << "option " << b.option << " in " << r.err;
  if (!b.value.empty()) {
    EXPECT_NE(r.err.find(b.value), std::string::npos) << "value " << b.value << " in " << r.err;
  }
}

TEST_P(CliBadInput, OneLineExitTwoNoFileCreated) {
  const BadInput& b = GetParam();
  TempDir dir;
  const std::string target = dir.file("result.out");
  // -o first: after the case's arguments it could become the missing value of the last option.
  std::vector<std::string> args = {"-o", target};
  args.insert(args.end(), b.args.begin(), b.args.end());
  const Outcome r = run(args);
  expect_one_error_line(r, b);
  EXPECT_FALSE(exists(target));
  EXPECT_TRUE(dir.entries().empty()) << "left behind: " << dir.entries().front();
}

TEST_P(CliBadInput, ExistingFileNotTruncated) {
  const BadInput& b = GetParam();
  TempDir dir;
  const std::string target = dir.file("result.out");
  std::ofstream(target) << "previous result\n";
  // -o first: after the case's arguments it could become the missing value of the last option.
  std::vector<std::string> args = {"-o", target};
  args.insert(args.end(), b.args.begin(), b.args.end());
  const Outcome r = run(args);
  expect_one_error_line(r, b);
  EXPECT_EQ(slurp(target), "previous result\n");
  EXPECT_EQ(dir.entries().size(), 1u);
}

const std::vector<BadInput> kBadInputs = {
    {"UnknownOption", {"--bogus"}, "--bogus", ""},
    {"UnknownSubcommand", {"bogus"}, "bogus", ""},
    {"UnknownOptionOfSubcommand", {"point", "--mu", "0.1", "--frobnicate"}, "--frobnicate", ""},
    {"NonNumericTheta", {"--theta", "abc"}, "--theta", "abc"},
    {"TrailingJunk", {"--gamma", "10x"}, "--gamma", "10x"},
    {"EmptyNumber", {"--sigma", ""}, "--sigma", ""},
    {"NaNTheta", {"--theta", "nan"}, "--theta", "nan"},
    {"InfLock", {"--gamma", "inf"}, "--gamma", "inf"},
    {"MinusInfLag", {"--omega-lag=-inf"}, "--omega-lag", "-inf"},
    {"OverflowingNumber", {"--cdo", "1e999"}, "--cdo", "1e999"},
    {"NegativeMu", {"point", "--mu", "-0.1"}, "--mu", "-0.1"},
    {"NaNMu", {"point", "--mu", "nan"}, "--mu", "nan"},
    {"NonNumericMu", {"system", "--mu", "fast"}, "--mu", "fast"},
    {"MissingMu", {"point"}, "--mu", ""},
    {"ZeroLock", {"--gamma", "0"}, "--gamma", "0"},
    {"NegativeLock", {"point", "--mu", "0.1", "--gamma", "-5"}, "--gamma", "-5"},
    {"ZeroSolidity", {"--sigma", "0"}, "--sigma", "0"},
    {"NegativeSolidity", {"critical", "--sigma", "-0.05"}, "--sigma", "-0.05"},
    {"ZeroLiftSlope", {"--lift-slope", "0"}, "--lift-slope", "0"},
    {"NegativeCdo", {"--cdo", "-0.01"}, "--cdo", "-0.01"},
    {"ZeroFlapFrequency", {"--omega-flap", "0"}, "--omega-flap", "0"},
    {"NegativeLagFrequency",
     {"sweep", "--mu", "0:0.1:0.05", "--omega-lag", "-1.2"},
     "--omega-lag",
     "-1.2"},
    {"NegativeFlapDamping", {"--damping-flap", "-0.01"}, "--damping-flap", "-0.01"},
    {"NegativeLagDamping", {"point", "--mu", "0", "--damping-lag", "-1"}, "--damping-lag", "-1"},
    {"ThetaBeyondHalfPi", {"--theta", "2"}, "--theta", "2"},
    {"ZeroSteps", {"--steps", "0"}, "--steps", "0"},
    {"NegativeSteps", {"point", "--mu", "0.1", "--steps", "-4"}, "--steps", "-4"},
    {"FractionalSteps", {"--steps", "2.5"}, "--steps", "2.5"},
    {"ZeroTerms", {"--terms", "0"}, "--terms", "0"},
    {"ZeroFlapModes", {"--flap-modes", "0"}, "--flap-modes", "0"},
    {"ZeroLagModes", {"--lag-modes", "0"}, "--lag-modes", "0"},
    {"UncompiledModeCount", {"--flap-modes", "3", "--lag-modes", "7"}, "--flap-modes", "3"},
    {"UnknownMethod", {"--method", "euler"}, "--method", "euler"},
    {"UnknownModeKind", {"--modes", "fuzzy"}, "--modes", "fuzzy"},
    {"UnknownModel", {"--model", "no-such-model"}, "--model", "no-such-model"},
    {"EmptyModel", {"point", "--mu", "0.1", "--model", ""}, "--model", ""},
    {"ReversedSweep", {"sweep", "--mu", "1:0:0.1"}, "--mu", "1:0:0.1"},
    {"EmptySweep", {"sweep", "--mu", "0.5:0.5:0.1"}, "--mu", "0.5:0.5:0.1"},
    {"EmptySweepText", {"sweep", "--mu", ""}, "--mu", ""},
    {"ZeroSweepStep", {"sweep", "--mu", "0:1:0"}, "--mu", "0:1:0"},
    {"NegativeSweepStep", {"sweep", "--mu", "0:1:-0.1"}, "--mu", "0:1:-0.1"},
    {"NegativeSweepStart", {"sweep", "--mu", "-0.2:1:0.1"}, "--mu", "-0.2:1:0.1"},
    {"MalformedSweep", {"sweep", "--mu", "0:1"}, "--mu", "0:1"},
    {"NaNInSweep", {"sweep", "--mu", "0:nan:0.1"}, "--mu", "0:nan:0.1"},
    {"UnknownSweepFormat", {"sweep", "--mu", "0:1:0.5", "--format", "xml"}, "--format", "xml"},
    {"NonPositiveMuMax", {"critical", "--mu-max", "0"}, "--mu-max", "0"},
    {"InfinitePsi", {"system", "--mu", "0.2", "--psi", "inf"}, "--psi", "inf"},
    {"UnknownSpec", {"models", "--spec", "no-such-model"}, "--spec", "no-such-model"},
    {"TipLossesReversed", {"--tip-loss-a", "0.8", "--tip-loss-b", "0.7"}, "--tip-loss-a", "0.8"},
    {"LengthRatioAboveOne", {"--length-ratio", "1.5"}, "--length-ratio", "1.5"},
    {"MissingValue", {"--theta"}, "--theta", ""},
};

INSTANTIATE_TEST_SUITE_P(Table, CliBadInput, ::testing::ValuesIn(kBadInputs),
                         [](const ::testing::TestParamInfo<BadInput>& i) {
                           return std::string(i.param.name);
                         });

// Unwritable output paths: the path itself is the bad value (these run as root too).
TEST(CliOutput, UnwritablePathsAreBadInput) {
  TempDir dir;
  const std::string file = dir.file("plain");
  std::ofstream(file) << "x";
  for (const std::string& target :
       {dir.file("no/such/dir/out.json"), file + "/below-a-file.json", dir.path(), std::string()}) {
    const BadInput b{"", {"point", "--mu", "0.1", "-o", target}, "-o", target};
    expect_one_error_line(run(b.args), b);
  }
  EXPECT_EQ(slurp(file), "x");
  EXPECT_EQ(dir.entries().size(), 1u);
}

// ---- good input ------------------------------------------------------------------------------

const std::vector<std::string> kFast = {"--method", "hsu", "--steps", "20"};

std::vector<std::string> fast(std::vector<std::string> args) {
  args.insert(args.end(), kFast.begin(), kFast.end());
  return args;
}

Json parse_json(const Outcome& r) {
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  return Json::parse(r.out);  // throws (test fails) on malformed JSON
}

TEST(CliGood, BareCommandIsTheTypicalCase) {
  const Outcome r = run(fast({}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* s : {"model", "paper", "assumed", "hsu", "Hover", "lambda", "g0_1", "h0_1",
                        "mu_c", "Liouville", "flap zeta", "lag zeta"}) {
    EXPECT_NE(r.out.find(s), std::string::npos) << s;
  }
}

TEST(CliGood, BareCommandJson) {
  const Json j = parse_json(run(fast({"--json"})));
  EXPECT_EQ(j["model"]["name"], "paper");
  EXPECT_TRUE(j["hover"].contains("inflow"));
  EXPECT_TRUE(j["critical"].contains("mu_c"));
  EXPECT_EQ(j["table"]["rows"].size(), 11u);
  EXPECT_EQ(j["table"]["rows"][10]["mu"].get<double>(), 1.0);
}

TEST(CliGood, PointJsonHasExponentsMultipliersResidual) {
  const Json j = parse_json(run(fast({"point", "--mu", "0.2", "--json"})));
  ASSERT_TRUE(j["exponents"].is_array());
  EXPECT_EQ(j["exponents"].size(), 4u);
  for (const Json& e : j["exponents"]) {
    EXPECT_TRUE(e["zeta"].is_number());
    EXPECT_TRUE(e["omega"].is_number());
    EXPECT_TRUE(e["label"] == "flap" || e["label"] == "lag") << e;
  }
  EXPECT_EQ(j["multipliers"].size(), 4u);
  EXPECT_TRUE(j["liouville_residual"].is_number());
  EXPECT_EQ(j["mu"].get<double>(), 0.2);
  // Parameters round-trip at full precision.
  EXPECT_EQ(j["parameters"]["lift_slope"].get<double>(), 6.283185307179586);
  EXPECT_EQ(j["parameters"]["omega_lag"].get<double>(), 1.28303);
  EXPECT_EQ(j["method"]["name"], "hsu");
  EXPECT_EQ(j["method"]["steps"], 20);
}

TEST(CliGood, OptionsReachTheAnalysis) {
  const Json j =
      parse_json(run(fast({"point", "--mu", "0.1", "--json", "--gamma", "5.5", "--theta=0.1",
                           "--no-reversed-flow", "--omega-lag", "0.7", "--damping-lag", "0.01"})));
  EXPECT_EQ(j["parameters"]["lock"].get<double>(), 5.5);
  EXPECT_EQ(j["parameters"]["theta"].get<double>(), 0.1);
  EXPECT_EQ(j["parameters"]["reversed_flow"], false);
  EXPECT_EQ(j["parameters"]["omega_lag"].get<double>(), 0.7);
  EXPECT_EQ(j["parameters"]["damping_lag"].get<double>(), 0.01);
  // Shared options given before the subcommand count as well.
  const Json k = parse_json(run(fast({"--gamma", "7", "point", "--mu", "0.1", "--json"})));
  EXPECT_EQ(k["parameters"]["lock"].get<double>(), 7.0);
}

TEST(CliGood, SystemJson) {
  // psi = 4.7 is inside the reversed-flow sector centred at 3 pi / 2 (Appendix D).
  const Json j = parse_json(run({"system", "--mu", "0.5", "--psi", "4.7", "--json"}));
  ASSERT_EQ(j["A"].size(), 4u);
  for (const Json& row : j["A"]) EXPECT_EQ(row.size(), 4u);
  EXPECT_EQ(j["f"].size(), 4u);
  EXPECT_EQ(j["region"], "reversed");
  EXPECT_FALSE(j["aero_integrals"].empty());
  EXPECT_FALSE(j["structural_integrals"].empty());
  EXPECT_TRUE(j["hover"]["equilibrium"].contains("g0_1"));
  const Json n = parse_json(run({"system", "--mu", "0.5", "--psi", "1", "--json"}));
  EXPECT_EQ(n["region"], "normal");
}

TEST(CliGood, SweepJsonAndCsv) {
  const Json j = parse_json(run(fast({"sweep", "--mu", "0:0.2:0.1", "--json"})));
  ASSERT_EQ(j["rows"].size(), 3u);
  for (const Json& row : j["rows"]) {
    EXPECT_TRUE(row["mu"].is_number());
    for (const char* mode : {"flap", "lag"}) {
      EXPECT_TRUE(row[mode]["zeta"].is_number()) << row;
      EXPECT_TRUE(row[mode]["omega"].is_number()) << row;
    }
  }
  const Outcome c = run(fast({"sweep", "--mu", "0:0.2:0.1", "--format", "csv"}));
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_EQ(c.out.rfind("mu,flap_zeta,flap_omega,lag_zeta,lag_omega,", 0), 0u) << c.out;
  EXPECT_EQ(std::count(c.out.begin(), c.out.end(), '\n'), 4);
}

TEST(CliGood, CriticalJson) {
  const Json j = parse_json(run({"critical", "--json"}));
  for (const char* key : {"mu_c", "omega", "mode", "kind", "model", "parameters"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  ASSERT_TRUE(j["mu_c"].is_number()) << j;  // the typical case is unstable below mu = 2
  EXPECT_TRUE(j["mode"] == "flap" || j["mode"] == "lag");
  EXPECT_TRUE(j["kind"] == "flutter" || j["kind"] == "periodic");
  // Stable up to a small limit: mu_c is null, not an error.
  const Json s = parse_json(run(fast({"critical", "--mu-max", "0.1", "--json"})));
  EXPECT_TRUE(s["mu_c"].is_null()) << s;
  EXPECT_EQ(s["found"], false);
}

TEST(CliGood, ModelsAndSpecs) {
  const Json j = parse_json(run({"models", "--json"}));
  bool has_paper = false;
  for (const Json& m : j["models"]) has_paper = has_paper || m["name"] == "paper";
  EXPECT_TRUE(has_paper);
  const Outcome s = run({"models", "--spec", "paper"});
  EXPECT_EQ(s.exit_code, 0);
  EXPECT_FALSE(s.out.empty());
}

TEST(CliGood, ModesJson) {
  const Json j = parse_json(run({"modes", "--json", "--nonrotating", "0:1:0.5", "--points", "5"}));
  EXPECT_EQ(j["fig9"].size(), 3u);
  EXPECT_EQ(j["flap"]["modes"][0]["value"].size(), 5u);
  EXPECT_NEAR(j["flap"]["modes"][0]["value"][4].get<double>(), 1.0, 1e-12);  // tip value 1
  EXPECT_NEAR(j["flap"]["rotating_first"].get<double>(), 1.175, 0.0);
}

TEST(CliGood, SeveralModesSelectTheirModel) {
  const Json j = parse_json(run(fast({"point", "--mu", "0.1", "--modes", "exact", "--flap-modes",
                                      "2", "--lag-modes", "2", "--json"})));
  EXPECT_EQ(j["model"]["name"], "paper-2x2");
  EXPECT_EQ(j["exponents"].size(), 8u);
}

TEST(CliGood, OutputFileIsWrittenCompletelyAndReplacedAtomically) {
  TempDir dir;
  const std::string target = dir.file("point.json");
  const std::vector<std::string> args = fast({"point", "--mu", "0.3", "--json"});
  const Outcome to_stdout = run(args);
  ASSERT_EQ(to_stdout.exit_code, 0);
  std::vector<std::string> with_o = args;
  with_o.insert(with_o.end(), {"-o", target});
  const Outcome first = run(with_o);
  EXPECT_EQ(first.exit_code, 0) << first.err;
  EXPECT_EQ(first.out, "");
  EXPECT_EQ(slurp(target), to_stdout.out);
  EXPECT_TRUE(Json::accept(slurp(target)));
  // Replacing an existing file: the new content in full, no temporaries left.
  std::ofstream(target) << "stale";
  with_o.back() = target;
  const Outcome second = run(with_o);
  EXPECT_EQ(second.exit_code, 0) << second.err;
  EXPECT_EQ(slurp(target), to_stdout.out);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"point.json"});
}

TEST(CliGood, HelpAndVersionExitZero) {
  const Outcome h = run({"--help"});
  EXPECT_EQ(h.exit_code, 0);
  EXPECT_NE(h.out.find("--omega-lag"), std::string::npos);
  const Outcome sh = run({"sweep", "--help"});
  EXPECT_EQ(sh.exit_code, 0);
  EXPECT_NE(sh.out.find("--format"), std::string::npos);
  EXPECT_NE(sh.out.find("--gamma"), std::string::npos);
}

}  // namespace
