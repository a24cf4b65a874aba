// Continuation in mu: hover labels, exponent tracking through crossings and integer wraps,
// critical mu for flutter (complex pair) and periodic (real multiplier) instabilities.
#include "flaplag/core/constants.h"
#include "flaplag/numerics/continuation.h"
#include "flaplag/rotor/hover.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <unsupported/Eigen/MatrixFunctions>

#include "flaplag/core/errors.h"
#include "test_util.h"

namespace flaplag {
namespace {

using testing::AbsClose;
using testing::RelClose;


// Two uncoupled oscillators in the model_api.h ordering y = [g', g, h', h]:
//   g'' + cg g' + kg g = 0,  h'' + ch h' + kh h = 0  (+ weak coupling kappa).
Eigen::MatrixXd oscillators(double cg, double kg, double ch, double kh, double kappa = 0.0) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(4, 4);
  A(0, 0) = -cg;
  A(0, 1) = -kg;
  A(0, 3) = -kappa;
  A(1, 0) = 1.0;
  A(2, 2) = -ch;
  A(2, 3) = -kh;
  A(2, 1) = -kappa;
  A(3, 2) = 1.0;
  return A;
}

// Stiffness giving damped frequency w for damping c: eigenvalues -c/2 +- i w.
double stiffness(double c, double w) { return w * w + 0.25 * c * c; }

// Constant-coefficient family: Phi = expm(2 pi A(mu)) exactly.
FloquetFunction constant_family(std::function<Eigen::MatrixXd(double)> A) {
  return [A](double mu) {
    const Eigen::MatrixXd a = A(mu);
    return floquet_exponents((kTwoPi * a).exp(), kTwoPi * a.trace());
  };
}

const LabelledExponent* find(const std::vector<LabelledExponent>& v, const std::string& label,
                             double omega_sign) {
  for (const LabelledExponent& e : v)
    if (e.label == label && e.omega * omega_sign > 0) return &e;
  return nullptr;
}

TEST(HoverModes, LabelsFlapAndLag) {
  const HoverModes h = label_hover_modes(
      oscillators(1.2, stiffness(1.2, 1.17), 0.04, stiffness(0.04, 1.28), 0.05), 1, 1);
  ASSERT_EQ(4u, h.labels.size());
  EXPECT_EQ(Status::Ok, h.status);
  for (std::size_t k = 0; k < 4; ++k) {
    // The weak coupling shifts the frequencies only slightly: 1.17 is flap, 1.28 lag.
    const double w = std::abs(h.eigenvalues[k].imag());
    EXPECT_EQ(std::abs(w - 1.17) < std::abs(w - 1.28) ? "flap" : "lag", h.labels[k]);
    EXPECT_TRUE(RelClose(1.0, h.eigenvectors[k].norm(), 1e-14));
  }
}

TEST(HoverModes, MultiModeSuffixes) {
  // M = 2 flap modes, N = 1 lag mode, uncoupled: y = [g1', g2', g1, g2, h', h].
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(6, 6);
  const double c[3] = {0.5, 0.3, 0.02}, w[3] = {1.1, 3.4, 0.7};
  const int vel[3] = {0, 1, 4}, dis[3] = {2, 3, 5};
  for (int i = 0; i < 3; ++i) {
    A(vel[i], vel[i]) = -c[i];
    A(vel[i], dis[i]) = -stiffness(c[i], w[i]);
    A(dis[i], vel[i]) = 1.0;
  }
  const HoverModes h = label_hover_modes(A, 2, 1);
  for (std::size_t k = 0; k < 6; ++k) {
    const double im = std::abs(h.eigenvalues[k].imag());
    const char* expect = std::abs(im - 1.1) < 1e-9   ? "flap1"
                         : std::abs(im - 3.4) < 1e-9 ? "flap2"
                                                     : "lag";
    EXPECT_EQ(expect, h.labels[k]) << "eigenvalue " << h.eigenvalues[k];
  }
  EXPECT_THROW(label_hover_modes(A, 1, 1), InvalidInput);
  EXPECT_THROW(label_hover_modes(A, -1, 4), InvalidInput);
  A(0, 0) = std::nan("");
  EXPECT_THROW(label_hover_modes(A, 2, 1), InvalidInput);
}

// Flap frequency rises from 1.17 through the lag frequency 1.28 and on past 1.5 (where the
// principal omega wraps from +1/2 to -1/2).  Uncoupled, so the eigenvectors tell the modes
// apart at the crossing even though the multipliers coincide there.
TEST(ExponentTracker, KeepsLabelsThroughCrossingAndIntegerWrap) {
  auto A = [](double mu) {
    return oscillators(0.6, stiffness(0.6, 1.17 + mu), 0.04, stiffness(0.04, 1.28));
  };
  const HoverModes hover = label_hover_modes(A(0.0), 1, 1);
  const ExponentSweep sw = sweep_exponents(hover, constant_family(A), 0.0, 0.6, 0.01);
  EXPECT_EQ(Status::Ok, sw.status) << sw.message;
  ASSERT_EQ(61u, sw.points.size());
  for (const SweepPoint& p : sw.points) {
    for (double sign : {1.0, -1.0}) {
      const LabelledExponent* flap = find(p.exponents, "flap", sign);
      const LabelledExponent* lag = find(p.exponents, "lag", sign);
      ASSERT_NE(nullptr, flap) << "mu = " << p.mu;
      ASSERT_NE(nullptr, lag) << "mu = " << p.mu;
      // omega with its true integer part, exactly the eigenvalue of the constant A(mu).
      EXPECT_TRUE(AbsClose(sign * (1.17 + p.mu), flap->omega, 1e-9)) << "mu = " << p.mu;
      EXPECT_TRUE(AbsClose(sign * 1.28, lag->omega, 1e-9)) << "mu = " << p.mu;
      EXPECT_TRUE(AbsClose(-0.3, flap->zeta, 1e-9));
      EXPECT_TRUE(AbsClose(-0.02, lag->zeta, 1e-9));
    }
    EXPECT_TRUE(p.stable);
  }
  EXPECT_DOUBLE_EQ(0.6, sw.points.back().mu);
}

// Lag damping falls linearly: zeta_lag(mu) = mu - 0.5037, a flutter crossing at mu = 0.5037
// with omega = 1.28 (not the principal 0.28).
TEST(FindCritical, FlutterCrossingOfConstantFamily) {
  auto A = [](double mu) {
    const double ch = 2.0 * (0.5037 - mu);
    return oscillators(1.2, stiffness(1.2, 1.17), ch, stiffness(ch, 1.28), 0.0);
  };
  const CriticalSearchResult r =
      find_critical(label_hover_modes(A(0.0), 1, 1), constant_family(A), {});
  ASSERT_TRUE(r.found) << r.message;
  EXPECT_EQ(Status::Ok, r.status) << r.message;
  EXPECT_TRUE(AbsClose(0.5037, r.mu_c, 1e-5));
  EXPECT_EQ("lag", r.label);
  EXPECT_TRUE(AbsClose(1.28, std::abs(r.omega), 1e-9));
  EXPECT_EQ(InstabilityKind::Flutter, r.kind);
  EXPECT_LT(r.evaluations, 51 + 30);  // the scan plus a Brent refinement
}

TEST(FindCritical, StableUpToMuMaxAndUnstableHover) {
  auto stable = [](double mu) {
    return oscillators(1.2, stiffness(1.2, 1.17), 0.04 + mu, stiffness(0.04, 1.28));
  };
  CriticalSearchOptions opt;
  opt.mu_max = 0.3;
  const CriticalSearchResult r =
      find_critical(label_hover_modes(stable(0.0), 1, 1), constant_family(stable), opt);
  EXPECT_FALSE(r.found);
  EXPECT_EQ(Status::Ok, r.status);
  EXPECT_EQ(0.3, r.mu_max);
  EXPECT_EQ(30, r.evaluations);

  auto unstable = [](double) {
    return oscillators(1.2, stiffness(1.2, 1.17), -0.04, stiffness(-0.04, 1.28));
  };
  const CriticalSearchResult u =
      find_critical(label_hover_modes(unstable(0.0), 1, 1), constant_family(unstable), opt);
  EXPECT_TRUE(u.found);
  EXPECT_EQ(0.0, u.mu_c);
  EXPECT_EQ("lag", u.label);
  EXPECT_EQ(Status::Warning, u.status);
}

// Damped Mathieu equation g'' + 2 xi g' + (delta + mu cos psi) g = 0 (one flap mode) near
// delta = 1/4: the pair at omega ~ +-1/2 collides on the negative real axis and one real
// multiplier leaves the unit circle: a periodic-type instability with omega = +-1/2.  The
// boundary is computed independently by plain bisection on the largest |multiplier| of a
// fine Magnus transition matrix, without tracking.
PeriodicSystem mathieu(double delta, double xi, double mu) {
  PeriodicSystem s;
  s.n = 2;
  Eigen::MatrixXd a0(2, 2), a1 = Eigen::MatrixXd::Zero(2, 2);
  a0 << -2 * xi, -delta, 1, 0;
  a1(0, 1) = -mu;
  s.normal.A = {a0, a1};
  return s;
}

TEST(FindCritical, MathieuTongueIsPeriodicType) {
  const double delta = 0.26, xi = 0.01;
  auto floquet = [&](double mu) {
    const PeriodicSystem s = mathieu(delta, xi, mu);
    return floquet_exponents(transition_matrix_magnus4(s, 100).phi, s.trace_integral());
  };
  auto max_zeta = [&](double mu) {
    double z = -1e300;
    for (const FloquetExponent& e : floquet(mu).exponents) z = std::max(z, e.zeta);
    return z;
  };
  double lo = 0.0, hi = 0.5;
  ASSERT_LT(max_zeta(lo), 0.0);
  ASSERT_GT(max_zeta(hi), 0.0);
  while (hi - lo > 1e-10) (max_zeta(0.5 * (lo + hi)) > 0 ? hi : lo) = 0.5 * (lo + hi);

  const HoverModes hover = label_hover_modes(mathieu(delta, xi, 0.0).normal.A[0], 1, 0);
  const CriticalSearchResult r = find_critical(hover, floquet, {});
  ASSERT_TRUE(r.found) << r.message;
  EXPECT_TRUE(AbsClose(lo, r.mu_c, 1e-5));
  EXPECT_EQ("flap", r.label);
  EXPECT_EQ(InstabilityKind::Periodic, r.kind);
  EXPECT_EQ(0.5, std::abs(r.omega));  // locked exactly: the multiplier is real
}

TEST(Continuation, ClassifyCrossing) {
  EXPECT_EQ(InstabilityKind::Periodic, classify_crossing(0.0));
  EXPECT_EQ(InstabilityKind::Periodic, classify_crossing(-1.5));
  EXPECT_EQ(InstabilityKind::Periodic, classify_crossing(2.0004));
  EXPECT_EQ(InstabilityKind::Flutter, classify_crossing(1.286));
  EXPECT_EQ(InstabilityKind::Flutter, classify_crossing(0.49));
  EXPECT_STREQ("periodic", kind_name(InstabilityKind::Periodic));
  EXPECT_STREQ("flutter", kind_name(InstabilityKind::Flutter));
  EXPECT_STREQ("warning", status_name(Status::Warning));
}

TEST(Continuation, SweepStartsAboveHoverAndIncludesEnd) {
  auto A = [](double mu) {
    return oscillators(0.6, stiffness(0.6, 1.17 + mu), 0.04, stiffness(0.04, 1.28));
  };
  int calls = 0;
  FloquetFunction f = [&](double mu) {
    ++calls;
    return constant_family(A)(mu);
  };
  const ExponentSweep sw = sweep_exponents(label_hover_modes(A(0.0), 1, 1), f, 0.5, 0.625, 0.05);
  ASSERT_EQ(4u, sw.points.size());  // 0.5, 0.55, 0.6, 0.625
  EXPECT_DOUBLE_EQ(0.5, sw.points[0].mu);
  EXPECT_DOUBLE_EQ(0.625, sw.points[3].mu);
  EXPECT_EQ(9 + 4, calls);  // 9 steps of 0.05 up to 0.5, then the 4 points
  // omega continued through the wrap at 1.5 (principal value -0.33 at mu = 0.5).
  EXPECT_TRUE(AbsClose(1.67, find(sw.points[0].exponents, "flap", 1.0)->omega, 1e-9));
}

TEST(Continuation, FailuresAreReportedNotThrown) {
  auto A = [](double) { return oscillators(0.6, 1.5, 0.04, 1.7); };
  FloquetFunction nan_after = [&](double mu) {
    if (mu > 0.1) {
      return floquet_exponents(
          Eigen::MatrixXd::Constant(4, 4, std::numeric_limits<double>::quiet_NaN()), 0.0);
    }
    return constant_family(A)(mu);
  };
  const HoverModes hover = label_hover_modes(A(0.0), 1, 1);
  const CriticalSearchResult r = find_critical(hover, nan_after, {});
  EXPECT_FALSE(r.found);
  EXPECT_EQ(Status::Failed, r.status);
  EXPECT_FALSE(r.message.empty());
  const ExponentSweep sw = sweep_exponents(hover, nan_after, 0.0, 0.3, 0.05);
  EXPECT_EQ(Status::Failed, sw.status);
  EXPECT_EQ(4u, sw.points.size());  // 0, 0.05, 0.1 and the failed 0.15
}

TEST(Continuation, InvalidArgumentsThrow) {
  auto A = [](double) { return oscillators(0.6, 1.5, 0.04, 1.7); };
  const HoverModes hover = label_hover_modes(A(0.0), 1, 1);
  CriticalSearchOptions o;
  o.step = 0.0;
  EXPECT_THROW(find_critical(hover, constant_family(A), o), InvalidInput);
  o = {};
  o.mu_max = std::nan("");
  EXPECT_THROW(find_critical(hover, constant_family(A), o), InvalidInput);
  o = {};
  o.tolerance = -1.0;
  EXPECT_THROW(find_critical(hover, constant_family(A), o), InvalidInput);
  EXPECT_THROW(find_critical(hover, FloquetFunction{}, {}), InvalidInput);
  EXPECT_THROW(sweep_exponents(hover, constant_family(A), 0.0, 1.0, -0.1), InvalidInput);
  EXPECT_THROW(sweep_exponents(hover, constant_family(A), 0.5, 0.4, 0.1), InvalidInput);
  ExponentTracker t(hover);
  FloquetResult wrong;
  wrong.exponents.resize(2);
  EXPECT_THROW(t.advance(wrong), InvalidInput);
}

}  // namespace
}  // namespace flaplag
