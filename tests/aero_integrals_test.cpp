// Production aerodynamic integrals (blade/aero_integrals.h, Chebyshev antiderivatives) against
// exact rational values (assumed mode, polynomial integrands) and against the Gauss quadrature of
// blade.h for exact modes.
#include "flaplag/blade/aero_integrals.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "flaplag/blade/rotating_modes.h"
#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "model_fixtures.h"
#include "test_util.h"

namespace flaplag::aero_integrals_test {
namespace {

using flaplag::model::Direction;
using testing::RelClose;
using namespace testing::fixtures;

// A span with a root offset, l/R < 1 and both tip-loss limits inside the blade.
SpanGeometry offset_span() {
  SpanGeometry g;
  g.e1 = 0.05;
  g.lr = 0.95;
  g.tip_loss_a = 0.1;
  g.tip_loss_b = 0.97;
  return g;
}

TEST(AeroIntegrals, ReversedFlowSplitExactValues) {
  const ModeSet m = assumed_modes(1.175, 1.28303);
  const SpanGeometry g = offset_span();
  const std::vector<AeroIntegral> list = {
      aero("x^2 eta", 2, {kEta}),
      aero("x^3 eta eta' gamma' gamma", 3, {kEta, kEtaP, kGammaP, kGamma})};
  const auto d = descriptor(list, {});
  const AeroIntegrals ai(d, m, g);
  const auto normal = ai.normal();
  ASSERT_EQ(2u, normal.size());
  EXPECT_TRUE(RelClose(0.2032798983095815392857, normal[0], 1e-14));

  // mu = 1/2: split at x0 = (mu - e1)/lr = 9/19; normal - reversed = 2 int_A^{9/19}.  The
  // difference cancels ~2 digits of the values (0.214 vs 0.002), hence 1e-12 there.
  const auto rev = ai.reversed(0.5);
  EXPECT_TRUE(RelClose(2.0 * 0.008549941432498036770422, normal[0] - rev[0], 1e-13));
  EXPECT_TRUE(RelClose(2.0 * 0.0009922597246163115682400, normal[1] - rev[1], 1e-12));
  for (std::size_t i = 0; i < list.size(); ++i) {
    const double inboard = aero_integral(list[i], m, g, 0.1, 9.0 / 19.0);
    EXPECT_TRUE(RelClose(normal[i] - 2.0 * inboard, rev[i], 1e-13));
  }
  // mu >= 1: whole span negated (eqs D.5-D.6).
  for (double mu : {1.0, 1.4}) {
    const auto r = ai.reversed(mu);
    for (std::size_t i = 0; i < list.size(); ++i) EXPECT_EQ(-normal[i], r[i]) << mu;
  }
  // Split below A (mu < e1 + lr A): no reversed part.
  const auto r0 = ai.reversed(0.1);
  for (std::size_t i = 0; i < list.size(); ++i) {
    EXPECT_TRUE(RelClose(normal[i], r0[i], 1e-14));
  }
  EXPECT_THROW(ai.reversed(-0.1), InvalidInput);
}

// Gauss reference of the reversed-sector values (eqs D.3-D.6), written independently of the
// antiderivative path.
std::vector<double> gauss_reversed(const model::ModelDescriptor& d, const ModeSet& m,
                                   const SpanGeometry& g, double mu) {
  std::vector<double> v;
  for (int j = 0; j < d.n_aero; ++j) {
    if (mu >= 1.0) {
      v.push_back(-aero_integral(d.aero[j], m, g, g.tip_loss_a, g.tip_loss_b));
      continue;
    }
    const double split = std::clamp((mu - g.e1) / g.lr, g.tip_loss_a, g.tip_loss_b);
    v.push_back(-aero_integral(d.aero[j], m, g, g.tip_loss_a, split) +
                aero_integral(d.aero[j], m, g, split, g.tip_loss_b));
  }
  return v;
}

// Every integral of the compiled 2 x 2 model with exact rotating modes, at several split points:
// the interpolated antiderivatives agree with Gauss quadrature to near rounding.  Untwisted (the
// twist integrals vanish identically and are skipped) and on a linearly twisted blade.
class ExactModesGauss : public ::testing::TestWithParam<bool> {};

TEST_P(ExactModesGauss, ProductionIntegralsMatchGaussQuadrature) {
  const model::ModelDescriptor* d =
      &model::instantiate(*model::registered_families().front(), 2, 2);
  ExactModeOptions opt;
  opt.flap_modes = 2;
  opt.lag_modes = 2;
  ModeSet modes = exact_modes(1.175, 1.28303, opt);
  if (GetParam()) {
    auto blade = std::make_shared<BladeProperties>(uniform_blade());
    blade->twist = {0.05, -0.15};
    modes.blade = blade;
  }
  SpanGeometry g;
  g.e1 = 0.02;
  g.lr = 0.98;
  g.tip_loss_b = 0.97;
  const AeroIntegrals ai(*d, modes, g);
  double scale = 0.0;
  for (int j = 0; j < d->n_aero; ++j) {
    const double ref = aero_integral(d->aero[j], modes, g, g.tip_loss_a, g.tip_loss_b);
    scale = std::max(scale, std::abs(ref));
  }
  for (int j = 0; j < d->n_aero; ++j) {
    const double ref = aero_integral(d->aero[j], modes, g, g.tip_loss_a, g.tip_loss_b);
    EXPECT_NEAR(ref, ai.normal()[j], 1e-13 * scale) << d->aero[j].name;
  }
  for (double mu : {0.0, 0.15, 0.5, 0.77, 0.999, 1.0, 2.5}) {
    const std::vector<double> ref = gauss_reversed(*d, modes, g, mu);
    const std::vector<double> got = ai.reversed(mu);
    ASSERT_EQ(ref.size(), got.size());
    for (std::size_t j = 0; j < ref.size(); ++j)
      EXPECT_NEAR(ref[j], got[j], 1e-13 * scale) << d->aero[j].name << " at mu = " << mu;
  }
}

INSTANTIATE_TEST_SUITE_P(Blades, ExactModesGauss, ::testing::Values(false, true),
                         [](const auto& tp) { return tp.param ? "Twisted" : "Untwisted"; });

// A uniform blade with the linear built-in twist theta_tw(x0) = theta_tw x0 in hover (e1 = 0,
// l/R = 1, A = 0, B = 1, mu = 0, uniform inflow lambda): blade-element theory gives
//   C_T / (sigma a) = (1/2) int_0^1 [(theta + theta_tw x) x^2 - lambda x] dx
//                   = theta/6 + theta_tw/8 - lambda/4.
// The model's thrust (ModelDescriptor::thrust, the flap load L_z of the derivation) with the
// integrals of the twisted blade, at the hover equilibrium of the same integrals, state y = 0:
// C_T / (sigma a) = T / 2 with T the azimuth mean of the thrust forcing.
// The first `count` integrals alone have the bits of the whole list's (the Clenshaw chains are
// independent), the others are NaN; a count outside the list is refused by name.  A list with
// an integrand that vanishes (not live) in the middle.
TEST(AeroIntegrals, ThePrefixHasTheBitsOfTheWholeList) {
  const ModeSet m = assumed_modes(1.175, 1.28303);
  const SpanGeometry g = offset_span();
  const std::vector<AeroIntegral> list = {
      aero("x^2 eta", 2, {kEta}), aero("x eta gamma", 1, {kEta, kGamma}),
      aero("x^3 eta eta' gamma' gamma", 3, {kEta, kEtaP, kGammaP, kGamma}),
      aero("x^2 gamma'", 2, {kGammaP})};
  const auto d = descriptor(list, {});
  const AeroIntegrals ai(d, m, g);
  for (double mu : {0.3, 0.5, 0.9, 1.2}) {
    const std::vector<double> whole = ai.reversed(mu);
    for (int count = 0; count <= 4; ++count) {
      std::vector<double> part;
      ai.reversed(mu, part, count);
      ASSERT_EQ(whole.size(), part.size());
      for (int j = 0; j < 4; ++j) {
        if (j < count)
          EXPECT_EQ(whole[j], part[j]) << mu << " " << count << " " << j;
        else
          EXPECT_TRUE(std::isnan(part[j])) << mu << " " << count << " " << j;
      }
    }
  }
  std::vector<double> out;
  for (int bad : {-1, 5}) {
    try {
      ai.reversed(0.5, out, bad);
      ADD_FAILURE() << bad;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find("count"), std::string::npos) << e.what();
    }
  }
}

TEST(AeroIntegrals, TwistedBladeHoverThrustIsBladeElementTheory) {
  const model::ModelDescriptor& d = *model::registered_models().front();  // paper, 1 x 1
  ASSERT_EQ(1, d.flap_modes);
  ASSERT_EQ(1, d.lag_modes);
  const int n = 2, H = d.n_harmonics;
  const SpanGeometry g;  // e1 = 0, l/R = 1, A = 0, B = 1
  struct Case {
    double theta, theta_tw, lambda;
  };
  const Case cases[] = {{0.15, 0.0, 0.05},  {0.15, -0.14, 0.05}, {0.08, 0.2, 0.03},
                        {0.25, -0.3, 0.07}, {0.0, 0.1, 0.0},     {-0.05, -0.09, 0.01}};
  for (const bool exact : {false, true}) {
    for (const Case& c : cases) {
      auto blade = std::make_shared<BladeProperties>();
      blade->x0 = {0.0, 1.0};
      blade->mass = {3.0, 3.0};
      blade->stiffness_flap = {1.0, 1.0};
      blade->stiffness_lag = {1.0, 1.0};
      blade->chord = {1.0, 1.0};
      blade->twist = {0.0, c.theta_tw};
      validate(*blade);
      ModeSet modes = exact ? exact_modes(1.175, 1.28303) : assumed_modes(1.175, 1.28303);
      modes.blade = blade;
      const AeroIntegrals ai(d, modes, g);
      const std::vector<double> structural = structural_integrals(d, modes, 0.0);
      // As SystemBuilder::inputs(): no structural damping, no elastic coupling.
      const std::vector<double> zeros(4, 0.0);
      std::vector<double> q0(n, 0.0);
      model::CoefficientInputs in{};
      in.lock = 10.0;
      in.lr = 1.0;
      in.theta = c.theta;
      in.inflow = c.lambda;
      in.cdo_a = 0.01 / (2.0 * kPi);
      in.mu = 0.0;
      for (const Direction dir : model::kDirections) {
        in.q0[model::index(dir)] = q0.data() + model::index(dir);  // one mode each: g0, h0
        in.omega[model::index(dir)] = modes[dir].omega.data();
        in.damping[model::index(dir)] = zeros.data();
        in.modes[model::index(dir)] = 1;
        for (const double*& block : in.elastic[model::index(dir)]) block = zeros.data();
      }
      in.aero = ai.normal().data();
      in.structural = structural.data();
      // The hover equilibrium S q0 = c of the twisted blade.
      std::vector<double> S(n * n), rhs(n);
      d.equilibrium(in, {S.data(), rhs.data()});
      const Eigen::Vector2d sol = Eigen::Matrix2d{{S[0], S[1]}, {S[2], S[3]}}.fullPivLu().solve(
          Eigen::Vector2d(rhs[0], rhs[1]));
      q0 = {sol(0), sol(1)};
      std::vector<double> force(H * 2 * n), forcing(H);
      d.thrust(in, {force.data(), forcing.data()});
      const double expected = c.theta / 6.0 + c.theta_tw / 8.0 - c.lambda / 4.0;
      const std::string what =
          std::string(exact ? "exact" : "assumed") + " modes, theta = " + std::to_string(c.theta) +
          ", theta_tw = " + std::to_string(c.theta_tw) + ", lambda = " + std::to_string(c.lambda);
      EXPECT_NEAR(expected, forcing[0] / 2.0, 1e-12) << what;
      for (int h = 1; h < H; ++h) EXPECT_NEAR(0.0, forcing[h], 1e-15) << what << ", harmonic " << h;
    }
  }
}

TEST(AeroIntegrals, RejectsAnEmptySpan) {
  const ModeSet m = assumed_modes(1.175, 1.28303);
  const std::vector<AeroIntegral> list = {aero("x^2 eta", 2, {kEta})};
  const auto d = descriptor(list, {});
  SpanGeometry g;
  g.tip_loss_a = 0.5;
  g.tip_loss_b = 0.5;
  EXPECT_THROW(AeroIntegrals(d, m, g), InvalidInput);
}

}  // namespace
}  // namespace flaplag::aero_integrals_test
