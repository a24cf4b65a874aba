// flaplag — the inflow models (inflow.h): eq 2.24 held, eq 2.25 at every mu, or a given lambda.
#include "flaplag/rotor/inflow.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "flaplag/core/format.h"
#include "flaplag/numerics/brent.h"
#include "flaplag/numerics/continuation.h"

namespace flaplag {

std::optional<InvalidInput> InflowModel::Validate() const {
  switch (kind) {
    case InflowKind::Uniform:
      return std::nullopt;
    case InflowKind::Momentum:
      return Requirements()
          .InRange("thrust_coefficient", thrust_coefficient, kThrustRange)
          .InRange("shaft_angle", shaft_angle, kShaftAngleRange)
          .Result();
    case InflowKind::Given:
      return Requirements()
          .Require(std::isfinite(lambda_given),
                   [&] {
                     return InvalidInput("inflow", round_trip_text(lambda_given),
                                         "must be a finite number");
                   })
          .Result();
  }
  return std::nullopt;
}

double InflowModel::lambda(const RotorParameters& p, double mu) const {
  ThrowIfInvalid(Validate());
  switch (kind) {
    case InflowKind::Uniform:
      return hover_inflow(p);
    case InflowKind::Given:
      return lambda_given;
    case InflowKind::Momentum: {
      const double lam = momentum_inflow(thrust_coefficient, mu, shaft_angle);
      if (!std::isfinite(lam))
        throw InvalidInput("inflow", "eq 2.25 at mu = " + round_trip_text(mu),
                           "the momentum inflow did not converge");
      return lam;
    }
  }
  return hover_inflow(p);
}

double momentum_inflow(double ct, double mu, double alpha) {
  if (!(std::isfinite(ct) && ct > 0.0)) {
    throw InvalidInput("thrust_coefficient", round_trip_text(ct), "must be > 0");
  }
  if (!std::isfinite(mu) || mu < 0.0 || mu > kMaxAdvanceRatio) {
    throw InvalidInput("mu", round_trip_text(mu),
                       "advance ratio must be >= 0 and <= " + round_trip_text(kMaxAdvanceRatio));
  }
  if (!(std::isfinite(alpha) && std::abs(alpha) < kHalfPi)) {
    throw InvalidInput("shaft_angle", round_trip_text(alpha), "must be in (-pi/2, pi/2)");
  }
  if (mu == 0.0) return std::sqrt(0.5 * ct);  // lambda = C_T / (2 |lambda|), lambda > 0
  const double base = mu * std::tan(alpha);
  // Where mu^2 underflows (mu below ~1.5e-154) or C_T / (2 mu) overflows, |(mu, lambda)| is
  // taken by hypot and the bracket by the bound below; elsewhere the plain forms (the same bits
  // as always).
  const bool tiny = mu * mu == 0.0 || !std::isfinite(ct / (2.0 * mu));
  auto norm = [&](double lam) {
    return tiny ? std::hypot(mu, lam) : std::sqrt(mu * mu + lam * lam);
  };
  auto f = [&](double lam) { return lam - base - ct / (2.0 * norm(lam)); };
  // f(base) < 0 and f(base + u) > 0 for any u above the induced part at the root, which is at
  // most C_T / (2 mu), since |(mu, lambda)| >= mu, and at most |base| + sqrt(C_T / 2), since
  // |(mu, lambda)| >= |lambda| >= u - |base| (doubled: at the bound itself f may round to -0).
  BrentOptions bo;
  bo.tolerance = 1e-17;
  bo.max_evaluations = 400;
  // The tighter of the two bounds: C_T / (2 mu) alone is astronomically wide for a small mu
  // (2e147 at mu = 1e-150, beyond Brent's evaluations).  Where f(base) is not finite (tiny mu:
  // C_T / 0), the lower end is base + sqrt(C_T / 2) / 4, where f < 0 still: there
  // 2 u |(mu, lambda)| <= 2 u (mu + |base| + u) < C_T.
  const double hover = std::sqrt(0.5 * ct);
  const double lo = tiny ? base + 0.25 * hover : base,
               hi = base + std::min(ct / (2.0 * mu), 2.0 * (std::abs(base) + hover));
  const double flo = f(lo), fhi = f(hi);
  if (fhi == 0.0) return hi;
  const BrentResult r = brent_zero(f, lo, flo, hi, fhi, bo);
  // Polish with Newton: the bracket tolerance is below rounding, one step fixes the last bit.
  double lam = r.root.x;
  for (int i = 0; i < 3; ++i) {
    const double s = norm(lam);
    const double d = 1.0 + ct * lam / (2.0 * s * s * s);
    const double step = f(lam) / d;
    if (!std::isfinite(step)) break;
    lam -= step;
  }
  // Not a root (Brent out of evaluations, say): NaN, which the trim reports as failed.
  if (!(std::abs(f(lam)) <= 1e-12 * std::max(1.0, std::abs(lam))))
    return std::numeric_limits<double>::quiet_NaN();
  return lam;
}

}  // namespace flaplag
