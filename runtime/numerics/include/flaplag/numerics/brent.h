// flaplag — Brent's method (zeroin: R. P. Brent, Algorithms for Minimization without
// Derivatives, 1973, ch. 4) for a sign change of a scalar function inside a bracket.
//
// Inverse quadratic interpolation or the secant step where they make progress, bisection where
// they do not.  Superlinear on a smooth simple root (far fewer evaluations than bisection);
// linear on a multiple root (about three evaluations per halving on a triple root); O(k^2)
// evaluations in the worst case for the k bisections the tolerance needs (such functions exist:
// G. Wilkins, M. Gu, Numer. Math. 2013), hence the cap max_evaluations.
// f need not be continuous: the result is always a bracket [lo, hi] across which f changes
// sign (a root of a continuous f, or the jump of a discontinuous one).
//
// The iteration is the one find_critical (continuation.cc) runs inline: the same trial points
// for the same f, bracket and tolerance.
//
// The caller that keeps per-point state (e.g. a copy of an exponent tracker for each trial mu)
// can store it inside f, keyed by the call number: BrentPoint::index says which evaluated point
// every end of the result is, so the caller can recover the state at the root estimate and at
// the bracket end on the positive side without evaluating again.
#pragma once

#include <climits>
#include <functional>
#include <optional>
#include <string>

#include "flaplag/core/outcome.h"
#include "flaplag/core/validation.h"

namespace flaplag {

struct BrentOptions {
  static constexpr Range kToleranceRange{{0.0, kUnbounded, true, false}, "finite and > 0"};
  static constexpr Range kEvaluationsRange{{1, INT_MAX, false, false}, ">= 1"};
  double tolerance = 1e-10;   // absolute tolerance on the root (> 0)
  int max_evaluations = 100;  // calls of f that brent_zero may make (>= 1)
  std::optional<InvalidInput> Validate() const;
  bool IsValid(std::string* error) const { return IsValidReport(Validate(), error); }
  void Check() const { ThrowIfInvalid(Validate()); }
};

// A point at which f is known.  index: 0 = a and 1 = b (the ends passed in), k >= 2 = the
// (k - 1)-th call of f made by brent_zero.
struct BrentPoint {
  double x = 0.0;
  double f = 0.0;
  int index = -1;
};

struct BrentResult : Outcome {
  // Ok: converged (hi.x - lo.x <= tolerance + 4 eps |root.x|, or f(root.x) == 0).
  // Warning: max_evaluations reached first; the bracket is still valid, only wider.
  // Failed: f returned a non-finite value (the message says where); the bracket is the last
  // valid one, and the failing point is the last call of f (index evaluations + 1).
  BrentResult() { status = Status::Failed; }  // until brent_zero says otherwise
  bool converged = false;                     // status == Ok
  // The best estimate (zeroin's b): one of the bracket ends, the one with the smaller |f|.
  BrentPoint root;
  // The final bracket, lo.x <= hi.x: f(lo) and f(hi) have opposite signs or one is zero.
  BrentPoint lo, hi;
  int evaluations = 0;  // calls of f made

  // The bracket end with the larger f: f > 0 (or f == 0 when the other end is negative).
  const BrentPoint& positive() const { return lo.f > hi.f ? lo : hi; }
  const BrentPoint& negative() const { return lo.f > hi.f ? hi : lo; }
};

// A sign change of f in the bracket [a, b] (either order), given fa = f(a) and fb = f(b) of
// opposite signs or with one of them zero (then that end is the root, with no call of f).
// f is called only at points strictly inside (a, b), through a copy of the std::function (pass
// std::ref(callable) to keep the state of a callable that stores it in itself).  Throws
// InvalidInput, naming the argument, if f is empty, a, b, fa or fb is not finite, fa and fb
// have the same sign, tolerance is not finite and > 0, or max_evaluations < 1.
BrentResult brent_zero(const std::function<double(double)>& f, double a, double fa, double b,
                       double fb, const BrentOptions& opt = {});

}  // namespace flaplag
