// The Floquet evaluators and their step control on numerics-only periodic systems (no rotor):
// Create() gives each method with its order and passes; fixed steps give the kernel's own Phi;
// the automatic rule resolves the exponents of exactly solvable systems to the tolerance it
// claims; method names and the enum map one to one.
#include "flaplag/numerics/floquet_evaluator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "flaplag/core/errors.h"
#include "flaplag/numerics/dense.h"
#include "periodic_fixtures.h"

namespace flaplag::floquet_evaluator_test {
namespace {

TransitionOptions options_of(TransitionMethod m, int steps, int terms = 4, double tol = 1e-6) {
  TransitionOptions o;
  o.method = m;
  o.steps = steps;
  o.terms = terms;
  o.zeta_tolerance = tol;
  return o;
}

std::vector<double> sorted_zetas(const FloquetResult& r) {
  std::vector<double> z;
  for (const FloquetExponent& e : r.exponents) z.push_back(e.zeta);
  std::sort(z.begin(), z.end());
  return z;
}

// The exact exponents eig(B) of a reducible system, real parts sorted.
std::vector<double> exact_zetas(const Eigen::MatrixXd& B) {
  const Eigen::VectorXcd ev = real_eigen_system(B, false, EigenStorage::Dynamic).values;
  std::vector<double> z;
  for (Eigen::Index k = 0; k < ev.size(); ++k) z.push_back(ev(k).real());
  std::sort(z.begin(), z.end());
  return z;
}

TEST(FloquetEvaluator, CreateGivesEachMethodWithItsOrderAndPasses) {
  const PeriodicSystem sector = fixtures::rotor_like();
  const PeriodicSystem varying = fixtures::sector_as_varying(sector);
  struct Expect {
    TransitionMethod method;
    int terms;
    int order;  // p of the error c K^-p
    bool pair;  // K and K/2 in one pass
    int levels;
  };
  for (const Expect& x :
       {Expect{TransitionMethod::RK4, 4, 4, false, 0}, Expect{TransitionMethod::Hsu, 4, 2, true, 0},
        Expect{TransitionMethod::Hsu, 1, 1, true, 0},
        Expect{TransitionMethod::Magnus4, 4, 6, false, 4}}) {
    SCOPED_TRACE(method_name(x.method));
    const auto e = FloquetEvaluator::Create(options_of(x.method, 50, x.terms));
    ASSERT_NE(e, nullptr);
    EXPECT_EQ(e->options().method, x.method);
    EXPECT_EQ(e->order(), x.order);
    EXPECT_EQ(e->has_pair(), x.pair);
    EXPECT_EQ(e->level_order(sector), x.levels);
    EXPECT_EQ(e->level_order(varying), 0);  // Magnus4's levels need a harmonic system
  }
}

TEST(FloquetEvaluator, CreateChecksTheOptions) {
  try {
    FloquetEvaluator::Create(options_of(TransitionMethod::Hsu, 50, 0));
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.name(), "terms");
  }
  const auto e = FloquetEvaluator::Create(options_of(TransitionMethod::RK4, 50));
  EXPECT_THROW(e->evaluate(fixtures::rotor_like(), 0.0), InvalidInput);
  EXPECT_THROW(e->evaluate(fixtures::rotor_like(), std::nan("")), InvalidInput);
}

TEST(FloquetEvaluator, FixedStepsGiveTheKernelsOwnPhi) {
  const PeriodicSystem sys = fixtures::rotor_like();
  for (TransitionMethod m : kTransitionMethods) {
    SCOPED_TRACE(method_name(m));
    const TransitionOptions o = options_of(m, 60);
    const auto e = FloquetEvaluator::Create(o, sys.n);
    const FloquetSample s = e->evaluate(sys, o.zeta_tolerance);
    EXPECT_EQ(s.steps, 60);
    const Eigen::MatrixXd phi = transition_matrix(sys, o).phi;
    ASSERT_EQ(s.floquet.phi.rows(), phi.rows());
    EXPECT_TRUE(s.floquet.phi.cwiseEqual(phi).all()) << "not the kernel's Phi bit for bit";
    EXPECT_TRUE((e->transition(sys, 60).array() == phi.array()).all());
    // The estimate against 2K: one error per exponent.
    EXPECT_EQ(s.zeta_errors.size(), s.floquet.exponents.size());
    ASSERT_TRUE(s.error.has_value());
  }
}

TEST(FloquetEvaluator, TooFewFixedStepsAreNotResolved) {
  const auto e = FloquetEvaluator::Create(options_of(TransitionMethod::RK4, 1));
  const FloquetSample s = e->evaluate(fixtures::rotor_like(), 1e-6);
  EXPECT_EQ(s.steps, 1);
  // One RK4 step over a period on a system with |A| ~ 5 is far from resolved: said, not Ok.
  EXPECT_EQ(s.status, Status::Warning);
  EXPECT_NE(s.message.find("increase `steps`"), std::string::npos) << s.message;
}

TEST(FloquetEvaluator, HsuPairHasTheBitsOfItsFineHalfAndTheCoarseToRounding) {
  const PeriodicSystem sys = fixtures::rotor_like();
  const auto e = FloquetEvaluator::Create(options_of(TransitionMethod::Hsu, 80));
  Eigen::MatrixXd phi, half;
  e->transition_pair(sys, 80, &phi, &half);
  EXPECT_TRUE((phi.array() == e->transition(sys, 80).array()).all());
  EXPECT_LT((half - e->transition(sys, 40)).cwiseAbs().maxCoeff(), 1e-12 * half.norm());
}

// The automatic rule on systems whose exponents are eig(B) exactly: every exponent within
// what the rule calls resolved, zeta_tolerance max(1, 100 |zeta|).  The Richardson estimate is
// not a bound, so a factor 2 is allowed for the estimate's own error.
TEST(FloquetEvaluator, AutomaticStepsResolveExactExponentsToTheTolerance) {
  for (const fixtures::ExactCase& c : fixtures::exact_cases()) {
    const std::vector<double> exact = exact_zetas(c.B);
    for (TransitionMethod m : kTransitionMethods) {
      for (double tol : {1e-5, 1e-7}) {
        SCOPED_TRACE(std::string(c.name) + ", " + method_name(m) + ", tol " + std::to_string(tol));
        const auto e =
            FloquetEvaluator::Create(options_of(m, TransitionOptions::kAutomatic, 4, tol), c.sys.n);
        const FloquetSample s = e->evaluate(c.sys, tol);
        ASSERT_EQ(s.status, Status::Ok) << s.message;
        EXPECT_GE(s.steps, 50);
        EXPECT_EQ(s.steps % 2, 0);
        ASSERT_TRUE(s.error.has_value());
        const std::vector<double> z = sorted_zetas(s.floquet);
        ASSERT_EQ(z.size(), exact.size());
        for (std::size_t k = 0; k < z.size(); ++k) {
          const double allowed = tol * std::max(1.0, 100.0 * std::abs(exact[k]));
          EXPECT_LE(std::abs(z[k] - exact[k]), 2.0 * allowed) << "exponent " << k;
        }
      }
    }
  }
}

// A request looser than the options' tolerance walks Magnus4's raw levels from 24 steps: it
// still meets the tolerance it was asked for.
TEST(FloquetEvaluator, LooseMagnusRequestsMeetTheirTolerance) {
  for (const fixtures::ExactCase& c : fixtures::exact_cases()) {
    SCOPED_TRACE(c.name);
    const std::vector<double> exact = exact_zetas(c.B);
    const auto e = FloquetEvaluator::Create(
        options_of(TransitionMethod::Magnus4, TransitionOptions::kAutomatic));
    const double loose = 1e-3;
    const FloquetSample s = e->evaluate(c.sys, loose);
    ASSERT_EQ(s.status, Status::Ok) << s.message;
    EXPECT_LT(s.steps, 50);  // the raw levels, not the ladder (which starts at 50)
    const std::vector<double> z = sorted_zetas(s.floquet);
    ASSERT_EQ(z.size(), exact.size());
    for (std::size_t k = 0; k < z.size(); ++k)
      EXPECT_LE(std::abs(z[k] - exact[k]), 2.0 * loose * std::max(1.0, 100.0 * std::abs(exact[k])));
  }
}

// A hint carries the count a continuation's next evaluation starts at: it is stored per
// tolerance, and a warm evaluation is resolved as well as a cold one.
TEST(FloquetEvaluator, StepsHintIsKeptPerToleranceAndWarmStartsResolve) {
  const fixtures::ExactCase c = fixtures::exact_cases()[3];  // 4 states with a sector
  const std::vector<double> exact = exact_zetas(c.B);
  const auto e =
      FloquetEvaluator::Create(options_of(TransitionMethod::Hsu, TransitionOptions::kAutomatic));
  StepsHint hint;
  EXPECT_EQ(hint.find(1e-6), 0);
  const FloquetSample cold = e->evaluate(c.sys, 1e-6, &hint);
  ASSERT_EQ(cold.status, Status::Ok) << cold.message;
  const int hinted = hint.find(1e-6);
  EXPECT_GE(hinted, 50);
  EXPECT_EQ(hinted % 2, 0);
  EXPECT_EQ(hint.find(1e-5), 0);  // another tolerance has its own count
  const FloquetSample warm = e->evaluate(c.sys, 1e-6, &hint);
  ASSERT_EQ(warm.status, Status::Ok) << warm.message;
  EXPECT_GE(warm.steps, hinted);
  const std::vector<double> z = sorted_zetas(warm.floquet);
  for (std::size_t k = 0; k < z.size(); ++k)
    EXPECT_LE(std::abs(z[k] - exact[k]), 2e-6 * std::max(1.0, 100.0 * std::abs(exact[k])));
}

TEST(FloquetEvaluator, SystemNoteMakesAWarningAndOverflowFails) {
  const auto e =
      FloquetEvaluator::Create(options_of(TransitionMethod::Hsu, TransitionOptions::kAutomatic));
  const FloquetSample s = e->evaluate(fixtures::exact_cases()[0].sys, 1e-6, nullptr, "approximate");
  EXPECT_EQ(s.status, Status::Warning);
  EXPECT_NE(s.message.find("approximate"), std::string::npos);
  PeriodicSystem bad = fixtures::rotor_like();
  bad.sets[0].A[0](0, 0) = std::numeric_limits<double>::infinity();
  const FloquetSample f = e->evaluate(bad, 1e-6);
  EXPECT_EQ(f.status, Status::Failed);
  EXPECT_NE(f.message.find("overflows"), std::string::npos);
}

TEST(TransitionMethodNames, RoundTripInOnePlace) {
  for (TransitionMethod m : kTransitionMethods) {
    TransitionMethod back =
        m == TransitionMethod::RK4 ? TransitionMethod::Hsu : TransitionMethod::RK4;
    ASSERT_TRUE(method_from_name(method_name(m), &back));
    EXPECT_EQ(back, m);
  }
  TransitionMethod unchanged = TransitionMethod::Hsu;
  EXPECT_FALSE(method_from_name("RK4", &unchanged));  // exactly the name
  EXPECT_FALSE(method_from_name("magnus4", &unchanged));
  EXPECT_FALSE(method_from_name("", &unchanged));
  EXPECT_EQ(unchanged, TransitionMethod::Hsu);
  EXPECT_EQ(method_names(), "rk4, hsu, magnus, auto");
}

// The default method is Automatic: Hsu for up to 4 states, Magnus4 above.  Create() resolves it
// for the state size it is given (and needs one); options() names the method it became; an
// explicit method is kept whatever the size.
TEST(AutomaticMethod, HsuForFourStatesMagnusAbove) {
  EXPECT_EQ(TransitionOptions{}.method, TransitionMethod::Automatic);
  EXPECT_EQ(TransitionOptions::Paper().method, TransitionMethod::Hsu);
  for (int n : {1, 2, 3, 4}) EXPECT_EQ(automatic_method(n), TransitionMethod::Hsu) << n;
  for (int n : {5, 6, 8, 12, 16, 20, 24, 96}) {
    EXPECT_EQ(automatic_method(n), TransitionMethod::Magnus4) << n;
  }
  EXPECT_THROW(automatic_method(0), InvalidInput);

  TransitionOptions o;
  o.terms = 3;
  o.zeta_tolerance = 1e-7;
  const auto four = FloquetEvaluator::Create(o, 4);
  EXPECT_EQ(four->options().method, TransitionMethod::Hsu);
  EXPECT_EQ(four->options().terms, 3);
  EXPECT_EQ(four->options().zeta_tolerance, 1e-7);
  EXPECT_EQ(four->order(), 2);
  for (int n : {8, 20}) {
    const auto many = FloquetEvaluator::Create(o, n);
    EXPECT_EQ(many->options().method, TransitionMethod::Magnus4) << n;
    EXPECT_EQ(many->order(), 6) << n;
  }
  EXPECT_THROW(FloquetEvaluator::Create(o), InvalidInput);  // no size to choose for
  for (TransitionMethod m :
       {TransitionMethod::RK4, TransitionMethod::Hsu, TransitionMethod::Magnus4}) {
    o.method = m;
    for (int n : {0, 4, 20}) EXPECT_EQ(FloquetEvaluator::Create(o, n)->options().method, m) << n;
  }
}

// transition_matrix() with an Automatic method is the chosen method's, bit for bit.
TEST(AutomaticMethod, TransitionMatrixUsesTheChosenMethod) {
  const PeriodicSystem s = fixtures::rotor_like();
  TransitionOptions o;
  o.steps = 40;
  const Eigen::MatrixXd automatic = transition_matrix(s, o).phi;
  EXPECT_EQ(0.0, (automatic - transition_matrix_hsu(s, 40, 4)).cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace flaplag::floquet_evaluator_test
