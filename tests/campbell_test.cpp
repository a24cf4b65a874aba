// The Campbell diagram (analysis/campbell.h): the blade's structural frequencies at rest and at
// the nominal speed against the Fig 9 relation, the coupled frequencies of a rotor without air
// against the structural ones, the per-rev crossings against the relation they interpolate,
// the same answer for any thread count, and the option checks; a blade table's diagram against
// the uniform blade's and against the table's absolute stiffness at each speed.
#include "flaplag/campbell.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "flaplag/blade/blade.h"
#include "flaplag/blade/blade_properties.h"
#include "flaplag/blade/imported_modes.h"
#include "flaplag/blade/rotating_modes.h"
#include "flaplag/core/errors.h"
#include "test_util.h"

namespace flaplag::campbell_test {
namespace {

using flaplag::model::Direction;
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
  ASSERT_EQ(c.labels, (std::vector<std::string>{"flap", "flap2", "lag"}));
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

// ---- a blade table -------------------------------------------------------------------------

// The uniform table is the uniform exact-mode blade at every speed, at rest mode by mode.
TEST(CampbellTable, TheUniformTableIsTheUniformBlade) {
  RotorParameters p;
  p.modes = ModeKind::Exact;
  p.model = "paper-2x1";
  p.root_offset = 0.05;
  const CampbellResult uniform = campbell_diagram(p, {}, coarse(3));
  p.blade = std::make_shared<const BladeProperties>(uniform_blade());
  const CampbellResult table = campbell_diagram(p, {}, coarse(3));
  ASSERT_EQ(uniform.labels, table.labels);
  ASSERT_EQ(uniform.points.size(), table.points.size());
  for (std::size_t i = 0; i < table.points.size(); ++i) {
    const CampbellPoint &u = uniform.points[i], &t = table.points[i];
    SCOPED_TRACE("speed " + std::to_string(t.speed));
    EXPECT_EQ(u.status, t.status) << t.message;
    EXPECT_TRUE(RelClose(u.omega_flap, t.omega_flap, 1e-10));
    EXPECT_TRUE(RelClose(u.omega_lag, t.omega_lag, 1e-10));
    ASSERT_EQ(u.modes.size(), t.modes.size());
    for (std::size_t m = 0; m < t.modes.size(); ++m)
      EXPECT_TRUE(RelClose(u.modes[m].frequency, t.modes[m].frequency, 1e-8)) << t.modes[m].label;
  }
  // At rest the cantilever's beta_k^2 ratio (written here) holds for the table too.
  const double b1 = cantilever_root(1), b2 = cantilever_root(2);
  const CampbellPoint& rest = table.points.front();
  EXPECT_TRUE(
      RelClose((b2 * b2) / (b1 * b1), rest.modes[1].frequency / rest.modes[0].frequency, 1e-10));
}

// A tapered blade with a tip mass, its columns the absolute stiffness k = EI / (Omega_0^2 l I_b)
// (as a dimensional table gives them): at speed s the same blade has k / s^2.
BladeProperties absolute_taper() {
  BladeProperties b;
  b.x0 = {0.0, 0.3, 1.0};
  b.mass = {1.5, 1.2, 0.7};
  b.tip_mass = 0.05;
  b.stiffness_flap = {0.012, 0.008, 0.0025};
  b.stiffness_lag = {0.09, 0.06, 0.02};
  b.chord = {1.0, 1.0, 1.0};
  b.twist = {0.0, 0.0, 0.0};
  b.source = "taper";
  return normalised_mass(b);
}

// The rotor of that blade at Omega_0: its first frequencies from the absolute columns.
RotorParameters taper_rotor(const BladeProperties& b, double root_offset) {
  RotorParameters p;
  p.modes = ModeKind::Exact;
  p.root_offset = root_offset;
  p.length_ratio = 1.0 - root_offset;
  p.blade = std::make_shared<const BladeProperties>(b);
  ExactModeOptions o;
  o.n_basis = galerkin_basis(p);
  o.e1_over_l = p.root_offset / p.length_ratio;
  o.blade = p.blade;
  const ExactModes m = blade_stiffness_modes(o);
  p.omega_flap = m.modes[Direction::Flap].omega[0];
  p.omega_lag = m.modes[Direction::Lag].omega[0];
  return p;
}

// Without air the coupled frequencies are the blade's: at speed s, s times the first rotating
// frequencies of the table with its columns divided by s^2 (blade_stiffness_modes, no scale
// solved), and at rest its nonrotating ones.  The analysis at each speed solves the scale of
// the columns back from the first frequencies the diagram gives it: 1 / s^2.
TEST(CampbellTable, AbsoluteColumnsAtEachSpeedWithoutAir) {
  const BladeProperties b = absolute_taper();
  RotorParameters p = taper_rotor(b, 0.05);
  p.gamma = 1e-6;
  p.theta = 0.0;  // no elastic flap-lag coupling (Appendix E: it goes with the pitch)
  const CampbellResult c = campbell_diagram(p, {}, coarse(4));  // speeds 0, 0.4, 0.8, 1.2
  EXPECT_TRUE(c.IsUsable()) << c.message;
  ASSERT_EQ(c.labels, (std::vector<std::string>{"flap", "lag"}));
  ExactModeOptions o;
  o.n_basis = galerkin_basis(p);
  o.e1_over_l = p.root_offset / p.length_ratio;
  for (const CampbellPoint& pt : c.points) {
    const double s = pt.speed;
    SCOPED_TRACE("speed " + std::to_string(s));
    ASSERT_EQ(pt.modes.size(), 2u) << pt.message;
    if (s == 0.0) {
      o.blade = p.blade;
      const ExactModes m = blade_stiffness_modes(o);
      EXPECT_TRUE(RelClose(m[Direction::Flap].omega_nonrotating, pt.modes[0].frequency, 1e-10));
      EXPECT_TRUE(RelClose(m[Direction::Lag].omega_nonrotating, pt.modes[1].frequency, 1e-10));
      continue;
    }
    BladeProperties at_s = b;
    for (double& k : at_s.stiffness_flap) k /= s * s;
    for (double& k : at_s.stiffness_lag) k /= s * s;
    o.blade = std::make_shared<const BladeProperties>(at_s);
    const ExactModes m = blade_stiffness_modes(o);
    EXPECT_TRUE(RelClose(m.modes[Direction::Flap].omega[0], pt.omega_flap, 1e-10));
    EXPECT_TRUE(RelClose(m.modes[Direction::Lag].omega[0], pt.omega_lag, 1e-10));
    EXPECT_TRUE(AbsClose(s * m.modes[Direction::Flap].omega[0], pt.modes[0].frequency, 1e-4));
    EXPECT_TRUE(AbsClose(s * m.modes[Direction::Lag].omega[0], pt.modes[1].frequency, 1e-4));
    // The analysis at this speed, given those first frequencies, scales the columns by 1 / s^2.
    RotorParameters at = p;
    at.omega_flap = pt.omega_flap;
    at.omega_lag = pt.omega_lag;
    const Analysis an(at, {});
    EXPECT_TRUE(RelClose(1.0 / (s * s), an.modes()[Direction::Flap].stiffness, 1e-10));
    EXPECT_TRUE(RelClose(1.0 / (s * s), an.modes()[Direction::Lag].stiffness, 1e-10));
  }
}

// A nondimensional table (columns a shape): the nominal scale s0 of the diagram is the
// analysis' own at Omega_0, and the analysis at speed s comes back to s0 / s^2; at Omega_0 the
// modes are the rotor's own point analysis.
TEST(CampbellTable, TheScaleAtEachSpeedIsTheNominalOneOverTheSpeedSquared) {
  BladeProperties shape = absolute_taper();
  for (double& k : shape.stiffness_flap) k /= 0.012;
  for (double& k : shape.stiffness_lag) k /= 0.09;
  RotorParameters p;
  p.modes = ModeKind::Exact;
  p.root_offset = 0.05;
  p.length_ratio = 0.95;
  p.omega_flap = 1.12;
  p.omega_lag = 0.75;
  p.blade = std::make_shared<const BladeProperties>(shape);
  CampbellOptions o = coarse(3);
  o.speed_max = 1.0;  // speeds 0, 0.5, 1
  const CampbellResult c = campbell_diagram(p, {}, o);
  ASSERT_TRUE(c.IsUsable()) << c.message;
  const Analysis nominal(p, {});
  const double s0_flap = nominal.modes()[Direction::Flap].stiffness,
               s0_lag = nominal.modes()[Direction::Lag].stiffness;
  for (std::size_t i = 1; i < c.points.size(); ++i) {
    const CampbellPoint& pt = c.points[i];
    const double s = pt.speed;
    RotorParameters at = p;
    at.omega_flap = pt.omega_flap;
    at.omega_lag = pt.omega_lag;
    const Analysis an(at, {});
    EXPECT_TRUE(RelClose(s0_flap / (s * s), an.modes()[Direction::Flap].stiffness, 1e-10)) << s;
    EXPECT_TRUE(RelClose(s0_lag / (s * s), an.modes()[Direction::Lag].stiffness, 1e-10)) << s;
  }
  const CampbellPoint& last = c.points.back();
  EXPECT_EQ(last.speed, 1.0);
  EXPECT_TRUE(RelClose(p.omega_flap, last.omega_flap, 1e-10));
  EXPECT_TRUE(RelClose(p.omega_lag, last.omega_lag, 1e-10));
  const PointResult hover = nominal.point(0.0);
  for (const CampbellFrequency& f : last.modes) {
    const LabelledExponent* e = dominant_exponent(hover, f.label);
    ASSERT_NE(e, nullptr);
    EXPECT_TRUE(RelClose(e->omega, f.omega, 1e-9)) << f.label;
  }
  // At rest: the table's first nonrotating frequencies at the nominal scale (the same blade
  // with the columns times s0, taken as absolute).
  BladeProperties absolute = shape;
  for (double& k : absolute.stiffness_flap) k *= s0_flap;
  for (double& k : absolute.stiffness_lag) k *= s0_lag;
  ExactModeOptions m;
  m.n_basis = galerkin_basis(p);
  m.e1_over_l = p.root_offset / p.length_ratio;
  m.blade = std::make_shared<const BladeProperties>(absolute);
  const ExactModes at_rest = blade_stiffness_modes(m);
  EXPECT_TRUE(
      RelClose(at_rest[Direction::Flap].omega_nonrotating, c.points[0].modes[0].frequency, 1e-10));
  EXPECT_TRUE(
      RelClose(at_rest[Direction::Lag].omega_nonrotating, c.points[0].modes[1].frequency, 1e-10));
}

// Imported shapes hold at one rotor speed: refused, naming the mode file.
TEST(CampbellTable, ImportedShapesAreRefused) {
  RotorParameters p;
  p.modes = ModeKind::Exact;
  ExactModeOptions o;
  o.n_basis = galerkin_basis(p);
  p.mode_shapes = std::make_shared<const ImportedModes>(parse_mode_table(
      mode_table_text(exact_modes(p.omega_flap, p.omega_lag, o), 41), "fe-modes.csv"));
  try {
    campbell_diagram(p, {}, coarse());
    ADD_FAILURE() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_EQ("mode_shapes", e.name());
    EXPECT_EQ("fe-modes.csv", e.value());
  }
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
}  // namespace flaplag::campbell_test
