// Continuation in mu: hover labels, exponent tracking through crossings and integer wraps,
// critical mu for flutter (complex pair) and periodic (real multiplier) instabilities.
#include "flaplag/numerics/continuation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/numerics/dense.h"
#include "flaplag/rotor/hover.h"
#include "test_util.h"

namespace flaplag::continuation_test {
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

// A FloquetFunction sample without an error estimate.
FloquetSample sample(FloquetResult r) {
  FloquetSample s;
  s.floquet = std::move(r);
  return s;
}

// Constant-coefficient family: Phi = expm(2 pi A(mu)) exactly.
FloquetFunction constant_family(std::function<Eigen::MatrixXd(double)> A) {
  return [A](double mu, double) {
    const Eigen::MatrixXd a = A(mu);
    return sample(floquet_exponents(matrix_exponential(kTwoPi * a), kTwoPi * a.trace()));
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
    const char* expect = std::abs(im - 1.1) < 1e-9   ? "flap"
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
  const SweepResult sw = sweep_exponents(hover, constant_family(A), 0.0, 0.6, 0.01);
  EXPECT_EQ(Status::Ok, sw.status) << sw.message;
  ASSERT_EQ(61u, sw.points.size());
  for (const PointResult& p : sw.points) {
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
    EXPECT_EQ(std::optional<bool>(true), p.stable);
  }
  EXPECT_DOUBLE_EQ(0.6, sw.points.back().mu);
}

// The same family tracked with multipliers only (eigenvectors on demand) and with every
// eigenvector: identical labels, zeta and omega at every step.  The multipliers alone decide
// the well-separated steps (min_similarity NaN), including the flap-lag crossing of omega
// (their zeta differ by 0.28 per rev); the eigenvectors are computed where the flap pair meets
// at omega = 1.5 (mu = 0.33: one real multiplier twice).  Without eigenvectors or Phi such a
// step is Failed with the state unchanged.
TEST(ExponentTracker, MultipliersDecideWhereTheyLeaveNoDoubt) {
  auto A = [](double mu) {
    return oscillators(0.6, stiffness(0.6, 1.17 + mu), 0.04, stiffness(0.04, 1.28));
  };
  const HoverModes hover = label_hover_modes(A(0.0), 1, 1);
  ExponentTracker full(hover), lazy(hover);
  FloquetResult r;
  int by_multipliers = 0, by_vectors = 0;
  for (int k = 1; k <= 60; ++k) {
    const double mu = 0.01 * k;
    const Eigen::MatrixXd phi = matrix_exponential(kTwoPi * A(mu));
    const double tr = kTwoPi * A(mu).trace();
    ASSERT_EQ(Status::Ok, full.advance(floquet_exponents(phi, tr), mu).status);
    floquet_exponents(phi, tr, FloquetVectors::OnDemand, &r);
    const TrackReport rep = lazy.advance(r, mu);
    ASSERT_EQ(Status::Ok, rep.status) << "mu = " << mu << ": " << rep.message;
    (std::isnan(rep.min_similarity) ? by_multipliers : by_vectors) += 1;
    if (std::abs(mu - 0.33) < 1e-9) {
      EXPECT_FALSE(std::isnan(rep.min_similarity));
    }
    for (std::size_t i = 0; i < 4; ++i) {
      EXPECT_EQ(full.exponents()[i].label, lazy.exponents()[i].label);
      EXPECT_EQ(full.exponents()[i].zeta, lazy.exponents()[i].zeta) << "mu = " << mu;
      EXPECT_EQ(full.exponents()[i].omega, lazy.exponents()[i].omega) << "mu = " << mu;
    }
  }
  EXPECT_GT(by_multipliers, 40);
  EXPECT_GT(by_vectors, 0);
  // The eigenvectors of the lazily tracked state, computed on request, are those of the full one.
  for (std::size_t i = 0; i < 4; ++i)
    EXPECT_GT(std::abs(full.eigenvectors()[i].dot(lazy.eigenvectors()[i])), 1.0 - 1e-12);

  // At the double multiplier with neither eigenvectors nor Phi: Failed, state unchanged.
  ExponentTracker t(hover);
  for (int k = 1; k <= 32; ++k) {
    const double mu = 0.01 * k;
    ASSERT_EQ(
        Status::Ok,
        t.advance(floquet_exponents(matrix_exponential(kTwoPi * A(mu)), kTwoPi * A(mu).trace()), mu)
            .status);
  }
  FloquetResult bare =
      floquet_exponents(matrix_exponential(kTwoPi * A(0.33)), kTwoPi * A(0.33).trace());
  bare.phi.resize(0, 0);
  for (FloquetExponent& e : bare.exponents) e.eigenvector.resize(0);
  const std::vector<LabelledExponent> before = t.exponents();
  const TrackReport rep = t.advance(bare, 0.33);
  EXPECT_EQ(Status::Failed, rep.status);
  EXPECT_NE(std::string::npos, rep.message.find("eigenvectors")) << rep.message;
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(before[i].zeta, t.exponents()[i].zeta);
}

// Lag damping falls linearly: zeta_lag(mu) = mu - 0.5037, a flutter crossing at mu = 0.5037
// with omega = 1.28 (not the principal 0.28).
TEST(FindCritical, FlutterCrossingOfConstantFamily) {
  auto A = [](double mu) {
    const double ch = 2.0 * (0.5037 - mu);
    return oscillators(1.2, stiffness(1.2, 1.17), ch, stiffness(ch, 1.28), 0.0);
  };
  const CriticalResult r = find_critical(label_hover_modes(A(0.0), 1, 1), constant_family(A), {});
  ASSERT_TRUE(r.mu_c.has_value()) << r.message;
  EXPECT_EQ(Status::Ok, r.status) << r.message;
  EXPECT_TRUE(AbsClose(0.5037, *r.mu_c, 1e-5));
  EXPECT_EQ("lag", r.mode);
  EXPECT_TRUE(AbsClose(1.28, std::abs(r.omega), 1e-9));
  EXPECT_EQ(InstabilityKind::Flutter, r.kind);
  EXPECT_LT(r.evaluations, 51 + 30);  // the scan plus a Brent refinement
}

// Lag damping -zeta_lag(mu) = -(mu - 0.3)(0.8 - mu)(mu - 1.2) changes sign three times: unstable
// on (0.3, 0.8) and from 1.2 on.  all_intervals reports both, the first one's onset is mu_c.
TEST(FindCritical, AllIntervalsOnsetAndRestabilization) {
  auto A = [](double mu) {
    const double zeta = (mu - 0.3) * (0.8 - mu) * (mu - 1.2) * -1.0;  // lag zeta
    const double ch = -2.0 * zeta;
    return oscillators(1.2, stiffness(1.2, 1.17), ch, stiffness(ch, 1.28), 0.0);
  };
  CriticalOptions opt;
  opt.mu_max = 1.5;
  opt.all_intervals = true;
  const CriticalResult r = find_critical(label_hover_modes(A(0.0), 1, 1), constant_family(A), opt);
  ASSERT_EQ(2u, r.intervals.size()) << r.message;
  EXPECT_TRUE(AbsClose(0.3, r.intervals[0].onset, 1e-5));
  ASSERT_TRUE(r.intervals[0].end.has_value());
  EXPECT_TRUE(AbsClose(0.8, *r.intervals[0].end, 1e-5));
  EXPECT_TRUE(AbsClose(1.2, r.intervals[1].onset, 1e-5));
  EXPECT_FALSE(r.intervals[1].end.has_value());  // unstable at mu_max
  EXPECT_EQ("lag", r.intervals[1].mode);
  ASSERT_TRUE(r.mu_c.has_value());
  EXPECT_EQ(r.intervals[0].onset, *r.mu_c);
  // Without all_intervals the search stops at mu_c.
  opt.all_intervals = false;
  const CriticalResult first =
      find_critical(label_hover_modes(A(0.0), 1, 1), constant_family(A), opt);
  EXPECT_EQ(1u, first.intervals.size());
  EXPECT_FALSE(first.intervals[0].end.has_value());
  EXPECT_LT(first.evaluations, r.evaluations);
}

// Regression: with all_intervals, an evaluation that fails past mu_c (a trimmed rotor whose
// trim no longer converges beyond the instability) used to fail the whole search and lose
// mu_c; the onset found stands, status Warning, the message says where the scan stopped.
TEST(FindCritical, AFailurePastMuCKeepsTheOnsetFound) {
  auto A = [](double mu) {
    const double ch = 2.0 * (0.5037 - mu);
    return oscillators(1.2, stiffness(1.2, 1.17), ch, stiffness(ch, 1.28), 0.0);
  };
  const FloquetFunction exact = constant_family(A);
  const FloquetFunction fails_above = [&](double mu, double tol) {
    FloquetSample s = exact(mu, tol);
    if (mu > 0.7) {
      s.status = Status::Failed;
      s.message = "no answer here";
    }
    return s;
  };
  CriticalOptions opt;
  opt.mu_max = 1.0;
  opt.all_intervals = true;
  const CriticalResult r = find_critical(label_hover_modes(A(0.0), 1, 1), fails_above, opt);
  ASSERT_TRUE(r.mu_c.has_value()) << r.message;
  EXPECT_TRUE(AbsClose(0.5037, *r.mu_c, 1e-5));
  EXPECT_EQ(Status::Warning, r.status);
  EXPECT_EQ(1u, r.intervals.size());
  EXPECT_NE(std::string::npos, r.message.find("stopped at mu = 0.7 ")) << r.message;
  EXPECT_NE(std::string::npos, r.message.find("no answer here")) << r.message;
  // Before mu_c a failure is still the search's failure.
  opt.all_intervals = false;
  const FloquetFunction fails_early = [&](double mu, double tol) {
    FloquetSample s = exact(mu, tol);
    if (mu > 0.3) s.status = Status::Failed;
    return s;
  };
  const CriticalResult f = find_critical(label_hover_modes(A(0.0), 1, 1), fails_early, opt);
  EXPECT_EQ(Status::Failed, f.status);
  EXPECT_FALSE(f.mu_c.has_value());
}

// A family whose samples are only as accurate as asked: every zeta is off by +tol / 2 and says
// so (zeta_errors = tol).  `asked` records (mu, tol, max zeta) of every call.
struct Request {
  double mu, tol, max_zeta;
};
FloquetFunction inexact_family(std::function<Eigen::MatrixXd(double)> A, double cap,
                               std::vector<Request>* asked) {
  const FloquetFunction exact = constant_family(A);
  return [=](double mu, double tol) {
    tol = std::min(tol, cap);
    FloquetSample s = exact(mu, tol);
    double top = -1e300;
    for (FloquetExponent& e : s.floquet.exponents) {
      e.zeta += 0.5 * tol;
      top = std::max(top, e.zeta);
    }
    s.zeta_errors.assign(s.floquet.exponents.size(), tol);
    s.error = tol;
    asked->push_back({mu, tol, top});
    return s;
  };
}

// Scan points far from the threshold are evaluated for their sign only (a looser tolerance);
// both ends of the bracket and everything the search reports are at the scan resolution, so
// mu_c, its error, mode and omega are those of a scan that asks scan_zeta_tolerance everywhere.
TEST(FindCritical, ScanPointsFarFromTheThresholdAreEvaluatedForTheirSignOnly) {
  auto A = [](double mu) {
    const double ch = 2.0 * (0.5037 - mu);
    return oscillators(1.2, stiffness(1.2, 1.17), ch, stiffness(ch, 1.28), 0.0);
  };
  const HoverModes hover = label_hover_modes(A(0.0), 1, 1);
  CriticalOptions opt;
  std::vector<Request> asked, strict_asked;
  const CriticalResult r = find_critical(hover, inexact_family(A, 1.0, &asked), opt);
  const CriticalResult strict =
      find_critical(hover, inexact_family(A, opt.scan_zeta_tolerance, &strict_asked), opt);
  ASSERT_TRUE(r.mu_c.has_value()) << r.message;
  ASSERT_TRUE(strict.mu_c.has_value()) << strict.message;
  EXPECT_EQ(*strict.mu_c, *r.mu_c);
  EXPECT_EQ(strict.mu_c_error, r.mu_c_error);
  EXPECT_EQ(strict.mode, r.mode);
  EXPECT_EQ(strict.omega, r.omega);
  EXPECT_EQ(Status::Ok, r.status) << r.message;
  int loose = 0;
  for (const Request& q : asked) {
    if (q.tol <= opt.scan_zeta_tolerance) continue;
    ++loose;
    EXPECT_LE(q.tol, 1e-3);
    // Asked only where the sign is beyond doubt or re-evaluated at the scan resolution.
    const bool again = std::any_of(asked.begin(), asked.end(), [&](const Request& o) {
      return o.mu == q.mu && o.tol <= opt.scan_zeta_tolerance;
    });
    EXPECT_TRUE(again || q.max_zeta + 10.0 * q.tol < 0.0) << "mu = " << q.mu;
  }
  EXPECT_GT(loose, 30);  // most of the 50 scan points below the crossing
  // The last point of a stable scan is reported: at the scan resolution; so is the grid point
  // before it, for the slope of the note that zeta still rises at mu_max (the lag damping
  // 2 (0.5037 - mu) falls).
  opt.mu_max = 0.3;
  asked.clear();
  const CriticalResult s = find_critical(hover, inexact_family(A, 1.0, &asked), opt);
  EXPECT_FALSE(s.mu_c.has_value());
  auto asked_at_scan_resolution = [&](double mu) {
    return std::any_of(asked.begin(), asked.end(), [&](const Request& q) {
      return q.mu == mu && q.tol <= opt.scan_zeta_tolerance;
    });
  };
  EXPECT_TRUE(asked_at_scan_resolution(0.3));
  EXPECT_TRUE(asked_at_scan_resolution(0.29));
  ASSERT_EQ(1u, s.notes.size());
  EXPECT_NE(std::string::npos, s.notes[0].find("still rising at mu_max")) << s.notes[0];
}

// Regression: a scan point just above a shallow crossing whose scan-resolution zeta has the
// wrong sign within its error estimate.  The lag zeta is 0.01 (mu - 0.4996); every sample is
// low by tol / 2 and says so, so at the scan resolution (1e-5) the grid point 0.50 reads
// zeta = 4e-6 - 5e-6 < 0 and the scan brackets [0.50, 0.51], which does not contain the
// crossing.  The search used to stop at the bracket's end (mu_c = 0.50, 4e-4 off, with a
// warning); it now resolves the lower end too and steps back to [0.49, 0.50].
TEST(FindCritical, ALowerEndOfTheWrongSignWithinItsErrorIsResolvedAndSteppedBelow) {
  const double mu_star = 0.4996, slope = 0.01;
  auto A = [&](double mu) {
    const double ch = -2.0 * slope * (mu - mu_star);  // lag zeta = -ch / 2
    return oscillators(1.2, stiffness(1.2, 1.17), ch, stiffness(ch, 1.28), 0.0);
  };
  const FloquetFunction exact = constant_family(A);
  const FloquetFunction low = [&](double mu, double tol) {
    FloquetSample s = exact(mu, tol);
    for (FloquetExponent& e : s.floquet.exponents) e.zeta -= 0.5 * tol;
    s.zeta_errors.assign(s.floquet.exponents.size(), tol);
    s.error = tol;
    return s;
  };
  CriticalOptions opt;
  ASSERT_EQ(1e-5, opt.scan_zeta_tolerance);  // the premise: 0.50 reads below the threshold
  ASSERT_LT(slope * (0.50 - mu_star) - 0.5 * opt.scan_zeta_tolerance, 0.0);
  const CriticalResult r = find_critical(label_hover_modes(A(0.0), 1, 1), low, opt);
  ASSERT_TRUE(r.mu_c.has_value()) << r.message;
  EXPECT_EQ(Status::Ok, r.status) << r.message;
  // The refinement asks 0.1 slope tolerance = 1e-8 of zeta: the root is mu_star + 5e-7.
  EXPECT_TRUE(AbsClose(mu_star, *r.mu_c, 2e-6));
  ASSERT_TRUE(r.mu_c_error.has_value());
  EXPECT_LE(*r.mu_c_error, 10.0 * opt.tolerance);
  EXPECT_EQ("lag", r.mode);
}

TEST(FindCritical, StableUpToMuMaxAndUnstableHover) {
  auto stable = [](double mu) {
    return oscillators(1.2, stiffness(1.2, 1.17), 0.04 + mu, stiffness(0.04, 1.28));
  };
  CriticalOptions opt;
  opt.mu_max = 0.3;
  const CriticalResult r =
      find_critical(label_hover_modes(stable(0.0), 1, 1), constant_family(stable), opt);
  EXPECT_FALSE(r.mu_c.has_value());
  EXPECT_FALSE(r.hover_unstable);
  EXPECT_EQ(Status::Ok, r.status);
  EXPECT_EQ(0.3, r.mu_max);
  EXPECT_EQ(30, r.evaluations);
  EXPECT_TRUE(r.notes.empty()) << r.notes.front();  // the lag damping grows with mu

  auto unstable = [](double) {
    return oscillators(1.2, stiffness(1.2, 1.17), -0.04, stiffness(-0.04, 1.28));
  };
  const CriticalResult u =
      find_critical(label_hover_modes(unstable(0.0), 1, 1), constant_family(unstable), opt);
  // Regression: an unstable hover used to come back as found = true, mu_c = 0, which a script
  // filtering on `found` recorded as mu_c = 0.
  EXPECT_TRUE(u.hover_unstable);
  EXPECT_FALSE(u.mu_c.has_value());
  EXPECT_EQ(Status::Warning, u.status);
  ASSERT_EQ(4u, u.exponents.size());
}

// Stable up to mu_max while the lag damping still falls: the result says that the least stable
// zeta is still rising there (zeta_lag = -(0.04 - 0.1 mu) / 2: -0.0185 at 0.29, -0.0035 at 0.3).
TEST(FindCritical, StableUpToMuMaxWhileZetaStillRisesIsNoted) {
  auto weakening = [](double mu) {
    return oscillators(1.2, stiffness(1.2, 1.17), 0.04 - 0.1 * mu, stiffness(0.04, 1.28));
  };
  CriticalOptions opt;
  opt.mu_max = 0.3;
  const CriticalResult r =
      find_critical(label_hover_modes(weakening(0.0), 1, 1), constant_family(weakening), opt);
  EXPECT_FALSE(r.mu_c.has_value());
  EXPECT_EQ(Status::Ok, r.status);
  ASSERT_EQ(1u, r.notes.size());
  EXPECT_NE(std::string::npos, r.notes[0].find("still rising at mu_max")) << r.notes[0];
  EXPECT_NE(std::string::npos, r.notes[0].find("at mu = 0.3")) << r.notes[0];
}

// Damped Mathieu equation g'' + 2 xi g' + (delta + mu cos psi) g = 0 (one flap mode) near
// delta = 1/4: the pair at omega ~ +-1/2 collides on the negative real axis and one real
// multiplier leaves the unit circle: a periodic-type instability with omega = +-1/2.  The
// boundary is computed independently by plain bisection on the largest |multiplier| of a
// fine Magnus transition matrix, without tracking.
PeriodicSystem mathieu(double delta, double xi, double mu) {
  Eigen::MatrixXd a0(2, 2), a1 = Eigen::MatrixXd::Zero(2, 2);
  a0 << -2 * xi, -delta, 1, 0;
  a1(0, 1) = -mu;
  return PeriodicSystem(HarmonicSet{{a0, a1}, {}});
}

TEST(FindCritical, MathieuTongueIsPeriodicType) {
  const double delta = 0.26, xi = 0.01;
  auto floquet = [&](double mu, double) {
    const PeriodicSystem s = mathieu(delta, xi, mu);
    return sample(floquet_exponents(transition_matrix_magnus4(s, 100).phi, s.trace_integral()));
  };
  auto max_zeta = [&](double mu) {
    double z = -1e300;
    for (const FloquetExponent& e : floquet(mu, 0.0).floquet.exponents) z = std::max(z, e.zeta);
    return z;
  };
  double lo = 0.0, hi = 0.5;
  ASSERT_LT(max_zeta(lo), 0.0);
  ASSERT_GT(max_zeta(hi), 0.0);
  while (hi - lo > 1e-10) (max_zeta(0.5 * (lo + hi)) > 0 ? hi : lo) = 0.5 * (lo + hi);

  const HoverModes hover = label_hover_modes(mathieu(delta, xi, 0.0).sets[0].A[0], 1, 0);
  const CriticalResult r = find_critical(hover, floquet, {});
  ASSERT_TRUE(r.mu_c.has_value()) << r.message;
  EXPECT_TRUE(AbsClose(lo, *r.mu_c, 1e-5));
  EXPECT_EQ("flap", r.mode);
  EXPECT_EQ(InstabilityKind::Periodic, r.kind);
  EXPECT_EQ(0.5, r.omega);  // locked exactly: the multiplier is real; reported >= 0
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

// Damping ratio -zeta/|lambda| of lambda = zeta + i omega (issue 9 item 6): a 3-4-5 triangle,
// the real exponents (omega = 0: +1 decaying, -1 growing), a zero multiplier (zeta = -inf)
// and the undefined lambda = 0.
TEST(Continuation, DampingRatio) {
  EXPECT_EQ(0.6, damping_ratio(-3.0, 4.0).value());
  EXPECT_EQ(0.6, damping_ratio(-3.0, -4.0).value());
  EXPECT_EQ(-0.6, damping_ratio(3.0, 4.0).value());
  EXPECT_EQ(1.0, damping_ratio(-0.2, 0.0).value());
  EXPECT_EQ(-1.0, damping_ratio(0.2, 0.0).value());
  EXPECT_EQ(0.0, damping_ratio(0.0, 1.5).value());
  EXPECT_EQ(1.0, damping_ratio(-std::numeric_limits<double>::infinity(), 0.5).value());
  EXPECT_FALSE(damping_ratio(0.0, 0.0).has_value());
  EXPECT_FALSE(damping_ratio(std::nan(""), 1.0).has_value());
  EXPECT_FALSE(damping_ratio(-0.1, std::numeric_limits<double>::infinity()).has_value());
  // A lightly damped oscillator: ratio ~ -zeta / omega.
  EXPECT_TRUE(RelClose(1e-3 / 1.28, damping_ratio(-1e-3, 1.28).value(), 1e-6));
}

// The damping ratio of a viscously damped oscillator h'' + c h' + k h = 0, whose exponents are
// lambda = -c/2 +- i sqrt(k - c^2/4): the textbook c / (2 sqrt(k)), here 0.04 / 2.56.
TEST(DampingCriterion, RatioOfAnOscillatorIsItsViscousDampingRatio) {
  const double c = 0.04, k = 1.28 * 1.28;
  const double zeta = -c / 2.0, omega = std::sqrt(k - c * c / 4.0);
  EXPECT_TRUE(RelClose(0.015625, damping_ratio(zeta, omega).value(), 1e-14));
  EXPECT_TRUE(RelClose(0.015625, damping_ratio(zeta, -omega).value(), 1e-14));
}

// A sweep of made-up points whose exponents are Pythagorean, so that every ratio is exact:
// -0.6 + 0.8i (0.6), -0.28 + 0.96i (0.28), -0.8 + 0.6i (0.8), 0.28 + 0.96i (-0.28).
PointResult made_point(double mu, std::vector<LabelledExponent> exponents,
                       std::optional<double> error = 1e-9, Status status = Status::Ok) {
  PointResult p;
  p.mu = mu;
  p.exponents = std::move(exponents);
  p.error = error;
  p.status = status;
  return p;
}

LabelledExponent made_exponent(const char* label, double zeta, double omega) {
  return LabelledExponent{label, zeta, omega, {}, {}};
}

TEST(DampingCriterion, CrossingIsTheLinearInterpolationBetweenTheBracketingPoints) {
  SweepResult s;
  // lag: 0.8 at mu = 0, 0.6 at 0.1, 0.28 at 0.2, -0.28 at 0.3; flap stays at 0.8.
  s.points = {
      made_point(0.0, {made_exponent("flap", -0.8, 0.6), made_exponent("lag", -0.8, 0.6)}),
      made_point(0.1, {made_exponent("flap", -0.8, 0.6), made_exponent("lag", -0.6, 0.8),
                       made_exponent("lag", -0.6, -0.8)}),
      made_point(0.2, {made_exponent("flap", -0.8, 0.6), made_exponent("lag", -0.28, 0.96)}),
      made_point(0.3, {made_exponent("flap", -0.8, 0.6), made_exponent("lag", 0.28, 0.96)})};
  apply_damping_criterion(s, {"flap", "lag"}, 0.5);
  ASSERT_EQ(s.damping_criterion, 0.5);
  ASSERT_EQ(s.damping_crossings.size(), 2u);
  const DampingCrossing& flap = s.damping_crossings[0];
  EXPECT_EQ(flap.mode, "flap");
  EXPECT_EQ(flap.status, CrossingStatus::NotCrossed);
  EXPECT_FALSE(flap.mu.has_value());
  const DampingCrossing& lag = s.damping_crossings[1];
  EXPECT_EQ(lag.mode, "lag");
  EXPECT_EQ(lag.status, CrossingStatus::Crossed);
  // By hand: 0.1 + (0.5 - 0.6) / (0.28 - 0.6) * (0.2 - 0.1) = 0.1 + 0.03125.
  EXPECT_TRUE(AbsClose(0.13125, lag.mu.value(), 1e-15));
  EXPECT_EQ(lag.mu_above, 0.1);
  EXPECT_EQ(lag.mu_below, 0.2);
  // C = 0: the stability boundary, between 0.2 (0.28) and 0.3 (-0.28): the midpoint.
  const std::vector<DampingCrossing> zero = damping_crossings(s, {"lag"}, 0.0);
  EXPECT_EQ(zero[0].status, CrossingStatus::Crossed);
  EXPECT_TRUE(AbsClose(0.25, zero[0].mu.value(), 1e-15));
  // Above every ratio of the lag mode: below at the start.
  const std::vector<DampingCrossing> high = damping_crossings(s, {"lag"}, 0.9);
  EXPECT_EQ(high[0].status, CrossingStatus::BelowAtStart);
  EXPECT_EQ(high[0].mu, 0.0);
  EXPECT_FALSE(high[0].mu_above.has_value());
}

TEST(DampingCriterion, CrossingBetweenUnresolvedPointsSaysSo) {
  auto sweep = [](std::optional<double> error, Status status, bool gap) {
    SweepResult s;
    s.points.push_back(made_point(0.1, {made_exponent("lag", -0.6, 0.8)}, error, status));
    if (gap) s.points.push_back(made_point(0.15, {}, std::nullopt, Status::Warning));
    s.points.push_back(made_point(0.2, {made_exponent("lag", -0.28, 0.96)}));
    return damping_crossings(s, {"lag"}, 0.5)[0];
  };
  EXPECT_EQ(sweep(1e-9, Status::Ok, false).status, CrossingStatus::Crossed);
  // An error estimate of 0.2 per rev spreads the ratio 0.6 by 0.2 / |lambda| = 0.2 > 0.1.
  const DampingCrossing wide = sweep(0.2, Status::Ok, false);
  EXPECT_EQ(wide.status, CrossingStatus::Unresolved);
  EXPECT_TRUE(AbsClose(0.13125, wide.mu.value(), 1e-15));
  EXPECT_EQ(sweep(0.05, Status::Ok, false).status, CrossingStatus::Crossed);
  EXPECT_EQ(sweep(std::nullopt, Status::Ok, false).status, CrossingStatus::Unresolved);
  EXPECT_EQ(sweep(1e-9, Status::Failed, false).status, CrossingStatus::Unresolved);
  // A point without a ratio between the two: unresolved, still interpolated across it.
  const DampingCrossing gap = sweep(1e-9, Status::Ok, true);
  EXPECT_EQ(gap.status, CrossingStatus::Unresolved);
  EXPECT_TRUE(AbsClose(0.13125, gap.mu.value(), 1e-15));
  // A sweep that stopped at a failed point does not know the rest.
  SweepResult stopped;
  stopped.points = {made_point(0.1, {made_exponent("lag", -0.6, 0.8)}),
                    made_point(0.2, {}, std::nullopt, Status::Failed)};
  EXPECT_EQ(damping_crossings(stopped, {"lag"}, 0.5)[0].status, CrossingStatus::Unresolved);
  EXPECT_FALSE(damping_crossings(stopped, {"lag"}, 0.5)[0].mu.has_value());
}

// Regression: the point's largest error estimate (a heavily damped flap mode's) decided whether a
// lag crossing was resolved; the mode's own estimate does when the point has it.
TEST(DampingCriterion, EachModeIsJudgedByItsOwnErrorEstimate) {
  auto sweep = [](std::optional<double> lag_error) {
    LabelledExponent lag = made_exponent("lag", -0.6, 0.8);
    lag.zeta_error = lag_error;
    SweepResult s;
    // The point's largest estimate, 0.2 per rev, would spread the ratio 0.6 by 0.2 > 0.1.
    s.points.push_back(made_point(0.1, {made_exponent("flap", -2.0, 0.5), lag}, 0.2));
    s.points.push_back(made_point(0.2, {made_exponent("lag", -0.28, 0.96)}));
    return damping_crossings(s, {"lag"}, 0.5)[0].status;
  };
  EXPECT_EQ(sweep(1e-6), CrossingStatus::Crossed);
  EXPECT_EQ(sweep(0.2), CrossingStatus::Unresolved);
  EXPECT_EQ(sweep(std::nullopt), CrossingStatus::Unresolved);  // the point's estimate
}

TEST(DampingCriterion, CriterionOutsideZeroToOneIsRefused) {
  for (double bad : {-1.0, -1e-300, 1.0, 2.0, std::nan(""), HUGE_VAL}) {
    EXPECT_THROW(check_damping_criterion(bad), InvalidInput) << bad;
    EXPECT_THROW(damping_crossings(SweepResult{}, {"lag"}, bad), InvalidInput) << bad;
  }
  try {
    check_damping_criterion(2.0);
    ADD_FAILURE();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.name(), "damping_criterion");
  }
  EXPECT_NO_THROW(check_damping_criterion(0.0));
  EXPECT_NO_THROW(check_damping_criterion(0.01));
}

TEST(Continuation, SweepStartsAboveHoverAndIncludesEnd) {
  auto A = [](double mu) {
    return oscillators(0.6, stiffness(0.6, 1.17 + mu), 0.04, stiffness(0.04, 1.28));
  };
  int calls = 0;
  FloquetFunction f = [&](double mu, double tol) {
    ++calls;
    return constant_family(A)(mu, tol);
  };
  const SweepResult sw = sweep_exponents(label_hover_modes(A(0.0), 1, 1), f, 0.5, 0.625, 0.05);
  ASSERT_EQ(4u, sw.points.size());  // 0.5, 0.55, 0.6, 0.625
  EXPECT_DOUBLE_EQ(0.5, sw.points[0].mu);
  EXPECT_DOUBLE_EQ(0.625, sw.points[3].mu);
  EXPECT_EQ(9 + 4, calls);  // 9 steps of 0.05 up to 0.5, then the 4 points
  // omega continued through the wrap at 1.5 (principal value -0.33 at mu = 0.5).
  EXPECT_TRUE(AbsClose(1.67, find(sw.points[0].exponents, "flap", 1.0)->omega, 1e-9));
}

TEST(Continuation, FailuresAreReportedNotThrown) {
  auto A = [](double) { return oscillators(0.6, 1.5, 0.04, 1.7); };
  FloquetFunction nan_after = [&](double mu, double tol) {
    if (mu > 0.1) {
      return sample(floquet_exponents(
          Eigen::MatrixXd::Constant(4, 4, std::numeric_limits<double>::quiet_NaN()), 0.0));
    }
    return constant_family(A)(mu, tol);
  };
  const HoverModes hover = label_hover_modes(A(0.0), 1, 1);
  const CriticalResult r = find_critical(hover, nan_after, {});
  EXPECT_FALSE(r.mu_c.has_value());
  EXPECT_EQ(Status::Failed, r.status);
  EXPECT_FALSE(r.message.empty());
  const SweepResult sw = sweep_exponents(hover, nan_after, 0.0, 0.3, 0.05);
  EXPECT_EQ(Status::Failed, sw.status);
  EXPECT_EQ(4u, sw.points.size());                    // 0, 0.05, 0.1 and the failed 0.15
  EXPECT_FALSE(sw.points.back().stable.has_value());  // unknown, not "stable"
}

TEST(Continuation, InvalidArgumentsThrow) {
  auto A = [](double) { return oscillators(0.6, 1.5, 0.04, 1.7); };
  const HoverModes hover = label_hover_modes(A(0.0), 1, 1);
  CriticalOptions o;
  o.scan_step = 0.0;
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
  // Regressions (issue 8): counts that used to overflow int or never finish.
  o = {};
  o.mu_max = 21474837;  // (int)ceil(mu_max / step) overflowed: "stable, status ok"
  EXPECT_THROW(find_critical(hover, constant_family(A), o), InvalidInput);
  o = {};
  o.scan_step = 1e-12;  // 2e12 scan steps
  EXPECT_THROW(find_critical(hover, constant_family(A), o), InvalidInput);
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_EQ(0u, why.find("scan_step = 1e-12: ")) << why;
  EXPECT_TRUE(CriticalOptions{}.IsValid(&why));
  EXPECT_THROW(sweep_exponents(hover, constant_family(A), 0.0, 3e4, 1e-5), InvalidInput);
  EXPECT_THROW(sweep_exponents(hover, constant_family(A), 0.0, 10.0, 1e-6), InvalidInput);
  ExponentTracker t(hover);
  FloquetResult wrong;
  wrong.exponents.resize(2);
  EXPECT_THROW(t.advance(wrong), InvalidInput);
}

// Regression (issue 8 item 1): a multiplier of exactly 0 (zeta = -inf) made every assignment
// cost +inf, the tracker kept match = -1 and read exponents[-1] (SIGSEGV).  It must be matched
// and keep its label.
TEST(ExponentTracker, ZeroMultiplierIsMatchedNotACrash) {
  const Eigen::MatrixXd A0 =
      oscillators(1.2, stiffness(1.2, 1.17), 0.04, stiffness(0.04, 1.28), 0.0);
  const HoverModes hover = label_hover_modes(A0, 1, 1);
  ExponentTracker t(hover);
  // Phi with the flap pair decayed to exactly 0 and the lag pair as at hover.
  const Eigen::MatrixXd phi_lag = matrix_exponential(kTwoPi * A0);
  Eigen::MatrixXd phi = phi_lag;
  phi.block(0, 0, 2, 4).setZero();
  phi.block(0, 0, 4, 2).setZero();
  const FloquetResult r = floquet_exponents(phi, kTwoPi * A0.trace());
  int zeros = 0;
  for (const FloquetExponent& e : r.exponents) zeros += e.zeta == -HUGE_VAL ? 1 : 0;
  ASSERT_EQ(2, zeros);
  for (double mu : {0.1, 0.2, 0.3}) {
    const TrackReport rep = t.advance(r, mu);
    EXPECT_NE(Status::Failed, rep.status) << rep.message;
  }
  int flap_zero = 0, lag_finite = 0;
  for (const LabelledExponent& e : t.exponents()) {
    if (e.label == "flap" && e.zeta == -HUGE_VAL) ++flap_zero;
    if (e.label == "lag" && std::isfinite(e.zeta)) ++lag_finite;
  }
  EXPECT_EQ(2, flap_zero);
  EXPECT_EQ(2, lag_finite);
  EXPECT_TRUE(std::isfinite(t.max_zeta()));
}

// A crossing whose exponents carry a large error estimate: mu_c comes back with its error
// estimate and a Warning naming the remedy, not as "ok".
TEST(FindCritical, UnresolvedCrossingIsAWarningWithAnErrorEstimate) {
  auto A = [](double mu) {
    const double ch = 2.0 * (0.5037 - mu);
    return oscillators(1.2, stiffness(1.2, 1.17), ch, stiffness(ch, 1.28), 0.0);
  };
  auto noisy = [&](double mu, double tol) {
    FloquetSample s = constant_family(A)(mu, tol);
    s.zeta_errors.assign(s.floquet.exponents.size(), 1e-3);  // 1e-3 per rev, slope 1
    s.error = 1e-3;
    return s;
  };
  const CriticalResult r = find_critical(label_hover_modes(A(0.0), 1, 1), noisy, {});
  ASSERT_TRUE(r.mu_c.has_value()) << r.message;
  ASSERT_TRUE(r.mu_c_error.has_value());
  // zeta error / slope = 1e-3; the verified bound (f beyond twice the error on both sides of
  // mu_c -+ 2d) is a few times that.
  EXPECT_GT(*r.mu_c_error, 1e-3);
  EXPECT_LT(*r.mu_c_error, 1e-2);
  EXPECT_EQ(Status::Warning, r.status);
  EXPECT_NE(std::string::npos, r.message.find("`steps`")) << r.message;
  // And the same crossing with exact exponents: no error estimate claimed, status ok.
  const CriticalResult exact =
      find_critical(label_hover_modes(A(0.0), 1, 1), constant_family(A), {});
  EXPECT_FALSE(exact.mu_c_error.has_value());
  EXPECT_EQ(Status::Ok, exact.status);
}

// ---- track_exponents in stretches (FloquetFunctionFactory) -------------------------------------

// A family whose functions carry state, as the analysis' warm start does: each evaluation is
// shifted by 1e-9 per earlier call of the same function, so that the result shows where each
// function (stretch) started.  `made` counts the functions.
FloquetFunctionFactory stateful_family(std::atomic<int>* made, double throw_above = HUGE_VAL,
                                       double fail_above = HUGE_VAL) {
  return [=] {
    ++*made;
    auto calls = std::make_shared<int>(0);
    return [calls, throw_above, fail_above](double mu, double) {
      if (mu > throw_above) throw std::runtime_error("thrown at mu = " + std::to_string(mu));
      const double shift = 1e-9 * (*calls)++;
      Eigen::MatrixXd a =
          oscillators(0.6, stiffness(0.6, 1.17 + 0.3 * mu), 0.04 + shift, stiffness(0.04, 1.28));
      if (mu > fail_above)
        return sample(floquet_exponents(
            Eigen::MatrixXd::Constant(4, 4, std::numeric_limits<double>::quiet_NaN()), 0.0));
      return sample(floquet_exponents(matrix_exponential(kTwoPi * a), kTwoPi * a.trace()));
    };
  };
}

HoverModes stateful_hover() {
  return label_hover_modes(oscillators(0.6, stiffness(0.6, 1.17), 0.04, stiffness(0.04, 1.28)), 1,
                           1);
}

std::vector<double> grid(int n, double step) {
  std::vector<double> mus;
  for (int k = 0; k < n; ++k) mus.push_back(step * k);
  return mus;
}

void expect_same_bits(const SweepResult& a, const SweepResult& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.message, b.message);
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    ASSERT_EQ(a.points[i].exponents.size(), b.points[i].exponents.size());
    EXPECT_EQ(a.points[i].mu, b.points[i].mu);
    for (std::size_t k = 0; k < a.points[i].exponents.size(); ++k) {
      const LabelledExponent &x = a.points[i].exponents[k], &y = b.points[i].exponents[k];
      EXPECT_EQ(x.label, y.label);
      EXPECT_EQ(x.zeta, y.zeta) << "point " << i;
      EXPECT_EQ(x.omega, y.omega) << "point " << i;
    }
  }
}

TEST(ContinuationStretch, LengthsDependOnlyOnThePointCount) {
  EXPECT_EQ(kMinStretch, continuation_stretch(1));
  EXPECT_EQ(kMinStretch, continuation_stretch(100));
  EXPECT_EQ(10u, continuation_stretch(151));  // 16 stretches of 10 (the last of 1)
  EXPECT_EQ(kMaxStretch, continuation_stretch(1000000));
}

TEST(StretchedTrack, TheSameBitsForAnyNumberOfThreads) {
  const HoverModes hover = stateful_hover();
  const std::vector<double> mus = grid(151, 0.01);
  std::atomic<int> made{0};
  const SweepResult one = track_exponents(hover, stateful_family(&made), mus, 0.01, 1e-5, 1);
  EXPECT_EQ(16, made.load());  // ceil(151 / 10) stretches, one function each
  ASSERT_EQ(151u, one.points.size());
  for (int threads : {2, 3, 0}) {
    const SweepResult other =
        track_exponents(hover, stateful_family(&made), mus, 0.01, 1e-5, threads);
    expect_same_bits(one, other);
  }
  // Each stretch starts a new function: point 10 (the first of stretch 1) has no shift, the
  // single-function form's has 10 calls' worth.
  const SweepResult single = [&] {
    std::atomic<int> n{0};
    return track_exponents(hover, stateful_family(&n)(), mus, 0.01, 1e-5);
  }();
  auto lag_zeta = [](const PointResult& p) { return find(p.exponents, "lag", 1.0)->zeta; };
  EXPECT_EQ(lag_zeta(single.points[9]) - lag_zeta(one.points[9]), 0.0);  // same function so far
  EXPECT_NEAR(-0.5e-8, lag_zeta(single.points[10]) - lag_zeta(one.points[10]), 1e-12);
}

TEST(StretchedTrack, OneStretchIsTheSingleFunctionForm) {
  const HoverModes hover = stateful_hover();
  const std::vector<double> mus = {0.05, 0.2, 0.35};  // steps of at most 0.05 in between
  std::atomic<int> made{0};
  const SweepResult stretched = track_exponents(hover, stateful_family(&made), mus, 0.05, 1e-5, 2);
  EXPECT_EQ(1, made.load());
  expect_same_bits(track_exponents(hover, stateful_family(&made)(), mus, 0.05, 1e-5), stretched);
}

TEST(StretchedTrack, AStretchTooLongToHoldIsIdentifiedAsItGoes) {
  // 5000 steps to mu = 0.5 and 5000 more to 1.0 (more than kSamplesInMemory in one stretch).
  const HoverModes hover = stateful_hover();
  std::atomic<int> made{0};
  const SweepResult stretched =
      track_exponents(hover, stateful_family(&made), {0.5, 1.0}, 1e-4, 1e-5, 2);
  ASSERT_EQ(2u, stretched.points.size());
  expect_same_bits(track_exponents(hover, stateful_family(&made)(), {0.5, 1.0}, 1e-4, 1e-5),
                   stretched);
}

TEST(StretchedTrack, AFailedStepStopsItAsInTheSingleFunctionForm) {
  const HoverModes hover = stateful_hover();
  const std::vector<double> mus = grid(60, 0.01);
  std::atomic<int> made{0};
  const SweepResult single =
      track_exponents(hover, stateful_family(&made, 0.4, 0.235)(), mus, 0.01, 1e-5);
  std::vector<SweepResult> r;
  for (int threads : {1, 2}) {
    // Non-finite from mu > 0.235 on, and a throw only beyond the failure: never reached.
    r.push_back(
        track_exponents(hover, stateful_family(&made, 0.4, 0.235), mus, 0.01, 1e-5, threads));
    EXPECT_EQ(Status::Failed, r.back().status);
    ASSERT_EQ(25u, r.back().points.size());  // 0 .. 0.23 and the failed 0.24
    EXPECT_FALSE(r.back().points.back().stable.has_value());
    EXPECT_EQ(single.points.size(), r.back().points.size());
    EXPECT_EQ(single.message, r.back().message);
  }
  expect_same_bits(r[0], r[1]);
}

TEST(StretchedTrack, AThrowComesFromTheFirstEvaluationThatThrew) {
  const HoverModes hover = stateful_hover();
  const std::vector<double> mus = grid(60, 0.01);
  for (int threads : {1, 2}) {
    std::atomic<int> made{0};
    try {
      track_exponents(hover, stateful_family(&made, 0.305), mus, 0.01, 1e-5, threads);
      ADD_FAILURE() << "no throw";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string("thrown at mu = ") + std::to_string(0.31), e.what());
    }
  }
}

TEST(StretchedTrack, InvalidArgumentsThrow) {
  const HoverModes hover = stateful_hover();
  std::atomic<int> made{0};
  EXPECT_THROW(track_exponents(hover, stateful_family(&made), {0.1}, 0.01, 1e-5, -1), InvalidInput);
  EXPECT_THROW(track_exponents(hover, stateful_family(&made), {0.1}, 0.01, 1e-5, 257),
               InvalidInput);
  EXPECT_THROW(track_exponents(hover, FloquetFunctionFactory{}, {0.1}, 0.01, 1e-5, 1),
               InvalidInput);
  EXPECT_THROW(track_exponents(
                   hover, [] { return FloquetFunction{}; }, {0.1}, 0.01, 1e-5, 1),
               InvalidInput);
  EXPECT_THROW(track_exponents(hover, stateful_family(&made), {0.2, 0.1}, 0.01, 1e-5, 1),
               InvalidInput);
}

// Finiteness is the library's promise, checked where results are made, so that every front end
// (the command line, Python) reports the same status for the same result.
TEST(CheckFinite, ANonFiniteErrorEstimateMakesTheSweepPointAWarning) {
  auto A = [](double) {
    return oscillators(0.6, stiffness(0.6, 1.17), 0.04, stiffness(0.04, 1.28));
  };
  const FloquetFunction exact = constant_family(A);
  const FloquetFunction nan_error = [&](double mu, double tol) {
    FloquetSample s = exact(mu, tol);
    s.error = std::numeric_limits<double>::quiet_NaN();
    return s;
  };
  const SweepResult sw = sweep_exponents(label_hover_modes(A(0.0), 1, 1), nan_error, 0.0, 0.2, 0.1);
  ASSERT_EQ(3u, sw.points.size());
  for (const PointResult& p : sw.points) {
    EXPECT_EQ(Status::Warning, p.status);
    EXPECT_EQ("non-finite error estimate (not shown)", p.message);
    ASSERT_TRUE(p.stable.has_value());  // the exponents themselves are fine
    EXPECT_TRUE(*p.stable);
  }
  EXPECT_EQ(Status::Warning, sw.status);
  EXPECT_EQ("at mu = 0: non-finite error estimate (not shown)", sw.message);
}

TEST(CheckFinite, ANonFiniteExponentFailsThePointAndItsStability) {
  PointResult p;
  p.mu = 0.3;
  p.stable = true;
  LabelledExponent ok{"flap", -0.1, 0.2, {0.5, 0.1}, {}};
  LabelledExponent zero{"flap", -std::numeric_limits<double>::infinity(), 0.0, {0.0, 0.0}, {}};
  LabelledExponent bad{"lag", -0.01, std::numeric_limits<double>::quiet_NaN(), {0.9, 0.0}, {}};
  p.exponents = {ok, zero};  // the -inf zeta of a zero multiplier is allowed
  check_finite(p);
  EXPECT_EQ(Status::Ok, p.status);
  EXPECT_EQ("", p.message);
  p.exponents.push_back(bad);
  p.Worsen(Status::Warning, "ambiguous");
  check_finite(p);
  EXPECT_EQ(Status::Failed, p.status);
  EXPECT_EQ("ambiguous; non-finite exponent of mode lag (not shown)", p.message);
  EXPECT_FALSE(p.stable.has_value());
  EXPECT_FALSE(p.IsUsable());
}

TEST(CheckFinite, ANonFiniteMuCIsDroppedAndFails) {
  CriticalResult c;
  c.mu_max = 2.0;
  c.mu_c = std::numeric_limits<double>::infinity();
  c.mu_c_error = 1e-6;
  c.message = "unstable above mu_c";
  check_finite(c);
  EXPECT_EQ(Status::Failed, c.status);
  EXPECT_FALSE(c.mu_c.has_value());
  EXPECT_EQ("unstable above mu_c; non-finite mu_c or omega (not shown)", c.message);
  CriticalResult d;
  d.mu_max = 2.0;
  d.mu_c = 0.5;
  d.mu_c_error = std::numeric_limits<double>::quiet_NaN();
  check_finite(d);
  EXPECT_EQ(Status::Warning, d.status);
  ASSERT_TRUE(d.mu_c.has_value());
  EXPECT_EQ(0.5, *d.mu_c);
  EXPECT_EQ("non-finite mu_c error estimate (not shown)", d.message);
}

}  // namespace
}  // namespace flaplag::continuation_test
