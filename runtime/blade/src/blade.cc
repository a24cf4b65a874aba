// flaplag — assumed mode (eq 4.1), nonrotating cantilever modes and the assumed-mode ModeSet.
#include "flaplag/blade/blade.h"

#include <cmath>
#include <string>

#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"

namespace flaplag {
namespace {

// Eq 4.1, eta = -(1/3) [1 - 4 x0 - (1 - x0)^4], and its derivatives written in powers of
// (1 - x0) so that the free-end conditions eta''(1) = eta'''(1) = 0 hold exactly in floating point.
class AssumedModeShape final : public ModeShape {
 public:
  double value(int d, double x0) const override {
    const double s = 1.0 - x0;
    switch (d) {
      case 0:
        return -(1.0 - 4.0 * x0 - s * s * s * s) / 3.0;
      case 1:
        return 4.0 / 3.0 * (1.0 - s * s * s);
      case 2:
        return 4.0 * s * s;
      case 3:
        return -8.0 * s;
      default:
        throw InvalidInput("derivative order", std::to_string(d), "must be 0..3");
    }
  }
};

// Clamped-free uniform beam mode j with the classical normalisation (Bishop & Johnson; Young &
// Felgar):  phi = cosh(bx) - cos(bx) - sigma (sinh(bx) - sin(bx)),
// sigma = (cosh b + cos b) / (sinh b + sin b),  int_0^1 phi^2 = 1,  phi(1) = 2 (-1)^(j+1).
//
// The hyperbolic part cosh - sigma sinh = [(1 - sigma) e^{bx} + (1 + sigma) e^{-bx}] / 2 loses all
// digits for large b x when formed directly (sigma -> 1, e^{bx} huge).  Using the frequency
// equation, (1 - sigma) e^{bx} / 2 = e^{-b (1 - x)} (sin b - cos b - e^{-b}) / D with
// D = 1 - e^{-2b} + 2 e^{-b} sin b, so every term below is O(1) and free of cancellation.
class CantileverModeShape final : public ModeShape {
 public:
  explicit CantileverModeShape(double beta) : beta_(beta) {
    const double em = std::exp(-beta);
    const double d = 1.0 - em * em + 2.0 * em * std::sin(beta);
    grow_ = (std::sin(beta) - std::cos(beta) - em) / d;  // coefficient of e^{-b(1-x)}
    const double one_minus_sigma = 2.0 * em * grow_;
    sigma_ = 1.0 - one_minus_sigma;
    decay_ = (1.0 + sigma_) / 2.0;  // coefficient of e^{-bx}
  }

  double value(int d, double x0) const override {
    if (d < 0 || d > 3) {
      throw InvalidInput("derivative order", std::to_string(d), "must be 0..3");
    }
    const double b = beta_;
    const double bx = b * x0;
    const double up = grow_ * std::exp(-b * (1.0 - x0));
    const double down = decay_ * std::exp(-bx);
    const double c = std::cos(bx);
    const double s = std::sin(bx);
    const double sign_down = (d % 2 == 0) ? 1.0 : -1.0;
    // Trigonometric part -cos + sigma sin and its derivatives divided by b^d.
    double trig = 0.0;
    switch (d) {
      case 0:
        trig = -c + sigma_ * s;
        break;
      case 1:
        trig = s + sigma_ * c;
        break;
      case 2:
        trig = c - sigma_ * s;
        break;
      default:
        trig = -s - sigma_ * c;
        break;
    }
    return std::pow(b, d) * (up + sign_down * down + trig);
  }

 private:
  double beta_;
  double sigma_ = 0.0;
  double grow_ = 0.0;
  double decay_ = 0.0;
};

constexpr int kMaxCantileverMode = 100;

void check_mode_number(int j) {
  if (j < 1 || j > kMaxCantileverMode) {
    throw InvalidInput("cantilever mode", std::to_string(j),
                       "mode number must be 1.." + std::to_string(kMaxCantileverMode));
  }
}

void check_frequency(const char* name, double omega) {
  if (!std::isfinite(omega) || omega <= 0.0) {
    throw InvalidInput(name, round_trip_text(omega),
                       "rotating frequency by Omega must be finite and positive");
  }
}

}  // namespace

std::shared_ptr<const ModeShape> assumed_mode_shape() {
  static const std::shared_ptr<const ModeShape> shape = std::make_shared<AssumedModeShape>();
  return shape;
}

double cantilever_root(int j) {
  check_mode_number(j);
  // 1 + cos b cosh b = 0 divided by cosh b: g(b) = cos b + sech b = 0.  This form neither
  // overflows nor loses the root to cancellation for large b; the roots approach (j - 1/2) pi.
  double b = (j == 1) ? 1.875 : (j - 0.5) * kPi;
  for (int it = 0; it < 50; ++it) {
    const double sech = 1.0 / std::cosh(b);
    const double g = std::cos(b) + sech;
    const double dg = -std::sin(b) - sech * std::tanh(b);
    const double step = g / dg;
    b -= step;
    if (std::abs(step) <= 1e-16 * b) break;
  }
  return b;
}

std::shared_ptr<const ModeShape> cantilever_mode(int j) {
  return std::make_shared<CantileverModeShape>(cantilever_root(j));
}

ModeSet assumed_modes(double omega_flap, double omega_lag) {
  check_frequency("omega_flap", omega_flap);
  check_frequency("omega_lag", omega_lag);
  ModeSet m;
  // One assumed mode (eq 4.1) per direction, with its first rotating frequency.
  const double omega[model::kDirectionCount] = {omega_flap, omega_lag};
  for (const model::Direction d : model::kDirections)
    m[d] = {{assumed_mode_shape()}, {omega[model::index(d)]}, 0.0};
  m.kind = "assumed";
  return m;
}

}  // namespace flaplag
