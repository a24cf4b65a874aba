// The memory limit of the command line (runtime/analysis limits.h, --memory-limit): a run
// whose size the user chose (a map's cells, a simulation's samples, a merge's output) is
// estimated before it starts and refused above the limit with one line and exit 2, never
// std::bad_alloc after minutes or gigabytes; the limit is raised with --memory-limit (or the
// case file key memory-limit).
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "command_line.h"
#include "flaplag/core/errors.h"
#include "flaplag/limits.h"
#include "process.h"

namespace cli_limits_test {

namespace {

using flaplag::testing::Outcome;
using flaplag::testing::TempDir;

Outcome run(const std::vector<std::string>& args, int seconds = 120) {
  return flaplag::testing::run_process(FLAPLAG_EXE, args, std::chrono::seconds(seconds));
}

// flaplag under a shell's `ulimit -v` (1 GiB of address space): a run that allocates its grid
// first dies with bad_alloc (exit 1) there; a run refused before it starts does not notice.
// Uncapped under AddressSanitizer (process.h), where the refusal is still checked.
Outcome run_in_1gib(const std::vector<std::string>& args, int seconds = 60) {
  std::string command = FLAPLAG_TEST_ASAN ? "exec \"$0\"" : "ulimit -v 1048576 && exec \"$0\"";
  for (std::size_t i = 0; i < args.size(); ++i) command += " \"$" + std::to_string(i + 1) + "\"";
  std::vector<std::string> sh{"-c", command, FLAPLAG_EXE};
  sh.insert(sh.end(), args.begin(), args.end());
  return flaplag::testing::run_process("/bin/sh", sh, std::chrono::seconds(seconds));
}

int lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

// One line "flaplag: error: <option> = <value>: ..." naming the size, the estimate and the
// option that raises the limit, exit 2, nothing on stdout.
void expect_refused(const Outcome& r, const std::string& head) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_EQ(r.err.rfind("flaplag: error: " + head, 0), 0u) << r.err;
  EXPECT_NE(r.err.find("would need about"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--memory-limit"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("bad_alloc"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}

TEST(CliLimits, HugeMapIsRefusedBeforeItAllocates) {
  // 10000 x 10000 cells: the whole grid used to be allocated first (bad_alloc, exit 1).
  const auto start = std::chrono::steady_clock::now();
  const Outcome r = run_in_1gib(
      {"map", "--x", "mu=0:0.9999:0.0001", "--y", "theta=0.0001:1:0.0001", "--json", "--quiet"});
  expect_refused(r, "--y = theta=0.0001:1:0.0001: a map of 10000 x 10000 cells");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
}

TEST(CliLimits, LongSimulationIsRefusedBeforeItRuns) {
  // 10^9 samples: grew to gigabytes before.
  const Outcome r =
      run_in_1gib({"simulate", "--mu", "0.3", "--revs", "100000", "--samples", "10000"});
  expect_refused(r, "--revs = 100000: a simulation of 1000000001 samples");
}

TEST(CliLimits, TheLimitIsRaisedWithTheOption) {
  TempDir dir;
  // 2000 revolutions x 36 samples: tens of MB.
  const std::vector<std::string> sim{"simulate", "--mu",   "0.3", "--revs",
                                     "2000",     "--json", "-o",  dir.file("s.json")};
  std::vector<std::string> low = sim, high = sim;
  low.insert(low.end(), {"--memory-limit", "4M"});
  high.insert(high.end(), {"--memory-limit", "512M"});
  expect_refused(run(low), "--revs = 2000: a simulation of 72001 samples");
  EXPECT_FALSE(flaplag::testing::exists(dir.file("s.json")));
  const Outcome r = run(high);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(flaplag::testing::slurp(dir.file("s.json")));
  EXPECT_EQ(j.at("psi").size(), 72001u);
}

TEST(CliLimits, TheLimitIsACaseFileKey) {
  TempDir dir;
  std::ofstream(dir.file("case.toml")) << "command = \"simulate\"\nmu = 0.3\nrevs = 2000\n"
                                          "memory-limit = \"4M\"\n";
  const Outcome r = run({"run", dir.file("case.toml")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("would need about"), std::string::npos) << r.err;
  // Typed after the file, the option overrides it.
  const Outcome ok = run({"run", dir.file("case.toml"), "--memory-limit", "1G", "--json"});
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

TEST(CliLimits, EveryRunWhoseSizeTheUserChoosesIsChecked) {
  expect_refused(run({"sweep", "--mu", "0:10:0.0001", "--memory-limit", "16M"}),
                 "--mu = 0:10:0.0001: a sweep of 100001 points");
  expect_refused(
      run({"study", "--vary", "omega-lag=0.5:2:0.0001", "--memory-limit", "16M", "--quiet"}),
      "--vary = omega-lag=0.5:2:0.0001: a study of 15001 values");
  expect_refused(run({"response", "--mu", "0.3", "--samples", "100000", "--memory-limit", "1M"}),
                 "--samples = 100000: a response of 100000 samples");
  // A --shard part is estimated for its own block of rows.
  expect_refused(run({"map", "--x", "mu=0:0.9999:0.0001", "--y", "theta=0.0001:1:0.0001", "--json",
                      "--quiet", "--shard", "2/2"}),
                 "--x = mu=0:0.9999:0.0001: a map of 10000 x 5000 cells");
}

TEST(CliLimits, BadLimitsAreRefusedByName) {
  for (const std::string bad : {"abc", "0", "2X", "-1G", "1.2.3G", "512", "2P"}) {
    const Outcome r = run({"simulate", "--mu", "0.3", "--memory-limit", bad});
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.err;
    EXPECT_EQ(lines(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("flaplag: error: --memory-limit = " + bad + ": ", 0), 0u) << r.err;
  }
  for (const std::string good : {"1M", "512MiB", "1.5g", "3000000000", "2 GiB", "1T"}) {
    const Outcome r = run({"response", "--mu", "0.3", "--memory-limit", good});
    EXPECT_EQ(r.exit_code, 0) << good << ": " << r.err;
  }
}

TEST(CliLimits, SizesAreParsedInPowersOf1024) {
  EXPECT_EQ(flaplag::parse_memory_size("m", "1M"), 1u << 20);
  EXPECT_EQ(flaplag::parse_memory_size("m", "2GiB"), std::uint64_t{2} << 30);
  EXPECT_EQ(flaplag::parse_memory_size("m", "1.5G"), std::uint64_t{3} << 29);
  EXPECT_EQ(flaplag::parse_memory_size("m", "3000000000"), 3000000000u);
  EXPECT_THROW(flaplag::parse_memory_size("m", "1023K"), flaplag::InvalidInput);
  EXPECT_EQ(flaplag::memory_text(std::uint64_t{2} << 30), "2 GiB");
  EXPECT_EQ(flaplag::memory_text(1536u << 20), "1.5 GiB");
}

// A part of a map, computed; `edit` changes its JSON before it is written back.
std::string small_part(const TempDir& dir) {
  const std::string file = dir.file("part.json");
  const Outcome r = run({"map", "--x", "mu=0:0.2:0.1", "--y", "theta=0.1,0.2", "--json", "--quiet",
                         "--shard", "1/1", "-o", file});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return file;
}

TEST(CliLimits, MergeOfACraftedPartWritesNothing) {
  // A 60 kB part whose pretty-printed merge is 1.8 GB (30000 nested arrays: an indentation
  // that grows with the depth on every line).  Refused, whichever check sees it first.
  TempDir dir;
  const std::string file = small_part(dir);
  auto j = nlohmann::ordered_json::parse(flaplag::testing::slurp(file));
  const std::string deep = std::string(30000, '[') + std::string(30000, ']');
  std::string text = j.dump();
  const std::string key = "\"message\":";
  text.insert(text.rfind(key), "\"notes\":" + deep + ",");
  std::ofstream(dir.file("evil.json")) << text;
  const Outcome r = run_in_1gib({"merge", dir.file("evil.json"), "-o", dir.file("out.json")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_FALSE(flaplag::testing::exists(dir.file("out.json")));
}

TEST(CliLimits, MergedOutputIsMeasuredExactlyBeforeItIsMade) {
  // check_merged_output against the text nlohmann::json would make: its length S (dump(2) and
  // a newline) needs 4 S bytes (limits.h json_output_memory), refused one byte below.
  nlohmann::ordered_json doc = {{"command", "map"},
                                {"empty", nlohmann::ordered_json::array()},
                                {"nothing", nlohmann::ordered_json::object()}};
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (int i = 0; i < 3000; ++i)
    rows.push_back({0.1 * i, nullptr, "flap \"lag\"\n", true, {{"k", {1, 2, {3}}}}});
  doc["max_zeta"] = rows;
  const std::uint64_t size = doc.dump(2).size() + 1;
  ASSERT_GT(4 * size, std::uint64_t{1} << 20);
  flaplag::cli::Request r;
  r.memory_limit = 4 * size;
  EXPECT_NO_THROW(flaplag::cli::check_merged_output(r, doc));
  r.memory_limit = 4 * size - 1;
  try {
    flaplag::cli::check_merged_output(r, doc);
    ADD_FAILURE() << "not refused";
  } catch (const flaplag::InvalidInput& e) {
    EXPECT_EQ(e.name(), "memory_limit");
    EXPECT_NE(std::string(e.what()).find(flaplag::memory_text(size) + " of JSON"),
              std::string::npos)
        << e.what();
  }
}

TEST(CliLimits, MergeOfAWidePartIsRefusedUnderTheLimit) {
  // Indentation multiplies a compact part: 20000 numbers 40 levels deep.
  TempDir dir;
  const std::string file = small_part(dir);
  std::string text = flaplag::testing::slurp(file);
  std::string wide = "0";
  for (int i = 1; i < 20000; ++i) wide += ",0";
  wide = std::string(40, '[') + wide + std::string(40, ']');
  text.insert(text.rfind("\"message\""), "\"notes\": " + wide + ",\n");
  std::ofstream(dir.file("wide.json")) << text;
  const Outcome r =
      run({"merge", dir.file("wide.json"), "-o", dir.file("out.json"), "--memory-limit", "1M"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_FALSE(flaplag::testing::exists(dir.file("out.json")));
  // Honest parts merge under the same limit.
  const Outcome ok = run({"merge", file, "-o", dir.file("ok.json"), "--memory-limit", "1M"});
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

}  // namespace

}  // namespace cli_limits_test
