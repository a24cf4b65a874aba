// The HTML report (cli/report.h), run as a user would: `flaplag report CASE|RESULT.json` and
// --report FILE.html on the analysis commands; pages opened in a real browser (headless
// Chromium, Debian `chromium`) that must load without a console message and show their figures.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "cli_run.h"
#include "process.h"

namespace report_test {

namespace {

using Json = nlohmann::ordered_json;
using flaplag::testing::Outcome;
using flaplag::testing::run;
using flaplag::testing::slurp;
using flaplag::testing::TempDir;

void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The error contract: exit 2, one line "flaplag: error: ...", nothing on stdout.
::testing::AssertionResult OneLineError(const Outcome& r) {
  static const std::regex kLine("flaplag: error: [^\n]+\n");
  if (r.exit_code == 2 && r.out.empty() && std::regex_match(r.err, kLine))
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "exit " << r.exit_code << ", stderr [" << r.err << "]";
}

// The page without what differs between two makings of it: the date and where it was made from.
std::string without_origin(std::string page) {
  page = std::regex_replace(page, std::regex("<tr><th>made on</th><td>[^<]*</td></tr>"), "");
  page = std::regex_replace(page, std::regex("<tr><th>made from</th><td>[^<]*</td></tr>"), "");
  page = std::regex_replace(page, std::regex("<title>[^<]*</title>"), "");
  // The command that reproduces a --json output names --json.
  page = std::regex_replace(page, std::regex(" --json"), "");
  return std::regex_replace(page, std::regex("<p class=\"sub\">[^<]*"), "");
}

TEST(Report, SectionsOfACriticalResult) {
  TempDir d;
  const std::string page = d.file("critical.html");
  const Outcome r = run({"critical", "--report", page});
  ASSERT_EQ(0, r.exit_code) << r.err;
  const std::string html = slurp(page);
  for (const char* id :
       {"outcome", "key", "warnings", "model", "inputs", "convergence", "results", "provenance"})
    EXPECT_NE(std::string::npos, html.find("<section id=\"" + std::string(id) + "\">")) << id;
  // The paper's typical case: mu_c with its error estimate, in the key results.
  const Json j = Json::parse(run({"critical", "--json"}).out);
  char mu_c[32];
  std::snprintf(mu_c, sizeof mu_c, "%.6g", j["mu_c"].get<double>());
  EXPECT_NE(std::string::npos, html.find("&mu;<sub>c</sub> = " + std::string(mu_c))) << mu_c;
  // No picture for a critical result; nothing that could run or load.
  EXPECT_EQ(std::string::npos, html.find("<svg"));
  EXPECT_EQ(std::string::npos, html.find("<script"));
  EXPECT_NE(std::string::npos, html.find("Content-Security-Policy\" content=\"default-src 'none'"));
  // Every rotor parameter with its symbol and units: the lag frequency as the paper writes it.
  EXPECT_NE(std::string::npos, html.find("&omega;&#772;<sub>L1</sub>"));
}

// --report leaves the command's own output as it was, byte for byte (text and JSON).
TEST(Report, BesideTheOutputChangesNothingOfIt) {
  TempDir d;
  for (const std::vector<std::string>& base :
       {std::vector<std::string>{"sweep", "--mu", "0:0.4:0.2"},
        std::vector<std::string>{"sweep", "--mu", "0:0.4:0.2", "--json"},
        std::vector<std::string>{"trim", "--mu", "0.2", "--json"},
        std::vector<std::string>{"modes"}}) {
    std::vector<std::string> with = base;
    with.insert(with.end(), {"--report", d.file("r.html")});
    const Outcome a = run(base), b = run(with);
    ASSERT_EQ(0, b.exit_code) << b.err;
    std::string expected = a.out;
    // The case of a JSON output records the options (--report is one of them).
    if (!expected.empty() && expected[0] == '{') {
      Json ja = Json::parse(a.out), jb = Json::parse(b.out);
      ja.erase("case");
      jb.erase("case");
      EXPECT_EQ(ja, jb);
    } else {
      EXPECT_EQ(a.out, b.out);
    }
    EXPECT_NE(std::string::npos, slurp(d.file("r.html")).find("</html>"));
  }
}

// The page of a run and the page of its --json output are the same page.
TEST(Report, OfAResultFileIsThePageOfTheRun) {
  TempDir d;
  const std::string example = std::string(FLAPLAG_SOURCE_DIR) + "/examples/fig03.toml";
  const Outcome a = run({"report", example, "-o", d.file("a.html")});
  ASSERT_EQ(0, a.exit_code) << a.err;
  const Outcome j = run({"run", example, "--json", "-o", d.file("r.json")});
  ASSERT_EQ(0, j.exit_code) << j.err;
  const Outcome b = run({"report", d.file("r.json"), "-o", d.file("b.html")});
  ASSERT_EQ(0, b.exit_code) << b.err;
  const std::string pa = slurp(d.file("a.html")), pb = slurp(d.file("b.html"));
  EXPECT_EQ(1u, count(pa, "<svg"));
  EXPECT_EQ(without_origin(pa), without_origin(pb));
  // To standard output without -o.
  const Outcome c = run({"report", d.file("r.json")});
  ASSERT_EQ(0, c.exit_code) << c.err;
  EXPECT_EQ(without_origin(pb), without_origin(c.out));
}

// A result file from someone else: every string is text on the page, nothing runs or loads.
TEST(Report, HostileStringsOfAResultAreText) {
  TempDir d;
  const Outcome r = run({"sweep", "--mu", "0:0.2:0.1", "--json"});
  ASSERT_EQ(0, r.exit_code) << r.err;
  Json j = Json::parse(r.out);
  const std::string payload =
      "</td></table><script>alert(1)</script><img src=\"http://127.0.0.1:9/x.png\">'\"&";
  j["message"] = payload;
  j["status"] = "warning";
  j["model"]["summary"] = payload;
  j["rows"][0]["message"] = payload;
  j["parameters"]["<b>key</b>"] = payload;
  j["case"]["theta"] = payload;
  j["flaplag"]["commit"] = payload;
  write(d.file("hostile.json"), j.dump());
  const Outcome p = run({"report", d.file("hostile.json"), "-o", d.file("h.html")});
  ASSERT_EQ(0, p.exit_code) << p.err;
  const std::string html = slurp(d.file("h.html"));
  EXPECT_EQ(std::string::npos, html.find("<script"));
  EXPECT_EQ(std::string::npos, html.find("<img"));
  EXPECT_EQ(std::string::npos, html.find("<b>key"));
  EXPECT_NE(std::string::npos, html.find("&lt;script&gt;alert(1)&lt;/script&gt;"));
  // The shell command that reproduces it quotes the value as one word.
  EXPECT_NE(std::string::npos, html.find("--theta &#39;&lt;/td&gt;"));
}

TEST(Report, RefusesWhatIsNotAResultAndWritesNothing) {
  TempDir d;
  write(d.file("other.json"), "{\"flaplag\": 1}");
  write(d.file("list.json"), "[1, 2]");
  const Outcome s = run({"sweep", "--mu", "0:0.2:0.1", "--json", "-o", d.file("s.json")});
  ASSERT_EQ(0, s.exit_code) << s.err;
  const Outcome m = run({"models", "--json", "-o", d.file("models.json")});
  ASSERT_EQ(0, m.exit_code) << m.err;
  const std::vector<std::vector<std::string>> bad = {
      {"report", d.file("other.json"), "-o", d.file("x.html")},
      {"report", d.file("list.json"), "-o", d.file("x.html")},
      {"report", d.file("models.json"), "-o", d.file("x.html")},
      {"report", d.file("missing.json"), "-o", d.file("x.html")},
      {"report", d.file("s.json"), "-o", d.file("x.txt")},                     // not a page
      {"report", d.file("s.json"), "--theta", "0.1", "-o", d.file("x.html")},  // not recomputed
      {"report"},
      {"critical", "--report", d.file("x.pdf")},
      {"study", "--vary", "theta=0.1,0.2", "--json", "--shard", "1/2", "--report",
       d.file("x.html")},
      {"report", d.file("s.json"), "-o", d.file("no/such/dir/x.html")},
  };
  for (const auto& args : bad) {
    const Outcome r = run(args);
    std::string line;
    for (const std::string& a : args) line += a + " ";
    EXPECT_TRUE(OneLineError(r)) << line;
  }
  EXPECT_FALSE(std::filesystem::exists(d.file("x.html")));
  EXPECT_FALSE(std::filesystem::exists(d.file("x.txt")));
  EXPECT_FALSE(std::filesystem::exists(d.file("x.pdf")));
}

// A case whose run is not ok says so at the top of its page, with the message.
TEST(Report, AResultNoBetterThanItsStatus) {
  TempDir d;
  // Unstable in hover: no critical advance ratio (the status is a warning).
  write(d.file("hover.toml"), "command = \"study\"\nvary = \"theta=0.1,0.2\"\n");
  const Outcome r = run({"report", d.file("hover.toml"), "-o", d.file("h.html")});
  ASSERT_EQ(0, r.exit_code) << r.err;
  const std::string html = slurp(d.file("h.html"));
  EXPECT_NE(std::string::npos, html.find("<p class=\"status s1\"><b>warning</b>")) << html;
  EXPECT_NE(std::string::npos, html.find("unstable in hover"));
}

// Regression: a damping crossing's status (crossed, unresolved, ...) was read as the outcome of a
// computation, so that a crossed criterion made the page "failed".  A crossing is a finding; an
// unresolved one is a warning.
TEST(Report, DampingCrossingsAreFindingsAndAnUnresolvedOneAWarning) {
  TempDir d;
  const std::string example = std::string(FLAPLAG_SOURCE_DIR) + "/examples/damping-criterion.toml";
  // As the example: the lag mode crosses 1 %.
  ASSERT_EQ(0, run({"report", example, "-o", d.file("a.html")}).exit_code);
  const std::string a = slurp(d.file("a.html"));
  EXPECT_NE(std::string::npos, a.find("<p class=\"status s0\"><b>ok</b>")) << a;
  EXPECT_NE(std::string::npos, a.find("<b>lag</b> falls below it at &mu; = 0.733"));
  // The same result with the lag crossing unresolved: a warning, not a failure.
  const Outcome j = run({"run", example, "--json"});
  ASSERT_EQ(0, j.exit_code) << j.err;
  Json result = Json::parse(j.out);
  ASSERT_EQ("lag", result["damping_crossings"][1]["mode"]);
  result["damping_crossings"][1]["status"] = "unresolved";
  write(d.file("unresolved.json"), result.dump());
  ASSERT_EQ(0, run({"report", d.file("unresolved.json"), "-o", d.file("b.html")}).exit_code);
  const std::string b = slurp(d.file("b.html"));
  EXPECT_NE(std::string::npos, b.find("<p class=\"status s1\"><b>warning</b>")) << b;
  EXPECT_NE(std::string::npos, b.find("unresolved for lag"));
}

// ---- in a real browser ------------------------------------------------------------------------

std::string chromium() {
  for (const char* p : {"/usr/bin/chromium", "/usr/bin/chromium-browser"})
    if (std::filesystem::exists(p)) return p;
  return "";
}

// Headless Chromium on `page` with its own profile in `dir`; extra: --screenshot=... or
// --dump-dom.  Console messages (a script error, a resource refused by the page's policy) are
// on stderr as ":CONSOLE" lines.
Outcome browse(const std::string& page, const TempDir& dir, const std::string& extra) {
  return flaplag::testing::run_process(
      chromium(),
      {"--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars", "--no-first-run",
       "--disable-extensions", "--disable-dev-shm-usage", "--enable-logging=stderr", "--v=0",
       "--user-data-dir=" + dir.file("profile"), "--window-size=1200,2400", extra,
       "file://" + page},
      std::chrono::seconds(120));
}

std::vector<std::string> console_lines(const std::string& err) {
  std::vector<std::string> lines;
  std::istringstream in(err);
  for (std::string l; std::getline(in, l);)
    if (l.find(":CONSOLE") != std::string::npos) lines.push_back(l);
  return lines;
}

class ReportBrowser : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    ASSERT_FALSE(chromium().empty())
        << "chromium is not installed (scripts/install-deps.sh installs it)";
  }
};

// Each example's page loads without a console message and renders; its picture is there when
// its command draws one.
TEST_P(ReportBrowser, ExamplePageLoadsWithItsFigures) {
  TempDir d;
  const std::string example = std::string(FLAPLAG_SOURCE_DIR) + "/examples/" + GetParam();
  const std::string page = d.file("page.html"), png = d.file("page.png");
  const Outcome r = run({"report", example, "-o", page});
  ASSERT_EQ(0, r.exit_code) << r.err;
  const std::string html = slurp(page);
  const std::string command = slurp(example);
  const bool drawn = std::regex_search(
      command, std::regex("command = \"(sweep|study|map|response|simulate|campbell)\""));
  EXPECT_EQ(drawn ? 1u : 0u, count(html, "<figure>\n<svg")) << GetParam();
  const Outcome b = browse(page, d, "--screenshot=" + png);
  ASSERT_EQ(0, b.exit_code) << b.err;
  EXPECT_EQ(std::vector<std::string>{}, console_lines(b.err));
  const std::string image = slurp(png);
  ASSERT_GT(image.size(), 8u);
  EXPECT_EQ("\x89PNG", image.substr(0, 4));
  // A rendered page of text and tables, not a blank one (a white 1200 x 2400 PNG is ~10 kB).
  EXPECT_GT(image.size(), 60000u) << GetParam();
}

std::vector<std::string> examples() {
  std::vector<std::string> names;
  for (const auto& e :
       std::filesystem::directory_iterator(std::string(FLAPLAG_SOURCE_DIR) + "/examples"))
    if (e.path().extension() == ".toml") names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

INSTANTIATE_TEST_SUITE_P(Examples, ReportBrowser, ::testing::ValuesIn(examples()),
                         [](const ::testing::TestParamInfo<std::string>& p) {
                           std::string n = p.param.substr(0, p.param.size() - 5);
                           for (char& c : n)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

// The figures are laid out at a readable size: a copy of the page with its policy relaxed for a
// measuring script, whose answer the browser writes into the title of the dumped DOM.
TEST_F(ReportBrowser, FiguresAreLaidOutAtAReadableSize) {
  TempDir d;
  const std::string page = d.file("page.html"), probe = d.file("probe.html");
  const Outcome r = run({"sweep", "--mu", "0:1:0.1", "--report", page});
  ASSERT_EQ(0, r.exit_code) << r.err;
  std::string html = slurp(page);
  html = std::regex_replace(html, std::regex("<meta http-equiv=\"Content-Security-Policy\"[^>]*>"),
                            "");
  html.insert(html.rfind("</body>"),
              "<script>document.title = Array.from(document.querySelectorAll('figure svg'))"
              ".map(function (e) { var b = e.getBoundingClientRect(); return Math.round(b.width) "
              "+ 'x' + Math.round(b.height); }).join(',');</script>");
  write(probe, html);
  const Outcome b = browse(probe, d, "--dump-dom");
  ASSERT_EQ(0, b.exit_code) << b.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(b.out, m, std::regex("<title>(\\d+)x(\\d+)</title>"))) << b.out;
  EXPECT_GE(std::stoi(m[1]), 600);  // the page's width less its margins
  EXPECT_GE(std::stoi(m[2]), 400);
}

// A hostile result's page in the browser: no script ran, nothing was fetched (either would be a
// console message: the policy refuses both), and the payload is text in the DOM.
TEST_F(ReportBrowser, HostileResultRunsAndLoadsNothing) {
  TempDir d;
  const Outcome r = run({"critical", "--json"});
  ASSERT_EQ(0, r.exit_code) << r.err;
  Json j = Json::parse(r.out);
  j["message"] = "<script>console.log('ran')</script><img src=\"http://127.0.0.1:9/x.png\">";
  j["status"] = "failed";
  write(d.file("hostile.json"), j.dump());
  ASSERT_EQ(0, run({"report", d.file("hostile.json"), "-o", d.file("h.html")}).exit_code);
  const Outcome b = browse(d.file("h.html"), d, "--dump-dom");
  ASSERT_EQ(0, b.exit_code) << b.err;
  EXPECT_EQ(std::vector<std::string>{}, console_lines(b.err));
  EXPECT_EQ(std::string::npos, b.out.find("<script"));
  EXPECT_EQ(std::string::npos, b.out.find("<img"));
  EXPECT_NE(std::string::npos, b.out.find("&lt;script&gt;console.log('ran')"));
}

}  // namespace

}  // namespace report_test
