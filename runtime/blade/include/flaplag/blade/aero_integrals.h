// flaplag — the aerodynamic spanwise integrals of a model for one blade, as the runtime uses them.
//
// Each integral  I_j = int x^p prod(factors) dx0  (model_api.h AeroIntegral) is needed over the
// whole aerodynamic span (normal flow) and, inside the reversed-flow sector, split at the station
// x = mu where the flow reverses (Appendix D, eqs D.3-D.6).  The split point moves with mu, so
// the integrands are interpolated once at Chebyshev-Gauss-Lobatto points (degree kDegree) and
// integrated exactly: a reversed-sector evaluation is one Clenshaw sum per integral instead of a
// quadrature.  A blade table's stations inside the span cut it into pieces interpolated apart
// (its distributions have corners there).  Exact (to rounding) for the assumed-mode polynomials;
// for exact modes the interpolation error is far below 1e-13 (tests/aero_integrals_test.cpp checks
// both against the Gauss quadrature of aero_integral() in blade.h).
#pragma once

#include <vector>

#include "flaplag/blade/blade.h"
#include "flaplag/model_api.h"

namespace flaplag {

class AeroIntegrals {
 public:
  static constexpr int kDegree = 48;

  AeroIntegrals() = default;
  // Throws InvalidInput for an invalid geometry (see blade.h) or a factor naming a missing mode.
  AeroIntegrals(const model::ModelDescriptor& m, const ModeSet& modes, const SpanGeometry& g);

  // Normal-flow values, int_A^B, in the order of the model's AeroIntegral list.
  const std::vector<double>& normal() const { return normal_; }

  // Values inside the reversed-flow sector at advance ratio mu (>= 0, finite; else
  // InvalidInput("mu", ...)):  -int_A^{x0} + int_{x0}^B with x0 = (mu - e1)/lr clamped to
  // [A, B] for mu < 1 (eqs D.3-D.4), and -int_A^B for mu >= 1 (eqs D.5-D.6).
  void reversed(double mu, std::vector<double>& out) const;
  std::vector<double> reversed(double mu) const;
  // The first `count` of them only (0 <= count <= the model's integrals); the others NaN.
  void reversed(double mu, std::vector<double>& out, int count) const;

  // int_A^s of every integrand, s clamped to [A, B].
  void partial(double s, std::vector<double>& out) const;
  // The first `count` integrals only, the others NaN (the same bits as partial() for those).
  void partial(double s, std::vector<double>& out, int count) const;

 private:
  // A stretch [lo, hi] of the aerodynamic span between corners of the blade's distributions
  // (one piece, [A, B], for a smooth blade).
  struct Piece {
    double lo, hi;
    int terms;                  // Chebyshev terms of the antiderivatives
    std::size_t offset;         // of its coefficients in coef_
    std::vector<double> start;  // int_A^lo of every integrand
  };
  void add_piece(const model::ModelDescriptor& m, const ModeSet& modes, const SpanGeometry& g,
                 const Piece& piece, int degree);

  double a_ = 0.0, b_ = 1.0, e1_ = 0.0, lr_ = 1.0;
  // Chebyshev coefficients of the antiderivatives per piece, of the integrals that do not
  // vanish identically (live_, ascending), term-major: coefficient i of live_[k] at
  // coef_[offset + i * live_.size() + k], so that partial() runs the Clenshaw recurrences of all
  // integrals side by side (independent chains instead of one latency-bound chain per
  // integral).  Piece::start holds the live integrals too.
  std::vector<double> coef_;
  std::vector<Piece> pieces_;
  std::vector<int> live_;
  int count_ = 0;
  std::vector<double> normal_;
};

}  // namespace flaplag
