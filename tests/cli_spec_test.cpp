// `flaplag --spec FILE.toml`: a model derived at run time gives the results of the compiled
// model of the same spec; bad specs and misplaced options are one line with exit code 2.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "process.h"

#ifndef FLAPLAG_EXE
#error "FLAPLAG_EXE must name the flaplag binary"
#endif

namespace cli_spec_test {

namespace {

using flaplag::testing::Outcome;
using flaplag::testing::TempDir;
using Json = nlohmann::json;

const std::string kPaper = std::string(FLAPLAG_SPEC_DIR) + "/paper.toml";

Outcome flaplag_run(const std::vector<std::string>& args) {
  return flaplag::testing::run_process(FLAPLAG_EXE, args);
}

// The JSON without what names the model or the command line (the model's name, the case).
Json without_model(Json j) {
  if (j.is_object()) {
    j.erase("case");
    j.erase("model");
    for (auto& [key, value] : j.items()) value = without_model(value);
  } else if (j.is_array()) {
    for (auto& value : j) value = without_model(value);
  }
  return j;
}

void expect_one_line_error(const Outcome& o, const std::string& start) {
  EXPECT_EQ(o.exit_code, 2) << o.err;
  EXPECT_TRUE(o.out.empty()) << o.out;
  EXPECT_EQ(o.err.rfind("flaplag: error: " + start, 0), 0u) << o.err;
  ASSERT_FALSE(o.err.empty());
  EXPECT_EQ(o.err.find('\n'), o.err.size() - 1) << o.err;
}

TEST(CliSpec, CriticalOfTheShippedSpecEqualsTheCompiledModel) {
  const Outcome compiled = flaplag_run({"--json", "critical"});
  const Outcome run_time = flaplag_run({"--json", "--spec", kPaper, "critical"});
  ASSERT_EQ(compiled.exit_code, 0) << compiled.err;
  ASSERT_EQ(run_time.exit_code, 0) << run_time.err;
  const Json a = Json::parse(compiled.out), b = Json::parse(run_time.out);
  EXPECT_EQ(b["case"]["spec"], kPaper);
  EXPECT_EQ(without_model(a), without_model(b));
  EXPECT_NE(run_time.out.find("spec:paper"), std::string::npos);
}

// The audit report of a shipped spec is its checked-in report.
TEST(CliSpec, AuditOfTheShippedSpecIsItsGeneratedReport) {
  TempDir dir;
  const Outcome o =
      flaplag_run({"--spec", kPaper, "--audit", dir.file("paper.md"), "point", "--mu", "0.1"});
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const std::string golden =
      flaplag::testing::slurp(std::string(FLAPLAG_SPEC_DIR) + "/../../generated/paper.md");
  ASSERT_FALSE(golden.empty());
  EXPECT_TRUE(flaplag::testing::slurp(dir.file("paper.md")) == golden);
}

TEST(CliSpec, AnyModeCounts) {
  const std::vector<std::string> args = {"--json",      "--modes", "exact", "--flap-modes", "2",
                                         "--lag-modes", "2",       "point", "--mu",         "0.3"};
  std::vector<std::string> with_spec = args;
  with_spec.insert(with_spec.begin(), {"--spec", kPaper});
  const Outcome compiled = flaplag_run(args), run_time = flaplag_run(with_spec);
  ASSERT_EQ(compiled.exit_code, 0) << compiled.err;
  ASSERT_EQ(run_time.exit_code, 0) << run_time.err;
  EXPECT_EQ(without_model(Json::parse(compiled.out)), without_model(Json::parse(run_time.out)));
  EXPECT_NE(run_time.out.find("spec:paper-2x2"), std::string::npos);
}

TEST(CliSpec, UserSpecInAScratchDirectoryAndItsAudit) {
  TempDir dir;
  std::ofstream(dir.file("paper.toml")) << flaplag::testing::slurp(kPaper);
  std::ofstream(dir.file("mine.toml")) << "base = \"paper\"\n[terms]\nradial_flow = false\n";
  const Outcome compiled = flaplag_run({"--json", "--model", "no-radial-flow", "critical"});
  const Outcome run_time = flaplag_run(
      {"--json", "--spec", dir.file("mine.toml"), "--audit", dir.file("mine.md"), "critical"});
  ASSERT_EQ(compiled.exit_code, 0) << compiled.err;
  ASSERT_EQ(run_time.exit_code, 0) << run_time.err;
  EXPECT_EQ(without_model(Json::parse(compiled.out)), without_model(Json::parse(run_time.out)));
  const std::string audit = flaplag::testing::slurp(dir.file("mine.md"));
  EXPECT_NE(audit.find("Every term, for any number of modes"), std::string::npos);
  // the case records the spec, never the audit file (where output goes is not the result)
  const Json c = Json::parse(run_time.out)["case"];
  EXPECT_EQ(c["spec"], dir.file("mine.toml"));
  EXPECT_FALSE(c.contains("audit"));
  // a case file may name the spec
  std::ofstream(dir.file("case.toml"))
      << "command = \"critical\"\nspec = \"" << dir.file("mine.toml") << "\"\njson = true\n";
  const Outcome from_case = flaplag_run({"run", dir.file("case.toml")});
  ASSERT_EQ(from_case.exit_code, 0) << from_case.err;
  EXPECT_EQ(without_model(Json::parse(compiled.out)), without_model(Json::parse(from_case.out)));
}

TEST(CliSpec, BadInputIsOneLine) {
  TempDir dir;
  std::ofstream(dir.file("bad.toml")) << "[kept]\nflap = \"two\"\n";
  expect_one_line_error(flaplag_run({"--spec", dir.file("bad.toml"), "critical"}),
                        "--spec = " + dir.file("bad.toml") + ": bad.toml: kept.flap = \"two\": ");
  expect_one_line_error(flaplag_run({"--spec", dir.file("missing.toml"), "critical"}),
                        "--spec = " + dir.file("missing.toml") + ": ");
  expect_one_line_error(flaplag_run({"--spec", kPaper, "--model", "paper", "critical"}),
                        "--model = paper: not with --spec");
  expect_one_line_error(flaplag_run({"--audit", dir.file("a.md"), "critical"}),
                        "--audit = " + dir.file("a.md") + ": needs --spec");
  EXPECT_FALSE(flaplag::testing::exists(dir.file("a.md")));
}

}  // namespace

}  // namespace cli_spec_test
