// The paper's assumed-mode results (Figs 3, 6-7, 8), with stated tolerances.  The paper's
// figures are read to about 3 digits.  Numbers flaplag computes are in docs/validation.md.
#include <gtest/gtest.h>

#include <cmath>

#include "flaplag/analysis.h"
#include "test_util.h"

namespace paper_figures_test {

using flaplag::Analysis;
using flaplag::RotorParameters;
using flaplag::TransitionMethod;
using flaplag::TransitionOptions;

namespace {

TransitionOptions method(TransitionMethod m, int steps, int terms = 4) {
  TransitionOptions o;
  o.method = m;
  o.steps = steps;
  o.terms = terms;
  return o;
}

flaplag::CriticalResult critical(const RotorParameters& p, const TransitionOptions& o,
                                 double mu_max = 2.0) {
  flaplag::CriticalOptions c;
  c.mu_max = mu_max;
  return Analysis(p, o).critical(c);
}

struct MethodCase {
  const char* name;
  TransitionOptions options;
};

class FigureThree : public ::testing::TestWithParam<MethodCase> {};

}  // namespace

// Fig 3: typical case, assumed modes, no elastic coupling: lag unstable at mu_c = 0.754 with
// omega = 1.286; RK4 and Hsu (J = 4, K = 50) agree.
TEST_P(FigureThree, LagFlutterAtMu0754Omega1286) {
  const auto c = critical(RotorParameters{}, GetParam().options);
  ASSERT_TRUE(c.mu_c.has_value()) << c.message;
  EXPECT_EQ(c.mode, "lag");
  EXPECT_EQ(c.kind, flaplag::InstabilityKind::Flutter);
  EXPECT_NEAR(c.mu_c.value_or(-1.0), 0.754, 0.002);
  EXPECT_NEAR(c.omega, 1.286, 0.002);
  // The reference: Magnus with automatically chosen, error-controlled steps.
  const auto ref =
      critical(RotorParameters{}, method(TransitionMethod::Magnus4, TransitionOptions::kAutomatic));
  EXPECT_NEAR(c.mu_c.value_or(-1.0), ref.mu_c.value_or(-1.0), 1e-3)
      << "reference (Magnus) mu_c " << ref.mu_c.value_or(-1.0);
}

INSTANTIATE_TEST_SUITE_P(
    Methods, FigureThree,
    ::testing::Values(MethodCase{"Hsu_K50_J4", method(TransitionMethod::Hsu, 50, 4)},
                      MethodCase{"RK4_N50", method(TransitionMethod::RK4, 50)},
                      MethodCase{"Magnus_50", method(TransitionMethod::Magnus4, 50)}),
    [](const auto& tp) { return std::string(tp.param.name); });

// Figs 6-7: without the radial-flow terms the lag instability disappears (up to mu = 1.5) and
// the flap mode goes unstable at mu = 1.33 with omega locked to 1 per rev.
TEST(FiguresSixSeven, NoRadialFlowFlapUnstableAt133LockedToOnePerRev) {
  RotorParameters p;
  p.model = "no-radial-flow";
  Analysis an(p, {});
  const auto sw = an.sweep(0.0, 1.5, 0.01);
  ASSERT_EQ(sw.status, flaplag::Status::Ok) << sw.message;
  for (const auto& pt : sw.points) {
    for (const auto& e : pt.exponents) {
      if (e.label == "lag") {
        EXPECT_LT(e.zeta, 0.0) << "lag unstable at mu = " << pt.mu;
      }
    }
  }
  const auto c = an.critical({});
  ASSERT_TRUE(c.mu_c.has_value());
  EXPECT_EQ(c.mode, "flap");
  EXPECT_NEAR(c.mu_c.value_or(-1.0), 1.33, 0.01);
  EXPECT_EQ(c.kind, flaplag::InstabilityKind::Periodic);
  EXPECT_NEAR(c.omega, std::round(c.omega), 1e-3) << "omega locked to an integer per rev";
}

// Fig 8 (what flaplag finds): every aerodynamic damping term of the lag equation at hover is
// O(eps^3) -- profile drag 2 (l/R) L14 C_Do/a and induced drag (l/R) L13 lambda theta in A33.
// Removing them (model lag-order-2) leaves the lag mode with only structural damping, and the
// coupled flap-lag system is unstable already in hover.  The difference of A33 between the two
// models is exactly those two terms.
TEST(FigureEight, LagOrderTwoLosesAllLagAerodynamicDampingAndIsUnstableInHover) {
  RotorParameters p;
  Analysis full(p, {});
  p.model = "lag-order-2";
  Analysis reduced(p, {});
  EXPECT_TRUE(full.hover().stable);
  EXPECT_FALSE(reduced.hover().stable);
  EXPECT_EQ(reduced.hover().status, flaplag::Status::Warning);
  // A33 (lag rate row/column, index 2 in y = [g', g, h', h]) in hover.
  const double a33_full = full.hover().A0(2, 2), a33_reduced = reduced.hover().A0(2, 2);
  const auto snap = full.snapshot(0.0, 0.0);
  const auto& model = full.model();
  double L13 = 0, L14 = 0, ML = 0;
  for (int j = 0; j < model.n_aero; ++j) {
    if (std::string(model.aero[j].paper_name) == "L13_11") L13 = snap.aero_integrals[j].second;
    if (std::string(model.aero[j].paper_name) == "L14_11") L14 = snap.aero_integrals[j].second;
  }
  for (int j = 0; j < model.n_structural; ++j) {
    if (std::string(model.structural[j].paper_name) == "M_L11") {
      ML = snap.structural_integrals[j].second;
    }
  }
  ASSERT_GT(L13 * L14 * ML, 0.0);
  const double lr = 1.0, gamma = p.gamma, cdo_a = p.cdo / p.lift_slope;
  const double expected =
      -gamma / 2 * lr * lr * (2 * lr * L14 * cdo_a + lr * L13 * full.hover().inflow * p.theta) / ML;
  EXPECT_TRUE(flaplag::testing::RelClose(expected, a33_full - a33_reduced, 1e-12));
  EXPECT_LT(a33_full, a33_reduced);  // the O(eps^3) terms are damping
}

// Fig 15 (assumed modes): the rotating lag frequency decides the type of instability.  Near
// omega_L1 = 1/2 the lag mode goes unstable with omega locked to 1/2 per rev; for
// 0.9 < omega_L1 < 1.6 the radial-flow lag flutter appears early, at a frequency close to
// omega_L1; omega_L1 ~ 0.75 and > 1.6 are the best choices.
TEST(FigureFifteen, LagFrequencyDecidesTheInstability) {
  auto crit = [](double omega_lag) {
    RotorParameters p;
    p.omega_lag = omega_lag;
    return critical(p, TransitionOptions::Paper());
  };
  const auto half = crit(0.5);
  ASSERT_TRUE(half.mu_c.has_value());
  EXPECT_EQ(half.mode, "lag");
  EXPECT_EQ(half.kind, flaplag::InstabilityKind::Periodic);
  EXPECT_NEAR(half.omega, 0.5, 1e-3);
  double worst_mid = 0.0;
  for (double w : {1.0, 1.2, 1.4}) {
    const auto c = crit(w);
    ASSERT_TRUE(c.mu_c.has_value()) << "omega_L1 = " << w;
    EXPECT_EQ(c.mode, "lag");
    EXPECT_EQ(c.kind, flaplag::InstabilityKind::Flutter);
    EXPECT_NEAR(c.omega, w, 0.05) << "flutter near the lag frequency";
    EXPECT_LT(c.mu_c.value_or(-1.0), 0.9);
    worst_mid = std::max(worst_mid, c.mu_c.value_or(-1.0));
  }
  const auto soft = crit(0.75);
  ASSERT_TRUE(soft.mu_c.has_value());
  EXPECT_GT(soft.mu_c.value_or(-1.0), worst_mid + 0.3);
  EXPECT_GT(soft.mu_c.value_or(-1.0), half.mu_c.value_or(-1.0) + 0.3);
  const auto stiff = crit(1.7);
  EXPECT_TRUE(!stiff.mu_c.has_value() || stiff.mu_c.value_or(-1.0) > worst_mid + 0.3);
}

}  // namespace paper_figures_test
