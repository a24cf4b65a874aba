// flaplag — stability analysis of the coupled flap-lag blade at advance ratio mu.
//
// Typical use (no I/O inside; safe to call in a loop):
//   flaplag::RotorParameters p;                 // the paper's typical case
//   flaplag::Analysis an(p, {});                // automatic method, fixed controls
//   auto crit = an.critical({});                // mu_c, mode, omega, kind
//   flaplag::Analysis at_ct(p, {}, flaplag::OperatingCondition::Trimmed(trim_options));
//   auto trimmed = at_ct.critical({});          // mu_c at fixed C_T; trimmed.trim: at mu_c
//
// Invalid parameters or options throw InvalidInput from the constructor, naming the field
// (RotorParameters, TransitionOptions, CriticalOptions) or the argument ("mu", "psi", ...) and
// the value.  Numerical outcomes (unstable hover, unconverged search, under-resolved transition
// matrices, ambiguous mode identification, overflow) come back with a Status and a message;
// field names inside messages are written in backticks (`steps`) so that a front end can show
// them in its own vocabulary.
//
// Accuracy: every Floquet evaluation estimates its own exponent error and resolves it to
// TransitionOptions::zeta_tolerance (numerics/floquet_evaluator.h; the rule: docs/numerics.md).
// The critical search refines mu_c with exponents resolved to 0.1 |d zeta/d mu| * tolerance and
// reports CriticalResult::mu_c_error.
#pragma once

#include <Eigen/Dense>
#include <atomic>
#include <complex>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "flaplag/blade/blade.h"
#include "flaplag/core/fields.h"
#include "flaplag/core/outcome.h"
#include "flaplag/core/parallel.h"
#include "flaplag/model_api.h"
#include "flaplag/numerics/continuation.h"
#include "flaplag/numerics/floquet.h"
#include "flaplag/numerics/floquet_evaluator.h"
#include "flaplag/numerics/periodic_system.h"
#include "flaplag/numerics/response.h"
#include "flaplag/rotor/hover.h"
#include "flaplag/rotor/parameters.h"
#include "flaplag/rotor/periodic_equilibrium.h"
#include "flaplag/trim.h"

namespace flaplag {

// What holds at every advance ratio an Analysis evaluates: the controls, the inflow and the
// solution the equations are linearized about.
//   - Fixed controls (the default, the paper): RotorParameters' theta, theta1c, theta1s and the
//     inflow model (rotor/inflow.h): eq 2.24 (the default), eq 2.25 at a given C_T at every mu,
//     or a given inflow ratio (e.g. a trim's: At()).
//   - Trimmed (trim.kind thrust or moment, Trimmed()): at every mu the rotor is trimmed first
//     (trim.h), each trim with its own eq 2.25 inflow, so mu_c is that of the rotor at fixed
//     C_T; the results carry the trims they rest on.
//   - Linearization (either condition): about the hover equilibrium (the paper, the default)
//     or about the periodic equilibrium q°(psi) of the nonlinear equations (About(); trim.h
//     Linearization).  Results about q° carry it (RotorPoint, RotorCritical; a trimmed one in
//     its trim).
struct OperatingCondition {
  TrimOptions trim;    // kind None: fixed controls
  InflowModel inflow;  // fixed controls only (a trim has its own): the default is eq 2.24
  Linearization linearization = Linearization::HoverEquilibrium;
  // The rotor trimmed at every mu with `o` (o.kind thrust or moment).
  static OperatingCondition Trimmed(const TrimOptions& o) {
    OperatingCondition c;
    c.trim = o;
    return c;
  }
  // Fixed at a trim's controls and inflow, linearized about what the trim was (its q° when it
  // trimmed the periodic equilibrium): Analysis(t.parameters, options, At(t)).
  static OperatingCondition At(const TrimResult& t) {
    OperatingCondition c;
    c.inflow = InflowModel::Given(t.inflow);
    c.linearization = t.linearization;
    return c;
  }
  // This condition linearized about `l`: OperatingCondition{}.About(PeriodicEquilibrium),
  // Trimmed(o).About(PeriodicEquilibrium).
  OperatingCondition About(Linearization l) const {
    OperatingCondition c = *this;
    c.linearization = l;
    return c;
  }
  bool trimmed() const { return trim.kind != TrimKind::None; }
  bool periodic() const { return linearization == Linearization::PeriodicEquilibrium; }
  // InvalidInput("inflow") for an inflow model other than eq 2.24 given with a trim; the inflow
  // model's and the trim's problems.  (The periodic equilibrium's own requirements, e.g. the
  // reversed-flow sector, are the Analysis's: InvalidInput "exact_reversed_flow".)
  std::optional<InvalidInput> Validate() const;
};

// The results of Analysis::point, sweep, track and critical: the numerics' results
// (numerics/continuation.h, exponents sorted by label, then by omega descending) and, for a
// trimmed rotor, the trims they rest on (a trim's problems are in the result's status).
// About the periodic equilibrium, a result carries the q° its exponents were computed about:
// at fixed controls in `equilibrium` (its coefficients, K, truncation, status and message; its
// linearization is not kept: Analysis::floquet(mu) rebuilds it), trimmed in its trim's
// `equilibrium` (not repeated).  periodic_equilibrium() finds it in either place.
struct RotorPoint : PointResult {
  std::optional<TrimResult> trim;  // trimmed: the trim at mu
  // Fixed controls about the periodic equilibrium: q° at mu (the last one evaluated there).
  std::optional<PeriodicEquilibrium> equilibrium;
  // q° the exponents rest on (equilibrium, or the trim's), or nullptr (about hover; no point).
  const PeriodicEquilibrium* periodic_equilibrium() const;
};
struct RotorSweep : SweepResult {
  std::vector<TrimResult> trims;  // trimmed: one per point, in order; else empty
  // Fixed controls about the periodic equilibrium: q° at each point, in order (the last one
  // evaluated at its mu; Failed where there is none); else empty.
  std::vector<PeriodicEquilibrium> equilibria;
};
struct RotorCritical : CriticalResult {
  std::optional<TrimResult> trim;  // trimmed: the trim at mu_c (none without mu_c)
  // Fixed controls about the periodic equilibrium: q° at mu_c; at a fold, beyond which there is
  // none, the last one found below it (equilibrium->mu < mu_c, within mu_c_error); none without
  // mu_c.
  std::optional<PeriodicEquilibrium> equilibrium;
  const PeriodicEquilibrium* periodic_equilibrium() const;  // as RotorPoint's
};

// Their tables: the numerics' result's rows, then what the analysis adds (a front end that writes
// the q° otherwise, e.g. the command line's K and truncation, takes the numerics' table).
constexpr auto describe(Tag<RotorPoint>) {
  return std::tuple_cat(
      describe(Tag<PointResult>{}),
      std::make_tuple(
          Field{"trim", &RotorPoint::trim, "", "trimmed: the trim at mu", kFieldOmitWhenEmpty},
          Field{"equilibrium", &RotorPoint::equilibrium, "",
                "about the periodic equilibrium at fixed controls: the q° at mu",
                kFieldOmitWhenEmpty}));
}
constexpr auto describe(Tag<RotorSweep>) {
  return std::tuple_cat(
      describe(Tag<SweepResult>{}),
      std::make_tuple(Field{"trims", &RotorSweep::trims, "", "trimmed: the trim at each point",
                            kFieldOmitWhenEmpty},
                      Field{"equilibria", &RotorSweep::equilibria, "",
                            "about the periodic equilibrium at fixed controls: the q° at each "
                            "point",
                            kFieldOmitWhenEmpty}));
}
constexpr auto describe(Tag<RotorCritical>) {
  return std::tuple_cat(
      describe(Tag<CriticalResult>{}),
      std::make_tuple(
          Field{"trim", &RotorCritical::trim, "", "trimmed: the trim at mu_c", kFieldOmitWhenEmpty},
          Field{"equilibrium", &RotorCritical::equilibrium, "",
                "about the periodic equilibrium at fixed controls: the q° at mu_c",
                kFieldOmitWhenEmpty}));
}

// The numbers an auditor needs at one (mu, psi).  Outcome: Failed when an entry of A or f or an
// integral is not finite.
struct SystemSnapshot : Outcome {
  double mu = 0.0, psi = 0.0;
  std::string region;  // "normal" or "reversed" (sector, or exact circle at this psi)
  Eigen::MatrixXd A;
  Eigen::VectorXd f;
  std::vector<std::pair<std::string, double>> aero_integrals;         // normal region values
  std::vector<std::pair<std::string, double>> aero_integrals_region;  // values used at psi
  std::vector<std::pair<std::string, double>> structural_integrals;
  std::vector<std::string> states;  // the name of each state (model::state_name)
  // The Appendix B name of each integral, in the order above ("" where there is none).
  std::vector<std::string> aero_paper_names, structural_paper_names;
};

// One aerodynamic integral of a snapshot: its values in normal flow and at psi.
struct AeroIntegral {
  std::string name, paper_name;
  double normal = 0.0;
  std::optional<double> at_psi;
};
constexpr auto describe(Tag<AeroIntegral>) {
  return std::make_tuple(
      Field{"name", &AeroIntegral::name, "", "the integral's name (int x^p ... dx0)"},
      Field{"paper_name", &AeroIntegral::paper_name, "", "its Appendix B name; \"\" if none"},
      Field{"normal", &AeroIntegral::normal, "-", "its value in normal flow"},
      Field{"at_psi", &AeroIntegral::at_psi, "-", "the value used at psi (its flow region's)"});
}
// One structural integral or generalized mass of a snapshot (by I_b).
struct StructuralIntegral {
  std::string name, paper_name;
  double value = 0.0;
};
constexpr auto describe(Tag<StructuralIntegral>) {
  return std::make_tuple(
      Field{"name", &StructuralIntegral::name, "", "the integral's name"},
      Field{"paper_name", &StructuralIntegral::paper_name, "", "its Appendix B name; \"\" if none"},
      Field{"value", &StructuralIntegral::value, "-", "its value, by I_b"});
}
std::vector<AeroIntegral> snapshot_aero_integrals(const SystemSnapshot& s);
std::vector<StructuralIntegral> snapshot_structural_integrals(const SystemSnapshot& s);

// A document (`flaplag system --json`) has the rows up to f, the hover, then the rest.
constexpr auto describe(Tag<SystemSnapshot>) {
  using S = SystemSnapshot;
  return std::make_tuple(
      Field{"mu", &S::mu, "-", "the advance ratio"}, Field{"psi", &S::psi, "rad", "the azimuth"},
      Field{"region", &S::region, "",
            "the flow region at psi: normal or reversed (the sector, or the exact circle)"},
      Field{"state", &S::states, "", "the state's names (dg1', dg1, dh1', dh1 for 1 x 1)"},
      Field{"A", &S::A, "1/rev", "A(psi) of y' = A(psi) y + f(psi)"},
      Field{"f", &S::f, "1/rev", "f(psi)"},
      Computed{"aero_integrals", &snapshot_aero_integrals, "",
               "the spanwise aerodynamic integrals over the aerodynamic span"},
      Computed{"structural_integrals", &snapshot_structural_integrals, "",
               "the generalized masses and structural integrals"},
      Field{"status", &S::status, "", "failed when an entry or an integral is not finite"},
      Field{"message", &S::message, "", "what went wrong", kFieldMessage});
}

// Thrown by Analysis::sweep and track when their cancel flag is set.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled") {}
};

// The tip motion of one blade direction (model_api.h DirectionBlock, in state order), by l:
// flap w/l = sum_k eta_k(1) g_k (up), lag v/l = sum_m gamma_m(1) h_m (positive lag, eq 2.12).
struct TipMotion {
  std::string direction;           // "flap", "lag"
  std::vector<double> deflection;  // at each psi of the result
  // ForcedResponse: the harmonics of deflection, value = c[0] + sum_n (c[2n-1] cos n psi +
  // c[2n] sin n psi), n = 1..5 (the harmonic index of periodic_system.h).  Else empty.
  std::vector<double> harmonics;
  // TipSimulation, nonlinear: the total deflection (reference included).  Else empty.
  std::vector<double> total;
  // TipSimulation: the envelope growth rate per rev (envelope_growth_rate) of deflection over the
  // last 3/4 of the run, to compare with the largest Floquet zeta; nullopt with fewer than 3
  // revolutions there.
  std::optional<double> growth_rate;
};
// The motion of `direction` in `tips` (InvalidInput("direction") when there is none).
const TipMotion& tip_motion(const std::vector<TipMotion>& tips, const std::string& direction);

// The periodic forced response at one mu (numerics/response.h) in blade terms.
struct ForcedResponse : Outcome {
  double mu = 0.0;
  PeriodicResponse periodic;  // of the perturbation state y about the hover equilibrium
  // Per direction: the tip deflections over one revolution at periodic.psi, hover equilibrium
  // included, and their harmonics (empty when Failed).
  std::vector<TipMotion> tips;
};

// A time-domain simulation (numerics/response.h) in blade terms.  Linear: the perturbation y
// about the hover equilibrium, y' = A(psi) y (+ f).  Nonlinear (SimulationOptions::nonlinear):
// the full state of the nonlinear equations (rotor/periodic_equilibrium.h NonlinearSystem),
// started at the reference equilibrium plus the given perturbation.
struct TipSimulation : Outcome {
  double mu = 0.0;
  bool nonlinear = false;
  // Linear: psi [rad] from 0 and the perturbation y(psi).  Nonlinear: the full state
  // y(psi) = [g', g, h', h] (model_api.h order).  Its status and message.
  Simulation simulation;
  // Nonlinear: what the perturbation is measured from, "periodic equilibrium" (q°(psi) by
  // harmonic balance with the default PeriodicEquilibriumOptions; at mu = 0 the hover
  // equilibrium) or, where there is none at this mu (beyond the fold of the hover branch),
  // "hover equilibrium" (then status Warning).  Linear: "hover equilibrium".
  std::string reference = "hover equilibrium";
  // Per direction: the tip perturbation deflections at simulation.psi (the state minus the
  // reference), their growth rates and (nonlinear) the total deflections.  Nonlinear: q° is a
  // K = 16 Fourier series, so a deviation below its truncation (~1e-5 of the state at mu = 0.5)
  // is not resolved; a decay below that floor flattens the growth rate.
  std::vector<TipMotion> tips;
  // The simulation's status, or Warning when the nonlinear reference is hover for want of a
  // periodic equilibrium.
};

// The tables of the time-domain results: their numbers (a front end shapes the states and the
// tips per direction itself).
constexpr auto describe(Tag<TipMotion>) {
  return std::make_tuple(
      Field{"direction", &TipMotion::direction, "", "the blade direction (flap, lag)"},
      Field{"deflection", &TipMotion::deflection, "- (by l)",
            "the tip deflection at each psi of the result"},
      Field{"harmonics", &TipMotion::harmonics, "- (by l)",
            "forced response: c of value = c[0] + sum_n (c[2n-1] cos n psi + c[2n] sin n psi), "
            "n = 1..5; else empty"},
      Field{"total", &TipMotion::total, "- (by l)",
            "nonlinear simulation: the total deflection, reference included; else empty"},
      Field{"growth_rate", &TipMotion::growth_rate, "1/rev",
            "simulation: the envelope growth rate of deflection over the last 3/4 of the run; "
            "null with fewer than 3 revolutions there"});
}
constexpr auto describe(Tag<ForcedResponse>) {
  using R = ForcedResponse;
  return std::tuple_cat(
      std::make_tuple(Field{"mu", &R::mu, "-", "the advance ratio"},
                      Computed{"psi", +[](const R& r) { return r.periodic.psi; }, "rad",
                               "the sample azimuths in [0, 2 pi)"},
                      Computed{"y0", +[](const R& r) { return r.periodic.y0; }, "-",
                               "the periodic perturbation state at psi = 0"},
                      Computed{"closure", +[](const R& r) { return r.periodic.closure; }, "-",
                               "|y(2 pi) - y(0)| / max(1, |y0|)"},
                      Computed{"error_estimate", +[](const R& r) { return r.periodic.error; }, "-",
                               "the estimated error of y0, relative; null when not estimated"},
                      Computed{"min_distance_to_one",
                               +[](const R& r) { return r.periodic.min_distance_to_one; }, "-",
                               "min |multiplier - 1| (near 0: no unique periodic solution)"},
                      Computed{"steps", +[](const R& r) { return r.periodic.steps; }, "",
                               "RK4 steps per period"}),
      describe(Tag<Outcome>{}));
}
// (A simulation's nonlinear and reference last: the Python class defaults them, to the linear
// simulation's.)
constexpr auto describe(Tag<TipSimulation>) {
  using S = TipSimulation;
  return std::tuple_cat(
      std::make_tuple(
          Field{"mu", &S::mu, "-", "the advance ratio"},
          Computed{"psi", +[](const S& s) { return s.simulation.psi; }, "rad", "from 0"},
          Computed{"steps_per_rev", +[](const S& s) { return s.simulation.steps_per_rev; }, "",
                   "RK4 steps per revolution"}),
      describe(Tag<Outcome>{}),
      std::make_tuple(
          Field{"nonlinear", &S::nonlinear, "", "the nonlinear equations (else the linear system)"},
          Field{"reference", &S::reference, "",
                "what the perturbation is measured from: periodic equilibrium or hover "
                "equilibrium"}));
}

class Analysis {
 public:
  // Checks params (validate()), options (TransitionOptions::Check()) and the condition; throws
  // InvalidInput (about the periodic equilibrium "exact_reversed_flow": q° is built with the
  // sector).  Trimmed: the rotor is trimmed in hover here (InvalidInput
  // "thrust_coefficient" when it cannot be), and parameters(), hover(), modes() and validity()
  // are those of that trim; system, snapshot, periodic_equilibrium, response, simulate and
  // floquet are of fixed controls and throw InvalidInput("trim") (make an Analysis At() the
  // trim at that mu instead).
  // With exact modes, point, sweep, track and critical are computed again with the neighbouring
  // Galerkin basis (rotor/parameters.h, reference_basis): the change is their basis_error,
  // included in their error estimates and, above 10 times the tolerance, in their status.
  // That blade is built at the first such call (floquet() and the other results do not use it);
  // a sweep's or track's progress counts both passes.  Imported mode shapes
  // (RotorParameters::mode_shapes) have no basis to compare with; when they are not
  // mass-orthogonal (mass_orthogonality_defect above kMassOrthogonalityWarning,
  // blade/imported_modes.h) point, sweep, track and critical carry a note saying so.
  Analysis(const RotorParameters& params, const TransitionOptions& options,
           const OperatingCondition& condition = {});
  ~Analysis();
  Analysis(Analysis&&) noexcept;
  Analysis& operator=(Analysis&&) noexcept;

  const RotorParameters& parameters() const;
  // The options as given, an Automatic method replaced by the one it stands for on this model
  // (automatic_method() of its state size).
  const TransitionOptions& options() const;
  const OperatingCondition& condition() const;
  const model::ModelDescriptor& model() const;
  const ModeSet& modes() const;

  const HoverResult& hover() const;
  // "" when the operating point (pitch, inflow, hover flap deflection) is inside the validity
  // envelope of the ordering models (rotor/validity.h); otherwise what lies outside, by name,
  // value and limit.  point, sweep, track and critical then come back with status Warning and
  // this in their message (every point of a sweep or track).
  const std::string& validity() const;
  // mu in [0, kMaxAdvanceRatio] (else InvalidInput("mu", ...)).  The linear system about the
  // hover equilibrium (the paper), whatever the condition's linearization; the system about the
  // periodic equilibrium is periodic_equilibrium(mu).linearization.
  PeriodicSystem system(double mu) const;
  // The periodic equilibrium of the nonlinear equations at mu and the linearization about it
  // (rotor/periodic_equilibrium.h); needs a model with nonlinear loads (else InvalidInput
  // "model").  About the periodic equilibrium (OperatingCondition::linearization), point,
  // sweep, track, critical and floquet use this linearization (harmonic balance with the
  // default options, K = 16) instead of the hover one.
  PeriodicEquilibrium periodic_equilibrium(double mu,
                                           const PeriodicEquilibriumOptions& options = {}) const;
  // psi any finite angle [rad], reduced to [0, 2 pi).  response, simulate and snapshot are of
  // the hover-linearized system: about the periodic equilibrium they throw
  // InvalidInput("linearization") rather than answer for another system.
  SystemSnapshot snapshot(double mu, double psi) const;

  // Exponents at mu with labels from continuation (steps of at most scan_step from hover;
  // mu / scan_step <= kMaxContinuationSteps).
  // Trimmed: every mu of the continuation is trimmed (a trim warm-started from the previous
  // one for the moment trim and about the periodic equilibrium), and each evaluation costs a
  // trim on top of the Floquet analysis; a trim that fails makes its evaluation Failed, one
  // not converged or outside the validity envelope (trim_problem) at least Warning.
  RotorPoint point(double mu, double scan_step = 0.01) const;
  // Sweep mu0..mu1 inclusive with the given step (0 <= mu0 < mu1 <= kMaxAdvanceRatio, step > 0,
  // at most kMaxContinuationSteps points).  Points carry the decimal grid value of mu.
  // threads: 0 = all cores, else 1..kMaxThreads (core/parallel.h).  The evaluations run in
  // stretches (track_exponents with a FloquetFunctionFactory, numerics/continuation.h), each
  // with its own warm start, so the result is the same for any number of threads; about the
  // periodic equilibrium (whose continuation cache is shared) and for a trimmed rotor (whose
  // trims continue from one another) the points are evaluated one after the other whatever
  // `threads` says.
  RotorSweep sweep(double mu0, double mu1, double step, int threads = 0) const;
  // Exponents at the given advance ratios (nondecreasing, each in [0, kMaxAdvanceRatio]),
  // continued from hover in steps of at most scan_step.  mu is reported as given.  Stretches
  // and threads as sweep: a track over the points of a sweep (the same step) is that sweep.
  RotorSweep track(const std::vector<double>& mus, double scan_step = 0.01, int threads = 0) const;
  // The same two with a cancel flag, polled before every evaluation (once set, the run stops
  // after the evaluations under way and throws Cancelled), and progress (evaluations done,
  // evaluations in all, the steps from hover included; from the evaluating threads, one call at
  // a time).  The result does not depend on them.
  RotorSweep sweep(double mu0, double mu1, double step, int threads,
                   const std::atomic<bool>* cancel, const ProgressFunction& progress) const;
  RotorSweep track(const std::vector<double>& mus, double scan_step, int threads,
                   const std::atomic<bool>* cancel, const ProgressFunction& progress) const;
  // opt.Check() first.  About the periodic equilibrium the search can end at a fold of the branch
  // of periodic equilibria through hover (a real multiplier reaches +1 and the equilibrium
  // ceases to exist: the blade loses it, a divergence-type loss of stability): mu_c is then the
  // fold, refined by bisection on the existence of q° and by the approach of that multiplier to
  // 1 (mu_c_error the larger of the bracket and the two estimates' difference; status Warning
  // when above opt.tolerance), kind Periodic at omega = 0, and the message says that the branch
  // ends there.  A failure where no multiplier approaches 1 stays Failed.
  // Trimmed, about the periodic equilibrium: the fold is that of the trimmed branch.
  // threads (0 = all cores, else 1..kMaxThreads): with exact modes, the search with the
  // neighbouring basis (basis_error) runs beside this one when it gives two or more; the
  // result does not depend on it.
  RotorCritical critical(const CriticalOptions& opt, int threads = 0) const;

  // The periodic forced response at mu; status Failed when there is none (a multiplier at 1),
  // Warning when the system is unstable (the blade does not settle onto it).
  ForcedResponse response(double mu, const ResponseOptions& options = {}) const;

  // Integrates y' = A(psi) y (+ f(psi) when forced) from y(0) = y0 (state_size() values, the
  // state order of model_api.h) at mu; options.Check() and y0 checked (InvalidInput "y0").
  // With options.nonlinear: the nonlinear equations y' = F(y, psi) from y_ref(0) + y0 (y_ref the
  // reference equilibrium, TipSimulation::reference), RK4 on the grid of the linearization
  // about it; needs a model with nonlinear loads (else InvalidInput "nonlinear"); `forced` must
  // be false (the loads are part of the equations; else InvalidInput "forced"); allowed about
  // the periodic equilibrium (no linearization is involved).
  TipSimulation simulate(double mu, const Eigen::VectorXd& y0, bool forced,
                         const SimulationOptions& options = {}) const;
  // The size of the state y: 2 (M + N).
  int state_size() const;
  // The tip deflection by l of each direction (TipMotion order) of a full state y (state_size()
  // values, model_api.h order; InvalidInput "y" otherwise), e.g. a periodic equilibrium's.
  std::vector<double> tip_deflections(const Eigen::VectorXd& y) const;
  // One empty TipMotion per direction of the model, named, in state order.
  std::vector<TipMotion> tip_motions() const;

  // One resolved Floquet evaluation at mu (the FloquetFunction of the numerics), for callers
  // that drive their own continuation.
  FloquetSample floquet(double mu, double zeta_tolerance) const;
  // The same about a given periodic equilibrium (its linearization), e.g. a trim's (trim.h
  // TrimResult::equilibrium), instead of the one this Analysis would continue from hover.
  // InvalidInput("equilibrium") when it failed or belongs to a model of another size.
  FloquetSample floquet(const PeriodicEquilibrium& equilibrium, double zeta_tolerance) const;

 private:
  struct Impl;
  // An Analysis made from its Impl: the same blade with the neighbouring basis of the exact
  // modes, which point, sweep, track and critical compute again to estimate the basis error.
  explicit Analysis(std::unique_ptr<Impl> impl);
  RotorCritical critical_with_this_basis(const CriticalOptions& options) const;
  // Throws InvalidInput("trim") for a trimmed rotor: `what` is of fixed controls.
  void require_fixed_controls(const char* what) const;
  TipSimulation simulate_nonlinear(double mu, const Eigen::VectorXd& y0, bool forced,
                                   const SimulationOptions& options) const;
  std::unique_ptr<Impl> impl_;
};

// The compiled model families (generated/) at their specs' mode counts, in name order.
const std::vector<const model::ModelDescriptor*>& compiled_models();
// Throws InvalidInput("model", name, ...) when unknown.
const model::ModelDescriptor& find_model(const std::string& name);
// Models are named "<family>" (its spec's mode counts) or "<family>-<M>x<N>".
// The model of family `base` (ModelDescriptor::base, e.g. "paper") with M flap and N lag modes.
// Throws InvalidInput for an unknown family or mode counts outside 1..model::kMaxModes.
const model::ModelDescriptor& find_model(const std::string& base, int flap_modes, int lag_modes);

}  // namespace flaplag
