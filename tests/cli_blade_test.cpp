// Blade tables and imported mode shapes from the command line and case files, as a designer
// hands them over: the uniform table is the paper's exact-mode blade, a dimensional table's
// groups follow from its SI data, a bad table is one line naming its row, and a result records
// the table's text (it never names a file to read).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "process.h"

namespace cli_blade_test {

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

Json json_of(const std::vector<std::string>& args) {
  std::vector<std::string> a = args;
  a.push_back("--json");
  const Outcome r = run(a);
  EXPECT_EQ(0, r.exit_code) << r.err;
  return r.exit_code == 0 ? Json::parse(r.out) : Json::object();
}

// The Campbell diagram of the uniform table is the uniform exact-mode blade's, speed by speed.
TEST(CliBlade, CampbellOfABladeTableIsTheUniformBladesForTheUniformTable) {
  TempDir d;
  write(d.file("uniform.csv"), kUniform);
  const std::vector<std::string> diagram = {"campbell", "--speed-max", "1.2", "--speeds", "4"};
  std::vector<std::string> a = {"--modes", "exact"}, b = {"--blade-table", d.file("uniform.csv")};
  a.insert(a.end(), diagram.begin(), diagram.end());
  b.insert(b.end(), diagram.begin(), diagram.end());
  const Json uniform = json_of(a), table = json_of(b);
  ASSERT_TRUE(table.contains("blade_table"));
  ASSERT_EQ(uniform["labels"], table["labels"]);
  ASSERT_EQ(4u, table["points"].size());
  for (std::size_t i = 0; i < 4; ++i) {
    const Json &u = uniform["points"][i], &t = table["points"][i];
    EXPECT_EQ(u["speed"], t["speed"]);
    EXPECT_EQ(u["status"], t["status"]) << t["message"];
    ASSERT_EQ(u["modes"].size(), t["modes"].size());
    for (std::size_t m = 0; m < t["modes"].size(); ++m) {
      const double fu = u["modes"][m]["frequency"].get<double>();
      EXPECT_NEAR(fu, t["modes"][m]["frequency"].get<double>(), 1e-8 * fu) << i << " " << m;
    }
  }
}

// Imported shapes are given at one rotor speed: the diagram is refused in one line.
TEST(CliBlade, CampbellOfImportedShapesIsRefused) {
  TempDir d;
  ASSERT_EQ(0, run({"--modes", "exact", "modes", "--export-shapes", d.file("m.csv")}).exit_code);
  expect_refused(run({"--modes", "exact", "--mode-shapes", d.file("m.csv"), "campbell"}),
                 "--mode-shapes = .*m\\.csv: the Campbell diagram needs the blade's frequencies "
                 "at every rotor speed; imported mode shapes give them at one speed only.*",
                 "campbell with imported shapes");
  expect_refused(run({"--modes", "exact", "--mode-shapes", d.file("m.csv"), "modes"}),
                 "--mode-shapes = .*m\\.csv: `flaplag modes` computes the exact modes of the "
                 "blade.*",
                 "modes with imported shapes");
}

// `modes` of the uniform table: the uniform blade's tables (the stiffness as the scale of the
// table's column, 1 here, so the same number), the table in the document, and the exported
// shapes the same numbers.
TEST(CliBlade, ModesOfTheUniformTableAreTheUniformBlades) {
  TempDir d;
  write(d.file("uniform.csv"), kUniform);
  const Json uniform = json_of(
      {"modes", "--flap-modes", "2", "--lag-modes", "2", "--export-shapes", d.file("u.csv")});
  const Json table = json_of({"--blade-table", d.file("uniform.csv"), "modes", "--flap-modes", "2",
                              "--lag-modes", "2", "--export-shapes", d.file("t.csv")});
  ASSERT_TRUE(table.contains("blade_table"));
  EXPECT_EQ(3, table["blade_table"]["stations"]);
  EXPECT_FALSE(uniform.contains("blade_table"));
  EXPECT_EQ("ok", table["status"]);
  ASSERT_EQ(uniform["fig9"].size(), table["fig9"].size());
  for (std::size_t i = 0; i < table["fig9"].size(); ++i) {
    for (const char* key : {"nonrotating", "flap_rotating", "lag_rotating"}) {
      const double u = uniform["fig9"][i][key].get<double>();
      EXPECT_NEAR(u, table["fig9"][i][key].get<double>(), 1e-10 * std::max(1.0, u))
          << "fig9 row " << i << " " << key;
    }
  }
  for (const char* dir : {"flap", "lag"}) {
    SCOPED_TRACE(dir);
    const Json &u = uniform[dir], &t = table[dir];
    EXPECT_FALSE(t.contains("stiffness"));  // a scale, named as such
    ASSERT_TRUE(t.contains("stiffness_scale"));
    EXPECT_NEAR(u["stiffness"].get<double>(), t["stiffness_scale"].get<double>(),
                1e-10 * u["stiffness"].get<double>());
    EXPECT_NEAR(u["nonrotating_first"].get<double>(), t["nonrotating_first"].get<double>(), 1e-10);
    ASSERT_EQ(u["rotating_all"].size(), t["rotating_all"].size());
    for (std::size_t i = 0; i < t["rotating_all"].size(); ++i) {
      const double w = u["rotating_all"][i].get<double>();
      EXPECT_NEAR(w, t["rotating_all"][i].get<double>(), 1e-10 * w) << i;
    }
    ASSERT_EQ(2u, t["modes"].size());
    for (std::size_t m = 0; m < 2; ++m) {
      const double w = t["modes"][m]["omega"].get<double>();
      // The Rayleigh quotient of an exact mode with the table's distributions is its frequency.
      EXPECT_NEAR(w, t["modes"][m]["rayleigh_omega"].get<double>(), 1e-9 * w) << m;
      EXPECT_NEAR(u["modes"][m]["rayleigh_omega"].get<double>(),
                  t["modes"][m]["rayleigh_omega"].get<double>(), 1e-9 * w);
      // (x0 is the document's, not the direction's: a missing key read through a const
      // reference was undefined, and the loop ran over nothing.)
      ASSERT_TRUE(table.contains("x0"));
      ASSERT_GT(table["x0"].size(), 10u);
      for (std::size_t q = 0; q < table["x0"].size(); q += 10) {
        EXPECT_NEAR(u["modes"][m]["value"][q].get<double>(),
                    t["modes"][m]["value"][q].get<double>(), 1e-9);
      }
    }
  }
  // The exported files: the same numbers, the table's stiffness comment naming the scale.
  const std::string ut = flaplag::testing::slurp(d.file("u.csv"));
  const std::string tt = flaplag::testing::slurp(d.file("t.csv"));
  EXPECT_NE(std::string::npos, tt.find("# stiffness scale s of the blade table's EI columns"));
  EXPECT_EQ(std::string::npos, ut.find("stiffness scale"));
  auto numbers = [](const std::string& text) {
    std::vector<double> v;
    const std::regex number("-?[0-9][0-9.e+-]*");
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
      if (line.empty() || line[0] == '#') continue;
      for (std::sregex_iterator it(line.begin(), line.end(), number), end; it != end; ++it)
        v.push_back(std::stod(it->str()));
    }
    return v;
  };
  const std::vector<double> un = numbers(ut), tn = numbers(tt);
  ASSERT_EQ(un.size(), tn.size());
  ASSERT_GT(tn.size(), 4000u);  // 1001 stations of x0 and 4 shapes
  for (std::size_t i = 0; i < tn.size(); ++i) EXPECT_NEAR(un[i], tn[i], 1e-9) << i;
  // The text labels the stiffness as the scale and names the table.
  const Outcome text = run({"--blade-table", d.file("uniform.csv"), "modes"});
  ASSERT_EQ(0, text.exit_code) << text.err;
  EXPECT_NE(std::string::npos, text.out.find("stiffness scale s of the table's EI")) << text.out;
  EXPECT_NE(std::string::npos, text.out.find("blade table " + d.file("uniform.csv"))) << text.out;
}

// A dimensional table's columns are absolute: the scale of its stiffness is 1 (to rounding), and
// its first frequencies are the ones every analysis of it reports.
TEST(CliBlade, ModesOfADimensionalTableHaveScaleOne) {
  TempDir d;
  write(d.file("rotor.csv"),
        "r, m, EI_flap, EI_lag, chord\n0.3, 4, 30000, 400000, 0.2\n1.5, 3, 20000, 300000, 0.2\n"
        "3, 2, 9000, 200000, 0.2\ntip_mass, 0.5\nrotor_speed_rpm, 400\nair_density, 1.2\n"
        "blades, 3\n");
  const Json j = json_of({"--blade-table", d.file("rotor.csv"), "modes"});
  EXPECT_EQ("ok", j["status"]);
  for (const char* dir : {"flap", "lag"}) {
    EXPECT_NEAR(1.0, j[dir]["stiffness_scale"].get<double>(), 1e-10) << dir;
    const double w = j[dir]["rotating_first"].get<double>();
    EXPECT_NEAR(w, j[dir]["rotating_all"][0].get<double>(), 1e-12 * w) << dir;
    EXPECT_NEAR(w, j[dir]["modes"][0]["rayleigh_omega"].get<double>(), 1e-9 * w) << dir;
    EXPECT_LT(j[dir]["nonrotating_first"].get<double>(), w) << dir;  // centrifugal stiffening
  }
  const Json c = json_of({"--blade-table", d.file("rotor.csv"), "point", "--mu", "0"});
  EXPECT_EQ(c["parameters"]["omega-flap"], j["flap"]["rotating_first"]);
  EXPECT_EQ(c["parameters"]["omega-lag"], j["lag"]["rotating_first"]);
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

}  // namespace cli_blade_test
