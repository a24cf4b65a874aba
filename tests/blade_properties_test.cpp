// Nonuniform blades (blade/blade_properties.h and every integral that weights by a blade table):
// the table's checks, the uniform table against the uniform model, and the nonuniform blade
// against references written here.
//
// Expected values come from elsewhere than the code under test: closed forms (eq 2.24, the
// moments of linear distributions), the uniform blade's own code path (no table), a
// Hermite-cubic finite-element model of the rotating cantilever, and composite Simpson rules
// over the mode shapes with the distributions interpolated here.
#include "flaplag/blade/blade_properties.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "flaplag/analysis.h"
#include "flaplag/blade/aero_integrals.h"
#include "flaplag/blade/blade.h"
#include "flaplag/blade/blade_elements.h"
#include "flaplag/blade/rotating_modes.h"
#include "flaplag/core/errors.h"
#include "flaplag/model_api.h"
#include "flaplag/rotor/parameters.h"
#include "test_util.h"

namespace flaplag::blade_properties_test {
namespace {

using flaplag::model::Direction;
using testing::AbsClose;
using testing::RelClose;

constexpr double kPiHere = 3.141592653589793;

// ---- distributions, written here ----------------------------------------------------------------

// Linear interpolation between stations x (increasing, 0..1) of the values v.
double linear(const std::vector<double>& x, const std::vector<double>& v, double s) {
  std::size_t i = 0;
  while (i + 2 < x.size() && s > x[i + 1]) ++i;
  return v[i] + (v[i + 1] - v[i]) * (s - x[i]) / (x[i + 1] - x[i]);
}

// int_0^1 m(x) x^2 dx of a piecewise-linear m, in closed form.
double second_moment(const std::vector<double>& x, const std::vector<double>& m) {
  double s = 0.0;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    const double a = x[i], b = x[i + 1];
    const double slope = (m[i + 1] - m[i]) / (b - a);
    const double i2 = (b * b * b - a * a * a) / 3.0, i3 = (b * b * b * b - a * a * a * a) / 4.0;
    s += m[i] * i2 + slope * (i3 - a * i2);
  }
  return s;
}

// A blade table: stations, mass shape (scaled here so that int mbar x0^2 + tip = 1), stiffness
// columns, chord, twist and tip mass.
BladeProperties table(std::vector<double> x0, const std::vector<double>& mass_shape,
                      std::vector<double> ky, std::vector<double> kz, std::vector<double> chord,
                      std::vector<double> twist, double tip) {
  BladeProperties b;
  const double scale = (1.0 - tip) / second_moment(x0, mass_shape);
  for (double m : mass_shape) b.mass.push_back(scale * m);
  b.x0 = std::move(x0);
  b.stiffness_flap = std::move(ky);
  b.stiffness_lag = std::move(kz);
  b.chord = std::move(chord);
  b.twist = std::move(twist);
  b.tip_mass = tip;
  b.source = "test";
  return b;
}

// Composite Simpson on [0, 1] with n (even) intervals whose nodes hold the corners.
double simpson(const std::function<double(double)>& f, int n = 4000) {
  const double h = 1.0 / n;
  double s = f(0.0) + f(1.0);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * f(i * h);
  return s * h / 3.0;
}

// ---- 1. the table's checks ----------------------------------------------------------------------

// Four stations, uniform mass 3 (int 3 x^2 = 1), a source so that messages carry station numbers.
BladeProperties good_blade() {
  BladeProperties b;
  b.x0 = {0.0, 0.25, 0.5, 1.0};
  b.mass = {3.0, 3.0, 3.0, 3.0};
  b.stiffness_flap = {1.0, 1.0, 1.0, 1.0};
  b.stiffness_lag = {2.0, 2.0, 2.0, 2.0};
  b.chord = {1.0, 1.0, 1.0, 1.0};
  b.twist = {0.0, 0.0, 0.0, 0.0};
  b.source = "t.csv";
  return b;
}

struct BadBlade {
  const char* what;
  std::function<void(BladeProperties&)> spoil;
  std::vector<std::string> says;  // what() must contain each
  const char* name = nullptr;     // InvalidInput::name(), when given
};

std::vector<BadBlade> bad_blades() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  return {
      {"one station",
       [](BladeProperties& b) {
         b = {};
         b.x0 = {0.0};
       },
       {"stations = 1"}},
      {"x0 decreasing",
       [](BladeProperties& b) { b.x0[2] = 0.2; },
       {"x0 (t.csv, station 3) = 0.2", "strictly increasing"}},
      {"x0 repeated",
       [](BladeProperties& b) { b.x0[2] = 0.25; },
       {"x0 (t.csv, station 3) = 0.25", "strictly increasing"}},
      {"x0 NaN", [nan](BladeProperties& b) { b.x0[1] = nan; }, {"x0 (t.csv, station 2) = nan"}},
      {"x0 from 0.1", [](BladeProperties& b) { b.x0[0] = 0.1; }, {"x0 = 0.1..1", "from 0"}},
      {"x0 to 0.9", [](BladeProperties& b) { b.x0[3] = 0.9; }, {"x0 = 0..0.9", "1 (tip)"}},
      {"x0 from -0.1", [](BladeProperties& b) { b.x0[0] = -0.1; }, {"x0 = -0.1..1"}},
      {"mass zero",
       [](BladeProperties& b) { b.mass[1] = 0.0; },
       {"mass at x0 = 0.25 (t.csv, station 2) = 0", "> 0"}},
      {"mass negative",
       [](BladeProperties& b) { b.mass[3] = -3.0; },
       {"mass at x0 = 1 (t.csv, station 4) = -3"}},
      {"mass NaN",
       [nan](BladeProperties& b) { b.mass[2] = nan; },
       {"mass at x0 = 0.5 (t.csv, station 3) = nan", "finite"}},
      {"EI_flap negative",
       [](BladeProperties& b) { b.stiffness_flap[3] = -1.0; },
       {"EI_flap at x0 = 1 (t.csv, station 4) = -1"}},
      {"EI_flap infinite",
       [inf](BladeProperties& b) { b.stiffness_flap[1] = inf; },
       {"EI_flap at x0 = 0.25 (t.csv, station 2) = inf", "finite"}},
      {"EI_lag zero",
       [](BladeProperties& b) { b.stiffness_lag[0] = 0.0; },
       {"EI_lag at x0 = 0 (t.csv, station 1) = 0"}},
      {"chord zero",
       [](BladeProperties& b) { b.chord[2] = 0.0; },
       {"chord at x0 = 0.5 (t.csv, station 3) = 0"}},
      {"chord negative",
       [](BladeProperties& b) { b.chord[0] = -0.5; },
       {"chord at x0 = 0 (t.csv, station 1) = -0.5"}},
      {"twist above pi/2",
       [](BladeProperties& b) { b.twist[1] = 1.6; },
       {"twist at x0 = 0.25 (t.csv, station 2) = 1.6", "< 1.57"}},
      {"twist at -pi/2",
       [](BladeProperties& b) { b.twist[3] = -kPiHere / 2; },
       {"twist at x0 = 1 (t.csv, station 4) = -1.57", "> -1.57"}},
      {"twist NaN",
       [nan](BladeProperties& b) { b.twist[2] = nan; },
       {"twist at x0 = 0.5 (t.csv, station 3) = nan"}},
      {"chord too short",
       [](BladeProperties& b) { b.chord.pop_back(); },
       {"chord = 3 values", "one value per station (4)"}},
      {"EI_lag too long",
       [](BladeProperties& b) { b.stiffness_lag.push_back(1.0); },
       {"EI_lag = 5 values", "one value per station (4)"}},
      {"twist missing", [](BladeProperties& b) { b.twist.clear(); }, {"twist = 0 values"}},
      {"tip mass negative",
       [](BladeProperties& b) { b.tip_mass = -0.1; },
       {"tip_mass = -0.1", ">= 0"}},
      {"tip mass NaN", [nan](BladeProperties& b) { b.tip_mass = nan; }, {"tip_mass = nan"}},
      // int 3.3 x^2 = 1.1
      {"mass not normalised",
       [](BladeProperties& b) {
         for (double& m : b.mass) m = 3.3;
       },
       {"mass = 1.0999", "tip_mass must be 1"},
       "mass"},
      {"tip mass on a full blade",
       [](BladeProperties& b) { b.tip_mass = 0.1; },
       {"mass = 1.1", "tip_mass must be 1"},
       "mass"},
  };
}

TEST(BladeValidation, AGoodTableIsAccepted) {
  EXPECT_NO_THROW(validate(good_blade()));
  EXPECT_NO_THROW(validate(uniform_blade(0.3, 0.7)));
  BladeProperties b = good_blade();
  b.twist = {1.5, -1.5, 0.0, 1.5};  // inside (-pi/2, pi/2)
  EXPECT_NO_THROW(validate(b));
}

TEST(BladeValidation, EachBadTableNamesItsColumnAndStation) {
  for (const BadBlade& c : bad_blades()) {
    SCOPED_TRACE(c.what);
    BladeProperties b = good_blade();
    c.spoil(b);
    try {
      validate(b);
      ADD_FAILURE() << "accepted";
    } catch (const InvalidInput& e) {
      const std::string what = e.what();
      for (const std::string& s : c.says) EXPECT_NE(what.find(s), std::string::npos) << what;
      if (c.name) {
        EXPECT_EQ(e.name(), c.name);
      }
    }
  }
}

// Without a source the station is named by its x0.
TEST(BladeValidation, WithoutASourceTheStationIsItsX0) {
  BladeProperties b = good_blade();
  b.source.clear();
  b.chord[1] = -1.0;
  try {
    validate(b);
    ADD_FAILURE() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.name(), "chord at x0 = 0.25");
    EXPECT_EQ(e.value(), "-1");
  }
}

// The normalisation is checked to 1e-12: a mass 2e-12 too large is refused, 2e-13 is not.
TEST(BladeValidation, MassNormalisationTolerance) {
  BladeProperties b = good_blade();
  for (double& m : b.mass) m = 3.0 * (1.0 + 2e-12);
  EXPECT_THROW(validate(b), InvalidInput);
  for (double& m : b.mass) m = 3.0 * (1.0 + 2e-13);
  EXPECT_NO_THROW(validate(b));
}

TEST(BladeValidation, NormalisedMassScalesMassAndTipMassTogether) {
  BladeProperties b = good_blade();
  b.mass = {40.0, 30.0, 25.0, 12.0};  // kg/m, say
  b.tip_mass = 4.0;
  const double total = second_moment(b.x0, b.mass) + b.tip_mass;
  const BladeProperties n = normalised_mass(b);
  EXPECT_NO_THROW(validate(n));
  for (std::size_t i = 0; i < b.mass.size(); ++i)
    EXPECT_TRUE(RelClose(b.mass[i] / total, n.mass[i], 1e-14));
  EXPECT_TRUE(RelClose(4.0 / total, n.tip_mass, 1e-14));
  EXPECT_TRUE(RelClose(1.0, second_moment(n.x0, n.mass) + n.tip_mass, 1e-14));
  // The other checks still apply.
  b.chord[2] = 0.0;
  EXPECT_THROW(normalised_mass(b), InvalidInput);
}

TEST(BladeValidation, UniformBladeIsThePapers) {
  const BladeProperties u = uniform_blade(0.4, 0.9);
  EXPECT_TRUE(RelClose(1.0, second_moment(u.x0, u.mass), 1e-15));
  EXPECT_EQ(u.tip_mass, 0.0);
  EXPECT_EQ(u.stiffness_flap, (std::vector<double>{0.4, 0.4}));
  EXPECT_EQ(u.stiffness_lag, (std::vector<double>{0.9, 0.9}));
  EXPECT_TRUE(u.corners().empty());
}

TEST(BladeValidation, InterpolationIsLinearBetweenStations) {
  const BladeProperties b = table({0.0, 0.25, 1.0}, {1.5, 1.2, 0.7}, {2, 1.2, 0.5}, {2, 1.2, 0.5},
                                  {1, 0.9, 0.6}, {0.0, -0.05, -0.2}, 0.05);
  for (double s : {0.0, 0.1, 0.25, 0.3, 0.77, 1.0}) {
    EXPECT_TRUE(RelClose(linear(b.x0, b.mass, s), b.mass_at(s), 1e-15)) << s;
    EXPECT_TRUE(RelClose(linear(b.x0, b.chord, s), b.chord_at(s), 1e-15)) << s;
    EXPECT_TRUE(AbsClose(linear(b.x0, b.twist, s), b.twist_at(s), 1e-16)) << s;
  }
  EXPECT_EQ(b.corners(), std::vector<double>{0.25});
}

// ---- shared -------------------------------------------------------------------------------------

const model::ModelDescriptor& paper_model(int M, int N) {
  for (const model::ModelFamily* f : model::registered_families())
    if (std::string(f->name) == "paper") return model::instantiate(*f, M, N);
  throw std::logic_error("no paper family");
}

std::shared_ptr<const BladeProperties> shared(const BladeProperties& b) {
  return std::make_shared<const BladeProperties>(b);
}

// ---- 2. the uniform table is the uniform model --------------------------------------------------

struct UniformCase {
  double omega_flap, omega_lag, e1_over_l;
  int n_basis;
};

class UniformTable : public ::testing::TestWithParam<UniformCase> {};

TEST_P(UniformTable, RotatingFrequenciesAndStiffnessesAreTheUniformModels) {
  const UniformCase c = GetParam();
  ExactModeOptions o;
  o.n_basis = c.n_basis;
  o.flap_modes = o.lag_modes = std::min(3, c.n_basis);
  o.e1_over_l = c.e1_over_l;
  const ExactModes uniform = exact_rotating_modes(c.omega_flap, c.omega_lag, o);
  o.blade = shared(uniform_blade());
  const ExactModes tab = exact_rotating_modes(c.omega_flap, c.omega_lag, o);
  ASSERT_EQ(tab[Direction::Flap].omega_all.size(), uniform[Direction::Flap].omega_all.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < uniform[Direction::Flap].omega_all.size(); ++i) {
    EXPECT_TRUE(
        RelClose(uniform[Direction::Flap].omega_all[i], tab[Direction::Flap].omega_all[i], 1e-10))
        << "flap " << i;
    EXPECT_TRUE(
        RelClose(uniform[Direction::Lag].omega_all[i], tab[Direction::Lag].omega_all[i], 1e-10))
        << "lag " << i;
    worst = std::max(
        {worst,
         std::abs(tab[Direction::Flap].omega_all[i] / uniform[Direction::Flap].omega_all[i] - 1.0),
         std::abs(tab[Direction::Lag].omega_all[i] / uniform[Direction::Lag].omega_all[i] - 1.0)});
  }
  std::printf("uniform table: %d rotating frequencies per direction within %.2g\n", c.n_basis,
              worst);
  // The column is 1: the scale is the uniform blade's k.
  EXPECT_TRUE(RelClose(uniform.modes[Direction::Flap].stiffness,
                       tab.modes[Direction::Flap].stiffness, 1e-10));
  EXPECT_TRUE(RelClose(uniform.modes[Direction::Lag].stiffness, tab.modes[Direction::Lag].stiffness,
                       1e-10));
  EXPECT_TRUE(RelClose(uniform[Direction::Flap].omega_nonrotating,
                       tab[Direction::Flap].omega_nonrotating, 1e-10));
  EXPECT_TRUE(RelClose(uniform[Direction::Lag].omega_nonrotating,
                       tab[Direction::Lag].omega_nonrotating, 1e-10));
  // The shapes (tip-normalised both).
  for (int k = 0; k < o.flap_modes; ++k) {
    for (double x : {0.2, 0.5, 0.9, 1.0}) {
      for (int d = 0; d <= 2; ++d) {
        EXPECT_TRUE(AbsClose(uniform.modes.shapes(Direction::Flap)[k]->value(d, x),
                             tab.modes.shapes(Direction::Flap)[k]->value(d, x),
                             1e-9 * std::pow(10.0, d)));
        EXPECT_TRUE(AbsClose(uniform.modes.shapes(Direction::Lag)[k]->value(d, x),
                             tab.modes.shapes(Direction::Lag)[k]->value(d, x),
                             1e-9 * std::pow(10.0, d)));
      }
    }
  }
  // The table's columns as absolute stiffness give the first frequencies back.
  o.blade = shared(uniform_blade(uniform.modes[Direction::Flap].stiffness,
                                 uniform.modes[Direction::Lag].stiffness));
  const ExactModes absolute = blade_stiffness_modes(o);
  EXPECT_TRUE(RelClose(c.omega_flap, absolute.modes[Direction::Flap].omega[0], 1e-10));
  EXPECT_TRUE(RelClose(c.omega_lag, absolute.modes[Direction::Lag].omega[0], 1e-10));
  EXPECT_EQ(absolute.modes[Direction::Flap].stiffness, 1.0);
  EXPECT_EQ(absolute.modes[Direction::Lag].stiffness, 1.0);
}

// The frequency functions of rotating_modes.h with the uniform table (column 1, mass 3: the scale
// is k) against the uniform blade's own code path.
TEST_P(UniformTable, FrequencyFunctionsAreTheUniformBlades) {
  const UniformCase c = GetParam();
  ExactModeOptions u;
  u.n_basis = c.n_basis;
  u.e1_over_l = c.e1_over_l;
  ExactModeOptions t = u;
  t.blade = shared(uniform_blade());
  // A shape that is no mode (for the Rayleigh quotient): two cantilever functions.
  const ModalCombination shape({cantilever_mode(1), cantilever_mode(2)},
                               (Eigen::VectorXd(2) << 1.0, 0.3).finished());
  for (const BendingDirection dir : {BendingDirection::Flap, BendingDirection::Lag}) {
    const bool flap = dir == BendingDirection::Flap;
    SCOPED_TRACE(flap ? "flap" : "lag");
    const double omega = flap ? c.omega_flap : c.omega_lag;
    EXPECT_TRUE(RelClose(centrifugal_limit(dir, u), centrifugal_limit(dir, t), 1e-10));
    const double k = stiffness_for_frequency(dir, omega, u);
    EXPECT_TRUE(RelClose(k, stiffness_for_frequency(dir, omega, t), 1e-10));
    const std::vector<double> ru = rotating_frequencies(dir, k, u);
    const std::vector<double> rt = rotating_frequencies(dir, k, t);
    const std::vector<double> nu = nonrotating_frequencies(dir, k, u);
    const std::vector<double> nt = nonrotating_frequencies(dir, k, t);
    ASSERT_EQ(rt.size(), static_cast<std::size_t>(c.n_basis));
    ASSERT_EQ(nt.size(), static_cast<std::size_t>(c.n_basis));
    ASSERT_EQ(nu.size(), nt.size());
    for (int i = 0; i < c.n_basis; ++i) {
      EXPECT_TRUE(RelClose(ru[i], rt[i], 1e-10)) << "rotating " << i + 1;
      EXPECT_TRUE(RelClose(nu[i], nt[i], 1e-10)) << "nonrotating " << i + 1;
      // The cantilever's own frequencies, written here: k beta^4 = mbar w^2.
      const double beta = cantilever_root(i + 1);
      EXPECT_TRUE(RelClose(std::sqrt(k / 3.0) * beta * beta, nt[i], 1e-10)) << i + 1;
    }
    EXPECT_TRUE(RelClose(omega, rt[0], 1e-12));
    EXPECT_TRUE(RelClose(nonrotating_frequency(dir, omega, u), nonrotating_frequency(dir, omega, t),
                         1e-10));
    EXPECT_TRUE(RelClose(rotating_frequency(dir, 3.0, u), rotating_frequency(dir, 3.0, t), 1e-10));
    const std::vector<FrequencyPair> fu = fig9_table(dir, 0.0, 6.0, 13, u);
    const std::vector<FrequencyPair> ft = fig9_table(dir, 0.0, 6.0, 13, t);
    ASSERT_EQ(fu.size(), ft.size());
    for (std::size_t i = 0; i < fu.size(); ++i) {
      EXPECT_EQ(fu[i].nonrotating, ft[i].nonrotating);
      EXPECT_TRUE(RelClose(fu[i].rotating, ft[i].rotating, 1e-10)) << "fig 9 row " << i;
    }
    EXPECT_TRUE(RelClose(rayleigh_frequency(dir, shape, k, c.e1_over_l, 3.0),
                         rayleigh_frequency(dir, shape, k, c.e1_over_l, *t.blade), 1e-12));
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, UniformTable,
                         ::testing::Values(UniformCase{1.175, 1.28303, 0.0, kMaxBasisFunctions},
                                           UniformCase{1.175, 1.28303, 0.1, kMaxBasisFunctions},
                                           UniformCase{1.12, 0.7, 0.05, 5},
                                           UniformCase{2.5, 3.5, 0.2, 8}));

// The integrals of the uniform table's modes against those of the uniform model's: the
// weighting (mass 3, chord 1) on the same shapes to rounding, and the table's own modes to the
// accuracy of their shapes.
TEST(UniformTable, IntegralsAreTheUniformModels) {
  const model::ModelDescriptor& m = paper_model(2, 2);
  ExactModeOptions o;
  o.n_basis = kMaxBasisFunctions;
  o.flap_modes = o.lag_modes = 2;
  o.e1_over_l = 0.1;
  const ModeSet uniform = exact_modes(1.175, 1.28303, o);
  ModeSet weighted = uniform;
  weighted.blade = shared(uniform_blade());
  o.blade = weighted.blade;
  const ModeSet tab = exact_modes(1.175, 1.28303, o);
  const SpanGeometry g{0.1, 1.0, 0.0, 1.0};

  const std::vector<double> s_ref = structural_integrals(m, uniform, o.e1_over_l);
  const std::vector<double> s_same = structural_integrals(m, weighted, o.e1_over_l);
  const std::vector<double> s_tab = structural_integrals(m, tab, o.e1_over_l);
  const AeroIntegrals a_ref(m, uniform, g), a_same(m, weighted, g), a_tab(m, tab, g);
  double worst_tab = 0.0;
  for (int i = 0; i < m.n_structural; ++i) {
    SCOPED_TRACE(m.structural[i].name);
    EXPECT_TRUE(RelClose(s_ref[i], s_same[i], 1e-12, 1.0));
    EXPECT_TRUE(RelClose(s_ref[i], s_tab[i], 1e-12, 1.0));
    worst_tab =
        std::max(worst_tab, std::abs(s_ref[i] - s_tab[i]) / std::max(1.0, std::abs(s_ref[i])));
  }
  for (double mu : {-1.0, 0.3, 0.75, 1.2}) {
    const std::vector<double> r = mu < 0 ? a_ref.normal() : a_ref.reversed(mu);
    const std::vector<double> s = mu < 0 ? a_same.normal() : a_same.reversed(mu);
    const std::vector<double> t = mu < 0 ? a_tab.normal() : a_tab.reversed(mu);
    for (int j = 0; j < m.n_aero; ++j) {
      SCOPED_TRACE(m.aero[j].name);
      EXPECT_TRUE(RelClose(r[j], s[j], 1e-12, 1.0)) << "mu " << mu;
      EXPECT_TRUE(RelClose(r[j], t[j], 1e-12, 1.0)) << "mu " << mu;
      worst_tab = std::max(worst_tab, std::abs(r[j] - t[j]) / std::max(1.0, std::abs(r[j])));
    }
  }
  std::printf("uniform table's own modes: integrals within %.2g of the uniform model's\n",
              worst_tab);
}

CriticalResult critical_of(const RotorParameters& p) { return Analysis(p, {}).critical({}); }

struct CriticalCase {
  const char* name;
  const char* model;
  double root_offset;
};

class UniformTableCritical : public ::testing::TestWithParam<CriticalCase> {};

TEST_P(UniformTableCritical, SameCriticalAdvanceRatio) {
  RotorParameters p;  // the typical case
  p.modes = ModeKind::Exact;
  p.model = GetParam().model;
  p.root_offset = GetParam().root_offset;
  const CriticalResult ref = critical_of(p);
  ASSERT_NE(ref.status, Status::Failed) << ref.message;
  ASSERT_TRUE(ref.mu_c.has_value());
  p.blade = shared(uniform_blade());
  const CriticalResult tab = critical_of(p);
  ASSERT_NE(tab.status, Status::Failed) << tab.message;
  ASSERT_TRUE(tab.mu_c.has_value());
  EXPECT_TRUE(RelClose(*ref.mu_c, *tab.mu_c, 1e-8));
  EXPECT_TRUE(RelClose(ref.omega, tab.omega, 1e-8));
  EXPECT_EQ(ref.mode, tab.mode);
  std::printf("%s: mu_c %.12g, table %.12g (difference %.2g)\n", GetParam().name, *ref.mu_c,
              *tab.mu_c, *tab.mu_c - *ref.mu_c);
}

INSTANTIATE_TEST_SUITE_P(TypicalCase, UniformTableCritical,
                         ::testing::Values(CriticalCase{"OneByOne", "paper", 0.0},
                                           CriticalCase{"TwoByTwo", "paper-2x2", 0.0},
                                           CriticalCase{"RootOffset", "paper", 0.1}),
                         [](const ::testing::TestParamInfo<CriticalCase>& c) {
                           return std::string(c.param.name);
                         });

// ---- 3. the rotating frequencies of a tapered blade against a finite-element model --------------

// Gauss-Legendre with 5 points on [0, 1] (exact to degree 9).
constexpr double kG5t[5] = {0.5 - 0.4530899229693320, 0.5 - 0.2692346550528416, 0.5,
                            0.5 + 0.2692346550528416, 0.5 + 0.4530899229693320};
constexpr double kG5w[5] = {0.1184634425280945, 0.2393143352496832, 0.2844444444444444,
                            0.2393143352496832, 0.1184634425280945};

// The centrifugal tension T(x) = int_x^1 mbar(x1) (x1 + e) dx1 + tip (1 + e): a quadratic
// integrand per station interval, integrated by the 5-point rule.
double tension(const BladeProperties& b, double e, double x) {
  double t = b.tip_mass * (1.0 + e);
  for (std::size_t i = 0; i + 1 < b.x0.size(); ++i) {
    const double lo = std::max(x, b.x0[i]), hi = b.x0[i + 1];
    if (!(hi > lo)) continue;
    for (int q = 0; q < 5; ++q) {
      const double s = lo + (hi - lo) * kG5t[q];
      t += (hi - lo) * kG5w[q] * linear(b.x0, b.mass, s) * (s + e);
    }
  }
  return t;
}

// Eigenvalues w^2 of the rotating cantilever on n equal Hermite-cubic beam elements (nodes w,
// w' per node, the root clamped): stiffness int k w''^2, geometric stiffness int T w'^2,
// consistent mass int mbar w^2 plus the tip mass on the tip node's w; lag adds -int mbar v^2
// - tip v(1)^2 to the stiffness (the -m Omega^2 v term).  The distributions are linear per
// element (the stations are nodes), so the 5-point rule integrates every element exactly.  Solved
// in long double: in double, rounding at 160 elements is of the size of the h^4 error there and
// spoils the extrapolation.  spin = (Omega / Omega_0)^2 multiplies the centrifugal terms (the
// tension and the lag's -m Omega^2 v; 0: the blade at rest), the eigenvalues staying by
// Omega_0^2 with the stiffness k by Omega_0^2.
Eigen::VectorXd fe_eigenvalues(const BladeProperties& b, double e, BendingDirection dir, int n,
                               double spin = 1.0) {
  for (double s : b.x0) {
    const double i = s * n;
    if (std::abs(i - std::round(i)) > 1e-12) throw std::logic_error("station between nodes");
  }
  const std::vector<double>& k = dir == BendingDirection::Flap ? b.stiffness_flap : b.stiffness_lag;
  const int dofs = 2 * (n + 1);
  using Mat = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
  Mat K = Mat::Zero(dofs, dofs), M = K;
  const double h = 1.0 / n;
  for (int el = 0; el < n; ++el) {
    const double xa = el * h;
    for (int q = 0; q < 5; ++q) {
      const double t = kG5t[q], w = kG5w[q] * h, x = xa + t * h;
      const Eigen::Vector4d N(1 - 3 * t * t + 2 * t * t * t, h * (t - 2 * t * t + t * t * t),
                              3 * t * t - 2 * t * t * t, h * (-t * t + t * t * t));
      const Eigen::Vector4d N1((-6 * t + 6 * t * t) / h, 1 - 4 * t + 3 * t * t,
                               (6 * t - 6 * t * t) / h, -2 * t + 3 * t * t);
      const Eigen::Vector4d N2((-6 + 12 * t) / (h * h), (-4 + 6 * t) / h, (6 - 12 * t) / (h * h),
                               (-2 + 6 * t) / h);
      const Eigen::Matrix4d ke = w * (linear(b.x0, k, x) * N2 * N2.transpose() +
                                      spin * tension(b, e, x) * N1 * N1.transpose());
      const Eigen::Matrix4d me = w * linear(b.x0, b.mass, x) * N * N.transpose();
      K.block<4, 4>(2 * el, 2 * el) += ke.cast<long double>();
      M.block<4, 4>(2 * el, 2 * el) += me.cast<long double>();
    }
  }
  M(2 * n, 2 * n) += b.tip_mass;
  if (dir == BendingDirection::Lag) K -= static_cast<long double>(spin) * M;
  const Mat Kf = K.bottomRightCorner(dofs - 2, dofs - 2);
  const Mat Mf = M.bottomRightCorner(dofs - 2, dofs - 2);
  Eigen::GeneralizedSelfAdjointEigenSolver<Mat> es(Kf, Mf, Eigen::EigenvaluesOnly);
  return es.eigenvalues().cast<double>();
}

struct Extrapolated {
  std::vector<double> omega;  // Richardson-extrapolated frequencies
  std::vector<double> error;  // the size of the extrapolation step (a bound on the error)
  std::vector<double> order;  // the observed order of convergence of w^2
};

// Eigenvalues on 40, 80 and 160 elements, extrapolated for the h^4 error of cubic elements.
Extrapolated fe_frequencies(const BladeProperties& b, double e, BendingDirection dir, int count,
                            double spin = 1.0) {
  const Eigen::VectorXd l1 = fe_eigenvalues(b, e, dir, 40, spin);
  const Eigen::VectorXd l2 = fe_eigenvalues(b, e, dir, 80, spin);
  const Eigen::VectorXd l3 = fe_eigenvalues(b, e, dir, 160, spin);
  Extrapolated r;
  for (int i = 0; i < count; ++i) {
    const double step = (l3[i] - l2[i]) / 15.0;
    const double lam = l3[i] + step;
    r.omega.push_back(std::sqrt(lam));
    r.error.push_back(std::abs(std::sqrt(lam) - std::sqrt(l3[i])));
    r.order.push_back(std::log2((l1[i] - l2[i]) / (l2[i] - l3[i])));
  }
  return r;
}

// A hingeless blade, soft in plane: mass 1.5 -> 0.7 and EI 2 -> 0.5 relative, linear with a
// corner at x0 = 0.25 (heavier and stiffer root), a tip mass 0.05 of I_b, e1/l = 0.05; absolute
// stiffness k = EI/(Omega^2 l I_b) 0.005 and 0.035 times the shape (first flap ~1.10, first
// lag ~0.70 per rev).
constexpr double kTaperE = 0.05;

BladeProperties tapered_blade() {
  const std::vector<double> shape = {2.0, 1.4, 0.5};
  std::vector<double> ky, kz;
  for (double s : shape) {
    ky.push_back(0.005 * s);
    kz.push_back(0.035 * s);
  }
  return table({0.0, 0.25, 1.0}, {1.5, 1.2, 0.7}, ky, kz, {1.0, 1.0, 1.0}, {0.0, 0.0, 0.0}, 0.05);
}

ExactModes tapered_modes(int n_basis) {
  ExactModeOptions o;
  o.n_basis = n_basis;
  o.flap_modes = 3;
  o.lag_modes = 2;
  o.e1_over_l = kTaperE;
  o.blade = shared(tapered_blade());
  return blade_stiffness_modes(o);
}

// Composite 5-point Gauss on [0, 1] in panels of 1/400 (the stations are panel edges).
double gauss_span(const std::function<double(double)>& f) {
  const int panels = 400;
  double s = 0.0;
  for (int p = 0; p < panels; ++p)
    for (int q = 0; q < 5; ++q) s += kG5w[q] * f((p + kG5t[q]) / panels);
  return s / panels;
}

// Measured (docs/validation.md, "Nonuniform blades"): the FE frequencies converge at order 4.0
// to ~1e-9; the Galerkin frequencies lie above them (a Ritz bound) by 2.8e-5, 3.0e-5, 1.0e-4
// (flap 1-3) and 2.1e-6, 5.4e-6 (lag 1-2) relative with 12 cantilever functions, decreasing
// with the basis, while 12 against 11 functions change them by 1.2e-5, 2.6e-5, 4.0e-7, 1.2e-7,
// 3.1e-6: the change of the basis understates the error of a frequency (by 1.1x to 250x here;
// about 2x for the uniform blade of the typical case).
constexpr double kGalerkinFrequencyTolerance = 2e-4;

TEST(TaperedBlade, RotatingFrequenciesAgreeWithAFiniteElementModel) {
  const BladeProperties b = tapered_blade();
  ASSERT_NO_THROW(validate(b));
  std::vector<ExactModes> galerkin;
  for (int n : {6, 8, 10, 12}) galerkin.push_back(tapered_modes(n));
  const ExactModes& g12 = galerkin.back();
  // The blade asked for: flap ~1.1, lag ~0.7 per rev.
  EXPECT_NEAR(g12.modes[Direction::Flap].omega[0], 1.1, 0.01);
  EXPECT_NEAR(g12.modes[Direction::Lag].omega[0], 0.7, 0.01);
  for (const BendingDirection dir : {BendingDirection::Flap, BendingDirection::Lag}) {
    const bool flap = dir == BendingDirection::Flap;
    const int count = flap ? 3 : 2;
    const Extrapolated fe = fe_frequencies(b, kTaperE, dir, count);
    for (int i = 0; i < count; ++i) {
      SCOPED_TRACE(std::string(flap ? "flap " : "lag ") + std::to_string(i + 1));
      // The reference: h^4 convergence, extrapolated to 1e-8.
      EXPECT_NEAR(fe.order[i], 4.0, 0.1);
      EXPECT_LT(fe.error[i], 1e-8 * fe.omega[i]);
      // Galerkin on nested bases: upper bounds that decrease toward the reference.
      double previous = std::numeric_limits<double>::infinity();
      for (const ExactModes& g : galerkin) {
        const double w = (flap ? g[Direction::Flap].omega_all : g[Direction::Lag].omega_all)[i];
        EXPECT_GT(w, fe.omega[i] - fe.error[i]);
        EXPECT_LT(w - fe.omega[i], previous);
        previous = w - fe.omega[i];
      }
      const double w12 = (flap ? g12[Direction::Flap].omega_all : g12[Direction::Lag].omega_all)[i];
      EXPECT_TRUE(RelClose(fe.omega[i], w12, kGalerkinFrequencyTolerance));
    }
  }
}

// The finite-element modes (blade_elements.h, the reference of a table's Galerkin modes in every
// result's basis_error) against the extrapolated reference above: within their h^4 error at 96
// elements per span (measured 0.5e-9 to 2e-8 relative), upper bounds like every Ritz method, and
// over 200 times closer to the reference than the 12 Galerkin functions are (measured 2000 to
// 5000 times), so that the change from the Galerkin modes to them is the Galerkin modes' error.
TEST(TaperedBlade, FiniteElementModesAreTheReferenceToTheirOwnError) {
  const BladeProperties b = tapered_blade();
  ExactModeOptions o;
  o.flap_modes = 3;
  o.lag_modes = 2;
  o.e1_over_l = kTaperE;
  o.blade = shared(b);
  const ExactModes el = element_stiffness_modes(o);
  const ExactModes g12 = tapered_modes(kMaxBasisFunctions);
  for (const BendingDirection dir : {BendingDirection::Flap, BendingDirection::Lag}) {
    const bool flap = dir == BendingDirection::Flap;
    const int count = flap ? 3 : 2;
    const Extrapolated fe = fe_frequencies(b, kTaperE, dir, count);
    for (int i = 0; i < count; ++i) {
      SCOPED_TRACE(std::string(flap ? "flap " : "lag ") + std::to_string(i + 1));
      const double w_el = (flap ? el[Direction::Flap].omega_all : el[Direction::Lag].omega_all)[i];
      const double w_g = (flap ? g12[Direction::Flap].omega_all : g12[Direction::Lag].omega_all)[i];
      std::printf("%s %d: reference %.12f, elements %+.2e, 12 functions %+.2e\n",
                  flap ? "flap" : "lag", i + 1, fe.omega[i], w_el / fe.omega[i] - 1.0,
                  w_g / fe.omega[i] - 1.0);
      EXPECT_TRUE(RelClose(fe.omega[i], w_el, 5e-8));
      EXPECT_GT(w_el, fe.omega[i] - fe.error[i]);
      EXPECT_LT(std::abs(w_el - fe.omega[i]), 0.005 * std::abs(w_g - fe.omega[i]));
    }
  }
  // The same stiffness: the scales are 1 (absolute columns) for both.
  EXPECT_EQ(1.0, el.modes[Direction::Flap].stiffness);
  EXPECT_EQ(1.0, el.modes[Direction::Lag].stiffness);
}

// The parts of a shape's Rayleigh quotient with the blade's distributions, by quadrature here:
// int k w''^2 (k the column given), int T w'^2, int mbar w^2 + tip w(1)^2.
struct Energies {
  double strain, pull, mass;
};
Energies energies_here(const BladeProperties& b, const std::vector<double>& k, const ModeShape& w) {
  const double strain = gauss_span([&](double x) {
    const double c = w.value(2, x);
    return linear(b.x0, k, x) * c * c;
  });
  const double pull = gauss_span([&](double x) {
    const double sl = w.value(1, x);
    return tension(b, kTaperE, x) * sl * sl;
  });
  const double tip = w.value(0, 1.0);
  const double mass = gauss_span([&](double x) {
                        const double v = w.value(0, x);
                        return linear(b.x0, b.mass, x) * v * v;
                      }) +
                      b.tip_mass * tip * tip;
  return {strain, pull, mass};
}

// The Galerkin matrices themselves, without the basis's truncation: the Rayleigh quotient of
// each computed shape (stiffness, tension and mass by quadrature here, the tip mass in the mass
// and the tension) is its frequency, and the shapes are orthogonal in the mass with the tip mass.
TEST(TaperedBlade, ShapesHaveTheirFrequenciesAsRayleighQuotients) {
  const BladeProperties b = tapered_blade();
  const ExactModes g = tapered_modes(kMaxBasisFunctions);
  double worst = 0.0, worst_orthogonality = 0.0;
  for (const BendingDirection dir : {BendingDirection::Flap, BendingDirection::Lag}) {
    const bool flap = dir == BendingDirection::Flap;
    const auto& shapes = flap ? g.modes.shapes(Direction::Flap) : g.modes.shapes(Direction::Lag);
    const std::vector<double>& k = flap ? b.stiffness_flap : b.stiffness_lag;
    auto mass = [&](const ModeShape& u, const ModeShape& v) {
      return gauss_span([&](double x) {
               return linear(b.x0, b.mass, x) * u.value(0, x) * v.value(0, x);
             }) +
             b.tip_mass * u.value(0, 1.0) * v.value(0, 1.0);
    };
    for (std::size_t i = 0; i < shapes.size(); ++i) {
      const ModeShape& w = *shapes[i];
      const Energies e = energies_here(b, k, w);
      const double m = e.mass;
      const double rayleigh = (e.strain + e.pull) / m - (flap ? 0.0 : 1.0);
      const double omega =
          (flap ? g.modes[Direction::Flap].omega : g.modes[Direction::Lag].omega)[i];
      EXPECT_TRUE(RelClose(omega, std::sqrt(rayleigh), 1e-10)) << (flap ? "flap " : "lag ") << i;
      worst = std::max(worst, std::abs(std::sqrt(rayleigh) / omega - 1.0));
      EXPECT_DOUBLE_EQ(w.value(0, 1.0), 1.0);  // tip-normalised
      for (std::size_t j = 0; j < i; ++j) {
        const double mij = mass(w, *shapes[j]);
        const double defect = std::abs(mij) / std::sqrt(m * mass(*shapes[j], *shapes[j]));
        EXPECT_LT(defect, 1e-10);
        worst_orthogonality = std::max(worst_orthogonality, defect);
      }
    }
  }
  std::printf("tapered blade: Rayleigh quotients within %.2g, mass orthogonality %.2g\n", worst,
              worst_orthogonality);
}

// Stiffness columns given as a shape: scaled to the first frequencies, the same blade.
TEST(TaperedBlade, ScaledColumnsGiveTheAbsoluteBlade) {
  const ExactModes absolute = tapered_modes(kMaxBasisFunctions);
  ExactModeOptions o;
  o.flap_modes = 3;
  o.lag_modes = 2;
  o.n_basis = kMaxBasisFunctions;
  o.e1_over_l = kTaperE;
  BladeProperties shape = tapered_blade();
  for (double& k : shape.stiffness_flap) k /= 0.005;
  for (double& k : shape.stiffness_lag) k /= 0.035;
  o.blade = shared(shape);
  const ExactModes scaled = exact_rotating_modes(absolute.modes[Direction::Flap].omega[0],
                                                 absolute.modes[Direction::Lag].omega[0], o);
  EXPECT_TRUE(RelClose(0.005, scaled.modes[Direction::Flap].stiffness, 1e-10));
  EXPECT_TRUE(RelClose(0.035, scaled.modes[Direction::Lag].stiffness, 1e-10));
  for (int i = 0; i < 3; ++i)
    EXPECT_TRUE(RelClose(absolute[Direction::Flap].omega_all[i],
                         scaled[Direction::Flap].omega_all[i], 1e-10));
  for (int i = 0; i < 2; ++i)
    EXPECT_TRUE(RelClose(absolute[Direction::Lag].omega_all[i], scaled[Direction::Lag].omega_all[i],
                         1e-10));
}

// The frequency functions of a table (rotating_modes.h) at rest and at other rotor speeds: the
// absolute blade at speed r Omega_0 has the scale 1 / r^2 (k = EI / (Omega^2 l I_b)); its
// frequencies by Omega_0, r omega(r), against the finite-element model with the centrifugal terms
// times r^2 (none at rest).
TEST(TaperedBlade, FrequenciesAtRestAndAtOtherSpeedsAgreeWithAFiniteElementModel) {
  const BladeProperties b = tapered_blade();
  ExactModeOptions o;
  o.n_basis = kMaxBasisFunctions;
  o.e1_over_l = kTaperE;
  o.blade = shared(b);
  for (const BendingDirection dir : {BendingDirection::Flap, BendingDirection::Lag}) {
    const bool flap = dir == BendingDirection::Flap;
    SCOPED_TRACE(flap ? "flap" : "lag");
    const Extrapolated rest = fe_frequencies(b, kTaperE, dir, 3, 0.0);
    const std::vector<double> nr = nonrotating_frequencies(dir, 1.0, o);
    ASSERT_EQ(nr.size(), static_cast<std::size_t>(kMaxBasisFunctions));
    for (int i = 0; i < 3; ++i) {
      EXPECT_LT(rest.error[i], 1e-8 * rest.omega[i]);
      EXPECT_GT(nr[i], rest.omega[i] - rest.error[i]) << "nonrotating " << i + 1;  // Ritz bound
      EXPECT_TRUE(RelClose(rest.omega[i], nr[i], kGalerkinFrequencyTolerance))
          << "nonrotating " << i + 1;
    }
    for (double r : {0.5, 1.6}) {
      const Extrapolated fe = fe_frequencies(b, kTaperE, dir, 2, r * r);
      const std::vector<double> w = rotating_frequencies(dir, 1.0 / (r * r), o);
      for (int i = 0; i < 2; ++i) {
        EXPECT_TRUE(RelClose(fe.omega[i], r * w[i], kGalerkinFrequencyTolerance))
            << "speed " << r << ", mode " << i + 1;
      }
    }
    // Fig 9 of the table: the first rotating frequency at scale 1 and the first nonrotating one
    // are each other's; doubling the nonrotating frequency is four times the scale.
    const double w1 = rotating_frequencies(dir, 1.0, o)[0];
    EXPECT_TRUE(RelClose(1.0, stiffness_for_frequency(dir, w1, o), 1e-10));
    EXPECT_TRUE(RelClose(nr[0], nonrotating_frequency(dir, w1, o), 1e-10));
    EXPECT_TRUE(RelClose(w1, rotating_frequency(dir, nr[0], o), 1e-10));
    const std::vector<FrequencyPair> fig9 = fig9_table(dir, 0.0, 2.0 * nr[0], 3, o);
    EXPECT_TRUE(RelClose(w1, fig9[1].rotating, 1e-10));
    EXPECT_TRUE(RelClose(rotating_frequencies(dir, 4.0, o)[0], fig9[2].rotating, 1e-10));
    // No stiffness: the centrifugal limit, the first frequency of the k -> 0 blade.
    EXPECT_EQ(rotating_frequencies(dir, 0.0, o)[0], centrifugal_limit(dir, o));
    EXPECT_TRUE(RelClose(centrifugal_limit(dir, o), fig9[0].rotating, 1e-12));
  }
}

// A column given in other units is the same blade with another scale.
TEST(TaperedBlade, AStifferColumnIsTheSameBladeAtASmallerScale) {
  ExactModeOptions o;
  o.n_basis = 8;
  o.e1_over_l = kTaperE;
  o.blade = shared(tapered_blade());
  ExactModeOptions stiff = o;
  BladeProperties b = tapered_blade();
  for (double& k : b.stiffness_flap) k *= 40.0;
  for (double& k : b.stiffness_lag) k *= 0.25;
  stiff.blade = shared(b);
  for (const BendingDirection dir : {BendingDirection::Flap, BendingDirection::Lag}) {
    const bool flap = dir == BendingDirection::Flap;
    const double factor = flap ? 40.0 : 0.25;
    const double omega = flap ? 1.3 : 0.9;
    const double s = stiffness_for_frequency(dir, omega, o);
    EXPECT_TRUE(RelClose(s / factor, stiffness_for_frequency(dir, omega, stiff), 1e-10));
    const std::vector<double> a = nonrotating_frequencies(dir, s, o);
    const std::vector<double> c = nonrotating_frequencies(dir, s / factor, stiff);
    const std::vector<double> ra = rotating_frequencies(dir, s, o);
    const std::vector<double> rc = rotating_frequencies(dir, s / factor, stiff);
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_TRUE(RelClose(a[i], c[i], 1e-10)) << i;
      EXPECT_TRUE(RelClose(ra[i], rc[i], 1e-10)) << i;
    }
    EXPECT_TRUE(RelClose(nonrotating_frequency(dir, omega, o),
                         nonrotating_frequency(dir, omega, stiff), 1e-10));
    EXPECT_EQ(centrifugal_limit(dir, o), centrifugal_limit(dir, stiff));
  }
}

// The Rayleigh quotient with the table's distributions: the exact modes' frequencies, and for a
// shape that is no mode the quotient written here (5-point Gauss panels, tension and tip mass as
// above).
TEST(TaperedBlade, RayleighFrequencyWeighsTheTablesDistributions) {
  const BladeProperties b = tapered_blade();
  const ExactModes g = tapered_modes(kMaxBasisFunctions);
  for (std::size_t i = 0; i < g.modes.shapes(Direction::Flap).size(); ++i)
    EXPECT_TRUE(RelClose(g.modes[Direction::Flap].omega[i],
                         rayleigh_frequency(BendingDirection::Flap,
                                            *g.modes.shapes(Direction::Flap)[i], 1.0, kTaperE, b),
                         1e-10));
  for (std::size_t i = 0; i < g.modes.shapes(Direction::Lag).size(); ++i)
    EXPECT_TRUE(RelClose(g.modes[Direction::Lag].omega[i],
                         rayleigh_frequency(BendingDirection::Lag,
                                            *g.modes.shapes(Direction::Lag)[i], 1.0, kTaperE, b),
                         1e-10));
  const ModalCombination shape({cantilever_mode(1), cantilever_mode(3)},
                               (Eigen::VectorXd(2) << 1.0, -0.2).finished());
  const double scale = 2.5;
  for (const BendingDirection dir : {BendingDirection::Flap, BendingDirection::Lag}) {
    const bool flap = dir == BendingDirection::Flap;
    const Energies e = energies_here(b, flap ? b.stiffness_flap : b.stiffness_lag, shape);
    const double expected = std::sqrt((scale * e.strain + e.pull) / e.mass - (flap ? 0.0 : 1.0));
    EXPECT_TRUE(RelClose(expected, rayleigh_frequency(dir, shape, scale, kTaperE, b), 1e-10))
        << (flap ? "flap" : "lag");
  }
}

// The nonrotating frequencies of a uniform table with a tip mass against the classical frequency
// equation of a uniform cantilever with a tip mass ratio q = M_tip / (m l):
//   1 + cos b cosh b + q b (cos b sinh b - sin b cosh b) = 0,   w^2 = (k / mbar) b^4,
// its roots found here by bisection.  The cantilever functions do not satisfy the tip mass's
// shear condition (a natural one): the Galerkin frequencies are upper bounds converging with
// the basis.
TEST(TipMass, NonrotatingFrequenciesAreTheClassicalTipMassCantilevers) {
  BladeProperties b = uniform_blade();
  b.tip_mass = 0.2;
  b.mass = {2.4, 2.4};  // int mbar x^2 + tip = 0.8 + 0.2
  ASSERT_NO_THROW(validate(b));
  const double q = b.tip_mass / b.mass[0];
  auto f = [&](double x) {
    return 1.0 + std::cos(x) * std::cosh(x) +
           q * x * (std::cos(x) * std::sinh(x) - std::sin(x) * std::cosh(x));
  };
  std::vector<double> roots;
  for (double lo = 0.5; roots.size() < 3; lo += 0.5) {
    double a = lo, c = lo + 0.5;
    if ((f(a) > 0.0) == (f(c) > 0.0)) continue;
    for (int it = 0; it < 200; ++it) {
      const double m = 0.5 * (a + c);
      ((f(m) > 0.0) == (f(a) > 0.0) ? a : c) = m;
    }
    roots.push_back(0.5 * (a + c));
  }
  const double k = 0.7;
  std::vector<std::vector<double>> errors;  // per basis, per mode: relative, above the exact
  for (int n : {6, 12}) {
    ExactModeOptions o;
    o.n_basis = n;
    o.blade = shared(b);
    const std::vector<double> w = nonrotating_frequencies(BendingDirection::Flap, k, o);
    const std::vector<double> lag = nonrotating_frequencies(BendingDirection::Lag, k, o);
    errors.emplace_back();
    for (int i = 0; i < 3; ++i) {
      const double exact = std::sqrt(k / b.mass[0]) * roots[i] * roots[i];
      EXPECT_GT(w[i], exact * (1.0 - 1e-12)) << n << " functions, mode " << i + 1;
      EXPECT_EQ(w[i], lag[i]);  // the same column, no rotation
      errors.back().push_back(w[i] / exact - 1.0);
    }
    std::printf(
        "tip-mass cantilever, %d functions: nonrotating frequencies %.2g, %.2g, %.2g above\n", n,
        errors.back()[0], errors.back()[1], errors.back()[2]);
  }
  // Measured: 6.1e-6, 1.6e-4, 8.8e-4 with 6 functions; 7.7e-7, 2.0e-5, 1.1e-4 with 12, i.e.
  // third order in the basis size (the shear condition is met only in the limit).
  for (int i = 0; i < 3; ++i) EXPECT_GT(errors[0][i] / errors[1][i], 6.0) << "mode " << i + 1;
  EXPECT_LT(errors[1][0], 1e-6);
  EXPECT_LT(errors[1][2], 2e-4);
}

// ---- 4. structural integrals with a tip mass ----------------------------------------------------

// Values of the spanwise factors of a mode set on the nodes of a uniform grid.
class Grid {
 public:
  Grid(const ModeSet& modes, int intervals, double e1_over_l) : n_(intervals), e_(e1_over_l) {
    for (int i = 0; i <= n_; ++i) x_.push_back(static_cast<double>(i) / n_);
    for (int kind = 0; kind < 4; ++kind) {
      const bool flap = kind < 2;
      const auto& shapes = flap ? modes.shapes(Direction::Flap) : modes.shapes(Direction::Lag);
      for (const auto& s : shapes) {
        std::vector<double> v;
        for (double x : x_) v.push_back(s->value(kind % 2, x));
        table_[kind].push_back(std::move(v));
      }
    }
  }
  int intervals() const { return n_; }
  double x(int i) const { return x_[i]; }
  // prod(factors) at node i.
  double product(const model::FactorRef* f, int count, int i) const {
    double p = 1.0;
    for (int j = 0; j < count; ++j) {
      if (f[j].kind == model::Factor::X0) {
        p *= x_[i];
      } else if (f[j].kind == model::Factor::Arm) {
        p *= x_[i] + e_;
      } else {
        p *= table_[static_cast<int>(f[j].kind)][f[j].mode][i];
      }
    }
    return p;
  }

 private:
  int n_;
  double e_;
  std::vector<double> x_;
  std::vector<std::vector<double>> table_[4];
};

// A structural integral (model_api.h) as an integral over the blade's mass measure
// dmu = mbar dx + tip delta(x - 1):
//   I = int F(x) J(x) [mbar^outer_mass dx, or dmu when outer_mass = 1],
//   J(x) = int over [x, 1] (tail) or [0, x] (head) of G [mbar^inner_mass dx, or dmu when
//   inner_mass = 1],
// by Simpson's rule: J accumulated interval by interval (the grid's odd nodes are the
// midpoints), then the outer integral over the even nodes.  The grid must hold the stations on
// even nodes.
double simpson_structural(const model::StructuralIntegral& s, const BladeProperties& b,
                          const Grid& grid) {
  const int n = grid.intervals();
  auto m = [&](int i, int power) { return std::pow(linear(b.x0, b.mass, grid.x(i)), power); };
  std::vector<double> J(n / 2 + 1, 1.0);  // on the even nodes
  double tip_g = 0.0;                     // the point mass's share of an inner integral
  if (s.inner != model::Inner::None) {
    std::vector<double> g(n + 1);
    for (int i = 0; i <= n; ++i)
      g[i] = m(i, s.inner_mass) * grid.product(s.inner_factors, s.n_inner, i);
    if (s.inner_mass == 1) tip_g = b.tip_mass * grid.product(s.inner_factors, s.n_inner, n);
    const double h = 2.0 / n;
    std::vector<double> head(n / 2 + 1, 0.0);  // int_0^x dx on the even nodes
    for (int k = 1; k <= n / 2; ++k)
      head[k] = head[k - 1] + h / 6.0 * (g[2 * k - 2] + 4.0 * g[2 * k - 1] + g[2 * k]);
    // The point mass at x = 1 lies in [x, 1] for every x, and in [0, x] at x = 1 only (a
    // point of no outer weight, unless the outer integral has the point mass too).
    for (int k = 0; k <= n / 2; ++k)
      J[k] = s.inner == model::Inner::Tail ? head[n / 2] - head[k] + tip_g : head[k];
  }
  double sum = 0.0;
  const double h = 2.0 / n;
  for (int k = 0; k <= n / 2; ++k) {
    const double w = (k == 0 || k == n / 2) ? 1.0 : (k % 2 ? 4.0 : 2.0);
    sum += w * m(2 * k, s.outer_mass) * grid.product(s.outer, s.n_outer, 2 * k) * J[k];
  }
  sum *= h / 3.0;
  if (s.outer_mass == 1) {
    // The point mass's own term F(1) J(1): J(1) over [1, 1] for a tail (the point mass alone),
    // over [0, 1] with the point mass for a head.
    const double J1 = s.inner == model::Inner::None   ? 1.0
                      : s.inner == model::Inner::Tail ? tip_g
                                                      : J.back() + tip_g;
    sum += b.tip_mass * grid.product(s.outer, s.n_outer, n) * J1;
  }
  return sum;
}

TEST(TipMass, StructuralIntegralsMatchSimpson) {
  const model::ModelDescriptor& m = paper_model(2, 2);
  ExactModeOptions o;
  o.n_basis = kMaxBasisFunctions;
  o.flap_modes = o.lag_modes = 2;
  o.e1_over_l = kTaperE;
  BladeProperties b = tapered_blade();
  b.tip_mass = 0.12;  // heavier, for a larger share of every integral
  b = normalised_mass(b);
  o.blade = shared(b);
  const ModeSet modes = blade_stiffness_modes(o).modes;
  const std::vector<double> production = structural_integrals(m, modes, kTaperE);
  const Grid grid(modes, 8000, kTaperE);  // the station 0.25 on node 2000 (even)
  BladeProperties no_tip = b;
  no_tip.tip_mass = 0.0;
  int kinds[3] = {0, 0, 0};
  double worst = 0.0;
  for (int i = 0; i < m.n_structural; ++i) {
    const model::StructuralIntegral& s = m.structural[i];
    SCOPED_TRACE(s.name);
    const double expected = simpson_structural(s, b, grid);
    EXPECT_TRUE(RelClose(expected, production[i], 1e-9, 1e-3));
    worst =
        std::max(worst, std::abs(production[i] - expected) / std::max(std::abs(expected), 1e-3));
    // Count, by kind, the integrals whose tip-mass term matters.
    const double without = simpson_structural(s, no_tip, grid);
    if (std::abs(expected - without) > 1e-3 * std::abs(expected))
      ++kinds[static_cast<int>(s.inner)];
  }
  EXPECT_GT(kinds[static_cast<int>(model::Inner::None)], 0);
  EXPECT_GT(kinds[static_cast<int>(model::Inner::Tail)], 0);
  EXPECT_GT(kinds[static_cast<int>(model::Inner::Head)], 0);
  std::printf(
      "tip mass: %d structural integrals within %.2g of Simpson (%d, %d, %d with a tip term)\n",
      m.n_structural, worst, kinds[0], kinds[1], kinds[2]);
}

// ---- 5. chord-weighted aerodynamic integrals ----------------------------------------------------

// A tapered chord with two interior stations, a root offset and tip-loss limits.
struct ChordCase {
  BladeProperties blade;
  ModeSet modes;
  SpanGeometry geometry;
  explicit ChordCase(SpanGeometry g = {0.05, 0.95, 0.1, 0.97}) : geometry(g) {
    blade = table({0.0, 0.3, 0.7, 1.0}, {1, 1, 1, 1}, {1, 1, 1, 1}, {1, 1, 1, 1},
                  {1.2, 1.0, 0.9, 0.6}, {0, 0, 0, 0}, 0.0);
    ExactModeOptions o;
    o.n_basis = kMaxBasisFunctions;
    o.flap_modes = o.lag_modes = 2;
    o.e1_over_l = geometry.e1 / geometry.lr;
    o.blade = shared(blade);
    modes = exact_modes(1.175, 1.28303, o);
  }
};

class ChordTaperGeometry : public ::testing::TestWithParam<SpanGeometry> {};

TEST_P(ChordTaperGeometry, AeroIntegralsAreTheGaussReferenceOverTheirSubSpans) {
  const ChordCase c(GetParam());
  const model::ModelDescriptor& m = paper_model(2, 2);
  const AeroIntegrals a(m, c.modes, c.geometry);
  const double A = c.geometry.tip_loss_a, B = c.geometry.tip_loss_b;
  const double e1 = c.geometry.e1, lr = c.geometry.lr;
  double scale = 0.0;
  for (int j = 0; j < m.n_aero; ++j) scale = std::max(scale, std::abs(a.normal()[j]));
  double worst = 0.0;
  for (int j = 0; j < m.n_aero; ++j) {
    SCOPED_TRACE(m.aero[j].name);
    const double expected = aero_integral(m.aero[j], c.modes, c.geometry, A, B);
    EXPECT_TRUE(AbsClose(expected, a.normal()[j], 1e-12 * scale));
    worst = std::max(worst, std::abs(expected - a.normal()[j]) / scale);
  }
  // mu below the root (no reversed flow on the span), inside each piece, on the stations 0.3
  // and 0.7, at the tip-loss limit, and the whole span reversed (mu >= 1).
  for (double mu :
       {0.02, 0.2, e1 + lr * 0.3, 0.5, e1 + lr * 0.7, 0.8, e1 + lr * B, 0.99, 1.0, 1.4}) {
    SCOPED_TRACE("mu " + std::to_string(mu));
    const std::vector<double> r = a.reversed(mu);
    const double split = std::clamp((mu - e1) / lr, A, B);
    for (int j = 0; j < m.n_aero; ++j) {
      SCOPED_TRACE(m.aero[j].name);
      const double expected = mu >= 1.0
                                  ? -aero_integral(m.aero[j], c.modes, c.geometry, A, B)
                                  : -aero_integral(m.aero[j], c.modes, c.geometry, A, split) +
                                        aero_integral(m.aero[j], c.modes, c.geometry, split, B);
      EXPECT_TRUE(AbsClose(expected, r[j], 1e-12 * scale));
      worst = std::max(worst, std::abs(expected - r[j]) / scale);
    }
  }
  std::printf("chord taper: AeroIntegrals within %.2g (of the largest integral) of Gauss\n", worst);
}

// The span with root offset and tip loss; the whole blade; a span that starts beyond the
// station 0.3 and ends on the station 0.7.
INSTANTIATE_TEST_SUITE_P(Spans, ChordTaperGeometry,
                         ::testing::Values(SpanGeometry{0.05, 0.95, 0.1, 0.97},
                                           SpanGeometry{0.0, 1.0, 0.0, 1.0},
                                           SpanGeometry{0.05, 0.95, 0.35, 0.7}));

// Composite Simpson on [a, b] with n (even) intervals.
double simpson_on(double a, double b, const std::function<double(double)>& f, int n) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * f(a + i * h);
  return s * h / 3.0;
}

// The chord in the integrand, written out here for three integrals: x^2 c, x^2 eta_1 c and
// x eta_1 gamma_2' c over the pieces between the stations.
TEST(ChordTaper, AeroIntegralsWeighTheChord) {
  const ChordCase c;
  const model::ModelDescriptor& m = paper_model(2, 2);
  const AeroIntegrals a(m, c.modes, c.geometry);
  const double e1 = c.geometry.e1, lr = c.geometry.lr;
  const std::vector<double> pieces = {c.geometry.tip_loss_a, 0.3, 0.7, c.geometry.tip_loss_b};
  auto integral = [&](const std::function<double(double)>& f, double upto) {
    double s = 0.0;
    for (std::size_t p = 0; p + 1 < pieces.size(); ++p) {
      const double lo = pieces[p], hi = std::min(pieces[p + 1], upto);
      if (hi > lo) s += simpson_on(lo, hi, f, 2000);
    }
    return s;
  };
  auto chord = [&](double x0) { return linear(c.blade.x0, c.blade.chord, x0); };
  const ModeShape& eta1 = *c.modes.shapes(Direction::Flap)[0];
  const ModeShape& gamma2 = *c.modes.shapes(Direction::Lag)[1];
  int checked = 0;
  for (int j = 0; j < m.n_aero; ++j) {
    const std::string name = m.aero[j].name;
    std::function<double(double)> f;
    if (name == "x^2") {
      f = [&](double x0) { return std::pow(e1 + lr * x0, 2) * chord(x0); };
    } else if (name == "x^2 eta1") {
      f = [&](double x0) { return std::pow(e1 + lr * x0, 2) * eta1.value(0, x0) * chord(x0); };
    } else if (name == "x eta1 gamma2'") {
      f = [&](double x0) {
        return (e1 + lr * x0) * eta1.value(0, x0) * gamma2.value(1, x0) * chord(x0);
      };
    } else {
      continue;
    }
    SCOPED_TRACE(name);
    ++checked;
    const double whole = integral(f, 2.0);
    EXPECT_TRUE(RelClose(whole, a.normal()[j], 1e-11));
    const double mu = 0.5, split = (mu - e1) / lr;
    EXPECT_TRUE(RelClose(whole - 2.0 * integral(f, split), a.reversed(mu)[j], 1e-11));
  }
  EXPECT_EQ(checked, 3);
}

// ---- 6. the hover inflow of a blade table -------------------------------------------------------

// Eq 2.24, lambda = sigma a / 16 [sqrt(1 + 24 theta / (sigma a)) - 1].
double eq_2_24(double sigma_a, double theta) {
  return sigma_a / 16.0 * (std::sqrt(1.0 + 24.0 * theta / sigma_a) - 1.0);
}

RotorParameters hover_case(const BladeProperties& b) {
  RotorParameters p;
  p.modes = ModeKind::Exact;
  p.blade = shared(b);
  return p;
}

// Stations 0, 0.4, 1 (a corner of nothing: the distributions stay linear through it).
BladeProperties linear_blade(double chord_root, double chord_tip, double twist_tip) {
  return table({0.0, 0.4, 1.0}, {1, 1, 1}, {1, 1, 1}, {1, 1, 1},
               {chord_root, chord_root + 0.4 * (chord_tip - chord_root), chord_tip},
               {0.0, 0.4 * twist_tip, twist_tip}, 0.0);
}

TEST(HoverInflow, LinearTwistIsThreeQuarterRadiusPitch) {
  for (double twist : {-0.14, 0.1}) {
    const RotorParameters p = hover_case(linear_blade(1.0, 1.0, twist));
    ASSERT_EQ(p.root_offset, 0.0);
    ASSERT_EQ(p.length_ratio, 1.0);
    EXPECT_TRUE(
        RelClose(eq_2_24(p.sigma * p.lift_slope, p.theta + 0.75 * twist), hover_inflow(p), 1e-14));
  }
  // The uniform table is the paper's eq 2.24.
  RotorParameters u = hover_case(uniform_blade());
  EXPECT_TRUE(RelClose(eq_2_24(u.sigma * u.lift_slope, u.theta), hover_inflow(u), 1e-14));
}

// A linear chord c0 -> c1: sigma times 3 int_0^1 (c0 + (c1 - c0) x) x^2 dx = c0/4 + 3 c1/4, and
// with a linear twist t x the thrust-weighted twist 3 int c t x^3 dx / (c0/4 + 3 c1/4)
// = t (3 c0/20 + 3 c1/5) / (c0/4 + 3 c1/4).
TEST(HoverInflow, ChordTaperScalesTheSolidity) {
  const double c0 = 1.3, c1 = 0.7;
  RotorParameters p = hover_case(linear_blade(c0, c1, 0.0));
  const double chord = 0.25 * c0 + 0.75 * c1;
  EXPECT_TRUE(RelClose(eq_2_24(p.sigma * p.lift_slope * chord, p.theta), hover_inflow(p), 1e-14));
  // Not the uniform blade's.
  EXPECT_GT(std::abs(hover_inflow(p) / eq_2_24(p.sigma * p.lift_slope, p.theta) - 1.0), 1e-3);
  const double t = -0.2;
  p = hover_case(linear_blade(c0, c1, t));
  const double twist = t * (0.15 * c0 + 0.6 * c1) / chord;
  EXPECT_TRUE(
      RelClose(eq_2_24(p.sigma * p.lift_slope * chord, p.theta + twist), hover_inflow(p), 1e-14));
}

// With a root offset the stations sit at x = e1 + (l/R) x0 and the root chord is held inboard:
// 3 int_0^1 c x^2 dx = c0 e1^3 + 3 int_e1^1 c(x) x^2 dx, c linear from c0 at e1 to c1 at 1.
TEST(HoverInflow, RootOffsetHoldsTheRootChordInboard) {
  const double c0 = 1.3, c1 = 0.7, e1 = 0.1;
  RotorParameters p = hover_case(linear_blade(c0, c1, 0.0));
  p.root_offset = e1;
  p.length_ratio = 1.0 - e1;
  const double slope = (c1 - c0) / (1.0 - e1);
  // int_e1^1 (c0 + slope (x - e1)) x^2 dx
  const double outboard =
      (c0 - slope * e1) * (1.0 - std::pow(e1, 3)) / 3.0 + slope * (1.0 - std::pow(e1, 4)) / 4.0;
  const double chord = c0 * std::pow(e1, 3) + 3.0 * outboard;
  EXPECT_TRUE(RelClose(eq_2_24(p.sigma * p.lift_slope * chord, p.theta), hover_inflow(p), 1e-14));
}

// ---- 7. the elastic coupling of a twisted blade -------------------------------------------------

TEST(Twist, ElasticCouplingAtEachStationsPitch) {
  // The tapered blade (stiffness columns with a corner at 0.25) with a twist that has its own
  // corner at 0.6, and the stiffness columns as shapes, scaled to the frequencies.
  BladeProperties b = table({0.0, 0.25, 0.6, 1.0}, {1.5, 1.2, 1.0, 0.7}, {2.0, 1.4, 1.0, 0.5},
                            {6.0, 4.0, 2.5, 1.0}, {1, 1, 1, 1}, {0.05, 0.0, -0.08, -0.2}, 0.05);
  ExactModeOptions o;
  o.n_basis = kMaxBasisFunctions;
  o.flap_modes = o.lag_modes = 2;
  o.e1_over_l = kTaperE;
  o.blade = shared(b);
  const ModeSet modes = exact_modes(1.12, 0.75, o);
  ASSERT_NE(modes[Direction::Flap].stiffness, 1.0);
  const double theta = 0.15;
  const ElasticCoupling e = elastic_coupling(modes, theta);
  auto dk = [&](double x) {
    return modes[Direction::Lag].stiffness * linear(b.x0, b.stiffness_lag, x) -
           modes[Direction::Flap].stiffness * linear(b.x0, b.stiffness_flap, x);
  };
  auto pitch = [&](double x) { return theta + linear(b.x0, b.twist, x); };
  // Simpson on 4000 intervals (0.25 and 0.6 are nodes) of each pair.
  auto expected = [&](const ModeShape& u, const ModeShape& v, bool cross) {
    return simpson([&](double x) {
      const double s = std::sin(pitch(x)), c = std::cos(pitch(x));
      return dk(x) * (cross ? s * c : s * s) * u.value(2, x) * v.value(2, x);
    });
  };
  const double scale = e.block(Direction::Flap, Direction::Flap).cwiseAbs().maxCoeff() +
                       e.block(Direction::Flap, Direction::Lag).cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.0);
  double worst = 0.0;
  for (int i = 0; i < 2; ++i) {
    for (int k = 0; k < 2; ++k) {
      SCOPED_TRACE(std::to_string(i) + "," + std::to_string(k));
      const ModeShape &fi = *modes.shapes(Direction::Flap)[i],
                      &fk = *modes.shapes(Direction::Flap)[k];
      const ModeShape &li = *modes.shapes(Direction::Lag)[i],
                      &lk = *modes.shapes(Direction::Lag)[k];
      EXPECT_TRUE(AbsClose(expected(fi, fk, false), e.block(Direction::Flap, Direction::Flap)(i, k),
                           1e-10 * scale));
      EXPECT_TRUE(AbsClose(expected(li, lk, false), e.block(Direction::Lag, Direction::Lag)(i, k),
                           1e-10 * scale));
      EXPECT_TRUE(AbsClose(expected(fi, lk, true), e.block(Direction::Flap, Direction::Lag)(i, k),
                           1e-10 * scale));
      EXPECT_TRUE(AbsClose(expected(li, fk, true), e.block(Direction::Lag, Direction::Flap)(i, k),
                           1e-10 * scale));
      for (const double d :
           {expected(fi, fk, false) - e.block(Direction::Flap, Direction::Flap)(i, k),
            expected(li, lk, false) - e.block(Direction::Lag, Direction::Lag)(i, k),
            expected(fi, lk, true) - e.block(Direction::Flap, Direction::Lag)(i, k),
            expected(li, fk, true) - e.block(Direction::Lag, Direction::Flap)(i, k)})
        worst = std::max(worst, std::abs(d) / scale);
    }
  }
  std::printf("twisted blade: elastic coupling within %.2g of Simpson\n", worst);
  // The twist matters: at the collective alone the coupling differs.
  BladeProperties untwisted = b;
  untwisted.twist = {0, 0, 0, 0};
  ModeSet same = modes;
  same.blade = shared(untwisted);
  EXPECT_GT(std::abs(elastic_coupling(same, theta).block(Direction::Flap, Direction::Flap)(0, 0) -
                     e.block(Direction::Flap, Direction::Flap)(0, 0)),
            0.05 * std::abs(e.block(Direction::Flap, Direction::Flap)(0, 0)));
}

}  // namespace
}  // namespace flaplag::blade_properties_test
