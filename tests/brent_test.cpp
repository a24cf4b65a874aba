// Brent's method (brent.h): roots of polynomials, sign changes at jumps, flat functions, roots
// at the bracket ends, the evaluation cut-off, non-finite values, per-point state of the caller,
// invalid arguments.
#include "flaplag/numerics/brent.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "flaplag/core/errors.h"
#include "test_util.h"

namespace flaplag::brent_test {
namespace {

using testing::AbsClose;

const double kEps = std::numeric_limits<double>::epsilon();

// Number of bisections that shrink [a, b] to the tolerance: Brent's method never needs many
// more, and on smooth simple roots (superlinear convergence) far fewer.
int bisections(double a, double b, double tol) {
  return static_cast<int>(std::ceil(std::log2(std::abs(b - a) / tol)));
}

// Searches [a, b] with brent_zero, recording every call, and checks what holds for every result:
// the bracket ends are evaluated points with the signs claimed, root is one of them, and every call
// lay strictly inside [a, b].
struct Search {
  BrentResult r;
  std::vector<double> xs;  // xs[k] = argument of the (k + 1)-th call
};

Search search(const std::function<double(double)>& f, double a, double b, BrentOptions opt = {}) {
  Search out;
  auto recorded = [&](double x) {
    out.xs.push_back(x);
    return f(x);
  };
  out.r = brent_zero(recorded, a, f(a), b, f(b), opt);
  const BrentResult& r = out.r;
  EXPECT_EQ(static_cast<int>(out.xs.size()), r.evaluations);
  EXPECT_LE(r.evaluations, opt.max_evaluations);
  EXPECT_EQ(r.status == Status::Ok, r.converged);
  EXPECT_FALSE(r.message.empty());
  EXPECT_LE(r.lo.x, r.hi.x);
  // Point indices: 0 = a, 1 = b, k >= 2 = the (k - 1)-th call; x and f agree with them.
  for (const BrentPoint* p : {&r.lo, &r.hi, &r.root}) {
    const double x = p->index == 0 ? a : p->index == 1 ? b : out.xs.at(p->index - 2);
    EXPECT_EQ(x, p->x) << "index " << p->index;
    EXPECT_EQ(f(x), p->f) << "index " << p->index;
  }
  EXPECT_TRUE(r.root.index == r.lo.index || r.root.index == r.hi.index);
  EXPECT_LE(std::abs(r.root.f), std::max(std::abs(r.lo.f), std::abs(r.hi.f)));
  EXPECT_FALSE((r.lo.f > 0 && r.hi.f > 0) || (r.lo.f < 0 && r.hi.f < 0));
  EXPECT_GE(r.positive().f, 0.0);
  EXPECT_LE(r.negative().f, 0.0);
  for (double x : out.xs) {
    EXPECT_GT(x, std::min(a, b));
    EXPECT_LT(x, std::max(a, b));
  }
  return out;
}

// Converged: the bracket is no wider than tolerance + 4 eps |root| and contains `exact`.
void expect_converged(const BrentResult& r, double exact, double tol) {
  EXPECT_EQ(Status::Ok, r.status) << r.message;
  EXPECT_TRUE(r.converged);
  EXPECT_LE(r.lo.x, exact);
  EXPECT_GE(r.hi.x, exact);
  EXPECT_LE(r.hi.x - r.lo.x, tol + 4 * kEps * std::abs(r.root.x));
  EXPECT_TRUE(AbsClose(exact, r.root.x, tol + 4 * kEps * std::abs(exact)));
}

TEST(Brent, PolynomialRoots) {
  BrentOptions opt;
  opt.tolerance = 1e-12;
  // x^2 - 2 on [0, 2] and reversed ([2, 0], f(a) > 0).
  auto sq = [](double x) { return x * x - 2.0; };
  for (auto [a, b] : {std::pair{0.0, 2.0}, std::pair{2.0, 0.0}}) {
    const Search s = search(sq, a, b, opt);
    expect_converged(s.r, std::sqrt(2.0), opt.tolerance);
    // Superlinear on a smooth simple root: fewer than half the 41 bisections.
    EXPECT_LT(s.r.evaluations, bisections(a, b, opt.tolerance) / 2);
  }
  // Wallis's cubic x^3 - 2x - 5 (Newton's example), root 2.0945514815423265...
  const Search w = search([](double x) { return (x * x - 2.0) * x - 5.0; }, 2.0, 3.0, opt);
  expect_converged(w.r, 2.0945514815423265, opt.tolerance);
  EXPECT_LT(w.r.evaluations, bisections(2.0, 3.0, opt.tolerance) / 2);
  // A root far from 0: the bracket cannot be narrower than the spacing of doubles there, so
  // the effective tolerance is tolerance + 4 eps |x| (here 1e6: 9e-10).
  const Search big = search([](double x) { return x - 1e6 - 0.1; }, 0.0, 2e6, opt);
  expect_converged(big.r, 1e6 + 0.1, opt.tolerance);
}

// A triple root ((x - 1)^3 on [0, 3]: f flat near the root, the interpolation converges only
// linearly, about three evaluations per halving of the bracket; the worst case of Brent's
// method is O(k^2) for k bisections, so the cap is (k + 1)^2) and a function so flat that it
// underflows to zero: sign(x - c) exp(-1 / (x - c)^2) is exactly +-0 for |x - c| <
// 1 / sqrt(745) = 0.0366 (e^{-745} is below the smallest subnormal), and any point with
// f == 0 is an accepted root.
TEST(Brent, FlatFunctions) {
  BrentOptions opt;
  opt.tolerance = 1e-10;
  const int k = bisections(0.0, 3.0, opt.tolerance);
  opt.max_evaluations = (k + 1) * (k + 1);
  const Search t = search(
      [](double x) {
        const double c = x - 1.0;
        return c * c * c;  // the sign of c^3 is exact
      },
      0.0, 3.0, opt);
  expect_converged(t.r, 1.0, opt.tolerance);
  EXPECT_GT(t.r.evaluations, k);  // slower than bisection here: linear convergence

  const double c = 0.3;
  const Search u =
      search([c](double x) { return std::copysign(std::exp(-1.0 / ((x - c) * (x - c))), x - c); },
             -1.0, 2.0, opt);
  EXPECT_EQ(Status::Ok, u.r.status);
  if (u.r.root.f == 0.0) {
    EXPECT_LT(std::abs(u.r.root.x - c), 0.0367);
  } else {
    expect_converged(u.r, c, opt.tolerance);
  }
}

// f need not be continuous: the result brackets the jump.  A step with no root at all, a jump
// across zero between two non-zero branches, and a strongly asymmetric step.  |f| does not
// shrink towards a jump, so interpolation steps are mostly rejected and the bisection fallback
// sets the pace: one evaluation per halving plus the rejected trials, at most 2 k.
TEST(Brent, SignChangeAtJump) {
  BrentOptions opt;
  opt.tolerance = 1e-9;
  const double jump = 0.7123;
  for (const std::function<double(double)>& f : std::vector<std::function<double(double)>>{
           [=](double x) { return x < jump ? -1.0 : 1.0; },
           [=](double x) { return x < jump ? x - 5.0 : x + 3.0; },
           [=](double x) { return x < jump ? -1e-3 : 1e3; }}) {
    const Search s = search(f, 0.0, 1.0, opt);
    EXPECT_EQ(Status::Ok, s.r.status) << s.r.message;
    EXPECT_LT(s.r.lo.x, jump);
    EXPECT_GE(s.r.hi.x, jump);
    EXPECT_LE(s.r.hi.x - s.r.lo.x, opt.tolerance);
    EXPECT_EQ(s.r.hi.index, s.r.positive().index);
    EXPECT_LE(s.r.evaluations, 2 * bisections(0.0, 1.0, opt.tolerance));
  }
}

// A zero at an end is the root without any call of f; -0.0 counts as zero.
TEST(Brent, RootAtBracketEnd) {
  auto never = [](double) -> double {
    ADD_FAILURE() << "f called";
    return 0.0;
  };
  for (double zero : {0.0, -0.0}) {
    const BrentResult ra = brent_zero(never, 1.0, zero, 2.0, 3.0);
    EXPECT_EQ(Status::Ok, ra.status);
    EXPECT_EQ(0, ra.evaluations);
    EXPECT_EQ(1.0, ra.root.x);
    EXPECT_EQ(0, ra.root.index);
    EXPECT_EQ(1.0, ra.lo.x);
    EXPECT_EQ(2.0, ra.hi.x);
    EXPECT_EQ(2.0, ra.positive().x);  // f = 3 there

    const BrentResult rb = brent_zero(never, 1.0, -3.0, 2.0, zero);
    EXPECT_EQ(Status::Ok, rb.status);
    EXPECT_EQ(0, rb.evaluations);
    EXPECT_EQ(2.0, rb.root.x);
    EXPECT_EQ(1, rb.root.index);
    EXPECT_EQ(2.0, rb.positive().x);  // the zero end, the other being negative
  }
  const BrentResult both = brent_zero(never, 1.0, 0.0, 2.0, 0.0);
  EXPECT_EQ(Status::Ok, both.status);
  EXPECT_EQ(0, both.evaluations);
  // An exact zero found inside stops the search at once.
  const Search inside = search([](double x) { return x - 0.5; }, 0.0, 1.0);
  EXPECT_EQ(Status::Ok, inside.r.status);
  EXPECT_EQ(0.5, inside.r.root.x);  // the first secant step lands on it exactly
  EXPECT_EQ(0.0, inside.r.root.f);
  EXPECT_EQ(1, inside.r.evaluations);
}

// max_evaluations bounds the calls; then Warning, not converged, and a valid (wider) bracket.
TEST(Brent, EvaluationCutOff) {
  auto f = [](double x) { return x * x - 2.0; };
  for (int max : {1, 3}) {
    BrentOptions opt;
    opt.tolerance = 1e-15;
    opt.max_evaluations = max;
    const Search s = search(f, 0.0, 2.0, opt);
    EXPECT_EQ(Status::Warning, s.r.status);
    EXPECT_FALSE(s.r.converged);
    EXPECT_EQ(max, s.r.evaluations);
    EXPECT_NE(std::string::npos, s.r.message.find("not converged")) << s.r.message;
    EXPECT_LE(s.r.lo.x, std::sqrt(2.0));
    EXPECT_GE(s.r.hi.x, std::sqrt(2.0));
    EXPECT_GT(s.r.hi.x - s.r.lo.x, opt.tolerance);
  }
}

// A non-finite value of f ends the search: Failed, the last valid bracket, a message naming the
// point; the failing point is the last call.  Here f = x - 0.8 below 0.55 and non-finite above,
// on [0, 1] with the end values -0.8 and 0.2 given: the first (secant) step goes to 0.8.
TEST(Brent, NonFiniteValueFails) {
  for (double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    std::vector<double> xs;
    auto f = [&xs, bad](double x) {
      xs.push_back(x);
      return x < 0.55 ? x - 0.8 : bad;
    };
    const BrentResult r = brent_zero(std::ref(f), 0.0, -0.8, 1.0, 0.2);
    EXPECT_EQ(Status::Failed, r.status);
    EXPECT_FALSE(r.converged);
    EXPECT_EQ(1, r.evaluations);
    ASSERT_EQ(1u, xs.size());
    EXPECT_NE(std::string::npos, r.message.find("0.8")) << r.message;
    EXPECT_NE(std::string::npos, r.message.find("not finite")) << r.message;
    EXPECT_EQ(0.0, r.lo.x);
    EXPECT_EQ(1.0, r.hi.x);
    EXPECT_EQ(1, r.root.index);  // the better end, |0.2| < |-0.8|
  }
}

// The caller's per-point state (as find_critical keeps a tracker per trial mu): stored by the
// callable under the call number and recovered through BrentPoint::index for the root and for
// the positive end of the bracket, with no further evaluation.
TEST(Brent, CallerStateThroughPointIndices) {
  struct State {
    double x;
    bool unstable;
  };
  std::vector<State> states = {{0.0, false}, {1.0, true}};  // indices 0 (a) and 1 (b)
  auto f = [&states](double x) {
    const double v = std::tanh(8.0 * (x - 0.61)) + 0.05 * x;  // root near 0.6056
    states.push_back({x, v > 0.0});
    return v;
  };
  const double fa = std::tanh(8.0 * (0.0 - 0.61)), fb = std::tanh(8.0 * 0.39) + 0.05;
  BrentOptions opt;
  opt.tolerance = 1e-12;
  const BrentResult r = brent_zero(std::ref(f), 0.0, fa, 1.0, fb, opt);
  ASSERT_EQ(Status::Ok, r.status);
  ASSERT_EQ(static_cast<std::size_t>(r.evaluations) + 2, states.size());
  EXPECT_EQ(r.root.x, states.at(r.root.index).x);
  EXPECT_EQ(r.positive().x, states.at(r.positive().index).x);
  EXPECT_TRUE(states.at(r.positive().index).unstable || r.positive().f == 0.0);
  EXPECT_FALSE(states.at(r.negative().index).unstable);
  EXPECT_LE(r.hi.x - r.lo.x, opt.tolerance + 4 * kEps);
}

TEST(Brent, InvalidArgumentsNameTheArgument) {
  auto f = [](double x) { return x; };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  auto name_of = [](auto&& call) -> std::string {
    try {
      call();
    } catch (const InvalidInput& e) {
      return e.name();
    }
    return "(no exception)";
  };
  EXPECT_EQ("f", name_of([&] { brent_zero(std::function<double(double)>(), -1, -1, 1, 1); }));
  EXPECT_EQ("a", name_of([&] { brent_zero(f, nan, -1, 1, 1); }));
  EXPECT_EQ("b", name_of([&] { brent_zero(f, -1, -1, inf, 1); }));
  EXPECT_EQ("fa", name_of([&] { brent_zero(f, -1, nan, 1, 1); }));
  EXPECT_EQ("fb", name_of([&] { brent_zero(f, -1, -1, 1, -inf); }));
  EXPECT_EQ("fb", name_of([&] { brent_zero(f, -1, 2, 1, 1); }));    // same sign, positive
  EXPECT_EQ("fb", name_of([&] { brent_zero(f, -1, -2, 1, -1); }));  // same sign, negative
  for (double tol : {0.0, -1e-9, nan, inf}) {
    BrentOptions opt;
    opt.tolerance = tol;
    EXPECT_EQ("tolerance", name_of([&] { brent_zero(f, -1, -1, 1, 1, opt); })) << tol;
  }
  for (int max : {0, -3}) {
    BrentOptions opt;
    opt.max_evaluations = max;
    EXPECT_EQ("max_evaluations", name_of([&] { brent_zero(f, -1, -1, 1, 1, opt); })) << max;
  }
}

}  // namespace
}  // namespace flaplag::brent_test
