// The Galerkin basis of the exact rotating modes as part of the answer's error: the default
// (converged) basis, the named paper basis, and the basis error every exact-mode result
// carries (rotor/parameters.h, analysis/src/basis.cc).
//
// The references are computed here with explicit bases (11 and 12 functions, the largest two):
// the exact modes converge alternately in the basis size (odd bases below, even above for the
// typical case), so that the converged mu_c lies between the two.  No expected value is copied
// from the code under test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "flaplag/analysis.h"
#include "flaplag/blade/blade_elements.h"
#include "flaplag/blade/rotating_modes.h"
#include "flaplag/rotor/parameter_table.h"
#include "flaplag/trim.h"
#include "test_util.h"

namespace basis_test {

using flaplag::Analysis;
using flaplag::CriticalOptions;
using flaplag::CriticalResult;
using flaplag::ModeKind;
using flaplag::RotorParameters;
using flaplag::Status;
using flaplag::TransitionOptions;

namespace {

RotorParameters typical_exact(int basis) {
  RotorParameters p;  // the paper's typical case
  p.modes = ModeKind::Exact;
  p.basis = basis;
  return p;
}

CriticalResult critical(int basis) {
  return Analysis(typical_exact(basis), TransitionOptions{}).critical(CriticalOptions{});
}

// The converged reference: the interval between the largest two bases.
struct Reference {
  double lo, hi;
};
const Reference& reference() {
  static const Reference r = [] {
    const CriticalResult a = critical(11), b = critical(12);
    EXPECT_TRUE(a.mu_c && b.mu_c);
    return Reference{std::min(*a.mu_c, *b.mu_c), std::max(*a.mu_c, *b.mu_c)};
  }();
  return r;
}

TEST(Basis, TheDefaultIsConvergedAndNamed) {
  const RotorParameters d;
  EXPECT_EQ(d.basis, flaplag::kConvergedBasis);
  EXPECT_EQ(flaplag::galerkin_basis(d), flaplag::kMaxBasisFunctions);
  const flaplag::ParameterSpec& row = *flaplag::find_parameter("basis");
  EXPECT_EQ(flaplag::parameter_text(d, row), "converged");
  int v = 0;
  ASSERT_TRUE(flaplag::integer_from_name(row, "paper", &v));
  EXPECT_EQ(v, 5);  // paper 4.1(b): five cantilever functions
  ASSERT_TRUE(flaplag::integer_from_name(row, "converged", &v));
  EXPECT_EQ(v, flaplag::kConvergedBasis);
  EXPECT_FALSE(flaplag::integer_from_name(row, "5", &v));
  EXPECT_NO_THROW(flaplag::validate(d));
  ASSERT_TRUE(flaplag::integer_from_name(row, "elements", &v));
  EXPECT_EQ(v, flaplag::kElementBasis);
  for (int bad : {-2, 13, 1000}) {
    RotorParameters p;
    p.basis = bad;
    EXPECT_THROW(flaplag::validate(p), flaplag::InvalidInput) << bad;
  }
}

TEST(Basis, ReferenceIsTheNeighbourHoldingTheModes) {
  RotorParameters p = typical_exact(flaplag::kConvergedBasis);
  EXPECT_EQ(flaplag::reference_basis(p, 1, 1), 11);
  EXPECT_EQ(flaplag::reference_basis(p, 11, 3), 11);
  EXPECT_EQ(flaplag::reference_basis(p, 12, 1), 0);  // no other basis holds 12 modes
  p.basis = 5;
  EXPECT_EQ(flaplag::reference_basis(p, 1, 1), 6);
  p.basis = 1;
  EXPECT_EQ(flaplag::reference_basis(p, 1, 1), 2);
  // Finite elements against the largest basis, a blade table's Galerkin modes against elements.
  p.basis = flaplag::kElementBasis;
  EXPECT_EQ(flaplag::reference_basis(p, 3, 2), flaplag::kMaxBasisFunctions);
  p.basis = flaplag::kConvergedBasis;
  p.blade = std::make_shared<const flaplag::BladeProperties>(flaplag::uniform_blade());
  EXPECT_EQ(flaplag::reference_basis(p, 1, 1), flaplag::kElementBasis);
}

// The finite-element modes: a second discretization whose mu_c lands in the interval of the two
// largest Galerkin bases (which holds the converged value), with the change to 12 functions as
// its error.
TEST(Basis, FiniteElementMuCLiesInTheGalerkinBracket) {
  const CriticalResult r = critical(flaplag::kElementBasis);
  ASSERT_TRUE(r.mu_c && r.mu_c_error && r.basis_error) << r.message;
  EXPECT_EQ(*r.basis, flaplag::kElementBasis);
  const Reference& ref = reference();
  std::printf("elements: mu_c %.10f, basis_error %.2e; 11 and 12 functions: %.10f, %.10f\n",
              *r.mu_c, *r.basis_error, ref.lo, ref.hi);
  const double tol = CriticalOptions{}.tolerance;
  EXPECT_GE(*r.mu_c, ref.lo - tol);
  EXPECT_LE(*r.mu_c, ref.hi + tol);
  EXPECT_GE(*r.basis_error, std::min(std::abs(*r.mu_c - ref.lo), std::abs(*r.mu_c - ref.hi)));
}

// The finite elements' own error in mu_c: the same uniform blade as a table with a station every
// 1/192 (so twice as many elements, the table's values all equal) moves it by less than 1e-7,
// far below the Galerkin modes' error the elements measure (~1e-5).
TEST(Basis, FiniteElementMuCIsConvergedInTheMesh) {
  const CriticalResult coarse = critical(flaplag::kElementBasis);
  flaplag::BladeProperties fine = flaplag::uniform_blade();
  const int n = 2 * flaplag::kElementsPerSpan;
  fine.x0.clear();
  for (int i = 0; i <= n; ++i) fine.x0.push_back(static_cast<double>(i) / n);
  for (auto* column :
       {&fine.mass, &fine.stiffness_flap, &fine.stiffness_lag, &fine.chord, &fine.twist})
    column->assign(fine.x0.size(), column->front());
  RotorParameters p = typical_exact(flaplag::kElementBasis);
  p.blade = std::make_shared<const flaplag::BladeProperties>(fine);
  const CriticalResult r = Analysis(p, TransitionOptions{}).critical({});
  ASSERT_TRUE(coarse.mu_c && r.mu_c) << coarse.message << r.message;
  std::printf("elements: mu_c %.12f (96 per span), %.12f (192)\n", *coarse.mu_c, *r.mu_c);
  EXPECT_LT(std::abs(*coarse.mu_c - *r.mu_c), 1e-7);
}

// A tapered blade with a corner and a tip weight (relative mass 1.5 -> 0.7, stiffness shape 2 ->
// 0.5): its Galerkin modes converge slowly, and the change to the next basis understated their
// error; the error is now the change to finite elements, computed here explicitly.
RotorParameters tapered_exact(int basis) {
  flaplag::BladeProperties b = flaplag::uniform_blade();
  b.x0 = {0.0, 0.25, 1.0};
  b.mass = {1.5, 1.2, 0.7};
  b.stiffness_flap = {2.0, 1.4, 0.5};
  b.stiffness_lag = b.stiffness_flap;
  b.chord = {1.0, 1.0, 1.0};
  b.twist = {0.0, 0.0, 0.0};
  b.tip_mass = 0.05;
  b.source = "tapered";
  RotorParameters p = typical_exact(basis);
  p.blade = std::make_shared<const flaplag::BladeProperties>(flaplag::normalised_mass(b));
  return p;
}

TEST(Basis, ATablesGalerkinModesAreCheckedAgainstFiniteElements) {
  const CriticalResult g = Analysis(tapered_exact(flaplag::kConvergedBasis), {}).critical({});
  ASSERT_TRUE(g.mu_c && g.basis_error) << g.message;
  EXPECT_EQ(*g.basis, flaplag::kMaxBasisFunctions);
  const CriticalResult e = Analysis(tapered_exact(flaplag::kElementBasis), {}).critical({});
  const CriticalResult g11 = Analysis(tapered_exact(11), {}).critical({});
  ASSERT_TRUE(e.mu_c && g11.mu_c) << e.message << g11.message;
  std::printf(
      "tapered: 12 functions %.10f (basis_error %.2e), 11 functions %.10f, elements "
      "%.10f\n",
      *g.mu_c, *g.basis_error, *g11.mu_c, *e.mu_c);
  EXPECT_TRUE(flaplag::testing::AbsClose(std::abs(*g.mu_c - *e.mu_c), *g.basis_error, 1e-15));
  EXPECT_GE(*g.mu_c_error, *g.basis_error);
  // Regression: the warning of an unresolved basis named the reference by its number (-1).
  const CriticalResult g5 = Analysis(tapered_exact(flaplag::kPaperBasis), {}).critical({});
  EXPECT_EQ(g5.status, Status::Warning) << g5.message;
  EXPECT_NE(g5.message.find("5 cantilever functions against cubic finite elements change mu_c"),
            std::string::npos)
      << g5.message;
}

// The default exact-mode mu_c of the typical case agrees with the converged reference within
// its reported error, and says which basis it used.
TEST(Basis, DefaultMuCAgreesWithTheLargeBasisReferenceWithinItsError) {
  const CriticalResult r =
      Analysis(typical_exact(RotorParameters{}.basis), TransitionOptions{}).critical({});
  ASSERT_TRUE(r.mu_c && r.mu_c_error) << r.message;
  EXPECT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_TRUE(r.basis.has_value());
  EXPECT_EQ(*r.basis, 12);
  ASSERT_TRUE(r.basis_error.has_value());
  EXPECT_GT(*r.basis_error, 0.0);
  EXPECT_GE(*r.mu_c_error, *r.basis_error);
  const Reference& ref = reference();
  // both ends of the interval that holds the converged value
  EXPECT_LE(std::abs(*r.mu_c - ref.lo), *r.mu_c_error);
  EXPECT_LE(std::abs(*r.mu_c - ref.hi), *r.mu_c_error);
  // and within 10 tolerances of it: the default is resolved in its basis
  EXPECT_LE(ref.hi - ref.lo, 10.0 * CriticalOptions{}.tolerance);
}

// The paper's five functions: the same number as ever, now with an error that covers the
// distance to the converged value, and not Ok.
TEST(Basis, PaperBasisErrorCoversTheConvergedValue) {
  const CriticalResult r = critical(flaplag::kPaperBasis);
  ASSERT_TRUE(r.mu_c && r.mu_c_error) << r.message;
  EXPECT_EQ(*r.basis, 5);
  const Reference& ref = reference();
  EXPECT_GE(*r.mu_c_error, std::abs(*r.mu_c - ref.lo));
  EXPECT_GE(*r.mu_c_error, std::abs(*r.mu_c - ref.hi));
  EXPECT_EQ(r.status, Status::Warning);
  EXPECT_NE(r.message.find("basis"), std::string::npos) << r.message;
}

// A basis whose change misses the tolerance says what to do about it: use a larger basis, or,
// at the largest (12 functions, compared with 11), that its error estimate carries the change.
TEST(Basis, TheUnresolvedMessageOffersALargerBasisOnlyWhenThereIsOne) {
  CriticalOptions tight;
  tight.tolerance = 1e-9;
  for (int b : {11, flaplag::kMaxBasisFunctions}) {
    const CriticalResult r = Analysis(typical_exact(b), TransitionOptions{}).critical(tight);
    ASSERT_TRUE(r.mu_c && r.basis_error) << b << ": " << r.message;
    ASSERT_GT(*r.basis_error, 10.0 * tight.tolerance) << b;  // not resolved at this tolerance
    EXPECT_EQ(r.status, Status::Warning) << b;
    EXPECT_NE(r.message.find("not resolved in their basis"), std::string::npos) << r.message;
    const bool largest = b == flaplag::kMaxBasisFunctions;
    EXPECT_EQ(!largest, r.message.find("use a larger `basis`") != std::string::npos) << r.message;
    EXPECT_EQ(largest, r.message.find("the basis is already the largest (12 cantilever "
                                      "functions): the change is included in the error "
                                      "estimate of mu_c") != std::string::npos)
        << r.message;
  }
}

// Regression: the 5-function mu_c was reported with the Floquet error alone (5e-6) while it is
// 9e-4 from the converged value.  No basis may claim an error smaller than its distance to the
// converged interval, and one that misses the tolerance by 10 is never Ok.
TEST(Basis, NoBasisClaimsLessThanItsDistanceToTheConvergedValue) {
  const Reference& ref = reference();
  const double tol = CriticalOptions{}.tolerance;
  for (int b = 3; b <= 10; ++b) {
    const CriticalResult r = critical(b);
    ASSERT_TRUE(r.mu_c && r.mu_c_error) << b << ": " << r.message;
    const double distance = std::max(std::abs(*r.mu_c - ref.lo), std::abs(*r.mu_c - ref.hi));
    EXPECT_GE(*r.mu_c_error, distance) << "basis " << b << ": mu_c " << *r.mu_c;
    if (distance > 10.0 * tol) {
      EXPECT_NE(r.status, Status::Ok) << "basis " << b;
    }
  }
}

// Points and sweeps carry the basis and include its error in their error estimates.
TEST(Basis, PointsIncludeTheBasisError) {
  const Analysis an(typical_exact(flaplag::kConvergedBasis), TransitionOptions{});
  const flaplag::PointResult p = an.point(0.5);
  ASSERT_EQ(p.status, Status::Ok) << p.message;
  ASSERT_TRUE(p.basis && p.basis_error && p.error);
  EXPECT_EQ(*p.basis, 12);
  EXPECT_GE(*p.error, *p.basis_error);
  // against the same point with 11 functions, computed here
  const flaplag::PointResult q = Analysis(typical_exact(11), TransitionOptions{}).point(0.5);
  double largest = 0.0;
  for (const auto& e : p.exponents)
    for (const auto& f : q.exponents)
      if (e.label == f.label && std::abs(e.omega - f.omega) < 1e-3)
        largest = std::max(largest, std::abs(e.zeta - f.zeta));
  EXPECT_GT(largest, 0.0);
  EXPECT_GE(*p.basis_error, largest * (1 - 1e-12));

  const flaplag::SweepResult s = an.sweep(0.0, 0.2, 0.1);
  ASSERT_EQ(s.points.size(), 3u);
  for (const auto& pt : s.points) {
    ASSERT_TRUE(pt.basis && pt.basis_error) << pt.mu;
    EXPECT_EQ(*pt.basis, 12);
  }
  // The paper basis at mu = 0.5 moves the zetas by more than 10 zeta tolerances: not Ok.
  const flaplag::PointResult five =
      Analysis(typical_exact(flaplag::kPaperBasis), TransitionOptions{}).point(0.5);
  EXPECT_GT(*five.basis_error, *p.basis_error);
}

// The largest |zeta change| between two results, exponent by exponent (the same label, the
// nearest omega), computed here.
double largest_zeta_change(const flaplag::PointResult& a, const flaplag::PointResult& b) {
  double largest = 0.0;
  for (const auto& e : a.exponents) {
    double best = std::numeric_limits<double>::infinity(), dz = 0.0;
    for (const auto& f : b.exponents)
      if (e.label == f.label && std::abs(e.omega - f.omega) < best) {
        best = std::abs(e.omega - f.omega);
        dz = std::abs(e.zeta - f.zeta);
      }
    if (std::isfinite(best)) largest = std::max(largest, dz);
  }
  return largest;
}

flaplag::TrimOptions thrust_trim() {
  flaplag::TrimOptions o;
  o.kind = flaplag::TrimKind::Thrust;
  o.thrust_coefficient = 0.004;
  return o;
}

// The point of p trimmed at mu with thrust_trim().
flaplag::RotorPoint trimmed_point(const RotorParameters& p, const TransitionOptions& t, double mu) {
  return Analysis(p, t, flaplag::OperatingCondition::Trimmed(thrust_trim())).point(mu);
}

// A trimmed point (the controls solved at mu, trim.h) with exact modes carries the basis error
// as an untrimmed one does: the whole trimmed computation with the neighbouring basis, whose
// trim moves with the basis too.  The reference here is the trimmed point with 11 functions.
TEST(Basis, TrimmedPointsIncludeTheBasisError) {
  const TransitionOptions t;
  const flaplag::PointResult p = trimmed_point(typical_exact(flaplag::kConvergedBasis), t, 0.3);
  ASSERT_NE(p.status, Status::Failed) << p.message;
  ASSERT_TRUE(p.basis && p.basis_error && p.error) << p.message;
  EXPECT_EQ(*p.basis, 12);
  EXPECT_GE(*p.error, *p.basis_error);
  const flaplag::PointResult q = trimmed_point(typical_exact(11), t, 0.3);
  ASSERT_NE(q.status, Status::Failed) << q.message;
  const double change = largest_zeta_change(p, q);
  EXPECT_GT(change, 0.0);
  EXPECT_GE(*p.basis_error, change * (1 - 1e-12));
  EXPECT_LE(*p.basis_error, change * (1 + 1e-12));

  // The assumed mode: no basis, as untrimmed.
  const flaplag::PointResult a = trimmed_point(RotorParameters{}, t, 0.3);
  EXPECT_FALSE(a.basis.has_value());
  EXPECT_FALSE(a.basis_error.has_value());
}

// A trimmed sweep carries it at every point, and about the periodic equilibrium too.
TEST(Basis, TrimmedSweepsAndThePeriodicEquilibriumIncludeTheBasisError) {
  RotorParameters p = typical_exact(flaplag::kPaperBasis);
  const flaplag::SweepResult s =
      Analysis(p, TransitionOptions{}, flaplag::OperatingCondition::Trimmed(thrust_trim()))
          .sweep(0.1, 0.2, 0.1);
  ASSERT_EQ(s.points.size(), 2u) << s.message;
  for (const auto& pt : s.points) {
    ASSERT_TRUE(pt.basis && pt.basis_error) << pt.mu << ": " << pt.message;
    EXPECT_EQ(*pt.basis, 5);
    EXPECT_GE(pt.error.value_or(0.0), *pt.basis_error);
  }
  const auto about_q0 =
      flaplag::OperatingCondition{}.About(flaplag::Linearization::PeriodicEquilibrium);
  const flaplag::PointResult e = Analysis(p, TransitionOptions{}, about_q0).point(0.3);
  ASSERT_NE(e.status, Status::Failed) << e.message;
  ASSERT_TRUE(e.basis && e.basis_error) << e.message;
  const flaplag::PointResult f = [&] {
    RotorParameters q = p;
    q.basis = 6;
    return Analysis(q, TransitionOptions{}, about_q0).point(0.3);
  }();
  EXPECT_GE(*e.basis_error, largest_zeta_change(e, f) * (1 - 1e-12));
}

// A sweep with exact modes runs twice (the reference basis): its progress counts both passes
// in one total, so that it neither stops at 100 % for the second nor runs backwards.
TEST(Basis, SweepProgressCountsTheReferencePass) {
  std::vector<std::pair<std::size_t, std::size_t>> calls;
  const flaplag::ProgressFunction progress = [&](std::size_t done, std::size_t all) {
    calls.emplace_back(done, all);
  };
  const Analysis exact(typical_exact(flaplag::kPaperBasis), TransitionOptions{});
  const flaplag::SweepResult s = exact.sweep(0.0, 0.3, 0.1, 1, nullptr, progress);
  ASSERT_EQ(s.points.size(), 4u) << s.message;
  ASSERT_FALSE(calls.empty());
  const std::size_t total = calls.front().second;
  std::size_t last = 0;
  for (const auto& [done, all] : calls) {
    EXPECT_EQ(all, total);
    EXPECT_GE(done, last);
    last = done;
  }
  EXPECT_EQ(calls.back().first, total);
  // the half-way mark is passed while the reference pass still has to report
  std::size_t half = 0;
  for (const auto& c : calls) half += c.first <= total / 2 ? 1 : 0;
  EXPECT_GE(half, 1u);
  EXPECT_LT(half, calls.size());
  // and the assumed mode counts one pass, to the same number of evaluations per pass
  std::vector<std::pair<std::size_t, std::size_t>> one;
  const flaplag::ProgressFunction single = [&](std::size_t done, std::size_t all) {
    one.emplace_back(done, all);
  };
  Analysis(RotorParameters{}, TransitionOptions{}).sweep(0.0, 0.3, 0.1, 1, nullptr, single);
  ASSERT_FALSE(one.empty());
  EXPECT_EQ(total, 2 * one.front().second);
}

// The 1974 mode shapes converge monotonically in the basis size: the change to the neighbouring
// basis is no bound on the error there (the paper basis' change is less than its distance to
// 12 functions), and every such result says so in a note; the correct shapes do not.
TEST(Basis, The1974ShapesSayTheirBasisErrorIsNoBound) {
  auto run = [](int basis, bool shapes_1974) {
    RotorParameters p = typical_exact(basis);
    p.paper_1974_shapes = shapes_1974;
    return Analysis(p, TransitionOptions{}).critical({});
  };
  auto noted = [](const CriticalResult& r) {
    for (const std::string& n : r.notes)
      if (n.find("converge monotonically") != std::string::npos) return true;
    return false;
  };
  const CriticalResult five = run(flaplag::kPaperBasis, true), twelve = run(12, true);
  ASSERT_TRUE(five.mu_c && twelve.mu_c && five.basis_error) << five.message;
  EXPECT_LT(*five.basis_error, std::abs(*five.mu_c - *twelve.mu_c));
  EXPECT_TRUE(noted(five));
  EXPECT_TRUE(noted(twelve));
  EXPECT_FALSE(noted(run(flaplag::kPaperBasis, false)));
}

// The assumed mode has no basis: no basis fields, and its numbers are untouched.
TEST(Basis, AssumedModeHasNoBasis) {
  const CriticalResult r = Analysis(RotorParameters{}, TransitionOptions{}).critical({});
  EXPECT_FALSE(r.basis.has_value());
  EXPECT_FALSE(r.basis_error.has_value());
  const flaplag::PointResult p = Analysis(RotorParameters{}, TransitionOptions{}).point(0.3);
  EXPECT_FALSE(p.basis.has_value());
}

// Twelve modes per direction leave no other basis: the error is not estimated, and says so.
TEST(Basis, WithoutAReferenceTheResultIsAWarning) {
  RotorParameters p = typical_exact(flaplag::kConvergedBasis);
  p.model = "paper-12x1";
  const flaplag::PointResult r = Analysis(p, TransitionOptions{}).point(0.1);
  ASSERT_NE(r.status, Status::Failed) << r.message;
  EXPECT_EQ(r.status, Status::Warning);
  EXPECT_NE(r.message.find("not estimated"), std::string::npos) << r.message;
  EXPECT_FALSE(r.basis_error.has_value());
}

// The search with the neighbouring basis may run beside the main one (threads != 1): the
// result is the same to the bit, with a reference, without one, and for a bad thread count the
// refusal names `threads`.
TEST(Basis, TheReferenceSearchBesideTheMainOneGivesTheSameResult) {
  for (const char* model : {"paper", "paper-12x1"}) {
    RotorParameters p = typical_exact(flaplag::kPaperBasis);
    if (std::string(model) == "paper-12x1") p.basis = flaplag::kConvergedBasis;
    p.model = model;
    const Analysis an(p, TransitionOptions{});
    const CriticalResult one = an.critical({}, 1), two = an.critical({}, 2);
    ASSERT_TRUE(one.mu_c && two.mu_c) << model << ": " << one.message;
    EXPECT_EQ(*one.mu_c, *two.mu_c) << model;
    EXPECT_EQ(one.mu_c_error, two.mu_c_error) << model;
    EXPECT_EQ(one.basis_error, two.basis_error) << model;
    EXPECT_EQ(one.status, two.status) << model;
    EXPECT_EQ(one.message, two.message) << model;
    EXPECT_EQ(one.evaluations, two.evaluations) << model;
  }
  const Analysis an(typical_exact(flaplag::kPaperBasis), TransitionOptions{});
  for (int threads : {-1, flaplag::kMaxThreads + 1}) {
    try {
      an.critical({}, threads);
      ADD_FAILURE() << "threads " << threads << " accepted";
    } catch (const flaplag::InvalidInput& e) {
      EXPECT_EQ(e.name(), "threads") << e.what();
    }
  }
}

}  // namespace

}  // namespace basis_test
