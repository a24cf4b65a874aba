// Transition matrix Phi(2 pi, 0): RK4, Hsu (eqs 3.21-3.28) and Magnus4 against closed forms
// and against each other; observed orders of convergence; sector-edge splitting.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/numerics/dense.h"
#include "flaplag/numerics/floquet.h"
#include "periodic_fixtures.h"
#include "test_util.h"

namespace flaplag::transition_test {
namespace {

using fixtures::rotor_hover_matrix;
using fixtures::rotor_like;
using testing::RelClose;

double max_abs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }
double rel_err(const Eigen::MatrixXd& ref, const Eigen::MatrixXd& x) {
  return max_abs(x - ref) / max_abs(ref);
}

PeriodicSystem constant_system(const Eigen::MatrixXd& A) {
  return PeriodicSystem(HarmonicSet{{A}, {}});
}

// The Taylor polynomial of degree J, sum_{j<=J} X^j / j!, written out independently.
Eigen::MatrixXd taylor(const Eigen::MatrixXd& X, int J) {
  Eigen::MatrixXd E = Eigen::MatrixXd::Identity(X.rows(), X.cols()), term = E;
  for (int j = 1; j <= J; ++j) {
    term = term * X / j;
    E += term;
  }
  return E;
}

TEST(Transition, ConstantMatrixAllMethods) {
  const Eigen::MatrixXd A = rotor_hover_matrix();
  const PeriodicSystem s = constant_system(A);
  const Eigen::MatrixXd exact = matrix_exponential(kTwoPi * A);

  // Magnus is exact for constant A (Omega = h A), Hsu with enough Taylor terms as well.
  EXPECT_LT(rel_err(exact, transition_matrix_magnus4(s, 7).phi), 1e-13);
  EXPECT_LT(rel_err(exact, transition_matrix_hsu(s, 50, 20)), 1e-13);
  // For constant A one RK4 step is the degree-4 Taylor polynomial of hA, and so is one Hsu
  // interval with J = 4: both equal T4(2 pi A / N)^N.
  Eigen::MatrixXd p = Eigen::MatrixXd::Identity(4, 4);
  const Eigen::MatrixXd t4 = taylor(kTwoPi / 50 * A, 4);
  for (int i = 0; i < 50; ++i) p = t4 * p;
  EXPECT_LT(rel_err(p, transition_matrix_rk4(s, 50)), 1e-13);
  EXPECT_LT(rel_err(p, transition_matrix_hsu(s, 50, 4)), 1e-13);
  // ... which converges to the exponential at fourth order.
  const double e50 = rel_err(exact, transition_matrix_rk4(s, 50));
  const double e100 = rel_err(exact, transition_matrix_rk4(s, 100));
  EXPECT_GT(std::log2(e50 / e100), 3.7);
  EXPECT_LT(std::log2(e50 / e100), 4.3);
  // Taylor orders J = 1, 2, 3 follow the same closed form.
  for (int J = 1; J <= 3; ++J) {
    Eigen::MatrixXd q = Eigen::MatrixXd::Identity(4, 4);
    const Eigen::MatrixXd tj = taylor(kTwoPi / 40 * A, J);
    for (int i = 0; i < 40; ++i) q = tj * q;
    EXPECT_LT(rel_err(q, transition_matrix_hsu(s, 40, J)), 1e-13) << "J = " << J;
  }
}

// y' = (a + b cos psi + c sin 2 psi + d cos 4 psi) y per component: Phi = exp(2 pi a).
// Diagonal systems commute, so Hsu with exact interval means and converged Taylor series is
// exact for any K: prod exp(Delta_k C_k) = exp(int A).  Dimensions 1, 2, 3, 4 exercise the
// generic and the fixed-size kernels.
TEST(Transition, DiagonalPeriodicClosedForm) {
  for (int n : {1, 2, 3, 4}) {
    HarmonicSet set;
    set.A.assign(9, Eigen::MatrixXd::Zero(n, n));
    Eigen::MatrixXd exact = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i) {
      const double a = -0.1 * (i + 1);
      set.A[0](i, i) = a;
      set.A[1](i, i) = 0.8 + 0.1 * i;  // cos psi
      set.A[4](i, i) = -0.6;           // sin 2 psi
      set.A[7](i, i) = 0.3;            // cos 4 psi
      exact(i, i) = std::exp(kTwoPi * a);
    }
    const PeriodicSystem s(set);
    EXPECT_LT(rel_err(exact, transition_matrix_hsu(s, 7, 30)), 1e-13) << "n = " << n;
    EXPECT_LT(rel_err(exact, transition_matrix_magnus4(s, 50).phi), 1e-11) << "n = " << n;
    const double r1 = rel_err(exact, transition_matrix_rk4(s, 200));
    const double r2 = rel_err(exact, transition_matrix_rk4(s, 400));
    EXPECT_GT(std::log2(r1 / r2), 3.5) << "n = " << n;
    EXPECT_LT(std::log2(r1 / r2), 4.5) << "n = " << n;
  }
}

// Scalar sector-switched system: a + b cos psi outside [s0, s1), a' + c sin 3 psi inside.
// Phi = exp(int A) with the integral split at the edges.  Without splitting the steps at the
// edges every method would drop to first order.
PeriodicSystem switched_scalar(double s0, double s1) {
  HarmonicSet normal, reversed;
  normal.A = {Eigen::MatrixXd::Constant(1, 1, -0.05), Eigen::MatrixXd::Constant(1, 1, 0.7)};
  reversed.A.assign(7, Eigen::MatrixXd::Zero(1, 1));
  reversed.A[0](0, 0) = 0.4;
  reversed.A[6](0, 0) = 1.1;  // sin 3 psi
  return fixtures::with_sector(normal, reversed, s0, s1);
}

double switched_exact(double s0, double s1) {
  auto normal = [](double a, double b) {
    return -0.05 * (b - a) + 0.7 * (std::sin(b) - std::sin(a));
  };
  const double inside = 0.4 * (s1 - s0) - 1.1 / 3.0 * (std::cos(3 * s1) - std::cos(3 * s0));
  return std::exp(normal(0.0, s0) + inside + normal(s1, kTwoPi));
}

TEST(Transition, SectorEdgesAreSplit) {
  // Edges off the grid (0.31 and 0.77 of a step), and edges on grid points.
  const double step = kTwoPi / 50;
  for (auto [s0, s1] : {std::pair{37.31 * step, 43.77 * step}, std::pair{30 * step, 45 * step}}) {
    const PeriodicSystem s = switched_scalar(s0, s1);
    const double exact = switched_exact(s0, s1);
    EXPECT_TRUE(RelClose(exact, transition_matrix_hsu(s, 50, 30)(0, 0), 1e-13));
    // Magnus: the Richardson estimate bounds the error, and the extrapolated result converges
    // at sixth order (the 4th-order method is symmetric: errors in h^4, h^6).
    const TransitionResult m50 = transition_matrix_magnus4(s, 50);
    const TransitionResult m100 = transition_matrix_magnus4(s, 100);
    EXPECT_LE(std::abs(m50.phi(0, 0) - exact), m50.error_estimate);
    EXPECT_LE(std::abs(m100.phi(0, 0) - exact), m100.error_estimate);
    EXPECT_GT(std::log2(std::abs(m50.phi(0, 0) - exact) / std::abs(m100.phi(0, 0) - exact)), 5.0);
    const double e50 = std::abs(transition_matrix_rk4(s, 50)(0, 0) - exact);
    const double e100 = std::abs(transition_matrix_rk4(s, 100)(0, 0) - exact);
    EXPECT_GT(std::log2(e50 / e100), 3.5) << "RK4 order with the sector";
  }
}

// Damped Mathieu equation y'' + 2 xi y' + (delta + eps cos psi) y = 0, state [y', y].
PeriodicSystem mathieu(double delta, double eps, double xi) {
  HarmonicSet set;
  set.A.assign(2, Eigen::MatrixXd::Zero(2, 2));
  set.A[0] << -2 * xi, -delta, 1, 0;
  set.A[1](0, 1) = -eps;
  return PeriodicSystem(set);
}

double max_zeta(const Eigen::MatrixXd& phi, double tr) {
  double z = -1e300;
  for (const FloquetExponent& e : floquet_exponents(phi, tr).exponents) z = std::max(z, e.zeta);
  return z;
}

// Inside the first instability tongue (delta near 1/4) the multipliers are real and distinct,
// so zeta_max is a smooth function of Phi and its error shows the order of each method.
// The varying-region path (transition_varying.cc) on a clipped scalar system with breaks off
// the grid: Phi = exp(int A) in closed form.  RK4 converges at fourth order only because the
// steps are split at the breaks; Hsu's 3-point Gauss means make its scalar Phi exact to O(h^6).
TEST(Transition, VaryingRegionBreaksAreSplit) {
  const PeriodicSystem s = fixtures::clipped_scalar(0.6);
  const double exact = std::exp(fixtures::clipped_log_phi(0.6));
  EXPECT_TRUE(RelClose(exact, transition_matrix_hsu(s, 200, 30)(0, 0), 1e-11));
  const TransitionResult m50 = transition_matrix_magnus4(s, 50);
  EXPECT_LE(std::abs(m50.phi(0, 0) - exact), m50.error_estimate);
  EXPECT_TRUE(RelClose(exact, transition_matrix_magnus4(s, 100).phi(0, 0), 1e-11));
  const double e1 = std::abs(transition_matrix_rk4(s, 50)(0, 0) - exact);
  const double e2 = std::abs(transition_matrix_rk4(s, 100)(0, 0) - exact);
  EXPECT_NEAR(4.0, std::log2(e1 / e2), 0.5) << e1 << " " << e2;
}

// On a varying region that reproduces the rotor-like system's sector, every method gives the
// sector result: RK4 and Magnus evaluate A at the same points (agreement to rounding), Hsu's
// Gauss means differ from the exact means by O(h^6).
TEST(Transition, VaryingRegionEqualsSector) {
  const PeriodicSystem s = rotor_like();
  const PeriodicSystem v = fixtures::sector_as_varying(s);
  EXPECT_LT(rel_err(transition_matrix_rk4(s, 300), transition_matrix_rk4(v, 300)), 1e-13);
  EXPECT_LT(rel_err(transition_matrix_magnus4(s, 60).phi, transition_matrix_magnus4(v, 60).phi),
            1e-13);
  EXPECT_LT(rel_err(transition_matrix_hsu(s, 200, 4), transition_matrix_hsu(v, 200, 4)), 1e-9);
}

TEST(Transition, MathieuMethodsAgreeAndConverge) {
  const PeriodicSystem s = mathieu(0.26, 0.4, 0.02);
  const double tr = s.trace_integral();
  const TransitionResult ref = transition_matrix_magnus4(s, 800);
  const double z_ref = max_zeta(ref.phi, tr);
  ASSERT_GT(z_ref, 0.0);  // really inside the tongue

  double hsu[3], rk4[3];
  const int K[3] = {50, 100, 200};
  for (int i = 0; i < 3; ++i) {
    hsu[i] = std::abs(max_zeta(transition_matrix_hsu(s, K[i], 4), tr) - z_ref);
    rk4[i] = std::abs(max_zeta(transition_matrix_rk4(s, K[i]), tr) - z_ref);
  }
  // eq 3.29: Hsu is second order in Delta (J >= 2).
  for (int i = 0; i < 2; ++i) {
    const double order = std::log2(hsu[i] / hsu[i + 1]);
    EXPECT_GT(order, 1.7) << "Hsu K = " << K[i];
    EXPECT_LT(order, 2.3) << "Hsu K = " << K[i];
    const double order4 = std::log2(rk4[i] / rk4[i + 1]);
    EXPECT_GT(order4, 3.5) << "RK4 N = " << K[i];
    EXPECT_LT(order4, 4.5) << "RK4 N = " << K[i];
  }
  // All methods agree with the reference to their accuracy at 200 steps.
  EXPECT_TRUE(RelClose(z_ref, max_zeta(transition_matrix_hsu(s, 200, 4), tr), 1e-3));
  EXPECT_TRUE(RelClose(z_ref, max_zeta(transition_matrix_rk4(s, 200), tr), 1e-7));
  EXPECT_TRUE(RelClose(z_ref, max_zeta(transition_matrix_magnus4(s, 50).phi, tr), 1e-9));
}

TEST(Transition, MagnusOrderAndErrorEstimate) {
  const PeriodicSystem s = mathieu(1.3, 0.9, 0.05);
  const Eigen::MatrixXd ref = transition_matrix_magnus4(s, 1600).phi;
  const TransitionResult m25 = transition_matrix_magnus4(s, 25);
  const TransitionResult m50 = transition_matrix_magnus4(s, 50);
  // The Richardson estimate measures the 4th-order Magnus error: it falls by ~2^4 per halving.
  const double order = std::log2(m25.error_estimate / m50.error_estimate);
  EXPECT_GT(order, 3.5);
  EXPECT_LT(order, 4.5);
  // ... and bounds the true error of the returned (extrapolated) matrix.
  for (const TransitionResult* m : {&m25, &m50}) {
    const double err = max_abs(m->phi - ref);
    EXPECT_LE(err, m->error_estimate);
    EXPECT_GT(m->error_estimate, 0.0);
  }
}

// The raw Magnus levels (transition_matrix_magnus4_level): levels 0 and 1 are the pair behind
// transition_matrix_magnus4 (the same extrapolation, bit for bit, on the rotor-like sector
// system); each level is fourth order (the error against the reference falls ~16x per
// bisection); a varying region and too many bisections are refused.
TEST(Transition, MagnusLevelsArePairsOfTheRichardsonExtrapolation) {
  const PeriodicSystem s = rotor_like();
  const Eigen::MatrixXd p0 = transition_matrix_magnus4_level(s, 25, 0);
  const Eigen::MatrixXd p1 = transition_matrix_magnus4_level(s, 25, 1);
  const Eigen::MatrixXd p2 = transition_matrix_magnus4_level(s, 25, 2);
  const TransitionResult m = transition_matrix_magnus4(s, 25);
  EXPECT_EQ(0.0, max_abs((16.0 * p1 - p0) / 15.0 - m.phi));
  const Eigen::MatrixXd ref = transition_matrix_magnus4(s, 800).phi;
  const double order = std::log2(max_abs(p1 - ref) / max_abs(p2 - ref));
  EXPECT_GT(order, 3.5);
  EXPECT_LT(order, 4.5);
  EXPECT_THROW(transition_matrix_magnus4_level(fixtures::sector_as_varying(s), 25, 0),
               InvalidInput);
  EXPECT_THROW(transition_matrix_magnus4_level(s, 25, -1), InvalidInput);
  EXPECT_THROW(transition_matrix_magnus4_level(s, 25, 16), InvalidInput);  // > kMaxSteps
}

// Magnus on many states (more than 8 without a plain kernel: the wide kernel, which balances
// the state by powers of two).  A block-diagonal system of similarity transforms
// T_k^-1 R T_k of the rotor-like 4-state system R (T_k with scales from 1e-3 to 1e3, so that the
// blocks are badly balanced, as the stiffness entries of the many-mode models make them) has
// Phi = blockdiag(T_k^-1 Phi_R T_k), with Phi_R from the 4-state kernel at the same steps; a
// constant 2-state block (exact: exp(2 pi B)) makes sizes that are not a multiple of 4.
TEST(Transition, MagnusOnManyStatesMatchesTheBlocksItIsMadeOf) {
  const PeriodicSystem r = rotor_like();
  Eigen::Matrix2d b;
  b << -0.05, 1.0, -30.0, -0.2;  // a stiff oscillator, |lambda| ~ 5.5
  const std::vector<Eigen::Vector4d> scales = {
      Eigen::Vector4d(1.0, 1.0, 1.0, 1.0), Eigen::Vector4d(1e3, 1.0, 3.0, 1e-3),
      Eigen::Vector4d(0.1, 70.0, 1e-2, 5.0), Eigen::Vector4d(1e-3, 1e-3, 1e3, 1e3),
      Eigen::Vector4d(7.0, 0.3, 0.3, 7.0)};
  // 14, 16, 20 and 22 states (12 has a plain kernel of its own)
  for (auto [blocks, with_constant] :
       {std::pair{3, true}, std::pair{4, false}, std::pair{5, false}, std::pair{5, true}}) {
    const int n = 4 * blocks + (with_constant ? 2 : 0);
    PeriodicSystem s = r;  // the same pieces
    s.n = n;
    for (std::size_t r_set = 0; r_set < s.sets.size(); ++r_set) {
      HarmonicSet* set = &s.sets[r_set];
      const HarmonicSet* from = &r.sets[r_set];
      set->A.assign(from->A.size(), Eigen::MatrixXd::Zero(n, n));
      for (std::size_t h = 0; h < from->A.size(); ++h) {
        for (int k = 0; k < blocks; ++k) {
          const Eigen::DiagonalMatrix<double, 4> t(scales[k]);
          set->A[h].block(4 * k, 4 * k, 4, 4) = t.inverse() * from->A[h] * t;
        }
        if (with_constant && h == 0) set->A[0].bottomRightCorner(2, 2) = b;
      }
    }
    for (int steps : {25, 60}) {
      for (int bisections : {0, 1}) {
        const Eigen::MatrixXd block = transition_matrix_magnus4_level(r, steps, bisections);
        const Eigen::MatrixXd phi = transition_matrix_magnus4_level(s, steps, bisections);
        ASSERT_EQ(phi.rows(), n);
        Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(n, n);
        for (int k = 0; k < blocks; ++k) {
          const Eigen::DiagonalMatrix<double, 4> t(scales[k]);
          expected.block(4 * k, 4 * k, 4, 4) = t.inverse() * block * t;
        }
        if (with_constant)
          expected.bottomRightCorner(2, 2) = matrix_exponential(Eigen::Matrix2d(kTwoPi * b));
        // each block to the rounding of its own scale: relative to the block's largest entry
        for (int k = 0; k < blocks; ++k) {
          EXPECT_LT(rel_err(expected.block(4 * k, 4 * k, 4, 4), phi.block(4 * k, 4 * k, 4, 4)),
                    1e-12)
              << "n = " << n << ", block " << k << ", steps " << steps;
        }
        if (with_constant) {
          EXPECT_LT(rel_err(expected.bottomRightCorner(2, 2), phi.bottomRightCorner(2, 2)), 1e-12)
              << "n = " << n;
        }
        // nothing leaks between the blocks
        Eigen::MatrixXd off = phi;
        for (int k = 0; k < blocks; ++k) off.block(4 * k, 4 * k, 4, 4).setZero();
        if (with_constant) off.bottomRightCorner(2, 2).setZero();
        EXPECT_EQ(0.0, max_abs(off)) << "n = " << n;
      }
    }
    // transition_matrix_magnus4 is the Richardson pass over the same levels
    const TransitionResult m = transition_matrix_magnus4(s, 25);
    const Eigen::MatrixXd p0 = transition_matrix_magnus4_level(s, 25, 0);
    const Eigen::MatrixXd p1 = transition_matrix_magnus4_level(s, 25, 1);
    EXPECT_EQ(0.0, max_abs((16.0 * p1 - p0) / 15.0 - m.phi)) << "n = " << n;
  }
}

TEST(Transition, RotorLikeReferenceAccuracy) {
  const PeriodicSystem s = rotor_like();
  const Eigen::MatrixXd ref = transition_matrix_magnus4(s, 1000).phi;
  // The accuracy quoted in transition.cc for this system: 25 / 50 / 100 steps give Phi to
  // 1e-7 / 2e-9 / 3e-11 relative (each checked with a factor 5 allowance), sixth order, and the
  // Richardson estimate is a bound that is two to three orders of magnitude pessimistic.
  const int steps[3] = {25, 50, 100};
  const double quoted[3] = {1e-7, 2e-9, 3e-11};
  double err[3];
  for (int i = 0; i < 3; ++i) {
    const TransitionResult mi = transition_matrix_magnus4(s, steps[i]);
    err[i] = rel_err(ref, mi.phi);
    EXPECT_LT(err[i], 5.0 * quoted[i]) << "steps = " << steps[i];
    const double pessimism = mi.error_estimate / max_abs(mi.phi - ref);
    EXPECT_GT(pessimism, 10.0) << "steps = " << steps[i];
    EXPECT_LT(pessimism, 1e4) << "steps = " << steps[i];
  }
  EXPECT_GT(std::log2(err[0] / err[1]), 5.0);
  EXPECT_GT(std::log2(err[1] / err[2]), 5.0);
  const TransitionResult m = transition_matrix_magnus4(s, 50);
  // Liouville: det Phi = exp(int tr A) holds to the accuracy of the method.
  EXPECT_LT(floquet_exponents(m.phi, s.trace_integral()).liouville_residual, 1e-9);
  // The paper's methods converge to it at their orders despite the jumps at the sector edges.
  const double h1 = rel_err(ref, transition_matrix_hsu(s, 100, 4));
  const double h2 = rel_err(ref, transition_matrix_hsu(s, 200, 4));
  EXPECT_GT(std::log2(h1 / h2), 1.7);
  EXPECT_LT(std::log2(h1 / h2), 2.3);
  const double r1 = rel_err(ref, transition_matrix_rk4(s, 200));
  const double r2 = rel_err(ref, transition_matrix_rk4(s, 400));
  EXPECT_GT(std::log2(r1 / r2), 3.5);
  EXPECT_LT(std::log2(r1 / r2), 4.5);
}

// Exactly solvable systems (periodic_fixtures.h: Lyapunov-reducible y = P(psi) z, z' = B z, 2
// and 4 states, with and without a sector, and the Markus-Yamabe example):
// Phi(2 pi) = P(0) e^{2 pi B} P(0)^{-1}.  Every method converges to it at its order, and its
// error stays within the a priori leading-term model of periodic_fixtures.h (factor 4).  On
// these systems (L = max ||A|| = 1.4 .. 4.4, C = max ||[A, A']|| = 5 .. 31) the models give
// RK4 N = 200: 3e-7 .. 8e-5 and Hsu K = 50, J = 4: 0.04 .. 0.28 (relative to max |Phi|).
TEST(Transition, ReducibleSystemsClosedForm) {
  for (const fixtures::ExactCase& c : fixtures::exact_cases()) {
    SCOPED_TRACE(c.name);
    const fixtures::SystemScale sc = fixtures::scale_of(c.sys);
    // RK4, fourth order.
    const double r100 = rel_err(c.phi, transition_matrix_rk4(c.sys, 100));
    const double r200 = rel_err(c.phi, transition_matrix_rk4(c.sys, 200));
    EXPECT_LT(r100, 4.0 * fixtures::rk4_error_model(sc, 100));
    EXPECT_LT(r200, 4.0 * fixtures::rk4_error_model(sc, 200));
    EXPECT_GT(std::log2(r100 / r200), 3.7);
    EXPECT_LT(std::log2(r100 / r200), 4.3);
    // Hsu J = 4, second order.
    const double h50 = rel_err(c.phi, transition_matrix_hsu(c.sys, 50, 4));
    const double h100 = rel_err(c.phi, transition_matrix_hsu(c.sys, 100, 4));
    EXPECT_LT(h50, 4.0 * fixtures::hsu_error_model(sc, 50, 4));
    EXPECT_LT(h100, 4.0 * fixtures::hsu_error_model(sc, 100, 4));
    EXPECT_GT(std::log2(h50 / h100), 1.8);
    EXPECT_LT(std::log2(h50 / h100), 2.2);
    // Magnus4 with Richardson extrapolation: sixth order, error within its own estimate.
    const TransitionResult m25 = transition_matrix_magnus4(c.sys, 25);
    const TransitionResult m50 = transition_matrix_magnus4(c.sys, 50);
    EXPECT_LE(max_abs(m25.phi - c.phi), m25.error_estimate);
    EXPECT_LE(max_abs(m50.phi - c.phi), m50.error_estimate);
    EXPECT_GT(std::log2(rel_err(c.phi, m25.phi) / rel_err(c.phi, m50.phi)), 5.3);
  }
}

// k decoupled copies of rotor_like() (block diagonal, the same sector): Phi is the block
// diagonal of k copies of the 4-state Phi.
PeriodicSystem copies_of_rotor_like(int k) {
  const PeriodicSystem one = rotor_like();
  PeriodicSystem s = one;
  s.n = 4 * k;
  for (std::size_t i = 0; i < s.sets.size(); ++i) {
    HarmonicSet* set = &s.sets[i];
    const HarmonicSet& src = one.sets[i];
    for (std::size_t h = 0; h < src.A.size(); ++h) {
      set->A[h] = Eigen::MatrixXd::Zero(4 * k, 4 * k);
      for (int b = 0; b < k; ++b) set->A[h].block(4 * b, 4 * b, 4, 4) = src.A[h];
    }
  }
  return s;
}

// Hsu's product over K intervals written out independently: taylor() (eq 3.27) of the exact
// interval means A_mean(), split at the sector edges.
Eigen::MatrixXd independent_hsu(const PeriodicSystem& s, int K) {
  Eigen::MatrixXd product = Eigen::MatrixXd::Identity(s.n, s.n);
  for (int i = 0; i < K; ++i) {
    const double a = i * kTwoPi / K, b = (i + 1 == K) ? kTwoPi : (i + 1) * kTwoPi / K;
    double lo = a;
    for (double e : s.breakpoints()) {
      if (e > a + 1e-12 && e < b - 1e-12) {
        product = taylor((e - lo) * s.A_mean(lo, e), 4) * product;
        lo = e;
      }
    }
    product = taylor((b - lo) * s.A_mean(lo, b), 4) * product;
  }
  return product;
}

// The fixed-size kernels (4, 8 and 12 states: plain arrays with AVX2/baseline clones, Hsu J = 4
// and Magnus), the wide kernel (Magnus at 16 and 20 states) and the general Eigen kernels (Hsu at
// 16 and 20 states) are different code: on k decoupled
// copies each diagonal block must reproduce the 4-state result to rounding and the
// off-diagonal blocks stay exactly zero.
TEST(Transition, FixedSizeKernelsAgreeWithTheGeneralOnes) {
  const PeriodicSystem one = rotor_like();
  const Eigen::MatrixXd hsu4 = transition_matrix_hsu(one, 50, 4);
  const Eigen::MatrixXd magnus4 = transition_matrix_magnus4(one, 25).phi;
  // The 4-state kernel against an independent product.
  EXPECT_LT(rel_err(independent_hsu(one, 50), hsu4), 1e-13);
  for (int k : {2, 3, 4, 5}) {
    const PeriodicSystem s = copies_of_rotor_like(k);
    const Eigen::MatrixXd h = transition_matrix_hsu(s, 50, 4);
    const Eigen::MatrixXd m = transition_matrix_magnus4(s, 25).phi;
    for (int b = 0; b < k; ++b) {
      for (int c = 0; c < k; ++c) {
        if (b == c) {
          EXPECT_LT(rel_err(hsu4, h.block(4 * b, 4 * b, 4, 4)), 1e-13) << "k = " << k;
          EXPECT_LT(rel_err(magnus4, m.block(4 * b, 4 * b, 4, 4)), 1e-12) << "k = " << k;
        } else {
          EXPECT_EQ(0.0, max_abs(h.block(4 * b, 4 * c, 4, 4))) << "k = " << k;
          EXPECT_EQ(0.0, max_abs(m.block(4 * b, 4 * c, 4, 4))) << "k = " << k;
        }
      }
    }
  }
}

// The system P S P^T for the state permutation `perm` (row i of the result is row perm[i] of S).
PeriodicSystem permuted(const PeriodicSystem& s, const std::vector<int>& perm) {
  PeriodicSystem out = s;
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(s.n, s.n);
  for (int i = 0; i < s.n; ++i) P(i, perm[i]) = 1.0;
  for (HarmonicSet& set : out.sets)
    for (Eigen::MatrixXd& a : set.A) a = P * a * P.transpose();
  return out;
}

// The plain kernel of 4 states sums the harmonics only into the even rows of A, which are the
// rows that vary in the layout of 1 x 1 modes (y = [g', g, h', h]); a 4-state system whose odd
// rows vary takes the Eigen kernel.  The permutation puts rotor_like()'s varying rows 0 and 2 at
// 1 and 3.
TEST(Transition, HsuTakesEveryRowThatVaries) {
  const PeriodicSystem even = rotor_like();
  const PeriodicSystem odd = permuted(even, {1, 0, 3, 2});
  for (int K : {8, 50, 101}) {
    EXPECT_LT(rel_err(independent_hsu(odd, K), transition_matrix_hsu(odd, K, 4)), 1e-13)
        << "K = " << K;
    EXPECT_LT(rel_err(independent_hsu(even, K), transition_matrix_hsu(even, K, 4)), 1e-13)
        << "K = " << K;
  }
}

// transition_matrix_hsu_pair: Phi at K with the bits of transition_matrix_hsu, Phi at K / 2
// equal to it to rounding, on grids where a sector edge falls inside a fine interval, on a
// fine grid point that is a coarse midpoint (K = 8, 24: 1.25 pi = 5 and 15 fine steps) and on
// a coarse grid point (K = 16); the sizes without a plain kernel and the fallbacks (6 and 16
// states, varying odd rows, J = 3, a varying region) give the two separate calls.
TEST(Transition, HsuPairIsBothGridsInOnePass) {
  const PeriodicSystem one = rotor_like();
  struct Case {
    const char* name;
    PeriodicSystem sys;
    int terms;
    bool exact_half;  // no plain kernel: *phi_half is the separate call itself
  };
  PeriodicSystem six = one;  // the same pieces
  six.n = 6;
  for (std::size_t i = 0; i < six.sets.size(); ++i) {
    HarmonicSet* set = &six.sets[i];
    const HarmonicSet& src = one.sets[i];
    set->A.assign(src.A.size(), Eigen::MatrixXd::Zero(6, 6));
    for (std::size_t h = 0; h < src.A.size(); ++h) {
      set->A[h].topLeftCorner(4, 4) = src.A[h];
      set->A[h].bottomRightCorner(2, 2) = src.A[h].topLeftCorner(2, 2);
    }
  }
  const std::vector<Case> cases{{"rotor_like", one, 4, false},
                                {"odd rows", permuted(one, {1, 0, 3, 2}), 4, true},
                                {"8 states", copies_of_rotor_like(2), 4, false},
                                {"12 states", copies_of_rotor_like(3), 4, false},
                                {"16 states", copies_of_rotor_like(4), 4, true},
                                {"6 states", six, 4, true},
                                {"J = 3", one, 3, true},
                                {"mathieu", mathieu(1.3, 0.9, 0.05), 4, true},
                                {"varying region", fixtures::sector_as_varying(one), 4, true}};
  for (const Case& c : cases) {
    for (int K : {2, 8, 16, 24, 50, 100}) {
      Eigen::MatrixXd phi, half;
      transition_matrix_hsu_pair(c.sys, K, c.terms, &phi, &half);
      const Eigen::MatrixXd ref = transition_matrix_hsu(c.sys, K, c.terms);
      const Eigen::MatrixXd ref_half = transition_matrix_hsu(c.sys, K / 2, c.terms);
      EXPECT_TRUE(phi == ref) << c.name << ", K = " << K;
      if (c.exact_half) {
        EXPECT_TRUE(half == ref_half) << c.name << ", K = " << K;
      } else {
        EXPECT_LT(rel_err(ref_half, half), 1e-13) << c.name << ", K = " << K;
      }
    }
  }
  Eigen::MatrixXd phi, half;
  EXPECT_THROW(transition_matrix_hsu_pair(one, 51, 4, &phi, &half), InvalidInput);
  EXPECT_THROW(transition_matrix_hsu_pair(one, 0, 4, &phi, &half), InvalidInput);
  EXPECT_THROW(transition_matrix_hsu_pair(one, 50, 0, &phi, &half), InvalidInput);
  EXPECT_THROW(transition_matrix_hsu_pair(one, 50, 4, nullptr, &half), InvalidInput);
  EXPECT_THROW(transition_matrix_hsu_pair(one, 50, 4, &phi, nullptr), InvalidInput);
}

TEST(Transition, DispatchAndNames) {
  const PeriodicSystem s = mathieu(1.3, 0.9, 0.05);
  TransitionOptions o;
  o.method = TransitionMethod::RK4;
  o.steps = 30;
  EXPECT_EQ(transition_matrix_rk4(s, 30), transition_matrix(s, o).phi);
  EXPECT_EQ(0.0, transition_matrix(s, o).error_estimate);
  o.method = TransitionMethod::Hsu;
  o.terms = 3;
  EXPECT_EQ(transition_matrix_hsu(s, 30, 3), transition_matrix(s, o).phi);
  o.method = TransitionMethod::Magnus4;
  EXPECT_EQ(transition_matrix_magnus4(s, 30).phi, transition_matrix(s, o).phi);
  EXPECT_STREQ("rk4", method_name(TransitionMethod::RK4));
  EXPECT_STREQ("hsu", method_name(TransitionMethod::Hsu));
  EXPECT_STREQ("magnus", method_name(TransitionMethod::Magnus4));
}

TEST(Transition, InvalidArgumentsThrow) {
  const PeriodicSystem s = mathieu(1.3, 0.9, 0.05);
  EXPECT_THROW(transition_matrix_rk4(s, 0), InvalidInput);
  EXPECT_THROW(transition_matrix_hsu(s, 0, 4), InvalidInput);
  EXPECT_THROW(transition_matrix_hsu(s, 50, 0), InvalidInput);
  EXPECT_THROW(transition_matrix_magnus4(s, -1), InvalidInput);
  PeriodicSystem bad = s;
  bad.sets[0].A[1] = Eigen::MatrixXd::Zero(3, 3);
  EXPECT_THROW(transition_matrix_hsu(bad, 50, 4), InvalidInput);
}

}  // namespace
}  // namespace flaplag::transition_test
