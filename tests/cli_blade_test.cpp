// Blade tables and imported mode shapes from the command line and case files, as a designer
// hands them over: the uniform table is the paper's exact-mode blade, a dimensional table's
// groups follow from its SI data, a bad table is one line naming its row, and a result records
// the table's text (it never names a file to read).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "process.h"

namespace {

using Json = nlohmann::json;
using flaplag::testing::Outcome;
using flaplag::testing::TempDir;

Outcome run(const std::vector<std::string>& args, const std::string& cwd = "") {
  std::vector<std::string> a = args;
  if (!cwd.empty()) {
    // The binary takes paths relative to its working directory: run it through a shell-free
    // `env -C` so that a case's relative table is found beside the case, not beside the test.
    a.insert(a.begin(), {"-C", cwd, FLAPLAG_EXE});
    return flaplag::testing::run_process("/usr/bin/env", a, std::chrono::seconds(300));
  }
  return flaplag::testing::run_process(FLAPLAG_EXE, a, std::chrono::seconds(300));
}

void write(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

Json critical(const std::vector<std::string>& args) {
  std::vector<std::string> a = args;
  a.push_back("critical");
  a.push_back("--json");
  const Outcome r = run(a);
  EXPECT_EQ(0, r.exit_code) << r.err;
  return Json::parse(r.out);
}

// Exit 2, nothing on stdout, and one line "flaplag: error: <pattern>".
void expect_refused(const Outcome& r, const std::string& pattern, const std::string& what) {
  EXPECT_EQ(2, r.exit_code) << what << "\n" << r.err;
  EXPECT_TRUE(std::regex_match(r.err, std::regex("flaplag: error: " + pattern + "\n")))
      << what << "\n"
      << r.err << "expected: flaplag: error: " << pattern;
  EXPECT_TRUE(r.out.empty()) << what;
}

const char* const kUniform =
    "# the paper's uniform blade, any units\n"
    "x, m, EI_flap, EI_lag\n"
    "0, 2.5, 7, 3\n"
    "0.5, 2.5, 7, 3\n"
    "1, 2.5, 7, 3\n";

TEST(CliBlade, UniformTableIsThePapersExactModeBlade) {
  TempDir d;
  write(d.file("uniform.csv"), kUniform);
  const Json exact = critical({"--modes", "exact"});
  const Json table = critical({"--blade-table", d.file("uniform.csv")});
  EXPECT_NEAR(exact["mu_c"].get<double>(), table["mu_c"].get<double>(), 1e-8);
  EXPECT_EQ("exact", table["mode_shapes"]);
  EXPECT_EQ(3, table["blade_table"]["stations"]);
  // The result records the table's text, never its file.
  EXPECT_EQ(kUniform, table["case"]["blade-csv"].get<std::string>());
  EXPECT_FALSE(table["case"].contains("blade-table"));
}

TEST(CliBlade, DimensionalTableGivesTheNondimensionalGroups) {
  // A uniform blade from r0 = 0.3 m to R = 3 m: I_b = m l^3 / 3 + M_tip l^2 about the root of
  // the elastic blade (Appendix B), gamma = rho a c R^4 / I_b, sigma = b c / (pi R).
  TempDir d;
  const double m = 4.0, c = 0.2, rho = 1.2, rpm = 400.0, tip = 0.5, R = 3.0, l = 2.7;
  write(d.file("rotor.csv"),
        "r, m, EI_flap, EI_lag, chord\n"
        "0.3, 4, 30000, 400000, 0.2\n"
        "3, 4, 30000, 400000, 0.2\n"
        "tip_mass, 0.5\n"
        "rotor_speed_rpm, 400\n"
        "air_density, 1.2\n"
        "blades, 3\n");
  const Json j = critical({"--blade-table", d.file("rotor.csv")});
  const double ib = m * l * l * l / 3.0 + tip * l * l;
  const double gamma = rho * 2.0 * M_PI * c * std::pow(R, 4) / ib;
  const double sigma = 3.0 * c / (M_PI * R);
  const Json& b = j["blade_table"];
  EXPECT_NEAR(ib, b["inertia"].get<double>(), 1e-12 * ib);
  EXPECT_NEAR(gamma, b["gamma"].get<double>(), 1e-12 * gamma);
  EXPECT_NEAR(gamma, j["parameters"]["gamma"].get<double>(), 1e-12 * gamma);
  EXPECT_NEAR(sigma, j["parameters"]["sigma"].get<double>(), 1e-14);
  EXPECT_NEAR(0.1, j["parameters"]["root-offset"].get<double>(), 1e-15);
  EXPECT_NEAR(0.9, j["parameters"]["length-ratio"].get<double>(), 1e-15);
  EXPECT_NEAR(tip * l * l / ib, b["tip_mass"].get<double>(), 1e-14);
  // The frequencies in Hz are the per-rev ones times the rotor speed.
  EXPECT_NEAR(j["parameters"]["omega-flap"].get<double>() * rpm / 60.0,
              b["omega_flap_hz"].get<double>(), 1e-12);
  // Given as well as the table: refused, naming both.
  expect_refused(run({"--blade-table", d.file("rotor.csv"), "--omega-lag", "0.7", "critical"}),
                 "--omega-lag = 0\\.7: not with a dimensional blade table \\(--blade-table .* "
                 "sets it\\)",
                 "omega-lag with a dimensional table");
}

TEST(CliBlade, BadTablesAreOneLineNamingTheRow) {
  TempDir d;
  struct Bad {
    const char* text;
    const char* pattern;
  };
  const Bad bad[] = {
      {"x, m, EI_flap, EI_lag\n0, 1, 1, 1\n0.6, 1, 1, 1\n0.5, 1, 1, 1\n1, 1, 1, 1\n",
       ":4: x = 0\\.5: stations must increase \\(the previous is 0\\.6\\)"},
      {"x, m, EI_flap, EI_lag\n0, 1, 1, 1\n# a comment\n1, -1, 1, 1\n",
       ":4: m = -1: must be positive"},
      {"x, m, EI_flap, EI_lag\n0, 1, 1, 1\n1, 1, 0, 1\n", ":3: EI_flap = 0: must be positive"},
      {"x, m, EI_flap, EI_lag\n0, 1, 1x, 1\n1, 1, 1, 1\n", ":2: EI_flap = 1x: not a number"},
      {"x, m, EI_flap, EI_lag\n0, 1, 1\n1, 1, 1, 1\n", ":2: row = 0, 1, 1: 3 cells for 4 columns"},
      {"x, mass, EI_flap, EI_lag\n0, 1, 1, 1\n1, 1, 1, 1\n",
       ":1: header = mass: unknown column .*"},
      {"x, m, EI_flap, EI_lag\n0, 1, 1, 1\n0.9, 1, 1, 1\n",
       ":3: x = 0\\.9: the last station is the tip, x = 1"},
      {"x, m, EI_flap, EI_lag\n0, 1, 1, 1\n1, 1, 1, 1\nblades, 4\n",
       ":4: blades = 4: only in a dimensional table \\(column r, SI units\\)"},
      {"x, m, EI_flap, EI_lag, twist_deg\n0, 1, 1, 1, 0\n1, 1, 1, 1, 95\n",
       ":3: twist_deg = 95: must be within \\(-90, 90\\) degrees"},
  };
  int k = 0;
  for (const Bad& b : bad) {
    const std::string file = d.file("bad" + std::to_string(k++) + ".csv");
    write(file, b.text);
    expect_refused(
        run({"--blade-table", file, "critical"}),
        "--blade-table " + std::regex_replace(file, std::regex("[.]"), "\\.") + b.pattern, b.text);
  }
  // A table given as text (what a result records) is named by its option, once.
  expect_refused(run({"--blade-csv=", "critical"}),
                 "--blade-csv = \\(empty\\): has no header line .*", "empty --blade-csv");
  expect_refused(run({"--blade-csv=x,m\n", "critical"}),
                 "--blade-csv:1: header = x,m: has no column EI_flap", "short --blade-csv");
  expect_refused(run({"--mode-shapes-csv=", "--modes", "exact", "critical"}),
                 "--mode-shapes-csv:1: .*", "empty --mode-shapes-csv");
  expect_refused(run({"--blade-table", d.file("missing.csv"), "critical"}),
                 "argument = .*missing\\.csv: blade table cannot be read.*", "missing file");
}

TEST(CliBlade, CaseFileTableIsFoundBesideTheCaseAndTheResultReruns) {
  TempDir d;
  write(d.file("taper.csv"),
        "x, m, EI_flap, EI_lag, chord, twist_deg\n"
        "0.1, 1.4, 2.0, 2.5, 1.2, 0\n"
        "0.5, 1.1, 1.2, 1.6, 1.0, -4\n"
        "1, 0.8, 0.5, 0.8, 0.7, -8\n"
        "tip_mass, 0.05\n");
  write(d.file("case.toml"),
        "command = \"point\"\n[blade]\nblade-table = \"taper.csv\"\n[parameters]\n"
        "omega-lag = 0.7\n[analysis]\nmu = 0.3\n");
  // Run from another directory: the table is read beside the case.
  const Outcome r = run({"run", d.file("case.toml"), "--json"}, "/");
  ASSERT_EQ(0, r.exit_code) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_NEAR(0.1, j["parameters"]["root-offset"].get<double>(), 1e-15);
  ASSERT_TRUE(j["case"].contains("blade-csv"));
  // The result reruns to the same document from its recorded text, anywhere.
  write(d.file("result.json"), r.out);
  const Outcome again = run({"run", d.file("result.json"), "--json"}, "/");
  ASSERT_EQ(0, again.exit_code) << again.err;
  Json a = Json::parse(again.out), b = j;
  EXPECT_EQ("--blade-csv", a["blade_table"]["source"]);  // a text now, no longer a file
  for (Json* x : {&a, &b}) {
    x->erase("case");
    (*x)["blade_table"].erase("source");
  }
  EXPECT_EQ(b.dump(), a.dump());
  // A result that names a table file instead is refused: it names no file to read.
  Json evil = j;
  evil["case"].erase("blade-csv");
  evil["case"]["blade-table"] = "/etc/passwd";
  write(d.file("evil.json"), evil.dump());
  expect_refused(run({"run", d.file("evil.json")}),
                 ".*evil\\.json: case\\.blade-table = /etc/passwd: a result file names no file "
                 "to read.*",
                 "a result naming a table");
}

// A report's inputs show what the table gave (not "none given").
TEST(CliBlade, ReportShowsTheBladeTablesGroups) {
  TempDir d;
  write(d.file("rotor.csv"),
        "r, m, EI_flap, EI_lag, chord\n0.3, 4, 30000, 400000, 0.2\n3, 4, 30000, 400000, 0.2\n"
        "rotor_speed_rpm, 400\nair_density, 1.2\nblades, 3\n");
  const Outcome r = run({"--blade-table", d.file("rotor.csv"), "point", "--mu", "0.2", "--report",
                         d.file("page.html")});
  ASSERT_EQ(0, r.exit_code) << r.err;
  const std::string page = flaplag::testing::slurp(d.file("page.html"));
  EXPECT_NE(std::string::npos, page.find("Blade table")) << page;
  EXPECT_NE(std::string::npos, page.find("Lock number rho a c_ref R^4 / I_b")) << page;
  EXPECT_EQ(std::string::npos, page.find("Dimensional inputs: none given")) << page;
}

// The Campbell diagram's speed-frequency relation is the uniform blade's: refused, not wrong.
TEST(CliBlade, CampbellOfABladeTableIsRefused) {
  TempDir d;
  write(d.file("uniform.csv"), kUniform);
  expect_refused(run({"--blade-table", d.file("uniform.csv"), "campbell"}),
                 "--blade-table = .*uniform\\.csv: the Campbell diagram is for the uniform blade "
                 "only .*",
                 "campbell with a table");
}

// `modes` shows the uniform blade's tables: refused with a blade table rather than shown wrong.
TEST(CliBlade, ModesOfABladeTableIsRefused) {
  TempDir d;
  write(d.file("uniform.csv"), kUniform);
  expect_refused(run({"--blade-table", d.file("uniform.csv"), "modes"}),
                 "--blade-table = .*uniform\\.csv: `flaplag modes` shows the uniform blade's "
                 "modes.*",
                 "modes with a table");
}

TEST(CliBlade, ExportedModeShapesImportToTheSameCriticalAdvanceRatio) {
  TempDir d;
  const Outcome e = run({"--modes", "exact", "modes", "--export-shapes", d.file("m.csv")});
  ASSERT_EQ(0, e.exit_code) << e.err;
  const Json exact = critical({"--modes", "exact"});
  const Json imported = critical({"--modes", "exact", "--mode-shapes", d.file("m.csv")});
  EXPECT_EQ("imported", imported["mode_shapes"]);
  EXPECT_NEAR(exact["mu_c"].get<double>(), imported["mu_c"].get<double>(), 1e-8);
  EXPECT_TRUE(imported["case"].contains("mode-shapes-csv"));
}

}  // namespace
