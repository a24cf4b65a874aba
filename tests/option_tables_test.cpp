// The field tables of the options structs (core/fields.h Option rows): every row names a member
// once, its range is what Validate() checks (a value just outside it is refused under the row's
// name with the range's words, the default is inside it), and the cross-field checks stay.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <set>
#include <string>
#include <type_traits>

#include "flaplag/campbell.h"
#include "flaplag/core/fields.h"
#include "flaplag/core/validation.h"
#include "flaplag/numerics/continuation.h"
#include "flaplag/numerics/floquet.h"
#include "flaplag/numerics/response.h"
#include "flaplag/rotor/inflow.h"
#include "flaplag/rotor/periodic_equilibrium.h"
#include "flaplag/trim.h"

namespace flaplag {
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
}  // namespace flaplag
