// --periodic-linearization at the command line: each point of a sweep document names the periodic
// equilibrium q°(psi) it rests on (`equilibrium`: K and the truncation), checked against the
// library's own periodic_equilibrium at the row's mu, continued from hover on its own.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_run.h"
#include "flaplag/analysis.h"

namespace flaplag::cli_equilibrium_test {
namespace {

using Json = nlohmann::json;
using flaplag::testing::run_json;

// The sweep's rows against an independent q° at each mu: the same K and the same size of the
// last harmonic (the continuations differ by the Newton tolerance, far below these numbers,
// which change by an order of magnitude from one row to the next).
TEST(CliEquilibrium, SweepRowsCarryTheEquilibriumAtTheirMu) {
  const Json j = run_json({"--periodic-linearization", "sweep", "--mu", "0.1:0.3:0.1"});
  ASSERT_EQ(j["status"], "ok") << j;
  const Json& rows = j["rows"];
  ASSERT_EQ(rows.size(), 3u) << j;
  const Analysis an(RotorParameters{}, {},
                    OperatingCondition{}.About(Linearization::PeriodicEquilibrium));
  std::vector<double> truncations;
  for (const Json& row : rows) {
    const double mu = row["mu"].get<double>();
    ASSERT_TRUE(row.contains("equilibrium")) << row;
    const PeriodicEquilibrium alone = an.periodic_equilibrium(mu);
    ASSERT_EQ(Status::Ok, alone.status) << alone.message;
    const Json& q = row["equilibrium"];
    EXPECT_EQ(q["harmonics"].get<int>(), alone.harmonics) << mu;
    const double truncation = q["truncation"].get<double>();
    EXPECT_NEAR(truncation, alone.truncation, 1e-6 * alone.truncation) << mu;
    EXPECT_GT(truncation, 0.0) << mu;  // a real q° away from hover, not a default
    truncations.push_back(truncation);
  }
  // each row its own q°: one row's would not pass for another's
  for (std::size_t k = 1; k < truncations.size(); ++k)
    EXPECT_GT(truncations[k], 2.0 * truncations[k - 1]) << k;
}

// About hover no row has an equilibrium; trimmed about q° the trim carries it (its
// `equilibrium`), not the row.
TEST(CliEquilibrium, NoRowEquilibriumAboutHoverOrWithATrim) {
  const Json hover = run_json({"sweep", "--mu", "0.1:0.3:0.1"});
  for (const Json& row : hover["rows"]) EXPECT_FALSE(row.contains("equilibrium")) << row;
  const Json trimmed =
      run_json({"--periodic-linearization", "--trim", "thrust", "sweep", "--mu", "0.1:0.2:0.1"});
  ASSERT_EQ(trimmed["rows"].size(), 2u) << trimmed;
  for (const Json& row : trimmed["rows"]) EXPECT_FALSE(row.contains("equilibrium")) << row;
  for (const Json& t : trimmed["trim"]) EXPECT_TRUE(t.contains("equilibrium")) << t;
}

// Beyond the fold of the branch from hover (mu = 0.666) there is no q°: the failed row says null,
// not a K with a truncation of 0 that would read as a perfect q°; the row before has its own.
TEST(CliEquilibrium, NoEquilibriumBeyondTheFold) {
  const flaplag::testing::Outcome o =
      flaplag::testing::run({"--periodic-linearization", "sweep", "--mu", "0.6:0.7:0.1", "--json"});
  const Json j = Json::parse(o.out);
  ASSERT_EQ(j["rows"].size(), 2u) << j;
  const Json& below = j["rows"][0];
  const Json& beyond = j["rows"][1];
  EXPECT_EQ(below["status"], "ok") << below;
  ASSERT_TRUE(below["equilibrium"].is_object()) << below;
  EXPECT_GT(below["equilibrium"]["truncation"].get<double>(), 0.0) << below;
  EXPECT_EQ(beyond["status"], "failed") << beyond;
  ASSERT_TRUE(beyond.contains("equilibrium")) << beyond;
  EXPECT_TRUE(beyond["equilibrium"].is_null()) << beyond;
}

}  // namespace
}  // namespace flaplag::cli_equilibrium_test
