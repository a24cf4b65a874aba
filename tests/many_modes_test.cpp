// The paper family's many-mode models (paper-3x3, paper-4x4, paper-5x5: 12, 16, 20 states) at
// run time: model lookup, hover labels, resolved Floquet evaluations, mode identification by
// continuation (the tracker is exact up to 8 states and greedy beyond) and the critical advance
// ratio of the typical case on exact modes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "flaplag/analysis.h"
#include "flaplag/model_api.h"

namespace many_modes_test {

using flaplag::Analysis;
using flaplag::ModeKind;
using flaplag::RotorParameters;
using flaplag::Status;
using flaplag::TransitionOptions;

namespace {

// The typical case on exact modes with k flap and k lag modes.
RotorParameters exact(int k) {
  RotorParameters p;
  p.modes = ModeKind::Exact;
  p.model = flaplag::find_model("paper", k, k).name;
  return p;
}

double max_zeta(const flaplag::FloquetSample& s) {
  double z = -INFINITY;
  for (const auto& e : s.floquet.exponents) z = std::max(z, e.zeta);
  return z;
}

class ManyModes : public ::testing::TestWithParam<int> {};

// (paper, k, k) names paper-kxk, with 4k states and the paper's family.
TEST_P(ManyModes, FamilyLookupGivesTheModelOfThatSize) {
  const int k = GetParam();
  const auto& m = flaplag::find_model("paper", k, k);
  EXPECT_EQ(std::string(m.name), "paper-" + std::to_string(k) + "x" + std::to_string(k));
  EXPECT_EQ(std::string(m.base), "paper");
  EXPECT_EQ(m.flap_modes, k);
  EXPECT_EQ(m.lag_modes, k);
  EXPECT_EQ(flaplag::model::state_count(k, k), 4 * k);
  Analysis an(exact(k), {});
  EXPECT_EQ(an.system(0.5).n, 4 * k);
}

// Hover: each of flap, flap2..flapk, lag, lag2..lagk labels exactly one pair of eigenvalues, and
// the frequencies increase with the mode number in each direction (one label scheme for every
// model: the first mode carries the direction's name alone, as in the 1 x 1 model).
TEST_P(ManyModes, HoverLabelsEveryModeOnce) {
  const int k = GetParam();
  Analysis an(exact(k), {});
  ASSERT_EQ(an.hover().status, Status::Ok) << an.hover().message;
  ASSERT_EQ(an.hover().labels.size(), static_cast<std::size_t>(4 * k));
  std::map<std::string, int> count;
  std::map<std::string, double> omega;
  for (std::size_t i = 0; i < an.hover().labels.size(); ++i) {
    const std::string& l = an.hover().labels[i];
    ++count[l];
    omega[l] = std::max(omega[l], an.hover().eigenvalues[i].imag());
  }
  for (const char* dir : {"flap", "lag"}) {
    auto label = [&](int j) { return j == 1 ? std::string(dir) : dir + std::to_string(j); };
    for (int j = 1; j <= k; ++j) {
      EXPECT_EQ(count[label(j)], 2) << label(j);
      if (j > 1) {
        EXPECT_GT(omega[label(j)], omega[label(j - 1)]) << label(j);
      }
    }
    EXPECT_EQ(count[std::string(dir) + "1"], 0) << dir;
  }
}

// The automatic resolution resolves mu = 0.8 (stable: mu_c is above 1.3 from 2 x 2 on) and
// mu = 1.45 (unstable) to the requested tolerance.
TEST_P(ManyModes, AutomaticStepsResolveStableAndUnstablePoints) {
  const int k = GetParam();
  Analysis an(exact(k), {});
  const auto stable = an.floquet(0.8, 1e-5);
  ASSERT_EQ(stable.status, Status::Ok) << stable.message;
  ASSERT_TRUE(stable.error.has_value());
  EXPECT_LE(*stable.error, 1e-5);
  EXPECT_LT(max_zeta(stable), -1e-3);
  const auto unstable = an.floquet(1.45, 1e-5);
  ASSERT_EQ(unstable.status, Status::Ok) << unstable.message;
  EXPECT_GT(max_zeta(unstable), 1e-3);
}

INSTANTIATE_TEST_SUITE_P(PaperFamily, ManyModes, ::testing::Values(3, 4, 5),
                         [](const ::testing::TestParamInfo<int>& i) {
                           return std::to_string(i.param) + "x" + std::to_string(i.param);
                         });

// The paper's fixed setting (Hsu K = 50, J = 4) cannot resolve 20 states: the fifth lag mode
// (about 69 per rev) needs |lambda| h <= 1, i.e. K of about 435.  The analysis must say so
// rather than return the spurious exponents silently.
TEST(ManyModesFixedSteps, PaperSettingIsFlaggedUnresolvedOnFiveByFive) {
  Analysis an(exact(5), TransitionOptions::Paper());
  const auto s = an.floquet(0.8, 1e-5);
  EXPECT_EQ(s.status, Status::Warning);
  EXPECT_NE(s.message.find("not resolved"), std::string::npos) << s.message;
  EXPECT_NE(s.message.find("`steps`"), std::string::npos) << s.message;
  // the same point with automatic steps is resolved and uses more than 400 intervals
  Analysis automatic(exact(5), {});
  const auto a = automatic.floquet(0.8, 1e-5);
  EXPECT_EQ(a.status, Status::Ok) << a.message;
  EXPECT_GT(a.steps, 400);
}

// Identification with 20 states (greedy assignment): continued from hover to mu = 1.45, the
// most unstable exponent is lag at about 1.29 per rev (flutter, the same mode as 1 x 1 to
// 4 x 4), and every label still names one pair.
TEST(ManyModesTracking, FiveByFiveKeepsTheLabelsOutToTheFlutterBoundary) {
  Analysis an(exact(5), {});
  const auto r = an.track({0.8, 1.45}, 0.05);
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_EQ(r.points.size(), 2u);
  for (const auto& pt : r.points) {
    std::map<std::string, int> count;
    for (const auto& e : pt.exponents) ++count[e.label];
    EXPECT_EQ(count.size(), 10u) << "mu " << pt.mu;
    for (const auto& [label, c] : count) EXPECT_EQ(c, 2) << label << " at mu " << pt.mu;
  }
  const auto& e = r.points[1].exponents;
  const auto top = std::max_element(e.begin(), e.end(),
                                    [](const auto& a, const auto& b) { return a.zeta < b.zeta; });
  EXPECT_EQ(top->label, "lag");
  EXPECT_GT(top->zeta, 0.0);
  EXPECT_NEAR(std::abs(top->omega), 1.29, 0.02);
}

// The default method is chosen for the model's size: Hsu for the 4 states of 1 x 1 (assumed
// and exact modes), Magnus4 from 2 x 2 (8 states) on; Analysis::options() names the method that
// runs, and an explicit method is kept whatever the size.
TEST(ManyModesMethod, DefaultIsHsuForOneByOneAndMagnusAbove) {
  EXPECT_EQ(Analysis(RotorParameters{}, {}).options().method, flaplag::TransitionMethod::Hsu);
  EXPECT_EQ(Analysis(exact(1), {}).options().method, flaplag::TransitionMethod::Hsu);
  for (int k = 2; k <= 5; ++k) {
    EXPECT_EQ(Analysis(exact(k), {}).options().method, flaplag::TransitionMethod::Magnus4) << k;
  }
  TransitionOptions hsu;
  hsu.method = flaplag::TransitionMethod::Hsu;
  EXPECT_EQ(Analysis(exact(5), hsu).options().method, flaplag::TransitionMethod::Hsu);
  TransitionOptions rk4;
  rk4.method = flaplag::TransitionMethod::RK4;
  EXPECT_EQ(Analysis(exact(3), rk4).options().method, flaplag::TransitionMethod::RK4);
  EXPECT_EQ(Analysis(RotorParameters{}, TransitionOptions::Paper()).options().method,
            flaplag::TransitionMethod::Hsu);
}

// mu_c of the typical case with 3 x 3 exact modes, automatic resolution: the value of
// the mode-convergence table of docs/paper.md, and the same boundary from RK4 (an independent
// transition method) within the two error estimates.  The scan steps by 0.05 (there is one
// crossing, and Brent refines it to the same tolerance), a quarter of the default scan's cost.
TEST(ManyModesCritical, ThreeByThreeMuCAgreesAcrossMethods) {
  flaplag::CriticalOptions opt;
  opt.scan_step = 0.05;
  RotorParameters p3 = exact(3);
  p3.basis = flaplag::kPaperBasis;  // the basis of the pinned value
  Analysis automatic(p3, {});
  const auto c = automatic.critical(opt);
  // resolved in the Floquet analysis; the five functions' error is a warning of its own
  ASSERT_NE(c.status, Status::Failed) << c.message;
  EXPECT_EQ(c.message.find("not resolved to"), std::string::npos) << c.message;
  ASSERT_TRUE(c.mu_c.has_value() && c.mu_c_error.has_value() && c.basis_error.has_value());
  EXPECT_LT(*c.mu_c_error - *c.basis_error, 2e-5);
  EXPECT_NEAR(*c.mu_c, 1.31581, 5e-5);
  EXPECT_EQ(c.mode, "lag");

  TransitionOptions rk4;
  rk4.method = flaplag::TransitionMethod::RK4;
  Analysis other(p3, rk4);
  const auto d = other.critical(opt);
  ASSERT_NE(d.status, Status::Failed) << d.message;
  EXPECT_EQ(d.message.find("not resolved to"), std::string::npos) << d.message;
  ASSERT_TRUE(d.mu_c.has_value() && d.mu_c_error.has_value() && d.basis_error.has_value());
  // the same basis: within the two Floquet errors
  EXPECT_LE(std::abs(*d.mu_c - *c.mu_c),
            (*c.mu_c_error - *c.basis_error) + (*d.mu_c_error - *d.basis_error));
}

}  // namespace

}  // namespace many_modes_test
