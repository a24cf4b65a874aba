// The field tables of core/fields.h: rows in order, members of a base, derived values, enums
// by name, and the tables of the results (keys unique and snake_case, every row documented).
#include "flaplag/core/fields.h"

#include <gtest/gtest.h>

#include <cctype>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "flaplag/core/outcome.h"
#include "flaplag/numerics/continuation.h"

namespace flaplag::fields_test {
namespace {

struct Sample : Outcome {
  double x = 0.0;
  int n = 0;
};

constexpr auto describe(Tag<Sample>) {
  return std::tuple_cat(
      std::make_tuple(Field{"x", &Sample::x, "rad", "an angle"},
                      Computed{"twice_n", +[](const Sample& s) { return 2 * s.n; }, "", "2 n"}),
      describe(Tag<Outcome>{}));
}

TEST(Fields, VisitsRowsInTableOrderWithTheirValues) {
  Sample s;
  s.x = 0.5;
  s.n = 4;
  s.status = Status::Warning;
  s.message = "m";
  std::vector<std::string> names;
  double x = 0.0;
  int twice = 0;
  Status status = Status::Ok;
  for_each_field(s, [&](const auto& row, const auto& value) {
    names.push_back(row.name);
    using V = std::decay_t<decltype(value)>;
    if constexpr (std::is_same_v<V, double>) x = value;
    if constexpr (std::is_same_v<V, int>) twice = value;
    if constexpr (std::is_same_v<V, Status>) status = value;
  });
  EXPECT_EQ((std::vector<std::string>{"x", "twice_n", "status", "message", "notes"}), names);
  EXPECT_EQ(0.5, x);
  EXPECT_EQ(8, twice);
  EXPECT_EQ(Status::Warning, status);
}

TEST(Fields, RowsWithoutAnObject) {
  std::vector<std::string> units;
  for_each_row<Sample>([&](const auto& row) { units.push_back(row.units); });
  EXPECT_EQ((std::vector<std::string>{"rad", "", "", "", ""}), units);
  EXPECT_EQ(5u, field_count<Sample>());
  static_assert(is_described_struct_v<Sample>);
  static_assert(!is_described_struct_v<double>);
}

TEST(Fields, EnumsByName) {
  EXPECT_STREQ("warning", enum_name(Status::Warning));
  EXPECT_STREQ("periodic", enum_name(InstabilityKind::Periodic));
  EXPECT_STREQ("failed", status_name(Status::Failed));
  EXPECT_STREQ("flutter", kind_name(InstabilityKind::Flutter));
}

// Keys are one snake_case word each, once per table, and every row says what it is.
template <class T>
void expect_well_formed(const char* what) {
  std::set<std::string> seen;
  for_each_row<T>([&](const auto& row) {
    const std::string name = row.name;
    EXPECT_TRUE(seen.insert(name).second) << what << ": " << name << " twice";
    EXPECT_FALSE(name.empty()) << what;
    for (char c : name)
      EXPECT_TRUE(std::islower(static_cast<unsigned char>(c)) ||
                  std::isdigit(static_cast<unsigned char>(c)) || c == '_')
          << what << ": " << name;
    EXPECT_GT(std::string(row.doc).size(), 5u) << what << ": " << name;
  });
}

TEST(Fields, ResultTablesAreWellFormed) {
  expect_well_formed<LabelledExponent>("LabelledExponent");
  expect_well_formed<PointResult>("PointResult");
  expect_well_formed<SweepResult>("SweepResult");
  expect_well_formed<InstabilityInterval>("InstabilityInterval");
  expect_well_formed<CriticalResult>("CriticalResult");
  expect_well_formed<FloquetSample>("FloquetSample");
}

// A sample's exponents become columns in one order: the k-th multiplier, zeta and omega are of
// the k-th exponent.
TEST(Fields, FloquetSampleColumns) {
  FloquetSample s;
  s.floquet.exponents.resize(2);
  s.floquet.exponents[0].multiplier = {0.5, 0.25};
  s.floquet.exponents[0].zeta = -0.1;
  s.floquet.exponents[0].omega = 0.125;
  s.floquet.exponents[1].multiplier = {-0.25, 0.0};
  s.floquet.exponents[1].zeta = -0.2;
  s.floquet.exponents[1].omega = 0.5;
  s.floquet.liouville_residual = 1e-9;
  std::vector<std::complex<double>> multipliers;
  std::vector<double> zeta, omega;
  double residual = 0.0;
  for_each_field(s, [&](const auto& row, const auto& value) {
    using V = std::decay_t<decltype(value)>;
    const std::string name = row.name;
    if constexpr (std::is_same_v<V, std::vector<std::complex<double>>>) {
      if (name == "multipliers") multipliers = value;
    } else if constexpr (std::is_same_v<V, std::vector<double>>) {
      if (name == "zeta") zeta = value;
      if (name == "omega") omega = value;
    } else if constexpr (std::is_same_v<V, double>) {
      if (name == "liouville_residual") residual = value;
    }
  });
  EXPECT_EQ((std::vector<std::complex<double>>{{0.5, 0.25}, {-0.25, 0.0}}), multipliers);
  EXPECT_EQ((std::vector<double>{-0.1, -0.2}), zeta);
  EXPECT_EQ((std::vector<double>{0.125, 0.5}), omega);
  EXPECT_EQ(1e-9, residual);
}

TEST(Fields, DerivedValuesOfTheResults) {
  PointResult p;
  p.exponents = {{"flap", -0.1, 0.25, {0.5, 0.25}, {}}, {"lag", -0.2, 0.75, {0.0, -0.5}, {}}};
  std::vector<std::complex<double>> multipliers;
  for_each_field(p, [&](const auto& row, const auto& value) {
    using V = std::decay_t<decltype(value)>;
    if constexpr (std::is_same_v<V, std::vector<std::complex<double>>>) {
      if (std::string(row.name) == "multipliers") multipliers = value;
    }
  });
  EXPECT_EQ((std::vector<std::complex<double>>{{0.5, 0.25}, {0.0, -0.5}}), multipliers);

  // Without mu_c the crossing's mode, omega and kind are absent, not "" / 0 / flutter.
  CriticalResult c;
  c.omega = 0.3;
  int absent = 0;
  for_each_field(c, [&](const auto& row, const auto& value) {
    using V = std::decay_t<decltype(value)>;
    const std::string name = row.name;
    if constexpr (std::is_same_v<V, std::optional<double>> ||
                  std::is_same_v<V, std::optional<std::string>> ||
                  std::is_same_v<V, std::optional<InstabilityKind>>) {
      if ((name == "mode" || name == "omega" || name == "kind") && !value) ++absent;
    }
  });
  EXPECT_EQ(3, absent);
}

}  // namespace
}  // namespace flaplag::fields_test
