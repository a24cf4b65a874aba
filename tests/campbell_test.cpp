// The Campbell diagram (analysis/campbell.h): the blade's structural frequencies at rest and at
// the nominal speed against the Fig 9 relation, the coupled frequencies of a rotor without air
// against the structural ones, the per-rev crossings against the relation they interpolate,
// the same answer for any thread count, and the option checks.
#include "flaplag/campbell.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "flaplag/blade/blade.h"
#include "flaplag/blade/rotating_modes.h"
#include "flaplag/core/errors.h"
#include "test_util.h"

namespace flaplag {
namespace {

using testing::AbsClose;
using testing::RelClose;

// The Galerkin basis of the blade the diagram describes.
ExactModeOptions shapes_of(const RotorParameters& p) {
  ExactModeOptions o;
  o.n_basis = galerkin_basis(p);
  return o;
}

CampbellOptions coarse(int points = 7) {
  CampbellOptions o;
  o.speed_max = 1.2;
  o.points = points;
  o.threads = 1;
  return o;
}

TEST(Campbell, AtRestTheNonrotatingFrequenciesOfFig9) {
  const RotorParameters p;  // the typical case
  const CampbellResult c = campbell_diagram(p, {}, coarse());
  ASSERT_EQ(c.labels, (std::vector<std::string>{"flap", "lag"}));
  ASSERT_EQ(c.points.size(), 7u);
  const CampbellPoint& rest = c.points.front();
  EXPECT_EQ(rest.speed, 0.0);
  EXPECT_EQ(rest.status, Status::Ok);
  EXPECT_FALSE(rest.notes.empty());
  ASSERT_EQ(rest.modes.size(), 2u);
  // The Fig 9 relation of the blade layer, inverted there by its own root finder.
  EXPECT_TRUE(RelClose(nonrotating_frequency(BendingDirection::Flap, p.omega_flap, shapes_of(p)),
                       rest.modes[0].frequency, 1e-10));
  EXPECT_TRUE(RelClose(nonrotating_frequency(BendingDirection::Lag, p.omega_lag, shapes_of(p)),
                       rest.modes[1].frequency, 1e-10));
  EXPECT_FALSE(rest.modes[0].damping_ratio.has_value());
}

TEST(Campbell, AtTheNominalSpeedTheGivenFrequencies) {
  const RotorParameters p;
  CampbellOptions o = coarse(6);
  o.speed_max = 1.0;  // the last speed is Omega_0
  const CampbellResult c = campbell_diagram(p, {}, o);
  const CampbellPoint& nominal = c.points.back();
  EXPECT_EQ(nominal.speed, 1.0);
  EXPECT_TRUE(RelClose(p.omega_flap, nominal.omega_flap, 1e-10));
  EXPECT_TRUE(RelClose(p.omega_lag, nominal.omega_lag, 1e-10));
  // The modes there are those of the rotor's own point analysis at mu = 0.
  const PointResult hover = Analysis(p, {}).point(0.0);
  for (const CampbellFrequency& f : nominal.modes) {
    const LabelledExponent* e = dominant_exponent(hover, f.label);
    ASSERT_NE(e, nullptr);
    // (The blade's frequencies at Omega_0 come back from its stiffness to 1e-10, not bit for bit.)
    EXPECT_TRUE(RelClose(e->omega, f.omega, 1e-9)) << f.label;
    EXPECT_EQ(f.frequency, f.omega) << f.label;
  }
}

// Without aerodynamic loads (gamma -> 0) and structural damping the coupled frequencies are the
// blade's rotating ones: omega Omega / Omega_0 = s omega_F1(s), with omega_F1(s) from the Fig 9
// relation at the nonrotating frequency omega_F1N / s.
TEST(Campbell, WithoutAirTheStructuralFan) {
  RotorParameters p;
  p.gamma = 1e-6;
  const CampbellResult c = campbell_diagram(p, {}, coarse());
  // Undamped: the stability of the lag mode is within its error of neutral (a warning).
  EXPECT_TRUE(c.IsUsable()) << c.message;
  const double flap_nr = nonrotating_frequency(BendingDirection::Flap, p.omega_flap, shapes_of(p));
  const double lag_nr = nonrotating_frequency(BendingDirection::Lag, p.omega_lag, shapes_of(p));
  for (std::size_t i = 1; i < c.points.size(); ++i) {
    const CampbellPoint& pt = c.points[i];
    const double s = pt.speed;
    const double flap = s * rotating_frequency(BendingDirection::Flap, flap_nr / s, shapes_of(p));
    const double lag = s * rotating_frequency(BendingDirection::Lag, lag_nr / s, shapes_of(p));
    EXPECT_TRUE(AbsClose(flap, pt.modes[0].frequency, 1e-4)) << "s = " << s;
    EXPECT_TRUE(AbsClose(lag, pt.modes[1].frequency, 1e-4)) << "s = " << s;
  }
}

// A soft-in-plane blade (omega_L1 = 0.7 at Omega_0) crosses 1/rev in lag below the nominal
// speed; the crossing lies where the blade's lag frequency by Omega is 1 (Fig 9 relation, no
// air), to the accuracy of the linear interpolation on the grid.
TEST(Campbell, TheLagModeCrossesOnePerRevWhereItsFrequencyIsOnePerRev) {
  RotorParameters p;
  p.gamma = 1e-6;
  p.omega_lag = 0.7;
  CampbellOptions o = coarse(121);
  o.harmonics = 2;
  const CampbellResult c = campbell_diagram(p, {}, o);
  const CampbellCrossing* lag1 = nullptr;
  for (const CampbellCrossing& x : c.crossings)
    if (x.label == "lag" && x.harmonic == 1) lag1 = &x;
  ASSERT_NE(lag1, nullptr);
  EXPECT_LT(lag1->speed, 1.0);
  EXPECT_EQ(lag1->frequency, lag1->speed);
  const double lag_nr = nonrotating_frequency(BendingDirection::Lag, p.omega_lag, shapes_of(p));
  EXPECT_TRUE(AbsClose(
      1.0, rotating_frequency(BendingDirection::Lag, lag_nr / lag1->speed, shapes_of(p)), 1e-3));
}

TEST(Campbell, ExactModesAtRestAreTheCantilever) {
  RotorParameters p;
  p.modes = ModeKind::Exact;
  p.model = "paper-2x1";
  const CampbellResult c = campbell_diagram(p, {}, coarse(3));
  ASSERT_EQ(c.labels, (std::vector<std::string>{"flap1", "flap2", "lag"}));
  const CampbellPoint& rest = c.points.front();
  const double b1 = cantilever_root(1), b2 = cantilever_root(2);
  EXPECT_TRUE(
      RelClose((b2 * b2) / (b1 * b1), rest.modes[1].frequency / rest.modes[0].frequency, 1e-12));
}

TEST(Campbell, TheSameForAnyThreadCount) {
  const RotorParameters p;
  CampbellOptions one = coarse(9), two = coarse(9);
  one.mu = two.mu = 0.3;
  two.threads = 2;
  const CampbellResult a = campbell_diagram(p, {}, one), b = campbell_diagram(p, {}, two);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i)
    for (std::size_t m = 0; m < a.points[i].modes.size(); ++m)
      EXPECT_EQ(0, std::memcmp(&a.points[i].modes[m].frequency, &b.points[i].modes[m].frequency,
                               sizeof(double)));
}

TEST(Campbell, OptionsAreCheckedByName) {
  const RotorParameters p;
  auto field_of = [&](CampbellOptions o) {
    try {
      campbell_diagram(p, {}, o);
    } catch (const InvalidInput& e) {
      return e.name();
    }
    return std::string("(accepted)");
  };
  CampbellOptions o = coarse();
  o.speed_max = 0.0;
  EXPECT_EQ("speed_max", field_of(o));
  o = coarse();
  o.points = 1;
  EXPECT_EQ("points", field_of(o));
  o = coarse();
  o.harmonics = 0;
  EXPECT_EQ("harmonics", field_of(o));
  o = coarse();
  o.mu = -0.1;
  EXPECT_EQ("mu", field_of(o));
  o = coarse();
  o.speed_max = NAN;
  EXPECT_EQ("speed_max", field_of(o));
}

}  // namespace
}  // namespace flaplag
