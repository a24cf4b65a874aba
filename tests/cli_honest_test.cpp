// Honest results at the command line: a result is never better than what it rests on (its
// trim, the validity of its controls, the resolution of its exponents), and messages say what
// happened.  Each test runs an example that used to come back "ok" (or misleading).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_run.h"
#include "process.h"

namespace cli_honest_test {

namespace {

using Json = nlohmann::json;
using flaplag::testing::Outcome;
using flaplag::testing::run;
using flaplag::testing::run_json;

// A soft-in-plane blade trimmed to C_T/sigma = 0.08: mu_c used to be "ok" next to a trim at
// mu_c that had not converged (a separate trim from the one the search made) -- and the
// search's own trim there lies far outside the validity envelope (theta0 ~ 65 deg).  The
// result reports the trim it rests on, and is no better than it.
TEST(CliHonest, TrimmedCriticalIsNoBetterThanItsTrim) {
  const Json j = run_json({"--trim", "moment", "--thrust-coefficient", "0.0056", "--omega-flap",
                           "1.12", "--omega-lag", "0.72", "--gamma", "6", "--sigma", "0.07",
                           "--theta", "0.10", "--damping-lag", "0.01", "critical"});
  ASSERT_TRUE(j["mu_c"].is_number()) << j;
  const Json& t = j["trim"];
  ASSERT_TRUE(t.is_object()) << j;
  // The trim at mu_c is the one the search made there.
  EXPECT_EQ(t["mu"], j["mu_c"]);
  // The rule: a trim with a problem (not converged, or outside the envelope) leaves the result
  // no better than a warning, and says so.
  const bool sound = t["converged"].get<bool>() && std::abs(t["theta0"].get<double>()) <= 0.35 &&
                     std::abs(t["theta1c"].get<double>()) <= 0.35 &&
                     std::abs(t["theta1s"].get<double>()) <= 0.35;
  ASSERT_FALSE(sound) << "the example's trim at mu_c is no longer questionable: " << t;
  EXPECT_NE(j["status"], "ok") << j["message"];
  EXPECT_NE(j["message"].get<std::string>().find("the trim at mu = "), std::string::npos)
      << j["message"];
}

// The same blade swept: each row reports the trim it rests on.  The sweep's trim table used
// to come from separate trims, so that the row at mu = 0.8 failed on its trim while the table
// showed an "ok" trim there, and a row resting on a trim outside the envelope said "ok".
TEST(CliHonest, TrimmedSweepRowsRestOnTheirTrims) {
  const Json j =
      run_json({"--trim", "moment", "--thrust-coefficient", "0.0056", "--omega-flap", "1.12",
                "--omega-lag", "0.72", "--gamma", "6", "--sigma", "0.07", "--theta", "0.10",
                "--damping-lag", "0.01", "sweep", "--mu", "0.5:0.9:0.1"});
  const Json& rows = j["rows"];
  const Json& trims = j["trim"];
  ASSERT_EQ(rows.size(), trims.size()) << j;
  bool failed_seen = false;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const Json& r = rows[k];
    const Json& t = trims[k];
    EXPECT_EQ(r["mu"], t["mu"]);
    const std::string rm = r["message"].get<std::string>();
    // A row that failed on its trim shows that failed trim.
    if (r["status"] == "failed" && rm.find("trim failed") != std::string::npos) {
      failed_seen = true;
      EXPECT_EQ(t["status"], "failed") << "mu = " << r["mu"] << ": " << t;
    }
    // A trim that did not converge, or lies outside the envelope, leaves its row no better
    // than a warning.
    const bool outside =
        t["message"].get<std::string>().find("validity envelope") != std::string::npos;
    if (!t["converged"].get<bool>() || outside) {
      EXPECT_NE(r["status"], "ok") << "mu = " << r["mu"] << ": " << t;
    }
  }
  EXPECT_TRUE(failed_seen) << "the example no longer fails a trim: " << j;
  // mu = 0.7: the trimmed controls put the angle of attack past the envelope.
  ASSERT_GE(rows.size(), 3u);
  EXPECT_EQ(rows[2]["mu"], 0.7);
  EXPECT_EQ(rows[2]["status"], "warning") << rows[2];
}

// The trim to C_T = 0.1 at mu = 0.3 gives theta0 = 80 deg: a warning naming theta0, its value
// and the limit (it used to say "ok").
TEST(CliHonest, TrimOutsideTheValidityEnvelopeWarns) {
  const Json j = run_json({"trim", "--mu", "0.3", "--thrust-coefficient", "0.1"});
  ASSERT_GT(j["theta0"].get<double>(), 1.0) << j;
  EXPECT_EQ(j["status"], "warning") << j;
  const std::string m = j["message"].get<std::string>();
  EXPECT_NE(m.find("theta0 = 1.40"), std::string::npos) << m;
  EXPECT_NE(m.find("<= 0.35 rad"), std::string::npos) << m;
  // Fixed controls outside it warn as well.
  const Json p = run_json({"point", "--mu", "0.3", "--theta", "0.5"});
  EXPECT_EQ(p["status"], "warning") << p;
  EXPECT_NE(p["message"].get<std::string>().find("theta0 = 0.5 rad"), std::string::npos) << p;
}

// A trim at a vanishing advance ratio is the hover trim: at mu = 1e-150 the momentum inflow's
// bracket was too wide for its root finder and a wrong trim (theta0 = 0.095, inflow 0) came
// back "ok"; at 5e-324 the run failed naming the root finder's bracket ("fa = -inf").
TEST(CliHonest, TrimAtAVanishingAdvanceRatioIsTheHoverTrim) {
  const Json hover = run_json({"trim", "--mu", "0"});
  for (const char* mu : {"1e-150", "5e-324"}) {
    const Json j = run_json({"trim", "--mu", mu});
    EXPECT_EQ(j["status"], "ok") << j;
    EXPECT_NEAR(j["theta0"].get<double>(), hover["theta0"].get<double>(), 1e-12) << mu;
    EXPECT_NEAR(j["inflow"].get<double>(), hover["inflow"].get<double>(), 1e-12) << mu;
  }
}

// A lift slope so small that C_Do / a overflows the loads was an internal error naming a
// derived matrix ("A0 = non-finite"); it is bad input naming --lift-slope.
TEST(CliHonest, ALiftSlopeThatOverflowsTheLoadsIsBadInput) {
  const Outcome o = run({"point", "--mu", "0.3", "--lift-slope", "5e-324"});
  EXPECT_EQ(o.exit_code, 2) << o.err;
  EXPECT_EQ(o.err.rfind("flaplag: error: --lift-slope = 5e-324: too small for --cdo=0.01", 0), 0u)
      << o.err;
}

// A blade of vanishing length: hover used to be "unstable" from zeta = 2e-92 and mu = 0.5
// "stable: true" with |zeta| below its own error estimate.  Both are unknown.
TEST(CliHonest, StabilityFromRoundingNoiseIsUnknown) {
  const Json c = run_json({"--length-ratio", "1e-9", "critical"});
  EXPECT_EQ(c["status"], "warning") << c;
  EXPECT_FALSE(c["hover_unstable"].get<bool>()) << c;
  EXPECT_TRUE(c["mu_c"].is_null()) << c;
  EXPECT_NE(c["message"].get<std::string>().find("unknown"), std::string::npos) << c["message"];
  for (const char* mu : {"0", "0.5"}) {
    const Json p = run_json({"--length-ratio", "1e-9", "point", "--mu", mu});
    double largest = -1.0;
    for (const Json& e : p["exponents"])
      if (e["zeta"].is_number()) largest = std::max(largest, e["zeta"].get<double>());
    ASSERT_TRUE(p["error_estimate"].is_number()) << p;
    ASSERT_LE(std::abs(largest), p["error_estimate"].get<double>()) << p;
    EXPECT_TRUE(p["stable"].is_null()) << "mu = " << mu << ": " << p;
    EXPECT_EQ(p["status"], "warning") << p;
    EXPECT_TRUE(p["hover"]["stable"].is_null()) << p["hover"];
    EXPECT_EQ(p["hover"]["status"], "warning") << p["hover"];
  }
}

// The scan at step 0.01 saw an instability at 1.18 only at the scan resolution, called it
// "vanished when resolved" and put mu_c at 1.50535, while a narrow interval starts at 1.18087
// (a scan at step 0.001 finds it): the neighbourhood is searched before anything vanishes.
// The numbers are the paper's five-function basis.
TEST(CliHonest, NarrowIntervalNextToTheGridIsFound) {
  const Json j = run_json({"critical", "--gamma",
                           "9.95",     "--sigma",
                           "0.03",     "--theta",
                           "0.25",     "--omega-flap",
                           "1.5",      "--omega-lag",
                           "1.531",    "--damping-lag",
                           "0.01435",  "--precone",
                           "0.04798",  "--droop",
                           "0.05",     "--modes",
                           "exact",    "--basis",
                           "paper",    "--no-elastic-coupling"});
  ASSERT_TRUE(j["mu_c"].is_number()) << j;
  EXPECT_NEAR(j["mu_c"].get<double>(), 1.180865, 1e-4) << j["message"];
  EXPECT_EQ(j["message"].get<std::string>().find("vanished"), std::string::npos) << j["message"];
}

// --zeta-tolerance's help states the rule, relative part included (estimates of 3.5e-4 used to
// come back "ok" next to a help that said only "target error").
TEST(CliHonest, ZetaToleranceHelpStatesTheRule) {
  const Outcome o = run({"--help"});
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const auto at = o.out.find("--zeta-tolerance REAL");
  ASSERT_NE(at, std::string::npos) << o.out;
  // The help is wrapped to the terminal: the rule is read with its line breaks as spaces.
  std::string help;
  for (char c : o.out.substr(at, 400)) {
    if (c == '\n' || c == ' ') {
      if (help.empty() || help.back() != ' ') help += ' ';
    } else {
      help += c;
    }
  }
  EXPECT_NE(help.find("max(1, 100 |zeta|)"), std::string::npos) << help;
  EXPECT_NE(help.find("relative"), std::string::npos) << help;
}

// Multi-mode results carry their Liouville residual (it used to be null on every one, with no
// word why).
TEST(CliHonest, MultiModeResultsCarryTheLiouvilleResidual) {
  const Json j = run_json(
      {"--modes", "exact", "--flap-modes", "2", "--lag-modes", "2", "point", "--mu", "0.3"});
  ASSERT_TRUE(j["liouville_residual"].is_number()) << j;
  EXPECT_LT(j["liouville_residual"].get<double>(), 1e-4);
}

// A transition matrix singular to working precision (an extremely damped lag mode on a blade
// with gamma = 0.002): the note used to print its condition number as "inf".
TEST(CliHonest, SingularTransitionMatrixIsSaidInWords) {
  const Outcome o = run({"sweep",
                         "--mu",
                         "0.0958233:0.1437:0.0130618",
                         "--gamma",
                         "0.002098",
                         "--omega-flap",
                         "100",
                         "--damping-lag",
                         "7.169",
                         "--exact-reversed-flow",
                         "--no-elastic-coupling",
                         "--terms",
                         "8",
                         "--zeta-tolerance",
                         "5.303e-07",
                         "--flap-modes",
                         "2",
                         "--steps",
                         "393",
                         "--modes",
                         "exact",
                         "--basis",
                         "paper"});  // the blade of the singular matrix: five functions
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_EQ(o.out.find("inf"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("singular to working precision"), std::string::npos) << o.out;
}

}  // namespace

}  // namespace cli_honest_test
