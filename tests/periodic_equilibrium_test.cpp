// The periodic equilibrium of the nonlinear equations and the linearization about it
// (rotor/periodic_equilibrium.h, issue 12 "Checks: Periodic equilibrium"):
//   - at mu = 0 it is the hover equilibrium and the linearization is the hover A;
//   - at mu > 0 the nonlinear time-domain solution (RK4, independent of the harmonic balance)
//     converges to it when it is stable, the closer the more harmonics;
//   - the Floquet multipliers of the linearization are those of small perturbations of the
//     nonlinear simulation (its monodromy by finite differences about the simulated orbit);
//   - beyond the fold of the hover branch there is no equilibrium: status Failed;
//   - options and models without nonlinear loads are rejected naming the input.
#include "flaplag/rotor/periodic_equilibrium.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>

#include "flaplag/analysis.h"
#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/numerics/dense.h"
#include "flaplag/numerics/floquet.h"
#include "flaplag/rotor/system_builder.h"
#include "test_util.h"

namespace flaplag::periodic_equilibrium_test {
namespace {

using testing::AbsClose;
using testing::RelClose;

RotorParameters nonlinear_case() {
  RotorParameters p;
  p.model = "paper-nonlinear";
  // Structural lag damping: the lag mode then settles within tens of revolutions, so that the
  // simulation checks stay cheap (the typical case's lag damping is -0.003 per rev at mu = 0.3).
  p.damping_lag = 0.05;
  return p;
}

TEST(PeriodicEquilibrium, AtHoverItIsTheHoverEquilibriumAndTheHoverA) {
  RotorParameters p;
  p.model = "paper-nonlinear";
  const Analysis an(p, {});
  const PeriodicEquilibrium eq = an.periodic_equilibrium(0.0);
  ASSERT_EQ(Status::Ok, eq.status) << eq.message;
  const Eigen::VectorXd& q0 = an.hover().q0;
  for (int j = 0; j < 2; ++j) {
    EXPECT_TRUE(RelClose(q0(j), eq.coefficients(j, 0), 1e-13));
    for (int c = 1; c < eq.coefficients.cols(); ++c) EXPECT_EQ(0.0, eq.coefficients(j, c));
  }
  const PeriodicSystem hover = an.system(0.0);
  ASSERT_EQ(1u, eq.linearization.sets.at(0).A.size());
  ASSERT_EQ(1u, eq.linearization.pieces.size());
  const Eigen::MatrixXd& A = eq.linearization.sets[0].A[0];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      EXPECT_TRUE(AbsClose(hover.sets[0].A[0](i, j), A(i, j), 1e-13)) << i << "," << j;
  // The paper's own model gives the same A (paper-nonlinear's linear part is the paper's).
  RotorParameters paper;
  const Eigen::MatrixXd A_paper = Analysis(paper, {}).system(0.0).sets[0].A[0];
  EXPECT_LT((A_paper - A).cwiseAbs().maxCoeff(), 1e-13);
  // The analysis switch: identical exponents at hover.
  const PointResult a = Analysis(p, {}).point(0.0),
                    b = Analysis(p, {},
                                 flaplag::OperatingCondition{}.About(
                                     flaplag::Linearization::PeriodicEquilibrium))
                            .point(0.0);
  ASSERT_EQ(a.exponents.size(), b.exponents.size());
  for (std::size_t k = 0; k < a.exponents.size(); ++k) {
    EXPECT_TRUE(AbsClose(a.exponents[k].zeta, b.exponents[k].zeta, 1e-12));
    EXPECT_TRUE(AbsClose(a.exponents[k].omega, b.exponents[k].omega, 1e-12));
  }
}

// Distance of the state after many revolutions of the nonlinear RK4 simulation (started at the
// hover state) from the harmonic-balance equilibrium at psi = 0.
double simulated_distance(const Analysis& an, const detail::SystemBuilder& b, double mu, int K) {
  PeriodicEquilibriumOptions o;
  o.harmonics = K;
  o.check_stability = false;
  const PeriodicEquilibrium eq = an.periodic_equilibrium(mu, o);
  EXPECT_EQ(Status::Ok, eq.status) << eq.message;  // converged, last harmonic small
  const NonlinearSystem sys(b, mu);
  Eigen::VectorXd y0 = Eigen::VectorXd::Zero(4);
  y0(1) = an.hover().q0(0);
  y0(3) = an.hover().q0(1);
  const auto revs = sys.integrate(y0, 60, 720);
  return (revs.back() - eq.state(0.0)).cwiseAbs().maxCoeff() / eq.state(0.0).cwiseAbs().maxCoeff();
}

TEST(PeriodicEquilibrium, NonlinearSimulationConvergesToIt) {
  const RotorParameters p = nonlinear_case();
  const Analysis an(p, {});
  const detail::SystemBuilder b(p, find_model(p.model));
  const double mu = 0.5;  // with reversed flow: the sector's kinks limit the Fourier series
  // (RK4 with 720 and 1440 steps per rev agree to 1e-10 here; after 60 revs the transient is
  // below 1e-13.)  The Fourier coefficients of the equilibrium fall like k^-3 (its second
  // derivative jumps at the sector edges): the distance falls like K^-2.
  // Relative distances (measured: K = 8 1.4e-4, K = 16 3.9e-5, K = 32 9.2e-6).
  const double d8 = simulated_distance(an, b, mu, 8), d16 = simulated_distance(an, b, mu, 16);
  EXPECT_LT(d16, 8e-5) << "K = 8: " << d8;
  EXPECT_LT(d16, 0.4 * d8) << "more harmonics must come closer";
}

TEST(PeriodicEquilibrium, FloquetMultipliersAreThoseOfPerturbedNonlinearSimulation) {
  const RotorParameters p = nonlinear_case();
  const Analysis an(p, {});
  const detail::SystemBuilder b(p, find_model(p.model));
  const double mu = 0.5;
  PeriodicEquilibriumOptions o;
  o.harmonics = 16;
  const PeriodicEquilibrium eq = an.periodic_equilibrium(mu, o);
  ASSERT_EQ(Status::Ok, eq.status) << eq.message;
  ASSERT_EQ(4u, eq.multiplier_moduli.size());
  const NonlinearSystem sys(b, mu);
  // The simulated orbit: from the equilibrium, settled (the residual is the truncation only).
  const Eigen::VectorXd y_orbit = sys.integrate(eq.state(0.0), 40, 720).back();
  // Monodromy of small perturbations by central differences over one revolution.
  const double delta = 1e-6;
  Eigen::MatrixXd phi(4, 4);
  for (int c = 0; c < 4; ++c) {
    Eigen::VectorXd yp = y_orbit, ym = y_orbit;
    yp(c) += delta;
    ym(c) -= delta;
    phi.col(c) =
        (sys.integrate(yp, 1, 720).back() - sys.integrate(ym, 1, 720).back()) / (2 * delta);
  }
  // against the transition matrix of the linearization about the harmonic-balance equilibrium
  const Eigen::MatrixXd phi_lin = transition_matrix_rk4(eq.linearization, 4096);
  EXPECT_LT((phi - phi_lin).cwiseAbs().maxCoeff(), 1e-6);
  const RealEigenSystem es = real_eigen_system(phi, false, EigenStorage::Dynamic);
  std::vector<double> sim;
  for (int k = 0; k < 4; ++k) sim.push_back(std::abs(es.values(k)));
  std::sort(sim.rbegin(), sim.rend());
  for (int k = 0; k < 4; ++k) {
    // zeta = ln|Lambda| / 2 pi from both
    EXPECT_TRUE(
        AbsClose(std::log(sim[k]) / kTwoPi, std::log(eq.multiplier_moduli[k]) / kTwoPi, 1e-5))
        << k;
  }
  // The analysis with the switch gives the same largest zeta, and it differs from the hover
  // linearization's: the periodic equilibrium matters at this mu.
  TransitionOptions fine;
  fine.zeta_tolerance = 1e-7;
  const PointResult periodic = Analysis(p, fine,
                                        flaplag::OperatingCondition{}.About(
                                            flaplag::Linearization::PeriodicEquilibrium))
                                   .point(mu, 0.1),
                    hover = an.point(mu, 0.1);
  ASSERT_NE(Status::Failed, periodic.status) << periodic.message;
  auto max_zeta = [](const PointResult& r) {
    double z = -1e300;
    for (const auto& e : r.exponents) z = std::max(z, e.zeta);
    return z;
  };
  EXPECT_TRUE(AbsClose(std::log(sim[0]) / kTwoPi, max_zeta(periodic), 1e-6));
  EXPECT_GT(std::abs(max_zeta(periodic) - max_zeta(hover)), 1e-3);
}

TEST(PeriodicEquilibrium, BeyondTheFoldOfTheHoverBranchThereIsNone) {
  RotorParameters p;
  p.model = "paper-nonlinear";
  const Analysis an(p, {});
  PeriodicEquilibriumOptions o;
  o.harmonics = 8;
  const PeriodicEquilibrium before = an.periodic_equilibrium(0.66, o);
  ASSERT_EQ(Status::Ok, before.status) << before.message;
  // approaching the fold a real multiplier approaches 1
  EXPECT_LT(before.min_distance_to_one, 0.4);
  o.check_stability = false;
  const PeriodicEquilibrium after = an.periodic_equilibrium(0.7, o);
  EXPECT_EQ(Status::Failed, after.status);
  EXPECT_NE(std::string::npos, after.message.find("fold")) << after.message;
  EXPECT_GT(after.continued_to, 0.66);
  EXPECT_LT(after.continued_to, 0.68);
}

// About the periodic equilibrium the typical case loses its equilibrium at the fold: critical
// reports it as mu_c (kind periodic, omega 0, the message says the branch ends there), inside
// the bracket where q° still exists below and no longer above, and a real multiplier near 1.
TEST(PeriodicEquilibrium, CriticalReportsTheFoldAsTheStabilityBoundary) {
  RotorParameters p;
  p.model = "paper-nonlinear";
  const Analysis an(
      p, {}, flaplag::OperatingCondition{}.About(flaplag::Linearization::PeriodicEquilibrium));
  CriticalOptions o;
  // (cheap: a coarse scan, 0.5 stable and 0.75 past the fold, then the fold search; the fold's
  // position to 1e-5 is in docs/validation.md, and the K = 8 fold is told from the converged one
  // by AutomaticHarmonicsDoNotAcceptACoarseSolutionPastTheFinerFold)
  o.scan_step = 0.25;
  o.tolerance = 1e-3;
  const RotorCritical c = an.critical(o);
  ASSERT_TRUE(c.mu_c.has_value()) << c.message;
  EXPECT_EQ(Status::Ok, c.status) << c.message;
  EXPECT_EQ(InstabilityKind::Periodic, c.kind);
  // it carries q° where it last exists below the fold (within mu_c_error of mu_c), the one the
  // analysis also finds there on its own
  ASSERT_TRUE(c.equilibrium.has_value());
  EXPECT_EQ(c.periodic_equilibrium(), &*c.equilibrium);
  EXPECT_LT(c.equilibrium->mu, *c.mu_c);
  EXPECT_GE(c.equilibrium->mu, *c.mu_c - *c.mu_c_error);
  EXPECT_NE(Status::Failed, c.equilibrium->status) << c.equilibrium->message;
  EXPECT_EQ(0.0, c.omega);
  ASSERT_TRUE(c.mu_c_error.has_value());
  EXPECT_LE(*c.mu_c_error, 1e-3);
  EXPECT_NE(std::string::npos, c.message.find("fold")) << c.message;
  // q° exists just below mu_c, continued from hover independently of the search's probes (and
  // not at 0.7: BeyondTheFoldOfTheHoverBranchThereIsNone), with a multiplier near 1
  const PeriodicEquilibrium below = an.periodic_equilibrium(*c.mu_c - 2e-3);
  ASSERT_NE(Status::Failed, below.status) << below.message;
  EXPECT_LT(below.min_distance_to_one, 0.3);
}

// Regression (found by the command-line fuzzer): where q° ends at once (a flap frequency of
// 0.001 with almost no lift) and the multipliers of the linearization there cannot be computed,
// the failed search said "min |Lambda - 1| = inf"; it says so in words, and no "inf" is shown.
TEST(PeriodicEquilibrium, AFailedFoldSearchWithoutMultipliersShowsNoInfinity) {
  RotorParameters p;
  p.model = "paper-cyclic-nonlinear";
  p.tip_loss_a = 0.4048;
  p.lift_slope = 0.01;
  p.cdo = 0.4416;
  p.omega_flap = 0.001;
  p.damping_lag = 8.2681090432109041;
  const Analysis an(
      p, TransitionOptions{TransitionMethod::Hsu, 163, 4, 1e-5},
      flaplag::OperatingCondition{}.About(flaplag::Linearization::PeriodicEquilibrium));
  CriticalOptions o;
  o.mu_max = 0.0742;
  o.scan_step = 0.1;
  // Hover's least stable zeta, -5e-12, is within rounding of zero for this A0 (||A0|| ~ 1e5):
  // at the threshold 0 the search stops there (stability unknown, no "inf" either); a threshold
  // clear of the rounding lets it reach the fold search this test is about.
  const CriticalResult neutral = an.critical(o);
  EXPECT_EQ(Status::Warning, neutral.status);
  EXPECT_EQ(std::string::npos, neutral.message.find("inf")) << neutral.message;
  o.zeta_threshold = 1e-6;
  const CriticalResult c = an.critical(o);
  EXPECT_EQ(Status::Failed, c.status);
  EXPECT_EQ(std::string::npos, c.message.find("inf")) << c.message;
  EXPECT_NE(std::string::npos, c.message.find("could not be computed")) << c.message;
}

// Regression: between the fold of the K = 16 (and 32) truncation, mu ~ 0.66603, and the later
// fold of K = 8, mu ~ 0.66606, only the K = 8 solution exists.  The automatic K used to fall
// back to it with a warning, so the critical search counted it as existing and put the fold,
// mu_c, at the K = 8 fold with an error estimate 20 times too small; it is a failure now.
TEST(PeriodicEquilibrium, AutomaticHarmonicsDoNotAcceptACoarseSolutionPastTheFinerFold) {
  RotorParameters p;
  p.model = "paper-nonlinear";
  const Analysis an(p, {});
  const double mu = 0.66605;
  PeriodicEquilibriumOptions fixed;
  fixed.check_stability = false;
  fixed.harmonics = 8;
  ASSERT_EQ(Status::Ok, an.periodic_equilibrium(mu, fixed).status);
  fixed.harmonics = 16;
  ASSERT_EQ(Status::Failed, an.periodic_equilibrium(mu, fixed).status);
  PeriodicEquilibriumOptions automatic;
  automatic.check_stability = false;
  const PeriodicEquilibrium e = an.periodic_equilibrium(mu, automatic);
  EXPECT_EQ(Status::Failed, e.status) << e.message;
  EXPECT_NE(std::string::npos, e.message.find("K = 16")) << e.message;
}

// Automatic K: the K doubles until two successive K agree to harmonics_tolerance; the estimate
// bounds the distance to the K = 64 solution (the cap, reached with a tolerance it cannot meet,
// which is a warning naming the option); a fixed K is kept and has no estimate.
TEST(PeriodicEquilibrium, AutomaticHarmonicsMeetTheirToleranceOrWarnAtTheCap) {
  RotorParameters p;
  p.model = "paper-nonlinear";
  const Analysis an(p, {});
  const double mu = 0.3;
  PeriodicEquilibriumOptions o;
  o.check_stability = false;
  const PeriodicEquilibrium automatic = an.periodic_equilibrium(mu, o);
  ASSERT_EQ(Status::Ok, automatic.status) << automatic.message;
  ASSERT_TRUE(std::isfinite(automatic.harmonics_error));
  EXPECT_LE(automatic.harmonics_error, o.harmonics_tolerance);
  EXPECT_GE(automatic.harmonics, 2 * PeriodicEquilibriumOptions::kFirstHarmonics);
  EXPECT_LT(automatic.harmonics, PeriodicEquilibriumOptions::kMaxHarmonics);

  o.harmonics_tolerance = 1e-12;  // not reachable (the coefficients fall like k^-3)
  const PeriodicEquilibrium capped = an.periodic_equilibrium(mu, o);
  EXPECT_EQ(Status::Warning, capped.status);
  EXPECT_NE(std::string::npos, capped.message.find("harmonics_tolerance")) << capped.message;
  EXPECT_EQ(PeriodicEquilibriumOptions::kMaxHarmonics, capped.harmonics);
  EXPECT_GT(capped.harmonics_error, 1e-12);
  // the estimate is conservative: the K = 64 solution is within it
  const Eigen::MatrixXd& fine = capped.coefficients;
  const int cols = static_cast<int>(automatic.coefficients.cols());
  double diff = fine.rightCols(fine.cols() - cols).cwiseAbs().maxCoeff();
  diff = std::max(diff, (fine.leftCols(cols) - automatic.coefficients).cwiseAbs().maxCoeff());
  EXPECT_LE(diff / fine.cwiseAbs().maxCoeff(), automatic.harmonics_error);

  PeriodicEquilibriumOptions fixed;
  fixed.check_stability = false;
  fixed.harmonics = 8;
  const PeriodicEquilibrium eight = an.periodic_equilibrium(mu, fixed);
  EXPECT_EQ(8, eight.harmonics);
  EXPECT_EQ(17, eight.coefficients.cols());
  EXPECT_TRUE(std::isnan(eight.harmonics_error));
}

TEST(PeriodicEquilibrium, BadOptionsAndModelsWithoutNonlinearLoadsAreRejected) {
  PeriodicEquilibriumOptions o;
  std::string why;
  EXPECT_TRUE(o.IsValid(&why));
  o.harmonics = 0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(std::string::npos, why.find("harmonics = 0")) << why;
  EXPECT_THROW(o.Check(), InvalidInput);
  o = {};
  o.tolerance = std::nan("");
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(std::string::npos, why.find("tolerance")) << why;
  o = {};
  o.harmonics_tolerance = 0.0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(std::string::npos, why.find("harmonics_tolerance = 0")) << why;
  o = {};
  o.max_iterations = 0;
  EXPECT_THROW(o.Check(), InvalidInput);
  o = {};
  o.min_continuation_step = 0.0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(std::string::npos, why.find("min_continuation_step")) << why;
  EXPECT_THROW(o.Check(), InvalidInput);

  // Every model has the nonlinear loads: the default one answers (it used to need a model of
  // its own).
  RotorParameters p;
  EXPECT_EQ(Analysis(p, {}).periodic_equilibrium(0.3).status, Status::Ok);
  EXPECT_NO_THROW(Analysis(
      p, {}, flaplag::OperatingCondition{}.About(flaplag::Linearization::PeriodicEquilibrium)));
}

// Regression: the harmonic balance integrates the loads with the normal and sector integrals
// only, so with the exact reversed-flow circle it used to answer for the sector silently; and
// response/simulate/snapshot, which are of the hover system, ignored the periodic linearization.
TEST(PeriodicEquilibrium, CombinationsItCannotAnswerAreRefusedByName) {
  RotorParameters p;
  p.model = "paper-nonlinear";
  p.exact_reversed_flow = true;
  auto field_of = [](const auto& call) {
    try {
      call();
    } catch (const InvalidInput& e) {
      return e.name();
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ("exact_reversed_flow", field_of([&] { Analysis(p, {}).periodic_equilibrium(0.5); }));
  const auto about_q0 =
      flaplag::OperatingCondition{}.About(flaplag::Linearization::PeriodicEquilibrium);
  EXPECT_EQ("exact_reversed_flow", field_of([&] { Analysis an(p, {}, about_q0); }));
  p.exact_reversed_flow = false;
  const Analysis an(p, {}, about_q0);
  EXPECT_EQ("linearization", field_of([&] { an.response(0.3); }));
  EXPECT_EQ("linearization",
            field_of([&] { an.simulate(0.3, Eigen::VectorXd::Zero(an.state_size()), true); }));
  EXPECT_EQ("linearization", field_of([&] { an.snapshot(0.3, 0.0); }));
  EXPECT_EQ("(accepted)", field_of([&] { an.system(0.3); }));  // documented: the hover system
}

// About the periodic equilibrium a result carries the q° its exponents were computed about: a
// point and each point of a sweep the q° at its mu, which the analysis finds again on its own
// (continued from hover, not from the search's cache) to the Newton tolerance; about hover none.
TEST(PeriodicEquilibrium, ResultsCarryTheEquilibriumTheyWereComputedAbout) {
  const RotorParameters p;
  const Analysis an(p, {}, OperatingCondition{}.About(Linearization::PeriodicEquilibrium));
  const double mu = 0.3;
  const PeriodicEquilibrium alone = an.periodic_equilibrium(mu);
  ASSERT_EQ(Status::Ok, alone.status) << alone.message;
  auto expect_same = [&](const PeriodicEquilibrium& carried) {
    ASSERT_NE(Status::Failed, carried.status) << carried.message;
    EXPECT_NEAR(carried.mu, mu, 1e-15);
    ASSERT_EQ(carried.harmonics, alone.harmonics);
    ASSERT_EQ(carried.coefficients.rows(), alone.coefficients.rows());
    ASSERT_EQ(carried.coefficients.cols(), alone.coefficients.cols());
    EXPECT_LT((carried.coefficients - alone.coefficients).cwiseAbs().maxCoeff(), 1e-9);
    // the mean flap deflection of q° at mu = 0.3 is not the hover one: a real q°, not a default
    EXPECT_GT(carried.coefficients.cwiseAbs().maxCoeff(), 1e-3);
  };
  const RotorPoint r = an.point(mu);
  ASSERT_NE(Status::Failed, r.status) << r.message;
  ASSERT_TRUE(r.equilibrium.has_value());
  EXPECT_EQ(r.periodic_equilibrium(), &*r.equilibrium);
  expect_same(*r.equilibrium);
  const RotorSweep s = an.sweep(0.1, mu, 0.1, 1);
  ASSERT_EQ(s.points.size(), 3u);
  ASSERT_EQ(s.equilibria.size(), s.points.size());
  for (std::size_t k = 0; k < s.points.size(); ++k)
    EXPECT_NEAR(s.equilibria[k].mu, s.points[k].mu, 1e-12) << k;
  expect_same(s.equilibria.back());
  // about hover nothing is carried
  const Analysis hover(p, {});
  const RotorPoint h = hover.point(mu);
  EXPECT_FALSE(h.equilibrium.has_value());
  EXPECT_EQ(h.periodic_equilibrium(), nullptr);
  EXPECT_TRUE(hover.sweep(0.1, mu, 0.1, 1).equilibria.empty());
}

}  // namespace
}  // namespace flaplag::periodic_equilibrium_test
