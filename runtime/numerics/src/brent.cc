// flaplag — Brent's zeroin (see brent.h).  The iteration is Brent's (1973) ALGOL procedure
// zero, in the form of Numerical Recipes' zbrent: b is the best estimate, c the opposite end of
// the bracket, a the previous b.
#include "flaplag/numerics/brent.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"

namespace flaplag {
namespace {

void require_finite(const char* name, double v) {
  if (!std::isfinite(v)) throw InvalidInput(name, round_trip_text(v), "must be finite");
}

}  // namespace

std::optional<InvalidInput> BrentOptions::Validate() const {
  return Requirements()
      .InRange("tolerance", tolerance, kToleranceRange)
      .InRange("max_evaluations", max_evaluations, kEvaluationsRange)
      .Result();
}

BrentResult brent_zero(const std::function<double(double)>& f, double a, double fa, double b,
                       double fb, const BrentOptions& opt) {
  if (!f) throw InvalidInput("f", "empty", "a function is required");
  require_finite("a", a);
  require_finite("b", b);
  require_finite("fa", fa);
  require_finite("fb", fb);
  if ((fa > 0.0 && fb > 0.0) || (fa < 0.0 && fb < 0.0))
    throw InvalidInput("fb", round_trip_text(fb),
                       "must have the opposite sign of fa = " + round_trip_text(fa) +
                           " (or one be zero): [a, b] does not bracket a sign change");
  opt.Check();

  BrentResult out;
  BrentPoint pa{a, fa, 0}, pb{b, fb, 1}, pc = pa;
  double d = b - a, e = d;
  const double eps = std::numeric_limits<double>::epsilon();
  auto finish = [&](Status status, std::string message) {
    out.status = status;
    out.converged = status == Status::Ok;
    out.message = std::move(message);
    out.root = pb;
    out.lo = pb.x <= pc.x ? pb : pc;
    out.hi = pb.x <= pc.x ? pc : pb;
    return out;
  };
  for (;;) {
    // c: the end of the bracket opposite to b (a sign change between b and c).
    if ((pb.f > 0.0) == (pc.f > 0.0)) {
      pc = pa;
      d = e = pb.x - pa.x;
    }
    // b: the end with the smaller |f|.
    if (std::abs(pc.f) < std::abs(pb.f)) {
      pa = pb;
      pb = pc;
      pc = pa;
    }
    const double tol1 = 2.0 * eps * std::abs(pb.x) + 0.5 * opt.tolerance;
    const double xm = 0.5 * (pc.x - pb.x);
    if (std::abs(xm) <= tol1 || pb.f == 0.0)
      return finish(Status::Ok, "root " + short_text(pb.x) + " after " +
                                    std::to_string(out.evaluations) + " evaluations");
    if (out.evaluations >= opt.max_evaluations)
      return finish(Status::Warning, "not converged after " + std::to_string(out.evaluations) +
                                         " evaluations: bracket [" +
                                         short_text(std::min(pb.x, pc.x)) + ", " +
                                         short_text(std::max(pb.x, pc.x)) + "]");
    if (std::abs(e) >= tol1 && std::abs(pa.f) > std::abs(pb.f)) {
      // Inverse quadratic interpolation through a, b, c (the secant when a == c).
      const double s = pb.f / pa.f;
      double p, q;
      if (pa.x == pc.x) {
        p = 2.0 * xm * s;
        q = 1.0 - s;
      } else {
        const double qa = pa.f / pc.f, r = pb.f / pc.f;
        p = s * (2.0 * xm * qa * (qa - r) - (pb.x - pa.x) * (r - 1.0));
        q = (qa - 1.0) * (r - 1.0) * (s - 1.0);
      }
      if (p > 0.0) q = -q;
      p = std::abs(p);
      // Accept the interpolation only inside the bracket and if it shrinks faster than the
      // step before last; otherwise bisect.
      if (2.0 * p < std::min(3.0 * xm * q - std::abs(tol1 * q), std::abs(e * q))) {
        e = d;
        d = p / q;
      } else {
        d = e = xm;
      }
    } else {
      d = e = xm;
    }
    pa = pb;
    const double next = pb.x + (std::abs(d) > tol1 ? d : (xm > 0.0 ? tol1 : -tol1));
    const double fnext = f(next);
    ++out.evaluations;
    if (!std::isfinite(fnext))
      return finish(Status::Failed,
                    "f(" + short_text(next) + ") = " + round_trip_text(fnext) + " is not finite");
    pb = {next, fnext, out.evaluations + 1};
  }
}

}  // namespace flaplag
