// flaplag — the inflow model: the inflow ratio lambda (positive down, by Omega R) at which the
// rotor is evaluated at each advance ratio mu.
//   Uniform (the paper, eq 2.24): the hover blade-element momentum inflow at the collective
//     theta, held at every mu.
//   Momentum (eq 2.25): lambda(mu) = mu tan alpha_R + C_T / (2 sqrt(mu^2 + lambda^2)) for a
//     given thrust coefficient C_T and shaft angle alpha_R (sqrt(C_T / 2) in hover): the inflow of
//     a rotor producing C_T, at every mu.  A trim solves it with its target C_T.
//   Given: one lambda at every mu (a trim's inflow, OperatingCondition::At).
// The derivation and the choice between them: docs/trim.md.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <tuple>

#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/fields.h"
#include "flaplag/core/validation.h"
#include "flaplag/rotor/parameters.h"

namespace flaplag {

enum class InflowKind { Uniform, Momentum, Given };

constexpr auto describe(Tag<InflowKind>) {
  return std::array<EnumName<InflowKind>, 3>{{{InflowKind::Uniform, "uniform"},
                                              {InflowKind::Momentum, "momentum"},
                                              {InflowKind::Given, "given"}}};
}

struct InflowModel {
  InflowKind kind = InflowKind::Uniform;
  double thrust_coefficient = 0.0;  // Momentum: C_T > 0
  double shaft_angle = 0.0;         // Momentum: alpha_R [rad], forward tilt positive
  double lambda_given = 0.0;        // Given: lambda
  // The admissible thrust coefficients and shaft angles (also a trim's: trim.h).
  static constexpr Range kThrustRange{{0.0, 0.1, true, false}, "in (0, 0.1] (C_T, not C_T/sigma)"};
  static constexpr Range kShaftAngleRange{{-kHalfPi, kHalfPi, true, true}, "in (-pi/2, pi/2)"};

  static InflowModel Uniform() { return {}; }
  static InflowModel Momentum(double thrust_coefficient, double shaft_angle) {
    InflowModel m;
    m.kind = InflowKind::Momentum;
    m.thrust_coefficient = thrust_coefficient;
    m.shaft_angle = shaft_angle;
    return m;
  }
  static InflowModel Given(double lambda) {
    InflowModel m;
    m.kind = InflowKind::Given;
    m.lambda_given = lambda;
    return m;
  }

  // Whether lambda depends on mu (Momentum); the others hold one lambda at every mu.
  bool varies_with_mu() const { return kind == InflowKind::Momentum; }
  // lambda at mu >= 0 for the rotor p (Uniform: hover_inflow(p), which needs a valid p).
  // Throws InvalidInput for a model that is not Validate()d, a bad mu, or a Momentum root that
  // does not converge (named "inflow").
  double lambda(const RotorParameters& p, double mu) const;
  // InvalidInput naming the first bad field: a Given lambda not finite ("inflow"); a Momentum
  // C_T or shaft angle outside the ranges above.
  std::optional<InvalidInput> Validate() const;
  bool IsValid(std::string* error) const { return IsValidReport(Validate(), error); }
  void Check() const { ThrowIfInvalid(Validate()); }
};

// The model's table: front ends set it by these rows (Python's options_from) and name its
// fields by them in messages.
constexpr auto describe(Tag<InflowModel>) {
  using M = InflowModel;
  return std::make_tuple(
      Option{"kind", &M::kind, "",
             "uniform (eq 2.24, held at every mu), momentum (eq 2.25 at every mu) or given"},
      Option{"thrust_coefficient", &M::thrust_coefficient, "-",
             "momentum: the thrust coefficient C_T of eq 2.25", &M::kThrustRange},
      Option{"shaft_angle", &M::shaft_angle, "rad", "momentum: the shaft angle alpha_R of eq 2.25",
             &M::kShaftAngleRange},
      Option{"lambda_given", &M::lambda_given, "-", "given: the inflow ratio lambda"});
}

// Solves eq 2.25 for lambda given C_T > 0 and mu >= 0 (the root in (mu tan alpha_R, mu tan
// alpha_R + C_T/(2 mu)] for mu > 0; sqrt(C_T/2) at mu = 0).  NaN when the root is not found.
double momentum_inflow(double thrust_coefficient, double mu, double shaft_angle);

}  // namespace flaplag
