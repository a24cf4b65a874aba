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

namespace flaplag::parameters_test {
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
  // the paper's reversed-flow model: the Appendix D sector, not the exact circle
  EXPECT_TRUE(p.reversed_flow);
  EXPECT_FALSE(p.exact_reversed_flow);
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

TEST(ParameterTable, EveryRowIsAFieldOnceWithItsDocumentation) {
  std::set<std::string> fields;
  for (const ParameterSpec& s : parameter_table()) {
    EXPECT_TRUE(fields.insert(s.field).second) << s.field;
    EXPECT_EQ(find_parameter(s.field), &s);
    EXPECT_NE(std::string(s.description), "") << s.field;
    EXPECT_NE(std::string(s.units), "") << s.field;
    // The runtime speaks fields only: no command-line spelling anywhere in the table.
    for (const char* text : {s.field, s.symbol, s.units, s.description, s.requirement}) {
      EXPECT_EQ(std::string(text).find("--"), std::string::npos) << s.field << ": " << text;
    }
    EXPECT_EQ(std::string(s.field).find('-'), std::string::npos) << s.field;
  }
  for (const char* f : {"gamma", "sigma", "root_offset", "omega_lag", "reversed_flow", "modes"}) {
    EXPECT_NE(find_parameter(f), nullptr) << f;
  }
  EXPECT_EQ(find_parameter("lock"), nullptr);
  EXPECT_EQ(find_parameter("--gamma"), nullptr);
}

// Every bound finite: each admissible value is a blade the solver answers for; the defaults
// (the paper's typical case) are inside.
TEST(ParameterTable, RealRangesAreBoundedAndHoldTheDefaults) {
  const RotorParameters defaults;
  for (const ParameterSpec& s : parameter_table()) {
    if (s.type != ParameterType::Real) continue;
    EXPECT_TRUE(std::isfinite(s.range.lo) && std::isfinite(s.range.hi)) << s.field;
    EXPECT_LT(s.range.lo, s.range.hi) << s.field;
    EXPECT_TRUE(in_range(s, defaults.*s.real)) << s.field;
    EXPECT_FALSE(in_range(s, kNaN)) << s.field;
    EXPECT_FALSE(in_range(s, kInf)) << s.field;
    EXPECT_FALSE(in_range(s, -kInf)) << s.field;
    EXPECT_EQ(in_range(s, s.range.lo), !s.range.lo_open) << s.field;
    EXPECT_EQ(in_range(s, s.range.hi), !s.range.hi_open) << s.field;
    EXPECT_NE(std::string(s.requirement), "") << s.field;
  }
}

// Integer rows: a closed range of whole numbers holding the default, and validate() accepting
// exactly that range (the basis: the paper's 5 by default, 1..12 admissible).
TEST(ParameterTable, IntegerRowsAreClosedWholeRanges) {
  const RotorParameters defaults;
  int integer_rows = 0;
  for (const ParameterSpec& s : parameter_table()) {
    if (s.type != ParameterType::Integer) continue;
    ++integer_rows;
    ASSERT_NE(s.integer, nullptr) << s.field;
    EXPECT_EQ(s.real, nullptr) << s.field;
    EXPECT_FALSE(s.range.lo_open || s.range.hi_open) << s.field;
    EXPECT_EQ(s.range.lo, std::floor(s.range.lo)) << s.field;
    EXPECT_EQ(s.range.hi, std::floor(s.range.hi)) << s.field;
    EXPECT_TRUE(integer_admissible(s, defaults.*s.integer)) << s.field;
    for (const int v : {static_cast<int>(s.range.lo), static_cast<int>(s.range.hi)}) {
      RotorParameters p;
      p.*s.integer = v;
      EXPECT_NO_THROW(validate(p)) << s.field << " = " << v;
      EXPECT_EQ(parameter_text(p, s), std::to_string(v));
    }
  }
  EXPECT_EQ(integer_rows, 1);
  const ParameterSpec* basis = find_parameter("basis");
  ASSERT_NE(basis, nullptr);
  EXPECT_EQ(basis->type, ParameterType::Integer);
  EXPECT_EQ(defaults.basis, flaplag::kConvergedBasis);  // named "converged"
  EXPECT_EQ(flaplag::kPaperBasis, 5);                   // paper 4.1(b)
  EXPECT_EQ(basis->range.lo, 1.0);
  EXPECT_EQ(basis->range.hi, 12.0);
}

TEST(ParameterTable, ValuesAsTextAndModeKinds) {
  RotorParameters p;
  p.omega_lag = 0.1 + 0.2;
  EXPECT_EQ(parameter_text(p, *find_parameter("omega_lag")), "0.30000000000000004");
  EXPECT_EQ(parameter_text(p, *find_parameter("reversed_flow")), "true");
  EXPECT_EQ(parameter_text(p, *find_parameter("modes")), "assumed");
  EXPECT_EQ(parameter_text(p, *find_parameter("model")), "paper");
  ModeKind k = ModeKind::Assumed;
  EXPECT_TRUE(mode_kind_from_name("exact", &k));
  EXPECT_EQ(k, ModeKind::Exact);
  EXPECT_FALSE(mode_kind_from_name("fuzzy", &k));
  EXPECT_FALSE(mode_kind_from_name("", &k));
  EXPECT_EQ(k, ModeKind::Exact);
  EXPECT_STREQ(mode_kind_name(ModeKind::Assumed), "assumed");
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
  const char* field;  // expected InvalidInput::name()
};

class ValidateRejects : public ::testing::TestWithParam<BadCase> {};

TEST_P(ValidateRejects, NamesTheField) {
  RotorParameters p;
  GetParam().change(p);
  try {
    validate(p);
    FAIL() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.name(), GetParam().field) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind(std::string(GetParam().field) + " = ", 0), 0u)
        << e.what();
    EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
  }
}

const BadCase kBad[] = {
    {"LockNaN", [](RotorParameters& p) { p.gamma = kNaN; }, "gamma"},
    {"LockZero", [](RotorParameters& p) { p.gamma = 0.0; }, "gamma"},
    {"LockNegative", [](RotorParameters& p) { p.gamma = -1.0; }, "gamma"},
    {"SolidityZero", [](RotorParameters& p) { p.sigma = 0.0; }, "sigma"},
    {"SolidityInf", [](RotorParameters& p) { p.sigma = kInf; }, "sigma"},
    {"LiftSlopeZero", [](RotorParameters& p) { p.lift_slope = 0.0; }, "lift_slope"},
    {"CdoNegative", [](RotorParameters& p) { p.cdo = -1e-3; }, "cdo"},
    {"ThetaNaN", [](RotorParameters& p) { p.theta = kNaN; }, "theta"},
    {"ThetaHalfPi", [](RotorParameters& p) { p.theta = M_PI / 2; }, "theta"},
    {"PreconeMinusHalfPi", [](RotorParameters& p) { p.precone = -M_PI / 2; }, "precone"},
    {"DroopBig", [](RotorParameters& p) { p.droop = 2.0; }, "droop"},
    {"OmegaFlapZero", [](RotorParameters& p) { p.omega_flap = 0.0; }, "omega_flap"},
    {"OmegaLagNegative", [](RotorParameters& p) { p.omega_lag = -1.0; }, "omega_lag"},
    {"OmegaLagInf", [](RotorParameters& p) { p.omega_lag = kInf; }, "omega_lag"},
    {"DampingFlapNegative", [](RotorParameters& p) { p.damping_flap = -0.01; }, "damping_flap"},
    {"DampingLagNegative", [](RotorParameters& p) { p.damping_lag = -0.01; }, "damping_lag"},
    {"LengthRatioZero", [](RotorParameters& p) { p.length_ratio = 0.0; }, "length_ratio"},
    {"LengthRatioAboveOne", [](RotorParameters& p) { p.length_ratio = 1.01; }, "length_ratio"},
    {"TipLossANegative", [](RotorParameters& p) { p.tip_loss_a = -0.1; }, "tip_loss_a"},
    {"TipLossBAboveOne", [](RotorParameters& p) { p.tip_loss_b = 1.1; }, "tip_loss_b"},
    {"TipLossesReversed",
     [](RotorParameters& p) {
       p.tip_loss_a = 0.6;
       p.tip_loss_b = 0.5;
     },
     "tip_loss_a"},
    {"TipLossesEqual",
     [](RotorParameters& p) {
       p.tip_loss_a = 0.5;
       p.tip_loss_b = 0.5;
     },
     "tip_loss_a"},
    {"RootOffsetNegative", [](RotorParameters& p) { p.root_offset = -0.01; }, "root_offset"},
    {"EmptyModel", [](RotorParameters& p) { p.model.clear(); }, "model"},
    // The upper bounds: beyond them A(psi) overflows at large mu (parameter_table.h).
    {"LockAboveBound", [](RotorParameters& p) { p.gamma = 1.0000000000000002e4; }, "gamma"},
    {"LockHuge", [](RotorParameters& p) { p.gamma = 1e308; }, "gamma"},
    {"SolidityAboveOne", [](RotorParameters& p) { p.sigma = 1.5; }, "sigma"},
    {"LiftSlopeAboveBound", [](RotorParameters& p) { p.lift_slope = 101.0; }, "lift_slope"},
    {"CdoAboveOne", [](RotorParameters& p) { p.cdo = 1e308; }, "cdo"},
    {"OmegaFlapAboveBound", [](RotorParameters& p) { p.omega_flap = 1000.5; }, "omega_flap"},
    {"OmegaLagHuge", [](RotorParameters& p) { p.omega_lag = 1e150; }, "omega_lag"},
    {"DampingFlapAboveBound", [](RotorParameters& p) { p.damping_flap = 10.5; }, "damping_flap"},
    {"DampingLagAboveBound", [](RotorParameters& p) { p.damping_lag = 1e10; }, "damping_lag"},
    {"RootOffsetAtRadius", [](RotorParameters& p) { p.root_offset = 1.0; }, "root_offset"},
    // The exact-mode Galerkin basis: 1..12 cantilever functions (rotating_modes.h).
    {"BasisNegative", [](RotorParameters& p) { p.basis = -5; }, "basis"},
    {"BasisThirteen", [](RotorParameters& p) { p.basis = 13; }, "basis"},
    // C_Do / a overflowed the aerodynamic loads, and the failure named a derived matrix (A0).
    {"LiftSlopeOverflowingDragOverLiftSlope", [](RotorParameters& p) { p.lift_slope = 5e-324; },
     "lift_slope"},
    {"ExactReversedFlowWithoutReversedFlow",
     [](RotorParameters& p) {
       p.reversed_flow = false;
       p.exact_reversed_flow = true;
     },
     "exact_reversed_flow"},
};

INSTANTIATE_TEST_SUITE_P(Table, ValidateRejects, ::testing::ValuesIn(kBad),
                         [](const ::testing::TestParamInfo<BadCase>& i) {
                           return std::string(i.param.name);
                         });

TEST(Validate, TipLossMessageNamesTheOtherFieldInBackticks) {
  RotorParameters p;
  p.tip_loss_a = 0.6;
  p.tip_loss_b = 0.5;
  try {
    validate(p);
    FAIL() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()), "tip_loss_a = 0.6: must be below `tip_loss_b` = 0.5");
  }
}

TEST(Validate, ASmallLiftSlopeWithoutProfileDragIsAccepted) {
  RotorParameters p;
  p.cdo = 0.0;
  p.lift_slope = 5e-324;
  EXPECT_NO_THROW(validate(p));
  p.cdo = 0.01;
  p.lift_slope = 1e-301;  // C_Do / a = 1e299, near the largest admitted
  EXPECT_NO_THROW(validate(p));
}

TEST(Validate, AcceptsUpperBoundaryValues) {
  RotorParameters p;
  p.gamma = 1e4;
  p.sigma = 1.0;
  p.lift_slope = 100.0;
  p.cdo = 1.0;
  p.omega_flap = 1000.0;
  p.omega_lag = 1000.0;
  p.damping_flap = 10.0;
  p.damping_lag = 10.0;
  p.root_offset = 0.999;
  EXPECT_NO_THROW(validate(p));
}

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
}  // namespace flaplag::parameters_test
