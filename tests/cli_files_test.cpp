// The files flaplag reads, as a user (or someone sending them one) would hand them over: a
// JSON result given to `run` never names a file to write, every file is read with bounded
// nesting and size, a case file gives each key once, and `merge` takes only parts that are what
// their case computes.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "cli_run.h"
#include "flaplag/documents/digest.h"
#include "flaplag/documents/read_file.h"
#include "process.h"
#include "shard.h"

namespace cli_files_test {

namespace {

using Json = nlohmann::json;
using Ordered = nlohmann::ordered_json;

using flaplag::testing::Outcome;
using flaplag::testing::run;
using flaplag::testing::slurp;
using flaplag::testing::TempDir;

void write(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Exit 2 and exactly one line "flaplag: error: <pattern>".
void expect_refused(const Outcome& r, const std::string& pattern, const std::string& what) {
  EXPECT_EQ(2, r.exit_code) << what << "\n" << r.err;
  EXPECT_TRUE(std::regex_match(r.err, std::regex("flaplag: error: " + pattern + "\n")))
      << what << "\n"
      << r.err << "expected: flaplag: error: " << pattern;
  EXPECT_TRUE(r.out.empty()) << what;
}

std::string quote(const std::string& s) { return std::regex_replace(s, std::regex("[.]"), "\\."); }

// ---- A JSON result never chooses where output goes --------------------------------------------

// A point is quick; its JSON case is what `flaplag run` takes back.
Ordered point_result() {
  const Outcome r = run({"point", "--mu", "0.2", "--json"});
  EXPECT_EQ(0, r.exit_code) << r.err;
  return Ordered::parse(r.out);
}

TEST(CliRunJson, OutputInTheCaseIsNeverAPath) {
  TempDir d;
  const std::string victim = d.file("victim.txt");
  write(victim, "precious\n");
  const Ordered honest = point_result();
  // At the top of the case and inside a group; as -o's long spelling ("output").
  for (const char* group : {"", "output"}) {
    Ordered evil = honest;
    if (*group == '\0')
      evil["case"]["output"] = victim;
    else
      evil["case"][group] = Ordered{{"output", victim}};
    const std::string file = d.file("evil.json");
    write(file, evil.dump(2));
    const Outcome r = run({"run", file});
    ASSERT_EQ(0, r.exit_code) << r.err;
    EXPECT_EQ("precious\n", slurp(victim)) << group;
    // The result goes to stdout: the same bytes as the honest result.
    EXPECT_EQ(honest.dump(2) + "\n", r.out) << group;
    EXPECT_TRUE(std::regex_match(
        r.err, std::regex("flaplag: warning: " + quote(file) + ": case\\.(output\\.)?output = " +
                          quote(victim) + " ignored: .*-o on the command line\\)\n")))
        << r.err;
  }
  // What the user types still counts.
  const std::string mine = d.file("mine.json");
  Ordered evil = honest;
  evil["case"]["output"] = victim;
  write(d.file("evil.json"), evil.dump(2));
  const Outcome typed = run({"run", d.file("evil.json"), "-o", mine});
  ASSERT_EQ(0, typed.exit_code) << typed.err;
  EXPECT_EQ("precious\n", slurp(victim));
  EXPECT_EQ(honest.dump(2) + "\n", slurp(mine));
}

// The mode file of `modes --export-shapes` is a file the user names, never a received result.
TEST(CliRunJson, ExportedShapesInTheCaseAreNotWritten) {
  TempDir d;
  const std::string victim = d.file("victim.csv"), file = d.file("modes.json");
  const Outcome honest = run({"modes", "--json", "--points", "5"});
  ASSERT_EQ(0, honest.exit_code) << honest.err;
  Ordered evil = Ordered::parse(honest.out);
  ASSERT_FALSE(evil["case"].contains("export-shapes"));
  evil["case"]["export-shapes"] = victim;
  write(file, evil.dump(2));
  const Outcome r = run({"run", file});
  ASSERT_EQ(0, r.exit_code) << r.err;
  EXPECT_FALSE(flaplag::testing::exists(victim));
  EXPECT_EQ(honest.out, r.out);
  EXPECT_TRUE(std::regex_match(
      r.err, std::regex("flaplag: warning: " + quote(file) +
                        ": case\\.export-shapes = " + quote(victim) + " ignored: .*\n")))
      << r.err;
}

// A value in a case is a value, whatever it looks like: never another option.
TEST(CliRunJson, ValueThatLooksLikeAnOptionIsAValue) {
  TempDir d;
  const std::string picture = d.file("p.svg"), file = d.file("r.json");
  write(file, "{\"case\": {\"command\": \"point\", \"mu\": \"0.1\", \"theta\": \"--plot=" +
                  picture + "\"}}");
  expect_refused(run({"run", file}),
                 quote(file) + ": case\\.theta = --plot=" + quote(picture) + ": not a number",
                 "theta");
  EXPECT_FALSE(flaplag::testing::exists(picture));
}

// A result made with --plot records the picture in its case; rerunning it does not draw it again
// (nor would a received one replace any file it names).
TEST(CliRunJson, PlotInTheCaseIsNotRedrawn) {
  TempDir d;
  const std::string picture = d.file("sweep.svg"), result = d.file("sweep.json");
  const Outcome first =
      run({"sweep", "--mu", "0:0.2:0.1", "--json", "--plot", picture, "-o", result});
  ASSERT_EQ(0, first.exit_code) << first.err;
  ASSERT_EQ(picture, Json::parse(slurp(result))["case"]["plot"]);
  std::filesystem::remove(picture);
  const Outcome again = run({"run", result});
  ASSERT_EQ(0, again.exit_code) << again.err;
  EXPECT_FALSE(flaplag::testing::exists(picture));
  // The same result; its case no longer names the picture.
  Json before = Json::parse(slurp(result));
  before["case"].erase("plot");
  EXPECT_EQ(before, Json::parse(again.out));
  EXPECT_NE(std::string::npos, again.err.find("case.plot = " + picture + " ignored"));
}

// A TOML case file is the user's own: its output goes where it says.
TEST(CliRunToml, OutputInATomlCaseIsWritten) {
  TempDir d;
  const std::string toml = d.file("case.toml"), out = d.file("out.json");
  write(toml, "command = \"point\"\nmu = 0.2\n[output]\njson = true\noutput = \"" + out + "\"\n");
  const Outcome r = run({"run", toml});
  ASSERT_EQ(0, r.exit_code) << r.err;
  EXPECT_TRUE(r.out.empty());
  EXPECT_EQ(0.2, Json::parse(slurp(out))["mu"].get<double>());
}

// ---- Bounded nesting and size on every file read ----------------------------------------------

std::string repeat(const std::string& s, std::size_t n) {
  std::string out;
  out.reserve(s.size() * n);
  for (std::size_t i = 0; i < n; ++i) out += s;
  return out;
}

TEST(CliFiles, DeepTomlIsRefusedWithOneLine) {
  TempDir d;
  struct Deep {
    const char* name;
    std::string text;
  };
  const std::vector<Deep> files = {
      {"dotted.toml", "a" + repeat(".a", 50000) + " = 1\n"},
      {"header.toml", "[a" + repeat(".a", 50000) + "]\nb = 1\n"},
      {"header_and_key.toml", "[a" + repeat(".a", 40) + "]\nb" + repeat(".b", 40) + " = 1\n"},
      {"array.toml", "theta = " + repeat("[", 70000) + repeat("]", 70000) + "\n"},
      {"inline.toml", "theta = " + repeat("{a = ", 50000) + "1" + repeat("}", 50000) + "\n"},
  };
  for (const Deep& f : files) {
    const std::string path = d.file(f.name);
    write(path, f.text);
    expect_refused(run({"run", path}),
                   quote(path) + ":[12] = \\(TOML\\): nested deeper than 64 levels .*", f.name);
  }
}

TEST(CliFiles, DeepJsonIsRefusedWithOneLineByRunPlotAndMerge) {
  TempDir d;
  const std::string objects = repeat("{\"a\":", 50000) + "1" + repeat("}", 50000);
  const std::string arrays = repeat("[", 70000) + repeat("]", 70000);
  // As the case, as a value in the case, as a value of a result.
  const std::vector<std::pair<std::string, std::string>> files = {
      {"case_objects.json", "{\"case\": " + objects + "}"},
      {"case_value.json", "{\"case\": {\"theta\": " + arrays + "}}"},
      {"result_value.json", "{\"flaplag\": {}, \"command\": \"sweep\", \"rows\": " + arrays + "}"},
  };
  for (const auto& [name, text] : files) {
    const std::string path = d.file(name);
    write(path, text);
    const std::string deep = "nested deeper than 64 levels \\(line 1\\)";
    expect_refused(run({"run", path}), quote(path) + " = \\(JSON\\): " + deep, "run " + name);
    expect_refused(run({"plot", path, "--plot", d.file("x.svg")}),
                   "argument = " + quote(path) + ": not a flaplag --json output: " + deep,
                   "plot " + name);
    expect_refused(run({"merge", path}), "argument = " + quote(path) + ": damaged part: " + deep,
                   "merge " + name);
  }
}

TEST(CliFiles, TooLargeOrNotAFileIsRefused) {
  TempDir d;
  // A sparse file just over the limit (the memory limit / 16: 128 MiB at the default 2 GiB):
  // refused from its size, before reading.
  const std::string big = d.file("big.json");
  write(big, "{");
  ASSERT_EQ(0, ::truncate(big.c_str(), (std::int64_t{128} << 20) + 1));
  const std::string why =
      " under --memory-limit 2 GiB, which reading JSON of this size may need: raise "
      "--memory-limit\\)";
  expect_refused(
      run({"plot", big, "--plot", d.file("x.svg")}),
      "argument = " + quote(big) + ": larger than 128 MiB \\(the limit on a result file" + why,
      "plot");
  expect_refused(run({"merge", big}),
                 "argument = " + quote(big) +
                     ": larger than 128 MiB \\(the limit on a part \\(with the parts before "
                     "it\\)" +
                     why,
                 "merge");
  expect_refused(
      run({"run", big}),
      "argument = " + quote(big) + ": larger than 128 MiB \\(the limit on a case file" + why,
      "run");
  // Under a raised limit the same file is read, and is then refused for what it holds.
  expect_refused(run({"plot", big, "--plot", d.file("x.svg"), "--memory-limit", "4G"}),
                 "argument = " + quote(big) + ": not JSON .*", "plot 4G");
  expect_refused(run({"run", big, "--memory-limit=4G"}),
                 quote(big) + " = \\(JSON\\): does not parse: .*", "run 4G");
  // A device that never ends is read up to the limit only.
  expect_refused(run({"run", "/dev/zero"}),
                 "argument = /dev/zero: larger than 128 MiB \\(the limit on a case file" + why,
                 "/dev/zero");
  // A TOML case has a smaller limit.
  const std::string toml = d.file("big.toml");
  write(toml, "# " + std::string((4 << 20), 'x') + "\n");
  expect_refused(
      run({"run", toml}),
      "argument = " + quote(toml) + ": larger than 4 MiB \\(the limit on a TOML case file\\)",
      "toml");
  // A directory is not a case (it used to run the typical case).
  expect_refused(run({"run", d.path()}),
                 "argument = " + quote(d.path()) + ": is a directory, not a case file", "run dir");
  expect_refused(run({"merge", d.path()}),
                 "argument = " + quote(d.path()) + ": is a directory, not a part", "merge dir");
  expect_refused(run({"plot", d.path(), "--plot", d.file("x.svg")}),
                 "argument = " + quote(d.path()) + ": is a directory, not a result file",
                 "plot dir");
}

TEST(ReadFile, DepthScans) {
  using flaplag::documents::json_too_deep;
  using flaplag::documents::toml_too_deep;
  EXPECT_EQ(0u, json_too_deep("{\"a\": [[1, 2], {\"b\": null}]}", 3));
  EXPECT_EQ(1u, json_too_deep("{\"a\": [[1, 2], {\"b\": [null]}]}", 3));
  EXPECT_EQ(2u, json_too_deep("[\n[[[]]]]", 3));
  // Brackets in strings (with escaped quotes) do not count.
  EXPECT_EQ(0u, json_too_deep("[\"[[[[\\\"[[[[\", \"{{{{\"]", 2));
  EXPECT_EQ(0u, toml_too_deep("[parameters]\ntheta = 0.15 # [[[[ ...\nname = \"a.b.c.d\"\n", 3));
  EXPECT_EQ(0u, toml_too_deep("x = '''\n[[[[a.b.c.d\n'''\ny = \"\"\"\na.b.c\\\"\"\"\n", 3));
  EXPECT_EQ(1u, toml_too_deep("a.b.c.d = 1", 2));
  EXPECT_EQ(0u, toml_too_deep("a.b.c = 1", 2));
  EXPECT_EQ(1u, toml_too_deep("[a.b.c.d]", 3));
  // A table header's parts count for the keys under it; the next header starts again.
  EXPECT_EQ(3u, toml_too_deep("[a.b]\nc = 1\nd.e = 2\n", 2));
  EXPECT_EQ(0u, toml_too_deep("[a.b]\nc = 1\n[d]\ne.f = 2\n", 2));
  // Arrays over lines, inline tables in arrays.
  EXPECT_EQ(0u, toml_too_deep("x = [\n 1.5,\n 2.5,\n]\n", 3));
  EXPECT_EQ(1u, toml_too_deep("x = [{a.b = [1]}]", 3));
}

TEST(ReadFile, JsonKeyTwiceInOneObjectIsRefused) {
  Json j;
  std::string error;
  EXPECT_EQ(flaplag::documents::JsonParse::Refused,
            flaplag::documents::parse_json("{\"case\": {\"theta\": 1, \"mu\": [{}], \"theta\": 2}}",
                                           &j, &error));
  EXPECT_EQ("key \"theta\" given twice in one object (at case.theta)", error);
  EXPECT_EQ(
      flaplag::documents::JsonParse::Ok,
      flaplag::documents::parse_json("{\"a\": {\"x\": 1}, \"b\": {\"x\": 1}, \"c\": [{\"x\": 1}, "
                                     "{\"x\": 2}]}",
                                     &j, &error));
  EXPECT_EQ(flaplag::documents::JsonParse::NotJson,
            flaplag::documents::parse_json("{", &j, &error));
}

// ---- A key once per case ----------------------------------------------------------------------

TEST(CliRunToml, KeyInTwoTablesIsRefusedNamingBoth) {
  TempDir d;
  const std::string toml = d.file("case.toml");
  // toml++ keeps tables sorted: [method] would have been read before [parameters].
  write(toml, "command = \"point\"\n[parameters]\ntheta = 0.1\nmu = 0.2\n[method]\ntheta = 0.2\n");
  expect_refused(
      run({"run", toml}),
      quote(toml) + ":6: theta = 0\\.2: given twice \\(also at " + quote(toml) + ":3: theta\\)",
      "theta twice");
  // Two spellings of one option.
  write(toml,
        "command = \"point\"\nmu = 0.2\n[parameters]\nreversed-flow = false\n"
        "[method]\nno-reversed-flow = true\n");
  expect_refused(run({"run", toml}),
                 quote(toml) + ":6: no-reversed-flow = true: given twice \\(also at " +
                     quote(toml) + ":4: reversed-flow\\)",
                 "two spellings");
  write(toml, "command = \"point\"\nmu = 0.2\n[output]\nmu = 0.3\n");
  expect_refused(
      run({"run", toml}),
      quote(toml) + ":4: mu = 0\\.3: given twice \\(also at " + quote(toml) + ":2: mu\\)",
      "top and table");
}

TEST(CliRunJson, KeyTwiceInTheCaseIsRefused) {
  TempDir d;
  const std::string file = d.file("r.json");
  write(file,
        "{\"case\": {\"command\": \"point\", \"mu\": \"0.2\", \"parameters\": {\"mu\": "
        "\"0.3\"}}}");
  expect_refused(run({"run", file}),
                 quote(file) + ": case\\.parameters\\.mu = 0\\.3: given twice \\(also at " +
                     quote(file) + ": case\\.mu\\)",
                 "two groups");
  write(file, "{\"case\": {\"command\": \"point\", \"mu\": \"0.2\", \"mu\": \"0.3\"}}");
  expect_refused(
      run({"run", file}),
      quote(file) + " = \\(JSON\\): key \"mu\" given twice in one object \\(at case\\.mu\\)",
      "one object");
}

// The typical case has no subcommand: its JSON records command "" and runs again as it is.
TEST(CliRunToml, EmptyCommandIsTheTypicalCase) {
  TempDir d;
  const std::string toml = d.file("case.toml");
  write(toml, "command = \"\"\ntheta = 0.2\njson = true\n");
  const Outcome r = run({"run", toml});
  ASSERT_EQ(0, r.exit_code) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ("typical", j["command"]);
  EXPECT_EQ("", j["case"]["command"]);
  const std::string json = d.file("typical.json");
  write(json, r.out);
  const Outcome again = run({"run", json});
  ASSERT_EQ(0, again.exit_code) << again.err;
  EXPECT_EQ(r.out, again.out);
  // A command that is not one is refused where it is written.
  write(toml, "theta = 0.2\ncommand = \"swep\"\n");
  expect_refused(run({"run", toml}), quote(toml) + ":2: command = swep: not a subcommand", "swep");
  write(toml, "command = \"\"\n[output]\ncommand = \"point\"\n");
  expect_refused(
      run({"run", toml}),
      quote(toml) + ":3: command = point: given twice \\(also at " + quote(toml) + ":1: command\\)",
      "command twice");
}

// ---- merge takes only what the case computes --------------------------------------------------

TEST(Digest, Sha256OfTheFips180Examples) {
  using flaplag::documents::sha256_hex;
  EXPECT_EQ("ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad", sha256_hex("abc"));
  EXPECT_EQ("e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855", sha256_hex(""));
  EXPECT_EQ("248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1",
            sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"));
  EXPECT_EQ("cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0",
            sha256_hex(std::string(1000000, 'a')));
}

const std::vector<std::string> kMap = {"map",   "--x", "mu=0:1:0.5", "--y", "omega-lag=0.8,1.2,1.6",
                                       "--json"};
const std::vector<std::string> kStudy = {"study",    "--vary", "omega-lag=1.0,1.3,1.45",
                                         "--mu-max", "1.2",    "--json"};

class CliMergeTampered : public ::testing::Test {
 protected:
  std::string part(const std::string& name, int i, int n, std::vector<std::string> args) {
    args.insert(args.end(),
                {"--shard", std::to_string(i) + "/" + std::to_string(n), "-o", d.file(name)});
    const Outcome r = run(args);
    EXPECT_EQ(0, r.exit_code) << r.err;
    return d.file(name);
  }
  // A copy of `file` changed by `edit`; `reseal`: with a digest made for the change (as a forger
  // would), so that only the checks against the case can refuse it.
  template <class Edit>
  std::string tampered(const std::string& file, const std::string& name, Edit edit, bool reseal) {
    Ordered j = Ordered::parse(slurp(file));
    edit(j);
    if (reseal) flaplag::cli::seal_part(j);
    write(d.file(name), j.dump(2) + "\n");
    return d.file(name);
  }
  void expect_merge_refused(const std::vector<std::string>& parts, const std::string& bad,
                            const std::string& reason) {
    std::vector<std::string> args = {"merge"};
    args.insert(args.end(), parts.begin(), parts.end());
    const std::string out = d.file("merged.json");
    args.insert(args.end(), {"-o", out});
    expect_refused(run(args), "argument = " + quote(bad) + ": " + reason, bad);
    EXPECT_FALSE(flaplag::testing::exists(out)) << bad;
  }
  TempDir d;
};

TEST_F(CliMergeTampered, EditedCellsAndLabelsFailTheDigest) {
  const std::string m1 = part("m1.json", 1, 2, kMap), m2 = part("m2.json", 2, 2, kMap);
  const std::string digest = "damaged part: its data do not match its digest .*";
  const std::string cell = tampered(
      m2, "cell.json", [](Ordered& j) { j["max_zeta"][0][1] = 0.5; }, false);
  expect_merge_refused({m1, cell}, cell, digest);
  int flipped = 0;
  const std::string label = tampered(
      m2, "label.json",
      [&flipped](Ordered& j) {
        for (auto& row : j["mode"])
          for (auto& c : row)
            if (c.is_string()) {
              c = c == "lag" ? "flap" : "lag";
              ++flipped;
            }
      },
      false);
  ASSERT_GT(flipped, 0);
  expect_merge_refused({label, m1}, label, digest);
  const std::string s1 = part("s1.json", 1, 2, kStudy), s2 = part("s2.json", 2, 2, kStudy);
  const std::string row = tampered(
      s2, "row.json", [](Ordered& j) { j["rows"][0]["mu_c"] = 0.9; }, false);
  expect_merge_refused({s1, row}, row, digest);
  const std::string none = tampered(
      s1, "none.json", [](Ordered& j) { j["shard"].erase("digest"); }, false);
  expect_merge_refused({none, s2}, none, "a part without a digest .*");
  // The untampered parts still merge to the file one run writes.
  const Outcome whole = run(kMap), merged = run({"merge", m2, m1});
  ASSERT_EQ(0, merged.exit_code) << merged.err;
  EXPECT_EQ(whole.out, merged.out);
}

TEST_F(CliMergeTampered, StatusThatIsNotTextIsRefused) {
  const std::string m1 = part("m1.json", 1, 2, kMap), m2 = part("m2.json", 2, 2, kMap);
  for (const bool reseal : {false, true}) {
    const std::string five = tampered(
        m2, "five.json", [](Ordered& j) { j["status"] = 5; }, reseal);
    expect_merge_refused({m1, five}, five, "damaged part: no valid \"status\"");
  }
}

// Changes a forger would make with a fresh digest: each contradicts the case.
TEST_F(CliMergeTampered, ResealedPartsThatContradictTheirCaseAreRefused) {
  const std::string m1 = part("m1.json", 1, 2, kMap), m2 = part("m2.json", 2, 2, kMap);
  const std::string s1 = part("s1.json", 1, 2, kStudy), s2 = part("s2.json", 2, 2, kStudy);
  struct Forgery {
    const char* name;
    std::string base, other;
    std::function<void(Ordered&)> edit;
    std::string reason;
    std::string second = "";  // the reason when it comes second, if another
  };
  const std::string not_computed = " is not what its case computes";
  const std::vector<Forgery> forgeries = {
      {"yvalues.json", m2, m1, [](Ordered& j) { j["y"]["values"][0] = 1.3; },
       "damaged part: y\\.values" + not_computed},
      {"xvalues.json", m2, m1, [](Ordered& j) { j["x"]["values"][1] = 0.25; },
       "damaged part: x\\.values" + not_computed,
       "not a part of the same case as " + quote(m1) + " \\(x\\.values differs\\)"},
      // 1 for 1.0: the same number, not the text flaplag writes.
      {"integer.json", m2, m1, [](Ordered& j) { j["x"]["values"][2] = 1; },
       "damaged part: x\\.values" + not_computed,
       "not a part of the same case as " + quote(m1) + " \\(x\\.values differs\\)"},
      // 10 for 10.0: the same number, not the bytes one run writes.
      {"header_integer.json", m1, m2, [](Ordered& j) { j["parameters"]["gamma"] = 10; },
       "damaged part: parameters\\.gamma" + not_computed,
       "not a part of the same case as " + quote(m2) + " \\(parameters\\.gamma differs\\)"},
      {"word.json", m2, m1, [](Ordered& j) { j["max_zeta"][0][0] = "abc"; },
       "damaged part: the cell \\(1, 1\\) of max_zeta, mode and kind" + not_computed},
      {"bool.json", m2, m1, [](Ordered& j) { j["max_zeta"][0][0] = true; },
       "damaged part: the cell \\(1, 1\\) of max_zeta, mode and kind" + not_computed},
      {"torsion.json", m2, m1, [](Ordered& j) { j["mode"][0][0] = "torsion"; },
       "damaged part: the cell \\(1, 1\\) of max_zeta, mode and kind" + not_computed},
      {"shape.json", m2, m1, [](Ordered& j) { j["kind"][0].erase(0); },
       "damaged part: the shape of kind" + not_computed},
      {"header.json", m1, m2, [](Ordered& j) { j["parameters"]["theta"] = 0.3; },
       "damaged part: parameters\\.theta" + not_computed,
       "not a part of the same case as " + quote(m2) + " \\(parameters\\.theta differs\\)"},
      {"block.json", m2, m1,
       [](Ordered& j) {
         j["shard"]["first"] = 0;
         j["shard"]["last"] = 2;
       },
       "damaged part: part 2/2 of its case is lines 1\\.\\.3 of 3 \\(y\\), not what its \"shard\" "
       "says"},
      {"index.json", m2, m1, [](Ordered& j) { j["case"]["shard"] = "1/2"; },
       "damaged part: its \"shard\" or \"command\" is not what its case asks for"},
      {"badcase.json", m2, m1, [](Ordered& j) { j["case"]["theta"] = "x"; },
       "damaged part: its case is not a command flaplag takes \\(.*\\)"},
      {"value.json", s2, s1, [](Ordered& j) { j["rows"][0]["value"] = 1.35; },
       "damaged part: row 1 value" + not_computed},
      {"rows.json", s2, s1, [](Ordered& j) { j["rows"].erase(1); },
       "damaged part: the number of rows" + not_computed},
      {"rowtype.json", s2, s1, [](Ordered& j) { j["rows"][1]["mu_c"] = "0.5"; },
       "damaged part: row 2" + not_computed},
      {"interval.json", s2, s1,
       [](Ordered& j) {
         j["rows"][1]["intervals"] = Ordered::array({Ordered::array({"a", 1})});
       },
       "damaged part: row 2" + not_computed},
  };
  for (const Forgery& f : forgeries) {
    const std::string bad = tampered(f.base, f.name, f.edit, true);
    // Named whether it comes first or second.
    expect_merge_refused({bad, f.other}, bad, f.reason);
    expect_merge_refused({f.other, bad}, bad, f.second.empty() ? f.reason : f.second);
  }
}

// Every change to one value of a part (any key, any depth, the digest too) is refused with one
// line naming the part, whichever way the value is replaced: three replacements per value, or
// FLAPLAG_MERGE_TAMPER_REPLACEMENTS (1..3; the sanitizer pass of .ci/run takes one, a different
// one for neighbouring values, so that every replacement is still tried).
TEST_F(CliMergeTampered, AnyChangedValueOfAPartIsRefused) {
  const std::size_t per_value = static_cast<std::size_t>(
      std::min(3L, flaplag::testing::env_long("FLAPLAG_MERGE_TAMPER_REPLACEMENTS", 3)));
  const std::string m1 = part("m1.json", 1, 2, kMap), m2 = part("m2.json", 2, 2, kMap);
  const Ordered original = Ordered::parse(slurp(m2));
  std::vector<Ordered::json_pointer> pointers;
  const Ordered flat = original.flatten();  // the leaves; their parents are added below
  for (const auto& [key, value] : flat.items()) {
    Ordered::json_pointer p(key);
    for (; !p.empty(); p = p.parent_pointer())
      if (std::find(pointers.begin(), pointers.end(), p) == pointers.end()) pointers.push_back(p);
  }
  const std::vector<Ordered> replacements = {nullptr,
                                             "x",
                                             5,
                                             -0.0,
                                             true,
                                             Ordered::array(),
                                             Ordered::object(),
                                             "-inf",
                                             1e300,
                                             Ordered::parse(repeat("[", 30) + repeat("]", 30))};
  // Every value (about 100 in this part), each with `per_value` of the replacements in turn.
  std::size_t runs = 0;
  for (std::size_t i = 0; i < pointers.size(); ++i) {
    const std::size_t tried[] = {i, i + 3, i + 7};
    for (std::size_t t = 0; t < per_value; ++t) {
      const std::size_t k = tried[t];
      Ordered j = original;
      const Ordered& replacement = replacements[k % replacements.size()];
      if (j.at(pointers[i]).dump() == replacement.dump()) continue;
      j.at(pointers[i]) = replacement;
      const std::string bad = d.file("mutated.json");
      write(bad, j.dump(2) + "\n");
      const Outcome r = run({"merge", m1, bad});
      ++runs;
      EXPECT_EQ(2, r.exit_code) << pointers[i].to_string() << " = " << replacement.dump();
      EXPECT_TRUE(std::regex_match(
          r.err, std::regex("flaplag: error: argument = " + quote(bad) + ": [^\\n]*\\n")))
          << pointers[i].to_string() << " = " << replacement.dump() << "\n"
          << r.err;
    }
  }
  EXPECT_GT(runs, 80u * per_value) << pointers.size();
}

// ---- Mutated files keep the contract ----------------------------------------------------------

// Exit 0 with output, or 2 (3: gnuplot failed) with one line "flaplag: error: ..."; never a
// signal, never an internal error; and nothing written but the files the test typed.
void expect_contract(const Outcome& r, const TempDir& d, const std::vector<std::string>& allowed,
                     const std::string& what) {
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 2 || r.exit_code == 3)
      << what << ": exit " << r.exit_code << "\n"
      << r.err;
  if (r.exit_code != 0) {
    // (Not std::regex: it recurses per character, and a line may be 100 kB.)
    EXPECT_EQ(0u, r.err.rfind("flaplag: error: ", 0)) << what << r.err;
    EXPECT_EQ(r.err.size() - 1, r.err.find('\n')) << what << r.err;
  }
  for (const std::string& name : d.entries())
    EXPECT_NE(allowed.end(), std::find(allowed.begin(), allowed.end(), name))
        << what << ": wrote " << name;
}

// Values that would be code, paths, options or resource bombs if taken for anything but data.
std::vector<Ordered> hostile_values(const TempDir& d) {
  return {"`touch " + d.file("pwned") + "`",
          "a'b\"c\\d",
          "line\nbreak",
          "system(\"touch " + d.file("pwned") + "\")",
          "@macro",
          "--plot=" + d.file("pwned.svg"),
          "-o",
          d.file("pwned.json"),
          "",
          std::string(100000, '9'),
          "nan",
          "1e999",
          -1e308,
          0,
          true,
          nullptr,
          Ordered::array({1, "x"}),
          Ordered::object({{"output", d.file("pwned.json")}}),
          Ordered::parse(repeat("[", 100) + repeat("]", 100))};
}

TEST(CliFiles, MutatedJsonCasesKeepTheContract) {
  TempDir d;
  const Ordered honest = point_result();
  const std::vector<Ordered> values = hostile_values(d);
  std::vector<std::string> keys;
  for (const auto& [key, value] : honest["case"].items()) keys.push_back(key);
  keys.insert(keys.end(), {"output", "plot", "label", "shard", "json", "parameters"});
  std::size_t runs = 0;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    for (std::size_t v = k % 3; v < values.size(); v += 3) {
      Ordered j = honest;
      j["case"][keys[k]] = values[v];
      write(d.file("case.json"), j.dump(2, ' ', false, Ordered::error_handler_t::replace));
      expect_contract(run({"run", d.file("case.json")}), d, {"case.json"},
                      keys[k] + " = " + values[v].dump().substr(0, 80));
      ++runs;
    }
  }
  EXPECT_GT(runs, 40u);
}

TEST(CliFiles, MutatedTomlCasesKeepTheContract) {
  TempDir d;
  const std::string base =
      "command = \"point\"\n[parameters]\ntheta = 0.12\n[analysis]\nmu = 0.2\n";
  std::vector<std::string> texts = {
      // The user's own picture: the one file a case may write.
      base + "[output]\njson = true\nplot = '" + d.file("pwned.svg") + "'\n",
      base + "[parameters]\ngamma = 8\n",             // a table twice
      base + "theta = 0.1\n",                         // a key twice
      base + "[output]\njson = true\njson = true\n",  // twice in one table
      base + "[output.deeper]\nx = 1\n",              // a table below a group
      base + "x = " + repeat("[", 100) + repeat("]", 100) + "\n",
      base + "x = " + repeat("{a=", 100) + "1" + repeat("}", 100) + "\n",
      base + "a" + repeat(".a", 100) + " = 1\n",
      base + "[a" + repeat(".a", 100) + "]\n",
      base + "theta = 1979-05-27\n",
      base + "\"theta\" = \"0.1\"\n",
      base + "omega-lag = '''\n1.2'''\n",
      "command = \"point\"\nmu = \"" + std::string(100000, '1') + "\"\n",
      "command = \"point\"\nmu = 0.2\n\xff\xfe = 1\n",
      "command = \"plot\"\nplot = '" + d.file("pwned.svg") + "'\n",
      "command = \"merge\"\n",
      "command = \"run\"\n",
      std::string("command = \"point\"\0mu = 0.2\n", 28),
      base.substr(0, base.size() / 2),
  };
  for (const Ordered& v : hostile_values(d))
    if (v.is_string()) texts.push_back(base + "[method]\nsteps = " + v.dump() + "\n");
  for (std::size_t i = 0; i < texts.size(); ++i) {
    write(d.file("case.toml"), texts[i]);
    const std::vector<std::string> allowed =
        i == 0 ? std::vector<std::string>{"case.toml", "pwned.svg"}
               : std::vector<std::string>{"case.toml"};
    expect_contract(run({"run", d.file("case.toml")}), d, allowed, "case " + std::to_string(i));
    std::filesystem::remove(d.file("pwned.svg"));
  }
}

TEST(CliFiles, MutatedResultsGivenToPlotKeepTheContract) {
  TempDir d;
  const Outcome sweep = run({"sweep", "--mu", "0:0.2:0.1", "--json"});
  ASSERT_EQ(0, sweep.exit_code) << sweep.err;
  const Ordered original = Ordered::parse(sweep.out);
  std::vector<Ordered::json_pointer> pointers;
  const Ordered flat = original.flatten();  // the leaves; their parents are added below
  for (const auto& [key, value] : flat.items()) {
    Ordered::json_pointer p(key);
    for (; !p.empty(); p = p.parent_pointer())
      if (std::find(pointers.begin(), pointers.end(), p) == pointers.end()) pointers.push_back(p);
  }
  const std::vector<Ordered> values = hostile_values(d);
  std::size_t runs = 0;
  for (std::size_t i = 0; i < pointers.size(); i += 1 + pointers.size() / 60) {
    Ordered j = original;
    j.at(pointers[i]) = values[i % values.size()];
    write(d.file("r.json"), j.dump(2, ' ', false, Ordered::error_handler_t::replace));
    expect_contract(
        run({"plot", d.file("r.json"), "--plot", d.file("x.svg")}), d, {"r.json", "x.svg"},
        pointers[i].to_string() + " = " + values[i % values.size()].dump().substr(0, 80));
    ++runs;
  }
  EXPECT_GT(runs, 30u);
}

}  // namespace

}  // namespace cli_files_test
