// Studies and maps (analysis/study.h): determinism across thread counts, agreement with the
// single-point analyses they are made of, instability intervals against a fine sweep,
// cancellation, and option checks.
#include "flaplag/study.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>

#include "flaplag/core/errors.h"
#include "test_util.h"

namespace flaplag::study_test {
namespace {

using testing::AbsClose;

bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same(const CriticalResult& a, const CriticalResult& b) {
  if (a.mu_c.has_value() != b.mu_c.has_value() || a.intervals.size() != b.intervals.size() ||
      a.status != b.status || a.message != b.message || a.mode != b.mode || !same(a.omega, b.omega))
    return false;
  if (a.mu_c && !same(*a.mu_c, *b.mu_c)) return false;
  for (std::size_t i = 0; i < a.intervals.size(); ++i)
    if (!same(a.intervals[i].onset, b.intervals[i].onset) ||
        a.intervals[i].end.has_value() != b.intervals[i].end.has_value() ||
        (a.intervals[i].end && !same(*a.intervals[i].end, *b.intervals[i].end)))
      return false;
  return true;
}

StudyOptions lag_frequency_study(int threads) {
  StudyOptions o;
  o.parameter = "omega_lag";
  o.values = {0.5, 0.75, 1.0, 1.28303, 1.45, 1.7};
  o.critical.mu_max = 1.5;
  o.threads = threads;
  return o;
}

TEST(Study, IdenticalForOneAndTwoThreadsAndEqualToSingleAnalyses) {
  RotorParameters p;
  p.modes = ModeKind::Exact;
  const StudyResult one = run_study(p, {}, lag_frequency_study(1));
  const StudyResult two = run_study(p, {}, lag_frequency_study(2));
  ASSERT_EQ(6u, one.rows.size());
  ASSERT_EQ(one.rows.size(), two.rows.size());
  EXPECT_FALSE(one.cancelled);
  for (std::size_t i = 0; i < one.rows.size(); ++i) {
    EXPECT_TRUE(same(one.rows[i].critical, two.rows[i].critical)) << "row " << i;
    // The same as one Analysis at that value.
    RotorParameters q = p;
    q.omega_lag = one.rows[i].value;
    CriticalOptions c = lag_frequency_study(1).critical;
    c.all_intervals = true;
    EXPECT_TRUE(same(one.rows[i].critical, Analysis(q, {}).critical(c))) << "row " << i;
  }
}

// The intervals of a study row agree with the sign changes of a fine mu sweep.  Exact modes at
// omega_L1 = 1.45: lag flutter that re-stabilizes and then returns.
TEST(Study, IntervalsAgreeWithTheSignChangesOfAFineSweep) {
  RotorParameters p;
  p.modes = ModeKind::Exact;
  StudyOptions o;
  o.parameter = "omega_lag";
  o.values = {1.45};
  o.critical.mu_max = 1.5;
  const StudyResult r = run_study(p, {}, o);
  ASSERT_EQ(1u, r.rows.size());
  const auto& iv = r.rows[0].critical.intervals;
  ASSERT_GE(iv.size(), 2u) << r.rows[0].critical.message;
  ASSERT_TRUE(iv[0].end.has_value());

  p.omega_lag = 1.45;
  const double step = 0.002;
  const SweepResult s = Analysis(p, {}).sweep(0.0, 1.5, step);
  std::vector<double> changes;
  for (std::size_t k = 1; k < s.points.size(); ++k)
    if (*s.points[k].stable != *s.points[k - 1].stable) changes.push_back(s.points[k].mu);
  ASSERT_EQ(3u, changes.size());
  EXPECT_TRUE(AbsClose(changes[0], iv[0].onset, step));
  EXPECT_TRUE(AbsClose(changes[1], *iv[0].end, step));
  EXPECT_TRUE(AbsClose(changes[2], iv[1].onset, step));
  EXPECT_EQ(iv[0].onset, *r.rows[0].critical.mu_c);
}

TEST(Study, FailedValuesAreRowsNotExceptions) {
  RotorParameters p;
  p.modes = ModeKind::Exact;
  StudyOptions o;
  o.parameter = "omega_lag";
  o.values = {0.1, 1.28303};  // 0.1 is below what 5 cantilever functions reach
  const StudyResult r = run_study(p, {}, o);
  ASSERT_EQ(2u, r.rows.size());
  EXPECT_EQ(Status::Failed, r.rows[0].critical.status);
  EXPECT_FALSE(r.rows[0].critical.mu_c.has_value());
  EXPECT_NE(Status::Failed, r.rows[1].critical.status);
  EXPECT_EQ(Status::Failed, r.status);
}

TEST(Study, InvalidOptions) {
  StudyOptions o = lag_frequency_study(1);
  o.parameter = "mu";
  EXPECT_THROW(run_study({}, {}, o), InvalidInput);
  o.parameter = "no_such_field";
  EXPECT_THROW(run_study({}, {}, o), InvalidInput);
  o = lag_frequency_study(1);
  o.values.clear();
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_EQ(0u, why.find("values = ")) << why;
  o = lag_frequency_study(1);
  o.threads = -1;
  EXPECT_THROW(o.Check(), InvalidInput);
  o = lag_frequency_study(1);
  o.critical.scan_step = 0.0;
  EXPECT_THROW(o.Check(), InvalidInput);
}

MapOptions lag_frequency_map(int threads) {
  MapOptions m;
  m.x.parameter = "mu";
  for (int k = 0; k <= 20; ++k) m.x.values.push_back(0.05 * k);
  m.y.parameter = "omega_lag";
  m.y.values = {0.8, 1.0, 1.28303, 1.5};
  m.threads = threads;
  return m;
}

TEST(Map, IdenticalForOneAndTwoThreadsAndRowsEqualThePlainSweep) {
  const MapResult one = run_map({}, {}, lag_frequency_map(1));
  const MapResult two = run_map({}, {}, lag_frequency_map(2));
  ASSERT_EQ(4u, one.cells.size());
  for (std::size_t i = 0; i < one.cells.size(); ++i) {
    ASSERT_EQ(21u, one.cells[i].size());
    for (std::size_t j = 0; j < one.cells[i].size(); ++j) {
      const MapCell& a = one.cells[i][j];
      const MapCell& b = two.cells[i][j];
      ASSERT_TRUE(a.computed && a.max_zeta && b.max_zeta);
      EXPECT_TRUE(same(*a.max_zeta, *b.max_zeta)) << i << "," << j;
      EXPECT_EQ(a.mode, b.mode);
    }
  }
  // Row y = omega_L1 = 1.28303 against Analysis::sweep(0, 1, 0.05) of that blade.
  RotorParameters p;
  p.omega_lag = 1.28303;
  const SweepResult s = Analysis(p, {}).sweep(0.0, 1.0, 0.05);
  ASSERT_EQ(21u, s.points.size());
  for (std::size_t j = 0; j < s.points.size(); ++j) {
    double z = -HUGE_VAL;
    for (const auto& e : s.points[j].exponents) z = std::max(z, e.zeta);
    EXPECT_TRUE(same(z, *one.cells[2][j].max_zeta)) << "mu = " << s.points[j].mu;
  }
}

TEST(Map, MuOnTheYAxisIsTheTransposedMap) {
  const MapOptions m = lag_frequency_map(2);
  MapOptions t = m;
  std::swap(t.x, t.y);
  const MapResult a = run_map({}, {}, m);
  const MapResult b = run_map({}, {}, t);
  ASSERT_EQ(a.cells.size(), b.cells[0].size());
  for (std::size_t i = 0; i < a.cells.size(); ++i)
    for (std::size_t j = 0; j < a.cells[i].size(); ++j)
      EXPECT_TRUE(same(*a.cells[i][j].max_zeta, *b.cells[j][i].max_zeta));
}

TEST(Map, TwoParametersAtAFixedMu) {
  MapOptions m;
  m.x.parameter = "theta";
  m.x.values = {0.1, 0.2};
  m.y.parameter = "gamma";
  m.y.values = {5.0, 10.0};
  m.mu = 0.4;
  const MapResult r = run_map({}, {}, m);
  RotorParameters p;
  p.theta = 0.2;
  p.gamma = 5.0;
  const PointResult pt = Analysis(p, {}).point(0.4);
  double z = -HUGE_VAL;
  for (const auto& e : pt.exponents) z = std::max(z, e.zeta);
  EXPECT_TRUE(same(z, *r.cells[0][1].max_zeta));
}

TEST(Map, CancelKeepsAPrefixOfFinishedLines) {
  std::atomic<bool> cancel{false};
  const MapResult r =
      run_map({}, {}, lag_frequency_map(1), &cancel, [&](std::size_t done, std::size_t) {
        if (done == 2) cancel = true;
      });
  EXPECT_TRUE(r.cancelled);
  EXPECT_EQ(2u, r.lines_done);
  for (std::size_t i = 0; i < r.cells.size(); ++i)
    for (const MapCell& c : r.cells[i]) EXPECT_EQ(i < 2, c.computed) << "row " << i;
}

TEST(Map, InvalidOptions) {
  MapOptions m = lag_frequency_map(1);
  m.x.values = {0.5, 0.2};  // mu must increase
  EXPECT_THROW(m.Check(), InvalidInput);
  m = lag_frequency_map(1);
  m.y.parameter = "mu";  // both axes mu
  EXPECT_THROW(m.Check(), InvalidInput);
  m = lag_frequency_map(1);
  m.y.parameter = "modes";  // not numeric
  EXPECT_THROW(m.Check(), InvalidInput);
}

// A trimmed study (issue 12 item 3): each row is the trimmed critical search of its value, and
// the trim matters (the row differs from the untrimmed one).
TEST(Study, TrimmedRowsAreTrimmedCriticalSearches) {
  RotorParameters p;
  p.model = "paper-cyclic";
  StudyOptions o;
  o.parameter = "omega_lag";
  o.values = {1.28303};
  o.critical.mu_max = 0.2;
  o.critical.scan_step = 0.1;
  o.trim.kind = TrimKind::Thrust;
  o.trim.thrust_coefficient = 0.0042384;
  const StudyResult s = run_study(p, {}, o);
  ASSERT_EQ(s.rows.size(), 1u);
  CriticalOptions c = o.critical;
  c.all_intervals = true;
  const flaplag::RotorCritical direct =
      Analysis(p, {}, flaplag::OperatingCondition::Trimmed(o.trim)).critical(c);
  EXPECT_TRUE(same(s.rows[0].critical, direct));
  EXPECT_EQ(s.rows[0].critical.status, Status::Ok) << s.rows[0].critical.message;
  // A trimmed map cell is the trimmed point at its mu.
  MapOptions m;
  m.x = {"mu", {0.2}};
  m.y = {"omega_lag", {1.28303}};
  m.scan_step = 0.1;
  m.trim = o.trim;
  const MapResult map = run_map(p, {}, m);
  const PointResult pt =
      Analysis(p, {}, flaplag::OperatingCondition::Trimmed(o.trim)).point(0.2, 0.1);
  ASSERT_TRUE(map.cells[0][0].max_zeta.has_value());
  double max_zeta = -1e300;
  for (const auto& e : pt.exponents) max_zeta = std::max(max_zeta, e.zeta);
  EXPECT_TRUE(same(*map.cells[0][0].max_zeta, max_zeta));
  const PointResult untrimmed = Analysis(p, {}).point(0.2, 0.1);
  double untrimmed_zeta = -1e300;
  for (const auto& e : untrimmed.exponents) untrimmed_zeta = std::max(untrimmed_zeta, e.zeta);
  EXPECT_GT(std::abs(untrimmed_zeta - max_zeta), 1e-6);
  o.trim.thrust_coefficient = -1.0;
  EXPECT_THROW(run_study(p, {}, o), InvalidInput);
}

// Untrimmed rows and cells at an inflow model are the analyses at that condition; a non-uniform
// model with a trim is refused naming `inflow`, a bad one naming its field.
TEST(Study, RowsAndCellsAtTheMomentumInflow) {
  const RotorParameters p;
  OperatingCondition at;
  at.inflow = InflowModel::Momentum(0.005, 0.0);
  StudyOptions o;
  o.parameter = "omega_lag";
  o.values = {1.28303};
  o.critical.mu_max = 1.0;
  o.critical.scan_step = 0.1;
  o.inflow = at.inflow;
  const StudyResult s = run_study(p, {}, o);
  ASSERT_EQ(s.rows.size(), 1u);
  CriticalOptions c = o.critical;
  c.all_intervals = true;
  const RotorCritical direct = Analysis(p, {}, at).critical(c);
  ASSERT_TRUE(direct.mu_c.has_value());
  EXPECT_TRUE(same(s.rows[0].critical, direct));
  const RotorCritical uniform = Analysis(p, {}).critical(c);
  ASSERT_TRUE(uniform.mu_c.has_value());
  EXPECT_GT(std::abs(*uniform.mu_c - *direct.mu_c), 1e-3);
  MapOptions m;
  m.x = {"theta", {0.15}};
  m.y = {"omega_lag", {1.28303}};
  m.mu = 0.3;
  m.scan_step = 0.1;
  m.inflow = at.inflow;
  const MapResult map = run_map(p, {}, m);
  double max_zeta = -1e300;
  for (const auto& e : Analysis(p, {}, at).point(0.3, 0.1).exponents)
    max_zeta = std::max(max_zeta, e.zeta);
  ASSERT_TRUE(map.cells[0][0].max_zeta.has_value());
  EXPECT_TRUE(same(*map.cells[0][0].max_zeta, max_zeta));

  o.trim.kind = TrimKind::Thrust;
  try {
    run_study(p, {}, o);
    ADD_FAILURE() << "a momentum inflow with a trim was taken";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.name(), "inflow");
  }
  m.trim.kind = TrimKind::Moment;
  EXPECT_FALSE(m.IsValid(nullptr));
  m.trim.kind = TrimKind::None;
  m.inflow.thrust_coefficient = 0.2;
  try {
    run_map(p, {}, m);
    ADD_FAILURE() << "C_T = 0.2 was taken";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.name(), "thrust_coefficient");
  }
}

}  // namespace
}  // namespace flaplag::study_test
