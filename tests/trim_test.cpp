// Rotor thrust and trim (trim.h): the thrust against hand-derived blade-element results, the
// inflow of eq 2.25, the round trips of issue 12 ("Checks: Trim"), moment trim, cyclic pitch
// in the system, and bad input.
#include "flaplag/trim.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "flaplag/analysis.h"
#include "flaplag/core/errors.h"
#include "test_util.h"

namespace trim_test {

namespace {

using flaplag::InvalidInput;
using flaplag::RotorParameters;
using flaplag::Status;
using flaplag::TrimKind;
using flaplag::TrimOptions;

RotorParameters cyclic_typical() {
  RotorParameters p;
  p.model = "paper-cyclic";
  return p;
}

// The moment trim at C_T = 0.005, whose branch (typical blade, hover linearization) ends near
// mu = 0.74.
TrimOptions moment_trim_005() {
  TrimOptions o;
  o.kind = TrimKind::Moment;
  o.thrust_coefficient = 0.005;
  return o;
}

// The model's C_T at theta = 0.15 in hover with the inflow of eq 2.25 (solved together).
double hover_thrust_at_015() {
  const auto t = flaplag::rotor_thrust_momentum(cyclic_typical(), 0.0, 0.0);
  EXPECT_EQ(t.status, Status::Ok) << t.message;
  return t.thrust_coefficient;
}

}  // namespace

// Uniform blade, no tip loss, hover: blade-element theory gives C_T = (sigma a/2)(theta/3 -
// lambda/2) (the y = 0 response; the hover equilibrium does not enter at mu = 0).
TEST(RotorThrust, HoverEqualsBladeElementFormula) {
  const RotorParameters p = cyclic_typical();
  const double lambda = 0.04;
  const auto t = flaplag::rotor_thrust(p, 0.0, lambda);
  ASSERT_EQ(t.status, Status::Ok) << t.message;
  const double expected = 0.5 * p.sigma * p.lift_slope * (p.theta / 3.0 - lambda / 2.0);
  EXPECT_NEAR(t.thrust_coefficient, expected, 1e-14) << "expected " << expected;
  EXPECT_EQ(t.inflow, lambda);
  // NaN inflow: eq 2.24.
  const auto t24 = flaplag::rotor_thrust(p, 0.0, std::nan(""));
  EXPECT_EQ(t24.inflow, flaplag::hover_inflow(p));
}

// In hover, eq 2.25 with the model's thrust is the quadratic 2 lambda^2 + (sigma a/4) lambda -
// sigma a theta/6 = 0: lambda = (sigma a/16)[sqrt(1 + 64 theta/(3 sigma a)) - 1], not eq 2.24's
// 24 theta/(sigma a) (the 3/4-radius relation).
TEST(RotorThrust, MomentumInflowInHoverIsNotEq224) {
  const RotorParameters p = cyclic_typical();
  const auto t = flaplag::rotor_thrust_momentum(p, 0.0, 0.0);
  ASSERT_EQ(t.status, Status::Ok) << t.message;
  const double sa = p.sigma * p.lift_slope;
  const double lambda = sa / 16.0 * (std::sqrt(1.0 + 64.0 * p.theta / (3.0 * sa)) - 1.0);
  EXPECT_NEAR(t.inflow, lambda, 1e-14) << "expected " << lambda;
  EXPECT_NEAR(t.inflow, std::sqrt(t.thrust_coefficient / 2.0), 1e-15);
  EXPECT_GT(flaplag::hover_inflow(p) - t.inflow, 3e-3);  // 0.04967 vs 0.04604
}

TEST(MomentumInflow, SolvesEq225) {
  for (double mu : {0.0, 0.05, 0.3, 1.2}) {
    for (double alpha : {-0.1, 0.0, 0.08}) {
      const double ct = 0.006;
      const double lam = flaplag::momentum_inflow(ct, mu, alpha);
      const double rhs = mu * std::tan(alpha) + ct / (2.0 * std::sqrt(mu * mu + lam * lam));
      EXPECT_NEAR(lam, rhs, 1e-16) << "mu " << mu << " alpha " << alpha;
    }
  }
}

// A vanishing advance ratio is hover: below mu ~ 1e-154 mu^2 underflowed and the bracket's end
// C_T / (2 mu) overflowed ("b = inf" was reported), and at mu = 1e-150 the bracket [0, 2e147]
// outlasted Brent's evaluations and a wrong inflow (0) came back.  Regression test.
TEST(MomentumInflow, AVanishingAdvanceRatioIsHover) {
  const double ct = 0.006, hover = std::sqrt(ct / 2.0);
  for (double mu : {5e-324, 1e-310, 1e-200, 1e-150, 1e-20, 1e-8}) {
    for (double alpha : {-0.1, 0.0, 0.08}) {
      const double lam = flaplag::momentum_inflow(ct, mu, alpha);
      // lambda (lambda - mu tan(alpha)) = C_T / 2 to O(mu^2): lambda = hover + mu tan(alpha) / 2.
      EXPECT_NEAR(lam, hover + 0.5 * mu * std::tan(alpha), 4e-15)
          << "mu " << mu << " alpha " << alpha;
    }
  }
}

// Issue 12: C_T at theta = 0.15 in hover (eq 2.25 inflow), trimmed back: theta = 0.15 to 1e-12.
TEST(Trim, HoverRoundTripRecoversThePitch) {
  const double ct = hover_thrust_at_015();
  RotorParameters p = cyclic_typical();
  p.theta = 0.1;  // (the trim starts from its own estimate)
  TrimOptions o;
  o.kind = TrimKind::Thrust;
  o.thrust_coefficient = ct;
  const auto r = flaplag::trim(p, 0.0, o);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  EXPECT_NEAR(r.theta0, 0.15, 1e-12);
  EXPECT_NEAR(r.thrust_coefficient, ct, 1e-15);
  EXPECT_EQ(r.parameters.theta, r.theta0);
}

class ThrustTrimAtMu : public ::testing::TestWithParam<double> {};

// Issue 12: the trimmed thrust equals the target to 1e-10 at mu = 0.3, 0.8, 1.2; and the trim
// is a trim: a different target gives a different pitch, the thrust is independent of how it is
// evaluated again.
TEST_P(ThrustTrimAtMu, TrimmedThrustEqualsTarget) {
  const double mu = GetParam();
  TrimOptions o;
  o.kind = TrimKind::Thrust;
  o.thrust_coefficient = 0.005;
  o.shaft_angle = 0.05;
  const auto r = flaplag::trim(cyclic_typical(), mu, o);
  ASSERT_NE(r.status, Status::Failed) << r.message;
  EXPECT_EQ(r.status, Status::Ok) << r.message;
  EXPECT_NEAR(r.thrust_coefficient, 0.005, 1e-10);
  EXPECT_NEAR(r.inflow, flaplag::momentum_inflow(0.005, mu, 0.05), 0.0);
  // independent re-evaluation of the thrust at the trimmed point
  const auto again = flaplag::rotor_thrust(r.parameters, mu, r.inflow);
  EXPECT_NEAR(again.thrust_coefficient, 0.005, 1e-10);
}

INSTANTIATE_TEST_SUITE_P(Mu, ThrustTrimAtMu, ::testing::Values(0.3, 0.8, 1.2));

// Wind-tunnel trim: thrust at target and the first flap harmonic below 1e-10; the cyclic pitch
// is really used (nonzero) and the untrimmed blade does flap at 1/rev.
TEST(Trim, MomentTrimRemovesTheFirstFlapHarmonic) {
  const double mu = 0.3;
  TrimOptions o;
  o.kind = TrimKind::Moment;
  o.thrust_coefficient = 0.005;
  const RotorParameters p = cyclic_typical();
  const auto untrimmed = flaplag::rotor_thrust(p, mu, flaplag::momentum_inflow(0.005, mu, 0.0));
  EXPECT_GT(std::hypot(untrimmed.flap_1c, untrimmed.flap_1s), 1e-3);
  const auto r = flaplag::trim(p, mu, o);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  EXPECT_LT(std::abs(r.flap_1c), 1e-10);
  EXPECT_LT(std::abs(r.flap_1s), 1e-10);
  EXPECT_NEAR(r.thrust_coefficient, 0.005, 1e-10);
  EXPECT_GT(std::hypot(r.theta1c, r.theta1s), 1e-3);
  // the harmonic of the Analysis response agrees (independent harmonic extraction)
  flaplag::Analysis an(r.parameters, {}, flaplag::OperatingCondition::At(r));
  const auto resp = an.response(mu);
  ASSERT_NE(resp.status, Status::Failed) << resp.message;
  EXPECT_LT(std::abs(flaplag::tip_motion(resp.tips, "flap").harmonics[1]), 1e-10);
  EXPECT_LT(std::abs(flaplag::tip_motion(resp.tips, "flap").harmonics[2]), 1e-10);
}

// With theta1c = theta1s = 0 the cyclic model is the paper model: same A(psi), f(psi).
// Regression (moment trim from a far start): Newton from the hover trim's controls straight to
// mu = 0.7 does not converge (the controls change by 0.2-0.4 rad on the way); the trim then
// continues in halved steps of mu from the last converged trim, and lands on the trim that a
// start at mu = 0.65 gives.
TEST(Trim, FromAFarStartItContinuesInHalvedSteps) {
  const RotorParameters p = cyclic_typical();
  TrimOptions o = moment_trim_005();
  const auto hover = flaplag::trim(p, 0.0, o);
  ASSERT_TRUE(hover.converged) << hover.message;
  const auto far = flaplag::trim(p, 0.7, o, &hover);
  ASSERT_TRUE(far.converged) << far.message;
  ASSERT_NE(far.status, Status::Failed) << far.message;
  EXPECT_NEAR(far.thrust_coefficient, o.thrust_coefficient, 1e-10 * o.thrust_coefficient);
  const auto near_start = flaplag::trim(p, 0.65, o, &hover);
  ASSERT_TRUE(near_start.converged) << near_start.message;
  const auto near = flaplag::trim(p, 0.7, o, &near_start);
  ASSERT_TRUE(near.converged) << near.message;
  EXPECT_NEAR(far.theta0, near.theta0, 1e-8);
  EXPECT_NEAR(far.theta1c, near.theta1c, 1e-8);
  EXPECT_NEAR(far.theta1s, near.theta1s, 1e-8);
}

// Regression: where no trim exists (the moment trim at C_T = 0.005 ends near mu = 0.74), the
// continuation in halved steps tried ever smaller steps with Newton solves that could not
// converge (23 s for one trim at mu = 0.8 of the typical case).  A trim now makes at most
// max_evaluations thrust evaluations (a small budget here, so that the test is quick) and says
// so.
TEST(Trim, WithoutASolutionItGivesUpWithinItsBudget) {
  const RotorParameters p = cyclic_typical();
  TrimOptions o = moment_trim_005();
  const auto hover = flaplag::trim(p, 0.0, o);
  ASSERT_TRUE(hover.converged) << hover.message;
  EXPECT_GT(hover.evaluations, 0);
  EXPECT_LT(hover.evaluations, 60);
  o.max_evaluations = 120;
  const auto none = flaplag::trim(p, 0.8, o, &hover);
  EXPECT_EQ(Status::Failed, none.status) << none.message;
  EXPECT_FALSE(none.converged);
  EXPECT_LE(none.evaluations, o.max_evaluations);
  EXPECT_EQ(0.8, none.mu);
  // Within the budget a trim that exists is still found (and the bound is an option).
  const auto far = flaplag::trim(p, 0.7, o, &hover);
  EXPECT_TRUE(far.converged) << far.message;
  EXPECT_LE(far.evaluations, o.max_evaluations);
  o.max_evaluations = 0;
  EXPECT_THROW(flaplag::trim(p, 0.7, o, &hover), InvalidInput);
}

TEST(CyclicPitch, ZeroCyclicEqualsPaperModel) {
  RotorParameters p;
  flaplag::Analysis paper(p, {});
  p.model = "paper-cyclic";
  flaplag::Analysis cyc(p, {});
  for (double psi : {0.2, 2.0, 4.5}) {
    const auto a = paper.snapshot(0.7, psi), b = cyc.snapshot(0.7, psi);
    EXPECT_LT((a.A - b.A).cwiseAbs().maxCoeff(), 1e-15) << psi;
    EXPECT_LT((a.f - b.f).cwiseAbs().maxCoeff(), 1e-15) << psi;
  }
  // and nonzero cyclic pitch changes the forcing at 1/rev even in hover
  p.theta1s = 0.02;
  flaplag::Analysis with(p, {});
  EXPECT_GT((with.snapshot(0.0, 1.0).f - cyc.snapshot(0.0, 1.0).f).cwiseAbs().maxCoeff(), 1e-4);
}

// Every model takes cyclic pitch (the default one used to refuse it): it changes the answer.
TEST(CyclicPitch, EveryModelTakesCyclicPitch) {
  RotorParameters p;  // model paper
  auto max_zeta = [](const RotorParameters& q) {
    double z = -1e300;
    for (const auto& e : flaplag::Analysis(q, {}).point(0.4).exponents) z = std::max(z, e.zeta);
    return z;
  };
  const double zeta0 = max_zeta(p);
  p.theta1c = 0.01;
  const double zeta1 = max_zeta(p);
  EXPECT_TRUE(std::isfinite(zeta1));
  EXPECT_GT(std::abs(zeta1 - zeta0), 1e-6) << zeta0 << " " << zeta1;
  p.theta1c = 0.0;
  p.theta1s = 2.0;  // out of range is validate()'s error
  EXPECT_THROW(flaplag::validate(p), InvalidInput);
}

TEST(Trim, BadInputNamesTheField) {
  TrimOptions o;
  o.kind = TrimKind::Thrust;
  std::string why;
  o.thrust_coefficient = -0.01;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_EQ(0u, why.find("thrust_coefficient = -0.01: ")) << why;
  try {
    o.Check();
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.name(), "thrust_coefficient");
    EXPECT_EQ(e.value(), "-0.01");
  }
  o.thrust_coefficient = std::nan("");
  EXPECT_THROW(o.Check(), InvalidInput);
  o.thrust_coefficient = 0.005;
  o.shaft_angle = 2.0;
  try {
    o.Check();
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.name(), "shaft_angle");
  }
  o.shaft_angle = 0.0;
  o.max_iterations = 0;
  EXPECT_THROW(o.Check(), InvalidInput);
  o.max_iterations = 30;
  o.response.samples = 1;
  try {
    o.Check();
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.name(), "samples");
  }
  o.response.samples = 72;
  // every model has the thrust: the default one trims
  EXPECT_EQ(flaplag::trim(RotorParameters{}, 0.3, o).status, flaplag::Status::Ok);
  // nothing to trim
  o.kind = TrimKind::None;
  EXPECT_THROW(flaplag::trim(cyclic_typical(), 0.3, o), InvalidInput);
  o.kind = TrimKind::Thrust;
  EXPECT_THROW(flaplag::trim(cyclic_typical(), -0.1, o), InvalidInput);
  EXPECT_THROW(flaplag::trim(cyclic_typical(), std::nan(""), o), InvalidInput);
  EXPECT_THROW(flaplag::momentum_inflow(0.0, 0.3, 0.0), InvalidInput);
  // the thrust has no exact-circle form: refused, not a thrust of another region
  {
    RotorParameters p = cyclic_typical();
    p.exact_reversed_flow = true;
    try {
      flaplag::trim(p, 0.3, o);
      FAIL();
    } catch (const InvalidInput& e) {
      EXPECT_EQ(e.name(), "exact_reversed_flow");
    }
  }
  TrimKind k;
  EXPECT_TRUE(flaplag::trim_kind_from_name("moment", &k));
  EXPECT_EQ(k, TrimKind::Moment);
  EXPECT_FALSE(flaplag::trim_kind_from_name("Moment", &k));
}

// A thrust the pitch cannot reach within (-pi/2, pi/2) comes back Failed or Warning with a
// message, never as ok.
TEST(Trim, UnreachableThrustIsAStatus) {
  TrimOptions o;
  o.kind = TrimKind::Thrust;
  o.thrust_coefficient = 0.1;
  o.max_iterations = 3;
  const auto r = flaplag::trim(cyclic_typical(), 0.3, o);
  if (r.status == Status::Ok) {
    EXPECT_LT(std::abs(r.theta0), 1.5707963267948966);
    EXPECT_NEAR(r.thrust_coefficient, 0.1, 1e-10);
  } else {
    EXPECT_FALSE(r.message.empty());
  }
}

// The exact-mode family of the cyclic model (paper-cyclic-2x2): the thrust sums over the modes.
// In hover (y = 0) it is the blade-element value whatever the modes; at mu = 0.3 the two-mode
// blade differs a little from the one-mode one.
TEST(RotorThrust, ExactModesTwoByTwo) {
  RotorParameters p = cyclic_typical();
  p.model = "paper-cyclic-2x2";
  p.modes = flaplag::ModeKind::Exact;
  const double lambda = 0.04;
  const auto hover = flaplag::rotor_thrust(p, 0.0, lambda);
  ASSERT_EQ(hover.status, Status::Ok) << hover.message;
  const double expected = 0.5 * p.sigma * p.lift_slope * (p.theta / 3.0 - lambda / 2.0);
  EXPECT_NEAR(hover.thrust_coefficient, expected, 1e-13) << "expected " << expected;
  const auto two = flaplag::rotor_thrust(p, 0.3, lambda);
  p.model = "paper-cyclic";
  const auto one = flaplag::rotor_thrust(p, 0.3, lambda);
  ASSERT_EQ(two.status, Status::Ok) << two.message;
  ASSERT_EQ(one.status, Status::Ok) << one.message;
  EXPECT_NEAR(two.thrust_coefficient, one.thrust_coefficient, 0.05 * one.thrust_coefficient);
  EXPECT_NE(two.thrust_coefficient, one.thrust_coefficient);
}

// ---- trim about the periodic equilibrium (model paper-cyclic-nonlinear) ----------------------

namespace {

// Trimmed about the periodic equilibrium (trim(..., kPeriodic)).
RotorParameters periodic_typical() {
  RotorParameters p;
  p.model = "paper-cyclic-nonlinear";
  return p;
}
constexpr flaplag::Linearization kPeriodic = flaplag::Linearization::PeriodicEquilibrium;

}  // namespace

// In hover q° is the hover equilibrium, so the thrust about it is the hover-linearized model's
// (paper-cyclic) to rounding, and the round trip of issue 12 holds about q° as well.
TEST(PeriodicTrim, HoverThrustIsTheHoverModelsAndTheRoundTripHolds) {
  const auto linear = flaplag::rotor_thrust_momentum(cyclic_typical(), 0.0, 0.0);
  const auto about = flaplag::rotor_thrust_momentum(periodic_typical(), 0.0, 0.0, {}, kPeriodic);
  ASSERT_EQ(about.status, Status::Ok) << about.message;
  EXPECT_NEAR(about.thrust_coefficient, linear.thrust_coefficient, 1e-15);
  RotorParameters p = periodic_typical();
  p.theta = 0.1;
  TrimOptions o;
  o.kind = TrimKind::Thrust;
  o.thrust_coefficient = about.thrust_coefficient;
  const auto r = flaplag::trim(p, 0.0, o, nullptr, kPeriodic);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  EXPECT_NEAR(r.theta0, 0.15, 1e-12);
  EXPECT_EQ(r.equilibrium.harmonics, 16);
}

// Thrust and moment trim at mu = 0.3 about q°: the thrust of the nonlinear equilibrium equals
// the target to 1e-10, and (moment) the first flap harmonic of q° is below 1e-10, also for q°
// computed again by the Analysis (continued from hover, not from the trim's warm starts).  The
// trim is not the hover-linearized one: its controls differ.
TEST(PeriodicTrim, ThrustAndFirstFlapHarmonicOfTheEquilibriumAreTrimmed) {
  const double mu = 0.3, ct = 0.005;
  TrimOptions o;
  o.kind = TrimKind::Moment;
  o.thrust_coefficient = ct;
  const auto r = flaplag::trim(periodic_typical(), mu, o, nullptr, kPeriodic);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  EXPECT_NEAR(r.thrust_coefficient, ct, 1e-10 * ct);
  EXPECT_LT(std::abs(r.flap_1c), 1e-10);
  EXPECT_LT(std::abs(r.flap_1s), 1e-10);
  ASSERT_EQ(r.equilibrium.coefficients.rows(), 2);
  EXPECT_EQ(r.equilibrium.mu, mu);
  const flaplag::Analysis an(r.parameters, {}, flaplag::OperatingCondition::At(r));
  const auto eq = an.periodic_equilibrium(mu);
  ASSERT_NE(eq.status, Status::Failed) << eq.message;
  const double tip = an.modes().shapes(flaplag::model::Direction::Flap)[0]->value(0, 1.0);
  EXPECT_LT(std::abs(tip * eq.coefficients(0, 1)), 1e-10);
  EXPECT_LT(std::abs(tip * eq.coefficients(0, 2)), 1e-10);
  EXPECT_NEAR(0.5 * r.parameters.sigma * r.parameters.lift_slope * eq.mean_thrust, ct, 1e-10 * ct);
  // the hover-linearized moment trim of the same rotor needs other controls
  const auto hover_linear = flaplag::trim(cyclic_typical(), mu, o);
  ASSERT_EQ(hover_linear.status, Status::Ok) << hover_linear.message;
  EXPECT_GT(std::abs(hover_linear.theta1s - r.theta1s) + std::abs(hover_linear.theta0 - r.theta0),
            1e-5);
  // Thrust trim about q° alone: the target to 1e-10, the flapping left in.
  o.kind = TrimKind::Thrust;
  const auto t = flaplag::trim(periodic_typical(), mu, o, nullptr, kPeriodic);
  ASSERT_EQ(t.status, Status::Ok) << t.message;
  EXPECT_NEAR(t.thrust_coefficient, ct, 1e-10 * ct);
  EXPECT_GT(std::hypot(t.flap_1c, t.flap_1s), 1e-3);
}

// The stability of the trimmed rotor about q°: the exponents about the trim's equilibrium are
// those of an Analysis that continues q° from hover itself at the trimmed controls.
TEST(PeriodicTrim, TrimmedPointIsTheFloquetAnalysisAboutTheTrimmedEquilibrium) {
  const double mu = 0.2;
  TrimOptions o;
  o.kind = TrimKind::Moment;
  o.thrust_coefficient = 0.0042;
  const flaplag::TransitionOptions t;
  const auto pt = flaplag::Analysis(periodic_typical(), t,
                                    flaplag::OperatingCondition::Trimmed(o).About(kPeriodic))
                      .point(mu, 0.1);
  ASSERT_NE(pt.status, Status::Failed) << pt.message;
  const auto r = flaplag::trim(periodic_typical(), mu, o, nullptr, kPeriodic);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  const flaplag::Analysis an(r.parameters, t, flaplag::OperatingCondition::At(r));
  const auto direct = an.floquet(mu, t.zeta_tolerance);
  ASSERT_NE(direct.status, Status::Failed) << direct.message;
  double zmax_pt = -1e9, zmax_direct = -1e9;
  for (const auto& e : pt.exponents) zmax_pt = std::max(zmax_pt, e.zeta);
  for (const auto& e : direct.floquet.exponents) zmax_direct = std::max(zmax_direct, e.zeta);
  EXPECT_NEAR(zmax_pt, zmax_direct, 1e-8);
  // The point carries q° in its trim only (not twice): the trimmed equilibrium, the same as the
  // one trim() finds on its own at mu.
  EXPECT_FALSE(pt.equilibrium.has_value());
  ASSERT_TRUE(pt.trim.has_value());
  EXPECT_EQ(pt.trim->linearization, kPeriodic);
  ASSERT_EQ(pt.periodic_equilibrium(), &pt.trim->equilibrium);
  ASSERT_EQ(pt.trim->equilibrium.coefficients.rows(), r.equilibrium.coefficients.rows());
  ASSERT_EQ(pt.trim->equilibrium.coefficients.cols(), r.equilibrium.coefficients.cols());
  EXPECT_LT((pt.trim->equilibrium.coefficients - r.equilibrium.coefficients).cwiseAbs().maxCoeff(),
            1e-8);
  // and about hover the same trimmed rotor has other exponents (the equilibrium matters)
  const auto about_hover =
      flaplag::Analysis(
          r.parameters, t,
          flaplag::OperatingCondition::At(r).About(flaplag::Linearization::HoverEquilibrium))
          .floquet(mu, 1e-5);
  double zmax_hover = -1e9;
  for (const auto& e : about_hover.floquet.exponents) zmax_hover = std::max(zmax_hover, e.zeta);
  EXPECT_GT(std::abs(zmax_hover - zmax_pt), 1e-4);
}

// About the periodic equilibrium the trim needs the nonlinear thrust: the models without it are
// refused naming the model.
// ---- Honest results: a trim outside the validity envelope, and results resting on trims ---

// C_T = 0.1 at mu = 0.3 trims the typical blade to theta0 near 80 deg: far outside the
// small-angle ordering, so the trim warns, naming the quantity, its value and the limit (it
// used to say "ok").
TEST(TrimHonest, TrimOutsideTheValidityEnvelopeWarns) {
  TrimOptions o;
  o.kind = TrimKind::Thrust;
  o.thrust_coefficient = 0.1;
  const flaplag::TrimResult t = flaplag::trim(cyclic_typical(), 0.3, o);
  ASSERT_NE(t.status, Status::Failed) << t.message;
  ASSERT_GT(std::abs(t.theta0), 0.35) << "the example no longer leaves the envelope";
  EXPECT_EQ(t.status, Status::Warning) << t.message;
  EXPECT_NE(t.validity.find("theta0 = "), std::string::npos) << t.validity;
  EXPECT_NE(t.validity.find("0.35 rad"), std::string::npos) << t.validity;
  EXPECT_NE(t.message.find(t.validity), std::string::npos) << t.message;
  EXPECT_EQ(flaplag::trim_problem(t), t.validity);
  // The default C_T is inside: nothing to say.
  o.thrust_coefficient = 0.005;
  const flaplag::TrimResult ok = flaplag::trim(cyclic_typical(), 0.3, o);
  EXPECT_EQ(ok.status, Status::Ok) << ok.message;
  EXPECT_TRUE(ok.validity.empty()) << ok.validity;
  EXPECT_TRUE(flaplag::trim_problem(ok).empty());
}

// A point resting on a trim outside the envelope is no better than that trim: a warning with
// the trim's message; the trims reported are the ones the results rest on, one per point.
TEST(TrimHonest, TrimmedResultsCarryTheirTrimsProblems) {
  // C_T = 0.015 (C_T / sigma = 0.3) needs theta0 = 0.41 rad at mu = 0.05.
  TrimOptions o;
  o.kind = TrimKind::Thrust;
  o.thrust_coefficient = 0.015;
  const flaplag::RotorPoint p =
      flaplag::Analysis(cyclic_typical(), {}, flaplag::OperatingCondition::Trimmed(o))
          .point(0.05, 0.05);
  ASSERT_TRUE(p.trim.has_value());
  EXPECT_EQ(p.trim->mu, 0.05);
  ASSERT_GT(p.trim->theta0, 0.35) << "the example no longer leaves the envelope";
  EXPECT_FALSE(flaplag::trim_problem(*p.trim).empty());
  ASSERT_NE(p.status, Status::Failed) << p.message;
  EXPECT_EQ(p.status, Status::Warning) << p.message;
  EXPECT_NE(p.message.find("trim at mu = 0.05: outside the model's validity envelope"),
            std::string::npos)
      << p.message;
  // A sweep inside the envelope: every point ok, each with the converged trim at its mu.
  o.thrust_coefficient = 0.005;
  const flaplag::RotorSweep s =
      flaplag::Analysis(cyclic_typical(), {}, flaplag::OperatingCondition::Trimmed(o))
          .sweep(0.0, 0.2, 0.1);
  const std::vector<flaplag::TrimResult>& trims = s.trims;
  ASSERT_EQ(trims.size(), s.points.size());
  for (std::size_t k = 0; k < trims.size(); ++k) {
    EXPECT_EQ(trims[k].mu, s.points[k].mu);
    EXPECT_TRUE(trims[k].converged);
    EXPECT_EQ(s.points[k].status, Status::Ok) << s.points[k].message;
  }
}

// ---- One Analysis at an operating condition ------------------------------------------------

// A trimmed critical result carries the trim at mu_c that it rests on: for the thrust trim
// (each mu trimmed from the blade-element start, so independent of the order of evaluation) it
// is the trim a user gets at mu_c directly, to the bit, and its thrust is the target.
TEST(OperatingCondition, TrimmedCriticalCarriesTheTrimAtMuC) {
  TrimOptions o;
  o.kind = TrimKind::Thrust;
  o.thrust_coefficient = 0.0042384;  // the typical case's C_T in hover
  flaplag::CriticalOptions c;
  c.mu_max = 1.1;
  c.scan_step = 0.1;
  RotorParameters p = cyclic_typical();
  p.omega_lag = 0.5;  // unstable below mu = 1.1 when trimmed
  const flaplag::RotorCritical r =
      flaplag::Analysis(p, {}, flaplag::OperatingCondition::Trimmed(o)).critical(c);
  ASSERT_TRUE(r.mu_c.has_value()) << r.message;
  ASSERT_TRUE(r.trim.has_value());
  EXPECT_EQ(r.trim->mu, *r.mu_c);
  const flaplag::TrimResult direct = flaplag::trim(p, *r.mu_c, o);
  EXPECT_EQ(r.trim->theta0, direct.theta0);
  EXPECT_EQ(r.trim->inflow, direct.inflow);
  EXPECT_TRUE(r.trim->converged);
  EXPECT_TRUE(flaplag::testing::RelClose(0.0042384, r.trim->thrust_coefficient, 1e-12));
  // Without mu_c there is no trim to carry.
  c.mu_max = 0.2;
  const flaplag::RotorCritical none =
      flaplag::Analysis(p, {}, flaplag::OperatingCondition::Trimmed(o)).critical(c);
  EXPECT_FALSE(none.mu_c.has_value());
  EXPECT_FALSE(none.trim.has_value());
  // With fixed controls no result carries a trim.
  const flaplag::Analysis fixed(cyclic_typical(), {});
  EXPECT_FALSE(fixed.point(0.3).trim.has_value());
  EXPECT_TRUE(fixed.sweep(0.0, 0.2, 0.1).trims.empty());
}

// The header of a trimmed analysis is the rotor trimmed in hover: its parameters carry the
// trimmed collective, its hover is the one at that pitch and the eq 2.25 inflow (the Analysis
// At() the hover trim), and what answers for fixed controls only is refused by name.
TEST(OperatingCondition, ATrimmedAnalysisIsTheRotorTrimmedInHover) {
  const TrimOptions o = moment_trim_005();
  const flaplag::Analysis an(cyclic_typical(), {}, flaplag::OperatingCondition::Trimmed(o));
  const flaplag::TrimResult h = flaplag::trim(cyclic_typical(), 0.0, o);
  EXPECT_EQ(an.parameters().theta, h.theta0);
  const flaplag::Analysis at(h.parameters, {}, flaplag::OperatingCondition::At(h));
  ASSERT_EQ(an.hover().eigenvalues.size(), at.hover().eigenvalues.size());
  for (std::size_t k = 0; k < at.hover().eigenvalues.size(); ++k)
    EXPECT_EQ(an.hover().eigenvalues[k], at.hover().eigenvalues[k]) << k;
  for (const auto& refused : std::vector<std::function<void()>>{
           [&] { an.system(0.3); }, [&] { an.snapshot(0.3, 0.0); }, [&] { an.response(0.3); },
           [&] { an.floquet(0.3, 1e-6); },
           [&] { an.simulate(0.3, Eigen::VectorXd::Zero(an.state_size()), false); }}) {
    try {
      refused();
      ADD_FAILURE() << "a fixed-control query of a trimmed analysis was answered";
    } catch (const InvalidInput& e) {
      EXPECT_EQ(e.name(), "trim") << e.what();
      EXPECT_NE(std::string(e.what()).find("fixed controls"), std::string::npos) << e.what();
    }
  }
}

// An inflow given together with a trim is refused (each trim has its own eq 2.25 inflow), and a
// trim that cannot be made in hover fails the constructor, naming the thrust coefficient.
TEST(OperatingCondition, BadConditionsNameTheField) {
  flaplag::OperatingCondition c = flaplag::OperatingCondition::Trimmed(moment_trim_005());
  c.inflow = flaplag::InflowModel::Given(0.05);
  try {
    flaplag::Analysis(cyclic_typical(), {}, c);
    ADD_FAILURE() << "inflow with a trim accepted";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.name(), "inflow") << e.what();
  }
  TrimOptions o;
  o.kind = TrimKind::Thrust;
  o.thrust_coefficient = 0.1;
  try {
    flaplag::Analysis(cyclic_typical(), {}, flaplag::OperatingCondition::Trimmed(o));
    ADD_FAILURE() << "an untrimmable rotor accepted";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.name(), "thrust_coefficient") << e.what();
  }
}

}  // namespace trim_test
