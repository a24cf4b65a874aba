// The field tables of the options structs (core/fields.h Option rows): every row names a member
// once, its range is what Validate() checks (a value just outside it is refused under the row's
// name with the range's words, the default is inside it), and the cross-field checks stay.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <type_traits>

#include "flaplag/analysis.h"
#include "flaplag/campbell.h"
#include "flaplag/core/fields.h"
#include "flaplag/core/validation.h"
#include "flaplag/numerics/continuation.h"
#include "flaplag/numerics/floquet.h"
#include "flaplag/numerics/response.h"
#include "flaplag/rotor/inflow.h"
#include "flaplag/rotor/periodic_equilibrium.h"
#include "flaplag/study.h"
#include "flaplag/trim.h"

namespace flaplag::option_tables_test {
namespace {

bool snake_case(const std::string& s) {
  if (s.empty() || !std::islower(static_cast<unsigned char>(s.front()))) return false;
  for (char c : s)
    if (!(std::islower(static_cast<unsigned char>(c)) ||
          std::isdigit(static_cast<unsigned char>(c)) || c == '_'))
      return false;
  return true;
}

// A value of the row's type just outside its interval (below lo, else above hi).
template <class V>
V outside(const Interval& i) {
  if constexpr (std::is_same_v<V, int>) {
    if (std::isfinite(i.lo)) return static_cast<int>(i.lo) - (i.lo_open ? 0 : 1);
    return static_cast<int>(i.hi) + (i.hi_open ? 0 : 1);
  } else {
    if (std::isfinite(i.lo)) return i.lo_open ? i.lo : std::nextafter(i.lo, -INFINITY);
    return i.hi_open ? i.hi : std::nextafter(i.hi, INFINITY);
  }
}

// Every row with a range: the default is admitted; a value outside is refused by Validate()
// naming the row, with "must be " + the range's words.  Returns the number of ranged rows.
template <class O>
int check_table(const O& defaults = O{}) {
  EXPECT_FALSE(defaults.Validate()) << defaults.Validate()->what();
  std::set<std::string> names;
  int ranged = 0;
  for_each_field(defaults, [&](const auto& row, const auto& value) {
    using V = std::decay_t<decltype(value)>;
    EXPECT_TRUE(snake_case(row.name)) << row.name;
    EXPECT_TRUE(names.insert(row.name).second) << "two rows called " << row.name;
    EXPECT_GT(std::string(row.doc).size(), 5u) << row.name;
    const Range* range = row_range(row);
    if constexpr (std::is_same_v<V, double> || std::is_same_v<V, int>) {
      if (range == nullptr) return;
      ++ranged;
      EXPECT_TRUE(range->interval.Contains(value)) << row.name << " default outside its range";
      O bad = defaults;
      row.get(bad) = outside<V>(range->interval);
      const std::optional<InvalidInput> e = bad.Validate();
      ASSERT_TRUE(e) << row.name << " = " << row.get(bad) << " admitted";
      EXPECT_EQ(e->name(), row.name);
      EXPECT_EQ(e->reason(), std::string("must be ") + range->words) << row.name;
    } else if constexpr (std::is_same_v<V, std::optional<double>>) {
      // Off by default; a value outside the range is refused once given.
      if (range == nullptr) return;
      ++ranged;
      EXPECT_FALSE(value.has_value()) << row.name;
      O bad = defaults;
      row.get(bad) = outside<double>(range->interval);
      const std::optional<InvalidInput> e = bad.Validate();
      ASSERT_TRUE(e) << row.name << " admitted outside its range";
      EXPECT_EQ(e->name(), row.name);
      EXPECT_EQ(e->reason(), std::string("must be ") + range->words) << row.name;
      row.get(bad) = range->interval.lo;  // in range when given
      EXPECT_FALSE(bad.Validate()) << row.name;
    } else {
      EXPECT_EQ(range, nullptr) << row.name << ": a range on a value that is not a number";
    }
  });
  EXPECT_EQ(names.size(), field_count<O>());
  return ranged;
}

TEST(OptionTables, EveryRangedRowIsWhatValidateChecks) {
  EXPECT_EQ(check_table<CriticalOptions>(), 6);
  EXPECT_EQ(check_table<TransitionOptions>(), 3);
  EXPECT_EQ(check_table<TrimOptions>(), 5);
  EXPECT_EQ(check_table<ResponseOptions>(), 3);
  EXPECT_EQ(check_table<SimulationOptions>(), 3);
  EXPECT_EQ(check_table<CampbellOptions>(), 5);
  EXPECT_EQ(check_table<PeriodicEquilibriumOptions>(), 4);
  // The inflow model's C_T and shaft angle are eq 2.25's: checked for the momentum model only.
  EXPECT_EQ(check_table(InflowModel::Momentum(0.005, 0.0)), 2);
  InflowModel uniform;
  uniform.thrust_coefficient = -1.0;
  EXPECT_FALSE(uniform.Validate());
  // A study and a map need their axes; the scalar rows are the table's.
  StudyOptions study;
  study.parameter = "omega_lag";
  study.values = {1.0, 1.3};
  EXPECT_EQ(check_table(study), 2);
  MapOptions map;
  map.x = {"theta", {0.1, 0.2}};
  map.y = {"omega_lag", {1.0}};
  EXPECT_EQ(check_table(map), 3);
}

// The rows of studies and maps: units, docs, the ranges and words Python's and the command
// line's errors have always had.
TEST(OptionTables, StudyAndMapRows) {
  auto words = [](auto tag, const char* name) {
    std::string w;
    visit_row<typename decltype(tag)::type>(name, [&](const auto& row) {
      EXPECT_NE(row.units, nullptr);
      if (const Range* r = row_range(row)) w = r->words;
    });
    return w;
  };
  EXPECT_EQ(words(Tag<StudyOptions>{}, "threads"), "0 (all cores) or 1..256");
  EXPECT_EQ(words(Tag<StudyOptions>{}, "damping_criterion"),
            ">= 0 and < 1 (a fraction of critical: 0.01 is 1 %)");
  EXPECT_EQ(words(Tag<MapOptions>{}, "mu"), "in [0, 1000]");
  EXPECT_EQ(words(Tag<MapOptions>{}, "scan_step"), "> 0");
  EXPECT_EQ(words(Tag<MapOptions>{}, "threads"), "0 (all cores) or 1..256");
  visit_row<MapOptions>("mu", [](const auto& row) { EXPECT_STREQ(row.units, "-"); });
  visit_row<StudyOptions>("damping_criterion",
                          [](const auto& row) { EXPECT_STREQ(row.units, "-"); });
  // The messages are threads_problem's and the range checks' of before the tables.
  StudyOptions s;
  s.parameter = "omega_lag";
  s.values = {1.0};
  s.threads = kMaxThreads + 1;
  ASSERT_TRUE(s.Validate());
  EXPECT_STREQ(s.Validate()->what(), threads_problem(kMaxThreads + 1)->what());
  s.threads = 0;
  s.damping_criterion = std::nan("");
  ASSERT_TRUE(s.Validate());
  EXPECT_STREQ(s.Validate()->what(),
               "damping_criterion = nan: must be >= 0 and < 1 (a fraction of critical: 0.01 is "
               "1 %)");
  MapOptions m;
  m.x = {"theta", {0.1}};
  m.y = {"omega_lag", {1.0}};
  m.mu = INFINITY;
  ASSERT_TRUE(m.Validate());
  EXPECT_STREQ(m.Validate()->what(), "mu = inf: must be in [0, 1000]");
}

// Of several bad fields the one named first is the one named before the tables: the ranged rows
// are checked where their checks stood, around the nested options' and the condition's.
TEST(OptionTables, StudyAndMapCheckOrder) {
  StudyOptions s;
  s.parameter = "omega_lag";
  s.values = {1.0};
  s.threads = -1;
  s.critical.scan_step = 0.0;
  ASSERT_TRUE(s.Validate());
  EXPECT_EQ(s.Validate()->name(), "scan_step");  // the search before the threads
  s.damping_criterion = 2.0;
  EXPECT_EQ(s.Validate()->name(), "damping_criterion");  // the criterion before the search
  MapOptions m;
  m.x = {"theta", {0.1}};
  m.y = {"omega_lag", {1.0}};
  m.threads = -1;
  m.trim.kind = TrimKind::Thrust;
  m.trim.thrust_coefficient = -1.0;
  ASSERT_TRUE(m.Validate());
  EXPECT_EQ(m.Validate()->name(), "thrust_coefficient");  // the trim before the threads
  m.scan_step = 0.0;
  EXPECT_EQ(m.Validate()->name(), "scan_step");
  m.mu = -1.0;
  EXPECT_EQ(m.Validate()->name(), "mu");
}

TEST(OptionTables, RowsReadAndWriteTheirMember) {
  CriticalOptions o;
  bool found = visit_row<CriticalOptions>("mu_max", [&](const auto& row) {
    using V = typename std::decay_t<decltype(row)>::value_type;
    if constexpr (std::is_same_v<V, double>) row.get(o) = 0.75;
  });
  EXPECT_TRUE(found);
  EXPECT_EQ(o.mu_max, 0.75);
  EXPECT_FALSE(visit_row<CriticalOptions>("mu-max", [](const auto&) {}));
  // The range words the help shows are those of the struct's own constant.
  visit_row<CriticalOptions>("mu_max", [](const auto& row) {
    ASSERT_NE(row_range(row), nullptr);
    EXPECT_STREQ(row_range(row)->words, "> 0 and <= 1000");
  });
}

TEST(OptionTables, CrossFieldChecksStay) {
  CriticalOptions o;
  o.scan_step = 1e-9;  // in its range, but too many steps up to mu_max
  const std::optional<InvalidInput> e = o.Validate();
  ASSERT_TRUE(e);
  EXPECT_EQ(e->name(), "scan_step");
  PeriodicEquilibriumOptions p;
  p.harmonics = 0;  // neither 1..128 nor -1
  ASSERT_TRUE(p.Validate());
  EXPECT_EQ(p.Validate()->name(), "harmonics");
  p.harmonics = PeriodicEquilibriumOptions::kAutomaticHarmonics;
  EXPECT_FALSE(p.Validate());
  TrimOptions t;
  t.response.samples = 1;  // the nested struct's own check
  ASSERT_TRUE(t.Validate());
  EXPECT_EQ(t.Validate()->name(), "samples");
}

TEST(OptionTables, DescribedEnumsByName) {
  TransitionMethod m = TransitionMethod::RK4;
  EXPECT_TRUE(enum_from_name("magnus", &m));
  EXPECT_EQ(m, TransitionMethod::Magnus4);
  EXPECT_FALSE(enum_from_name("Magnus", &m));
  for (TransitionMethod k : kTransitionMethods) EXPECT_STREQ(enum_name(k), method_name(k));
}

}  // namespace
}  // namespace flaplag::option_tables_test

namespace flaplag::option_tables_test {
namespace {

// The result rows of studies and maps: one snake_case name each, documented, with the units of
// their quantities; a map document's grids are rows of MapCell, and a study row is its own rows
// and keys of its search (CriticalResult), each in the search's units.
TEST(ResultTables, StudyRowAndMapCell) {
  std::set<std::string> cell;
  for_each_row<MapCell>([&](const auto& row) {
    EXPECT_TRUE(snake_case(row.name)) << row.name;
    EXPECT_TRUE(cell.insert(row.name).second) << row.name;
    EXPECT_GT(std::string(row.doc).size(), 5u) << row.name;
  });
  for (const char* grid : kMapGridRows) EXPECT_EQ(cell.count(grid), 1u) << grid;
  visit_row<MapCell>("max_zeta", [](const auto& row) {
    EXPECT_STREQ(row.units, "per rev");
    EXPECT_TRUE(row.flags & kFieldNegativeInfinity);  // a zero multiplier's zeta
  });
  visit_row<MapCell>("omega", [](const auto& row) { EXPECT_STREQ(row.units, "per rev"); });
  std::map<std::string, std::string> critical_units;
  for_each_row<CriticalResult>([&](const auto& row) { critical_units[row.name] = row.units; });
  std::set<std::string> study, own;
  for_each_row<StudyRow>([&](const auto& row) {
    EXPECT_TRUE(snake_case(row.name)) << row.name;
    EXPECT_TRUE(study.insert(row.name).second) << row.name;
    EXPECT_GT(std::string(row.doc).size(), 5u) << row.name;
    const auto c = critical_units.find(row.name);
    if (c == critical_units.end())
      own.insert(row.name);
    else
      EXPECT_EQ(c->second, row.units) << row.name << ": the search's key in other units";
  });
  EXPECT_EQ(own, (std::set<std::string>{"value", "trim", "damping_crossings"}));
}

}  // namespace
}  // namespace flaplag::option_tables_test
