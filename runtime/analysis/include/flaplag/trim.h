// flaplag — rotor thrust and trim: the collective and cyclic pitch and the inflow that give a
// prescribed thrust coefficient C_T (not C_T/sigma), and (moment trim) no first-harmonic flap.
// The thrust is the model's own (the flap load of its derivation, integrated over the span, at
// the hover equilibrium plus the periodic response; about the periodic equilibrium, along q°);
// a trim's inflow is eq 2.25 with the target C_T, not the paper's eq 2.24; the controls come
// from Newton's method with Broyden updates.  Derivation, formulas and choices: docs/trim.md.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <atomic>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "flaplag/core/constants.h"
#include "flaplag/core/outcome.h"
#include "flaplag/core/parallel.h"
#include "flaplag/numerics/continuation.h"
#include "flaplag/numerics/floquet.h"
#include "flaplag/numerics/response.h"
#include "flaplag/rotor/inflow.h"
#include "flaplag/rotor/parameters.h"
#include "flaplag/rotor/periodic_equilibrium.h"

namespace flaplag {

enum class TrimKind { None, Thrust, Moment };
const char* trim_kind_name(TrimKind k);  // "none", "thrust", "moment"
constexpr auto describe(Tag<TrimKind>) {
  return std::array<EnumName<TrimKind>, 3>{
      {{TrimKind::None, "none"}, {TrimKind::Thrust, "thrust"}, {TrimKind::Moment, "moment"}}};
}
// false when `name` is none of them.
bool trim_kind_from_name(std::string_view name, TrimKind* kind);

// The solution the equations of motion are linearized about (part of an operating condition,
// analysis.h OperatingCondition): the hover equilibrium q0 (the paper) or the periodic
// equilibrium q°(psi) of the nonlinear equations (rotor/periodic_equilibrium.h; harmonic balance
// continued in mu from hover, every model has the nonlinear loads).  A trim about the periodic
// equilibrium trims q° itself (its thrust and first flap harmonic).
enum class Linearization { HoverEquilibrium, PeriodicEquilibrium };
constexpr auto describe(Tag<Linearization>) {
  return std::array<EnumName<Linearization>, 2>{{{Linearization::HoverEquilibrium, "hover"},
                                                 {Linearization::PeriodicEquilibrium, "periodic"}}};
}

struct TrimOptions {
  static constexpr Range kThrustRange = InflowModel::kThrustRange;
  static constexpr Range kShaftAngleRange = InflowModel::kShaftAngleRange;
  static constexpr Range kIterationsRange{{1, 1000, false, false}, "1..1000"};
  static constexpr Range kEvaluationsRange{{1, 1000000, false, false}, "1..1000000"};
  static constexpr Range kToleranceRange{{0.0, 1e-3, true, false}, "in (0, 1e-3]"};
  TrimKind kind = TrimKind::None;
  double thrust_coefficient = 0.005;  // target C_T (not C_T / sigma), in (0, 0.1]
  double shaft_angle = 0.0;           // alpha_R of eq 2.25 [rad], in (-pi/2, pi/2)
  int max_iterations = 30;            // Newton iterations, 1..1000
  // Evaluations of the rotor's thrust (each a periodic response; about q° a harmonic balance as
  // well) that one trim(), its continuation in mu included, may make, 1..1000000; then status
  // Failed, naming the last mu the continuation trimmed.  A converging Newton solve takes 5 to
  // 50; the examples' trims take at most 668 (the moment trim of trim-study.toml at gamma = 8,
  // mu = 0.79, where the branch turns).  The bound keeps a trim without a solution from trying
  // halved steps of mu without end; it bounds their number, not their cost (at extreme mu a
  // single periodic response can take a second).
  int max_evaluations = 1000;
  // Converged when |C_T - target| <= tolerance * target and (moment) |flap 1c|, |flap 1s| <=
  // tolerance (tip deflection by l), in (0, 1e-3].
  double tolerance = 1e-13;
  ResponseOptions response;  // for the periodic response inside the thrust and the moment
  std::optional<InvalidInput> Validate() const;
  bool IsValid(std::string* error) const { return IsValidReport(Validate(), error); }
  void Check() const { ThrowIfInvalid(Validate()); }
};

constexpr auto describe(Tag<TrimOptions>) {
  using O = TrimOptions;
  return std::make_tuple(
      Option{"kind", &O::kind, "",
             "none, thrust (theta0 and lambda) or moment (also theta1c, theta1s)"},
      Option{"thrust_coefficient", &O::thrust_coefficient, "-", "target thrust coefficient",
             &O::kThrustRange},
      Option{"shaft_angle", &O::shaft_angle, "rad", "shaft angle alpha_R of eq 2.25",
             &O::kShaftAngleRange},
      Option{"max_iterations", &O::max_iterations, "", "Newton iterations", &O::kIterationsRange},
      Option{"max_evaluations", &O::max_evaluations, "",
             "thrust evaluations one trim may make, its continuation in mu included",
             &O::kEvaluationsRange},
      Option{"tolerance", &O::tolerance, "-",
             "on C_T relative to the target and (moment) on the first flap harmonic",
             &O::kToleranceRange},
      Option{"response", &O::response, "", "the periodic response inside the thrust"});
}

// The model's thrust at one operating point.
struct ThrustResult : Outcome {
  double mu = 0.0;
  double inflow = 0.0;                  // lambda used
  double thrust_coefficient = 0.0;      // C_T of the model's own lift distribution (docs/trim.md)
  double flap_1c = 0.0, flap_1s = 0.0;  // first harmonic of the flap tip deflection, by l
  // Outcome: Failed: no periodic response (a multiplier at 1)
};

constexpr auto describe(Tag<ThrustResult>) {
  return std::tuple_cat(
      std::make_tuple(
          Field{"mu", &ThrustResult::mu, "-", "the advance ratio"},
          Field{"inflow", &ThrustResult::inflow, "-", "the inflow ratio lambda used"},
          Field{"thrust_coefficient", &ThrustResult::thrust_coefficient, "-",
                "C_T of the model's own lift distribution (azimuth mean; not C_T/sigma)"},
          Field{"flap_1c", &ThrustResult::flap_1c, "-",
                "first flap tip harmonic, cos psi part (w/l)"},
          Field{"flap_1s", &ThrustResult::flap_1s, "-",
                "first flap tip harmonic, sin psi part (w/l)"}),
      describe(Tag<Outcome>{}));
}

// C_T at mu with inflow lambda (NaN: eq 2.24) and p's pitch.  p.model must emit the thrust
// (a cyclic-pitch model), else InvalidInput("model", ...); p is validated.  `about`: the
// periodic response about hover (the default) or, PeriodicEquilibrium, along q°.
ThrustResult rotor_thrust(const RotorParameters& p, double mu, double inflow,
                          const ResponseOptions& response = {},
                          Linearization about = Linearization::HoverEquilibrium);
// C_T at mu with p's pitch and the inflow of eq 2.25 for that same C_T (solved together):
// the thrust the rotor actually produces at this pitch.
ThrustResult rotor_thrust_momentum(const RotorParameters& p, double mu, double shaft_angle,
                                   const ResponseOptions& response = {},
                                   Linearization about = Linearization::HoverEquilibrium);

struct TrimResult : Outcome {
  double mu = 0.0;
  TrimKind kind = TrimKind::None;
  double theta0 = 0.0, theta1c = 0.0, theta1s = 0.0;  // [rad]
  double inflow = 0.0;                                // lambda, eq 2.25
  double thrust_coefficient = 0.0;                    // C_T achieved
  double target = 0.0;                                // C_T asked for
  double flap_1c = 0.0, flap_1s = 0.0;                // first flap tip harmonic at the trim
  int iterations = 0;
  int evaluations = 0;         // thrust evaluations of the whole trim() (at most max_evaluations)
  RotorParameters parameters;  // the input with theta, theta1c, theta1s trimmed
  // What was trimmed: the rotor linearized about hover, or (PeriodicEquilibrium) q° itself.
  Linearization linearization = Linearization::HoverEquilibrium;
  bool converged = false;  // the residual met `tolerance`
  // Jacobian of the residual [(C_T - target)/target, flap 1c, flap 1s] in (theta0, theta1c,
  // theta1s) at the end (Broyden-updated): a warm start for a neighbouring mu.
  Eigen::MatrixXd jacobian;
  // About the periodic equilibrium: the periodic equilibrium q° at the trim (its
  // linearization included), whose thrust and first flap harmonic were trimmed; empty
  // coefficients otherwise.
  PeriodicEquilibrium equilibrium;
  // "" when the trimmed controls, inflow and hover flap deflection are inside the validity
  // envelope of the ordering models (rotor/validity.h); otherwise what lies outside (by name,
  // value and limit), also in `message` with status (at least) Warning.
  std::string validity;
  // Ok: converged.  Warning: converged but the trimmed system is unstable (the periodic
  // solution is not what the blade settles to), max_iterations reached (converged false;
  // the last iterate is reported), or outside the validity envelope.  Failed: no periodic
  // response, a Jacobian that does not reduce the residual (singular or unreachable target), a
  // pitch outside (-pi/2, pi/2).
};

// The periodic equilibrium a trim rests on, in a TrimResult's table (`equilibrium`).
struct TrimEquilibrium {
  int harmonics = 0;        // K
  double truncation = 0.0;  // PeriodicEquilibrium::truncation
};

constexpr auto describe(Tag<TrimEquilibrium>) {
  return std::make_tuple(
      Field{"harmonics", &TrimEquilibrium::harmonics, "", "K, the harmonics of q°"},
      Field{"truncation", &TrimEquilibrium::truncation, "-",
            "amplitude of harmonic K of q° relative to its largest coefficient"});
}

// The table of a trim: the controls and what they achieve (not the Jacobian, the parameters or
// the equilibrium itself, which are for the library's callers).
constexpr auto describe(Tag<TrimResult>) {
  return std::tuple_cat(
      std::make_tuple(
          Field{"mu", &TrimResult::mu, "-", "the advance ratio"},
          Field{"kind", &TrimResult::kind, "",
                "thrust (theta0 for C_T; theta1c, theta1s as given) or moment (theta0, theta1c, "
                "theta1s for C_T and no first flap harmonic)"},
          Field{"theta0", &TrimResult::theta0, "rad", "the trimmed collective pitch"},
          Field{"theta1c", &TrimResult::theta1c, "rad", "the trimmed cyclic pitch, cos psi part"},
          Field{"theta1s", &TrimResult::theta1s, "rad", "the trimmed cyclic pitch, sin psi part"},
          Field{"inflow", &TrimResult::inflow, "-", "the inflow ratio lambda (eq 2.25)"},
          Field{"thrust_coefficient", &TrimResult::thrust_coefficient, "-",
                "C_T achieved (the model's own lift, azimuth mean; not C_T/sigma)"},
          Field{"target", &TrimResult::target, "-", "C_T asked for"},
          Field{"flap_1c", &TrimResult::flap_1c, "-",
                "first flap tip harmonic at the trim, cos psi part (w/l)"},
          Field{"flap_1s", &TrimResult::flap_1s, "-",
                "first flap tip harmonic at the trim, sin psi part (w/l)"},
          Field{"iterations", &TrimResult::iterations, "", "Newton iterations"},
          Field{"converged", &TrimResult::converged, "", "the residual met the tolerance"},
          Computed{"equilibrium",
                   +[](const TrimResult& t) {
                     return t.linearization == Linearization::PeriodicEquilibrium
                                ? std::optional<TrimEquilibrium>(TrimEquilibrium{
                                      t.equilibrium.harmonics, t.equilibrium.truncation})
                                : std::nullopt;
                   },
                   "",
                   "the periodic equilibrium trimmed about (periodic linearization only; JSON: "
                   "absent otherwise)",
                   kFieldOmitWhenEmpty}),
      describe(Tag<Outcome>{}));
}

// What is wrong with a trim that a result at its mu rests on: "" for a converged trim inside
// the validity envelope; else its message (not converged, failed) or what lies outside the
// envelope.  (An unstable trimmed system is no problem of the trim: the exponents say so.)
std::string trim_problem(const TrimResult& t);

// o.Check() first; o.kind must not be None.  p.model must emit the thrust (InvalidInput
// "model").  mu in [0, kMaxAdvanceRatio].
// start: a previous trim (e.g. at a neighbouring mu) whose controls and Jacobian start the
// Newton iteration; nullptr: blade-element estimate and a finite-difference Jacobian.
// about: the thrust and flap harmonic of the periodic response about hover (the default), or
// (PeriodicEquilibrium) of q°, which is then trimmed and kept in the result's `equilibrium`;
// the sector only (InvalidInput "exact_reversed_flow").
TrimResult trim(const RotorParameters& p, double mu, const TrimOptions& o,
                const TrimResult* start = nullptr,
                Linearization about = Linearization::HoverEquilibrium);

// Stability at fixed C_T (every mu trimmed first): Analysis with OperatingCondition::Trimmed
// (analysis.h); its results carry the trims they rest on.

}  // namespace flaplag
