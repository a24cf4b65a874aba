// Rotor parameters: the name table, validate() and the hover inflow of eq 2.24.
#include "flaplag/rotor/parameters.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <set>
#include <string>

#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/rotor/parameter_table.h"
#include "test_util.h"

namespace flaplag {
namespace {

using flaplag::testing::RelClose;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(Parameters, DefaultsAreThePapersTypicalCaseAndValid) {
  const RotorParameters p;
  EXPECT_NO_THROW(validate(p));
  EXPECT_EQ(p.model, "paper");
  EXPECT_EQ(p.gamma, 10.0);
  EXPECT_EQ(p.theta, 0.15);
  EXPECT_EQ(p.omega_flap, 1.175);
  EXPECT_EQ(p.omega_lag, 1.28303);
}

// Eq 2.24 evaluated independently: sigma a = 0.05 * 2 pi, 24 theta / (sigma a) = 11.4591559...,
// lambda = sigma a / 16 * (sqrt(12.4591559...) - 1), worked to 40 digits by hand (decimal
// arithmetic) as 0.0496715830600416807928...
TEST(Parameters, HoverInflowEq224) {
  RotorParameters p;
  p.theta = 0.15;
  p.sigma = 0.05;
  p.lift_slope = 2.0 * M_PI;
  EXPECT_TRUE(RelClose(0.04967158306004168079, hover_inflow(p), 1e-15));
  // It is the positive root of 32 lambda^2 + 4 sigma a lambda - 3 sigma a theta = 0, which is
  // eq 2.24 squared out.
  const double sa = p.sigma * p.lift_slope;
  const double l = hover_inflow(p);
  EXPECT_NEAR(32 * l * l + 4 * sa * l - 3 * sa * p.theta, 0.0, 1e-15);
}

TEST(Parameters, HoverInflowKeepsDigitsForSmallPitch) {
  // lambda -> 3 theta / 4 as theta -> 0; the literal form of eq 2.24 would cancel here.
  RotorParameters p;
  p.theta = 1e-12;
  EXPECT_TRUE(RelClose(0.75e-12, hover_inflow(p), 1e-9));
  p.theta = 0.0;
  EXPECT_EQ(hover_inflow(p), 0.0);
}

TEST(Parameters, HoverInflowUndefinedBelowItsBranchPoint) {
  RotorParameters p;
  p.theta = -0.05;  // below -sigma a / 24 = -0.0131
  EXPECT_THROW(hover_inflow(p), InvalidInput);
  EXPECT_THROW(validate(p), InvalidInput);
}

TEST(ParameterTable, EveryRowNamesAnOptionOnceAndRoundTrips) {
  std::set<std::string> fields, options;
  for (const ParameterSpec& s : parameter_table()) {
    EXPECT_TRUE(fields.insert(s.field).second) << s.field;
    EXPECT_TRUE(options.insert(s.option).second) << s.option;
    EXPECT_EQ(std::string(s.option).rfind("--", 0), 0u) << s.option;
    EXPECT_EQ(find_parameter(s.field), &s);
    EXPECT_EQ(find_parameter(s.option), &s);
    EXPECT_EQ(option_for(s.field), s.option);
    EXPECT_NE(std::string(s.help), "");
  }
  EXPECT_EQ(option_for("lock"), "--gamma");
  EXPECT_EQ(option_for("omega_lag"), "--omega-lag");
  EXPECT_EQ(option_for("not-a-field"), "not-a-field");
  EXPECT_EQ(find_parameter("--nope"), nullptr);
}

TEST(ParameterTable, RealRowsSetExactlyTheirOwnField) {
  for (const ParameterSpec& s : parameter_table()) {
    if (s.type != ParameterType::Real) continue;
    RotorParameters p;
    set_parameter(p, s, "0.123456789012345678");
    EXPECT_EQ(p.*s.real, 0.123456789012345678) << s.option;
    // No other real field moved.
    const RotorParameters defaults;
    for (const ParameterSpec& o : parameter_table()) {
      if (o.type == ParameterType::Real && o.real != s.real) {
        EXPECT_EQ(p.*o.real, defaults.*o.real) << s.option << " changed " << o.option;
      }
    }
    EXPECT_EQ(parameter_text(p, s), "0.12345678901234568");
  }
}

TEST(ParameterTable, FlagsAndChoices) {
  RotorParameters p;
  set_parameter(p, *find_parameter("--no-reversed-flow"), "");
  EXPECT_FALSE(p.reversed_flow);
  set_parameter(p, *find_parameter("--no-elastic-coupling"), "");
  EXPECT_FALSE(p.elastic_coupling);
  set_parameter(p, *find_parameter("--paper-1974-shapes"), "");
  EXPECT_TRUE(p.paper_1974_shapes);
  set_parameter(p, *find_parameter("--modes"), "exact");
  EXPECT_EQ(p.modes, ModeKind::Exact);
  EXPECT_THROW(set_parameter(p, *find_parameter("--modes"), "fuzzy"), InvalidInput);
}

TEST(ParseReal, AcceptsWholeNumbersOnly) {
  EXPECT_EQ(parse_real("--x", "1e-3"), 1e-3);
  EXPECT_EQ(parse_real("--x", "-0.5"), -0.5);
  EXPECT_EQ(parse_real("--x", "+2"), 2.0);
  for (const char* bad : {"", " 1", "1 ", "1x", "abc", "nan", "inf", "-inf", "1e999", "0.1.2"}) {
    EXPECT_THROW(parse_real("--x", bad), InvalidInput) << '"' << bad << '"';
  }
  try {
    parse_real("--theta", "abc");
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.name(), "--theta");
    EXPECT_EQ(e.value(), "abc");
  }
}

TEST(ParseInt, RangeAndSyntax) {
  EXPECT_EQ(parse_int("--n", "50", 1, 100), 50);
  EXPECT_EQ(parse_int("--n", "+3", 1, 100), 3);
  for (const char* bad : {"", "0", "101", "1.5", "x", "99999999999999999999", "-1"}) {
    EXPECT_THROW(parse_int("--n", bad, 1, 100), InvalidInput) << bad;
  }
}

TEST(RoundTripText, ShortestExact) {
  EXPECT_EQ(round_trip_text(0.1), "0.1");
  EXPECT_EQ(round_trip_text(1.28303), "1.28303");
  EXPECT_EQ(round_trip_text(kNaN), "nan");
  EXPECT_EQ(round_trip_text(-kInf), "-inf");
  const double x = 0.1 + 0.2;
  EXPECT_EQ(std::stod(round_trip_text(x)), x);
}

struct BadCase {
  const char* name;
  std::function<void(RotorParameters&)> change;
  const char* option;  // expected InvalidInput::name()
};

class ValidateRejects : public ::testing::TestWithParam<BadCase> {};

TEST_P(ValidateRejects, NamesTheOption) {
  RotorParameters p;
  GetParam().change(p);
  try {
    validate(p);
    FAIL() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.name(), GetParam().option) << e.what();
    EXPECT_NE(std::string(e.what()).find(GetParam().option), std::string::npos);
  }
}

const BadCase kBad[] = {
    {"LockNaN", [](RotorParameters& p) { p.gamma = kNaN; }, "--gamma"},
    {"LockZero", [](RotorParameters& p) { p.gamma = 0.0; }, "--gamma"},
    {"LockNegative", [](RotorParameters& p) { p.gamma = -1.0; }, "--gamma"},
    {"SolidityZero", [](RotorParameters& p) { p.sigma = 0.0; }, "--sigma"},
    {"SolidityInf", [](RotorParameters& p) { p.sigma = kInf; }, "--sigma"},
    {"LiftSlopeZero", [](RotorParameters& p) { p.lift_slope = 0.0; }, "--lift-slope"},
    {"CdoNegative", [](RotorParameters& p) { p.cdo = -1e-3; }, "--cdo"},
    {"ThetaNaN", [](RotorParameters& p) { p.theta = kNaN; }, "--theta"},
    {"ThetaHalfPi", [](RotorParameters& p) { p.theta = M_PI / 2; }, "--theta"},
    {"PreconeMinusHalfPi", [](RotorParameters& p) { p.precone = -M_PI / 2; }, "--precone"},
    {"DroopBig", [](RotorParameters& p) { p.droop = 2.0; }, "--droop"},
    {"OmegaFlapZero", [](RotorParameters& p) { p.omega_flap = 0.0; }, "--omega-flap"},
    {"OmegaLagNegative", [](RotorParameters& p) { p.omega_lag = -1.0; }, "--omega-lag"},
    {"OmegaLagInf", [](RotorParameters& p) { p.omega_lag = kInf; }, "--omega-lag"},
    {"DampingFlapNegative", [](RotorParameters& p) { p.damping_flap = -0.01; }, "--damping-flap"},
    {"DampingLagNegative", [](RotorParameters& p) { p.damping_lag = -0.01; }, "--damping-lag"},
    {"LengthRatioZero", [](RotorParameters& p) { p.length_ratio = 0.0; }, "--length-ratio"},
    {"LengthRatioAboveOne", [](RotorParameters& p) { p.length_ratio = 1.01; }, "--length-ratio"},
    {"TipLossANegative", [](RotorParameters& p) { p.tip_loss_a = -0.1; }, "--tip-loss-a"},
    {"TipLossBAboveOne", [](RotorParameters& p) { p.tip_loss_b = 1.1; }, "--tip-loss-b"},
    {"TipLossesReversed",
     [](RotorParameters& p) {
       p.tip_loss_a = 0.6;
       p.tip_loss_b = 0.5;
     },
     "--tip-loss-a"},
    {"TipLossesEqual",
     [](RotorParameters& p) {
       p.tip_loss_a = 0.5;
       p.tip_loss_b = 0.5;
     },
     "--tip-loss-a"},
    {"RootOffsetNegative", [](RotorParameters& p) { p.root_offset = -0.01; }, "--root-offset"},
    {"EmptyModel", [](RotorParameters& p) { p.model.clear(); }, "--model"},
};

INSTANTIATE_TEST_SUITE_P(Table, ValidateRejects, ::testing::ValuesIn(kBad),
                         [](const ::testing::TestParamInfo<BadCase>& i) {
                           return std::string(i.param.name);
                         });

TEST(Validate, AcceptsBoundaryValues) {
  RotorParameters p;
  p.cdo = 0.0;
  p.damping_flap = 0.0;
  p.length_ratio = 1.0;
  p.tip_loss_a = 0.0;
  p.tip_loss_b = 1.0;
  p.theta = 1.5;
  p.precone = -1.5;
  EXPECT_NO_THROW(validate(p));
}

}  // namespace
}  // namespace flaplag
