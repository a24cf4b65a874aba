// flaplag — mode identification by continuation in the advance ratio mu, and the critical mu.
//
// The Floquet exponents lambda = zeta + i omega of Phi(2 pi) fix omega only up to an integer
// (eq 3.19).  At mu = 0 the system has constant coefficients and the exponents are exactly the
// eigenvalues of A0, integer part included; labels (flap/lag) come from the eigenvectors there.
// ExponentTracker carries both along small steps in mu by matching multipliers (and eigenvectors
// where two candidates are close) and choosing the integer that keeps omega continuous (paper 4.2
// step 3: "the degrees of freedom are identified by tracing back their history from mu = 0").
//
// Nothing here knows about rotors: labels are strings given with the hover modes.
//
// Invalid arguments throw InvalidInput; numerical outcomes (non-finite multipliers, ambiguous
// identification, instability in hover) come back as a status and a message.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <complex>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "flaplag/core/outcome.h"
#include "flaplag/core/validation.h"
#include "flaplag/numerics/floquet.h"

namespace flaplag {

// Periodic when omega is within `tolerance` of an integer or half-integer.
InstabilityKind classify_crossing(double omega, double tolerance = 1e-3);

// Damping ratio of the characteristic exponent lambda = zeta + i omega (per rev):
// -zeta / |lambda|, the viscous damping ratio of a constant-coefficient oscillator with that
// exponent.  In (-1, 1) for omega != 0; for omega = 0 (a real exponent, no oscillation) it is
// +1 when the mode decays and -1 when it grows; +1 for zeta = -inf (a zero multiplier).
// nullopt for lambda = 0 and for non-finite input otherwise.  Note that omega is known only up
// to an integer from Phi(2 pi) (eq 3.19); the ratio uses the omega continued from hover.
std::optional<double> damping_ratio(double zeta, double omega);

struct LabelledExponent {
  std::string label;   // "flap", "lag" ("flap2", "lag2", ... when M or N > 1)
  double zeta = 0.0;   // per rev
  double omega = 0.0;  // per rev, integer part fixed by continuation from hover
  std::complex<double> multiplier;
  // The estimated error of this zeta, per rev (the Floquet method's estimate for this exponent,
  // plus its change to the neighbouring basis with exact modes); nullopt when not estimated
  // (and in the exponents of a critical result).
  std::optional<double> zeta_error;
};

constexpr auto describe(Tag<LabelledExponent>) {
  return std::make_tuple(
      Field{"label", &LabelledExponent::label, "",
            "the mode: flap, lag (flap2, lag2, ... when M or N > 1)"},
      Field{"zeta", &LabelledExponent::zeta, "1/rev",
            "real part of the exponent lambda = zeta + i omega (> 0: unstable; -inf: the "
            "multiplier underflowed to 0)",
            kFieldNegativeInfinity},
      Field{"omega", &LabelledExponent::omega, "per rev",
            "imaginary part of lambda, its integer part fixed by continuation from hover"},
      Computed{
          "damping_ratio",
          +[](const LabelledExponent& e) { return damping_ratio(e.zeta, e.omega); },
          "- (fraction of critical)",
          "-zeta/|lambda| with omega as above (continued from hover, not reduced modulo 1/rev); "
          "text and pictures show it in % of critical; for omega = 0 +1 when decaying, -1 when "
          "growing; null for lambda = 0 (undefined)"},
      Field{"multiplier", &LabelledExponent::multiplier, "-",
            "the characteristic multiplier exp(2 pi lambda), an eigenvalue of Phi(2 pi)"},
      Field{"zeta_error", &LabelledExponent::zeta_error, "1/rev",
            "estimated error of this zeta (the method's estimate for this exponent, plus its "
            "change to the neighbouring basis with exact modes); left out when not estimated, "
            "and in the exponents of a critical result",
            kFieldOmitWhenEmpty});
}

// Eigen-decomposition of the hover matrix A0 with a label per eigenvalue (the rotor layer
// labels them: rotor/hover.h).
struct HoverModes : Outcome {
  std::vector<std::complex<double>> eigenvalues;  // eig(A0), per rev
  std::vector<Eigen::VectorXcd> eigenvectors;     // unit 2-norm
  std::vector<std::string> labels;
  // The rounding level of the eigenvalues' real parts (per rev; label_hover_modes: a few ulps
  // times ||A0||): a real part within it of the stability threshold leaves hover's stability
  // unknown (find_critical).  0: exact.
  double zeta_rounding = 0.0;
};

// Outcome of one continuation step.
struct TrackReport : Outcome {
  // smallest |v_old^H v_new| in the chosen assignment; NaN when the multipliers alone decided
  // it (no eigenvectors were computed: see ExponentTracker::advance)
  double min_similarity = 1.0;
};

class ExponentTracker {
 public:
  // Starts at hover: exponents = eig(A0), multipliers = exp(2 pi lambda).
  explicit ExponentTracker(const HoverModes& hover);

  // Matches the exponents of `next` (at the neighbouring parameter value `mu`) to the tracked
  // ones.  Each tracked exponent is predicted at mu by linear extrapolation from its last two
  // values (or taken as its last value when mu is NaN or there is no history yet); the
  // assignment minimises  sum (1 - |v_old^H v_new|) + 2 pi |lambda_new - lambda_predicted|,
  // the omega difference taken modulo integers, over all permutations (branch and bound,
  // n <= 8; greedy beyond).  Each omega then gets the integer that puts it closest to its
  // prediction, so a real multiplier keeps omega locked at the integer or half-integer next to
  // where its mode came from, and a conjugate pair passing through a half-integer (where the
  // eigenvectors are momentarily real and the pair indistinguishable) keeps its direction.
  // A zero multiplier (zeta = -inf: the mode decays by more than double precision can hold in
  // one revolution) is matched by its multiplier and keeps its label; NaN or infinite
  // multipliers leave the state unchanged and report Failed; a best match with eigenvector
  // similarity below 0.5 reports Warning.  Throws InvalidInput when the number of
  // exponents differs from the tracked one.
  //
  // Eigenvectors are needed only where the multipliers leave a doubt.  When `next` carries no
  // eigenvectors (FloquetVectors::OnDemand), the assignment is first made by the prediction
  // distance alone; it is kept when every tracked exponent's nearest new exponent is distinct,
  // within kMultiplierStep of its prediction and nearer than every other candidate by more
  // than 1 -- the most the eigenvector term can change a cost, so the full rule above gives
  // the same assignment whatever the eigenvectors (report.min_similarity is then NaN).
  // Otherwise the eigenvectors of next.phi and of the previous point's Phi are computed (or
  // drawn from their FloquetResult::eigensystem, the same bits) and the full rule applies;
  // without them (no phi) the step reports Failed.
  TrackReport advance(const FloquetResult& next,
                      double mu = std::numeric_limits<double>::quiet_NaN());

  // Largest 2 pi |lambda_new - lambda_predicted| (about the relative change of the multiplier)
  // that the multipliers alone may decide; a larger jump is checked by the eigenvectors.
  static constexpr double kMultiplierStep = 0.25;

  // In hover order (the order of HoverModes), conjugate pairs tracked individually.
  const std::vector<LabelledExponent>& exponents() const { return exponents_; }
  // Eigenvectors of the current state (computed here if the last steps did not need them).
  const std::vector<Eigen::VectorXcd>& eigenvectors() const;
  // Index and value of the largest zeta.
  int most_unstable() const;
  double max_zeta() const;
  double mu() const { return mu_; }  // parameter of the current state (0 at hover)

 private:
  // The eigenvectors of the current state, valid when vectors_valid_; else they are those of
  // last_phi_ (the Phi of the current state) for the current multipliers.
  bool ensure_vectors() const;

  std::vector<LabelledExponent> exponents_;
  mutable std::vector<Eigen::VectorXcd> vectors_;
  mutable bool vectors_valid_ = true;
  Eigen::MatrixXd last_phi_;
  std::shared_ptr<const FloquetEigenSystem> last_eigensystem_;  // of last_phi_, if computed
  std::vector<Eigen::VectorXcd> next_vectors_;  // scratch: eigenvectors of a next Phi
  std::vector<std::complex<double>> previous_;  // zeta + i omega one step back
  double mu_ = 0.0;
  double previous_mu_ = 0.0;
  bool has_previous_ = false;
};

// One evaluation of the caller's Floquet analysis at mu.
struct FloquetSample : Outcome {
  FloquetResult floquet;
  // Estimated error of zeta_k for each exponent of `floquet` (same order), per rev (the
  // method's own estimate, e.g. Richardson from a coarser resolution); empty: not estimated.
  std::vector<double> zeta_errors;
  // max of zeta_errors; nullopt: not estimated.
  std::optional<double> error;
  int steps = 0;  // steps per period behind `floquet` (0: not a stepping method)
  // Outcome: Warning: not resolved to the requested tolerance; Failed: no usable multipliers
  // (message says why)
};

// The table of a sample: its exponents as columns (multipliers, zeta, omega, in one order).
constexpr auto describe(Tag<FloquetSample>) {
  return std::tuple_cat(
      std::make_tuple(
          Computed{"multipliers",
                   +[](const FloquetSample& s) {
                     std::vector<std::complex<double>> v;
                     for (const FloquetExponent& e : s.floquet.exponents) v.push_back(e.multiplier);
                     return v;
                   },
                   "-", "the characteristic multipliers, eigenvalues of Phi(2 pi)"},
          Computed{"zeta",
                   +[](const FloquetSample& s) {
                     std::vector<double> v;
                     for (const FloquetExponent& e : s.floquet.exponents) v.push_back(e.zeta);
                     return v;
                   },
                   "1/rev", "the damping exponents ln|multiplier| / 2 pi", kFieldNegativeInfinity},
          Computed{"omega",
                   +[](const FloquetSample& s) {
                     std::vector<double> v;
                     for (const FloquetExponent& e : s.floquet.exponents) v.push_back(e.omega);
                     return v;
                   },
                   "1/rev",
                   "the frequencies arg(multiplier) / 2 pi, principal value in (-1/2, 1/2]"},
          Field{"zeta_errors", &FloquetSample::zeta_errors, "1/rev",
                "estimated error of each zeta (empty: not estimated)"},
          Field{"error_estimate", &FloquetSample::error, "1/rev",
                "the largest of zeta_errors; null when not estimated"},
          Field{"steps", &FloquetSample::steps, "",
                "steps per period behind the multipliers (0: not a stepping method)"},
          Computed{"liouville_residual",
                   +[](const FloquetSample& s) { return s.floquet.liouville_residual; }, "-",
                   "|det Phi - exp int tr A| / exp int tr A"}),
      describe(Tag<Outcome>{}));
}

// The caller builds the periodic system at mu and returns its Floquet analysis, resolved so that
// the estimated exponent error is at most `zeta_tolerance` per rev where it can (the caller
// decides what it can afford; a sample that misses it says so in its status).
using FloquetFunction = std::function<FloquetSample(double mu, double zeta_tolerance)>;

// Limits that keep every loop bounded and every count representable.
inline constexpr double kMaxAdvanceRatio = 1000.0;      // mu beyond this is refused
inline constexpr long kMaxContinuationSteps = 1000000;  // steps of a scan or sweep

// The labelled exponents at one mu.
struct PointResult : Outcome {
  double mu = 0.0;
  std::vector<LabelledExponent> exponents;  // hover order (Analysis sorts by label, then omega)
  // |det Phi - exp int tr A| / exp int tr A; nullopt when not representable (a multiplier
  // underflowed to 0 while exp int tr A did not, or the reverse) or when the caller's Floquet
  // analysis cannot check it (Analysis: det Phi below the rounding of Phi's determinant; its
  // message says so)
  std::optional<double> liouville_residual;
  std::optional<double> error;  // estimated max zeta error, per rev (FloquetSample)
  int steps = 0;                // steps per period used (FloquetSample)
  // all zeta <= 0; nullopt when unknown: Failed, or (status Warning) the largest zeta is
  // within its own error estimate (or the rounding level of Phi) of 0, so that its sign is not
  // known
  std::optional<bool> stable;
  // Set by the analysis of a blade with exact modes: the cantilever functions of their Galerkin
  // basis, and the largest change of a zeta to a neighbouring basis (included in `error`).
  std::optional<int> basis;
  std::optional<double> basis_error;
};

constexpr auto describe(Tag<PointResult>) {
  return std::tuple_cat(
      std::make_tuple(
          Field{"mu", &PointResult::mu, "-", "the advance ratio"},
          Field{"exponents", &PointResult::exponents, "",
                "the labelled exponents, sorted by label, then by omega (descending)"},
          Computed{"multipliers",
                   +[](const PointResult& p) {
                     std::vector<std::complex<double>> m;
                     for (const LabelledExponent& e : p.exponents) m.push_back(e.multiplier);
                     return m;
                   },
                   "-", "the multipliers of `exponents`, in their order"},
          Field{"liouville_residual", &PointResult::liouville_residual, "-",
                "|det Phi - exp int tr A| / exp int tr A; null when not representable or not "
                "checked"},
          Field{"error_estimate", &PointResult::error, "1/rev",
                "estimated largest zeta error (the method's own estimate, e.g. Richardson from K "
                "and K/2, plus basis_error with exact modes); null when not estimated"},
          Field{"steps", &PointResult::steps, "", "steps per period of the transition matrix used"},
          Field{"stable", &PointResult::stable, "",
                "all zeta <= 0; null when unknown (failed, or the largest zeta is within its error "
                "of 0)"},
          Field{"basis", &PointResult::basis, "",
                "exact modes: the cantilever functions of the Galerkin basis used, -1 for finite "
                "elements; null for the assumed mode"},
          Field{"basis_error", &PointResult::basis_error, "1/rev",
                "exact modes: the largest change of a zeta to the reference discretization (the "
                "neighbouring basis; finite elements for a blade table; included in "
                "error_estimate); null when not estimated"}),
      describe(Tag<Outcome>{}));
}

// ---- the damping criterion of a design review ---------------------------------------------
//
// A mode's damping ratio at a point is the damping_ratio() of its dominant exponent (below),
// -zeta/|lambda| with the omega continued from hover (its integer part fixed by continuation,
// not reduced modulo 1/rev): a fraction of critical.  A review asks for every mode to keep it
// above a criterion C (say 0.01, 1 % of critical) and for the first mu where it does not.

// The exponent that decides mode `label`'s stability at p: the largest zeta among the exponents
// so labelled; of a conjugate pair (equal zeta) the one with omega >= 0.  nullptr when p has
// none (a failed point).
const LabelledExponent* dominant_exponent(const PointResult& p, const std::string& label);

// The labels in the order given, each once (hover's labels: one per exponent).
std::vector<std::string> distinct_labels(const std::vector<std::string>& labels);

// Admissible criteria: a fraction of critical damping, 0 <= C < 1 (a damping ratio is at most
// 1, so C = 1 would be crossed by every oscillating mode at once).
inline constexpr Range kDampingCriterionRange{{0.0, 1.0, false, true},
                                              ">= 0 and < 1 (a fraction of critical: 0.01 is 1 %)"};
// InvalidInput("damping_criterion", value, ...) when criterion is outside the range (or NaN).
void check_damping_criterion(double criterion);

enum class CrossingStatus {
  Crossed,       // interpolated between two resolved points, the first below C
  Unresolved,    // below C, but a bracketing point is failed, has no error estimate or lies
                 // within its estimated error of C, or points between have no ratio
  BelowAtStart,  // already below C at the first point of the sweep
  NotCrossed,    // at or above C at every point with a ratio (Unresolved, mu nullopt, when
                 // the sweep stopped at a failed point)
};
constexpr auto describe(Tag<CrossingStatus>) {
  return std::array<EnumName<CrossingStatus>, 4>{{{CrossingStatus::Crossed, "crossed"},
                                                  {CrossingStatus::Unresolved, "unresolved"},
                                                  {CrossingStatus::BelowAtStart, "below_at_start"},
                                                  {CrossingStatus::NotCrossed, "not_crossed"}}};
}

// The first advance ratio where one mode's damping ratio falls below the criterion C.
struct DampingCrossing {
  std::string mode;
  // Linear interpolation of the damping ratio between mu_above and mu_below:
  // mu_above + (C - r_above) (mu_below - mu_above) / (r_below - r_above).  The first point
  // (below_at_start); nullopt when not crossed, or unresolved without a point above C before it.
  std::optional<double> mu;
  CrossingStatus status = CrossingStatus::NotCrossed;
  std::optional<double> mu_above;  // the last sweep point at or above C before the crossing
  std::optional<double> mu_below;  // the first sweep point below C
};

constexpr auto describe(Tag<DampingCrossing>) {
  return std::make_tuple(
      Field{"mode", &DampingCrossing::mode, "", "the mode label"},
      Field{"mu", &DampingCrossing::mu, "-",
            "first advance ratio where the mode's damping ratio falls below the criterion, "
            "interpolated linearly between mu_above and mu_below (the first point when "
            "below_at_start); null when not crossed, or unresolved without a point above"},
      Field{"status", &DampingCrossing::status, "",
            "crossed; unresolved (a bracketing point failed, has no error estimate or lies within "
            "its error of the criterion, a point between has no ratio, or the sweep stopped at "
            "a failed point); below_at_start; not_crossed (at or above the criterion at every "
            "point)"},
      Field{"mu_above", &DampingCrossing::mu_above, "-",
            "the last sweep point at or above the criterion before the crossing; null if none"},
      Field{"mu_below", &DampingCrossing::mu_below, "-",
            "the first sweep point below the criterion; null when not crossed"});
}

struct SweepResult : Outcome {
  std::vector<PointResult> points;
  // Outcome: the worst point's status, and the first problem met (Outcome::Include)
  // Set by apply_damping_criterion (empty otherwise): C, and one crossing per mode.
  std::optional<double> damping_criterion;
  std::vector<DampingCrossing> damping_crossings;
};

constexpr auto describe(Tag<SweepResult>) {
  return std::tuple_cat(
      std::make_tuple(
          Field{"points", &SweepResult::points, "",
                "one result per advance ratio; a failed step ends the sweep (the failed point "
                "last)"},
          Field{"damping_criterion", &SweepResult::damping_criterion, "- (fraction of critical)",
                "the damping ratio asked of every mode (0.01: 1 % of critical); only when given",
                kFieldOmitWhenEmpty},
          Field{"damping_crossings", &SweepResult::damping_crossings, "",
                "per mode (in hover order), the first mu where its damping ratio -zeta/|lambda| "
                "(omega continued from hover) falls below damping_criterion; only with it",
                kFieldOmitWhenEmpty}),
      describe(Tag<Outcome>{}));
}

// The crossing of the criterion by each mode of `labels` (in that order) along s.points (in
// their order).  A point's ratio is unknown where the mode has no exponent or damping_ratio()
// is undefined (lambda = 0); such points are skipped, and a crossing across them is Unresolved.
// A bracketing point lies within its error of C when |r - C| <= error_estimate / |lambda|.
// check_damping_criterion(criterion) first.
std::vector<DampingCrossing> damping_crossings(const SweepResult& s,
                                               const std::vector<std::string>& labels,
                                               double criterion);
// Sets s.damping_criterion and s.damping_crossings (the status of s is not changed: a crossing
// is a finding, not a problem of the computation).
void apply_damping_criterion(SweepResult& s, const std::vector<std::string>& labels,
                             double criterion);

// Search for the critical advance ratio.  Validated as every options struct (core/validation.h).
struct CriticalOptions {
  static constexpr Range kMuMaxRange{{0.0, kMaxAdvanceRatio, true, false}, "> 0 and <= 1000"};
  static constexpr Range kZetaThresholdRange{{0.0, kUnbounded, false, false}, ">= 0"};
  static constexpr Range kOmegaToleranceRange{{0.0, 0.25, false, true}, "in [0, 0.25)"};

  double mu_max = 2.0;                     // scan limit, 0 < mu_max <= kMaxAdvanceRatio
  double scan_step = 0.01;                 // scan / continuation step, > 0, at most
                                           // kMaxContinuationSteps steps up to mu_max
  double tolerance = 1e-5;                 // on mu_c, > 0
  double zeta_threshold = 0.0;             // unstable means zeta > zeta_threshold (>= 0)
  double periodic_omega_tolerance = 1e-3;  // see classify_crossing, >= 0
  // Exponent accuracy asked of the scan (per rev); the Brent refinement asks for
  // min(this, 0.1 * |d zeta/d mu| * tolerance) so that mu_c is as good as `tolerance` says.
  double scan_zeta_tolerance = 1e-5;
  // false: stop at the first onset (mu_c).  true: scan to mu_max and report every interval of
  // instability (onset and re-stabilization).
  bool all_intervals = false;

  std::optional<InvalidInput> Validate() const;
  bool IsValid(std::string* error) const { return IsValidReport(Validate(), error); }
  void Check() const { ThrowIfInvalid(Validate()); }
};

constexpr auto describe(Tag<CriticalOptions>) {
  using O = CriticalOptions;
  return std::make_tuple(
      Option{"mu_max", &O::mu_max, "-", "scan limit", &O::kMuMaxRange},
      Option{"scan_step", &O::scan_step, "-", "continuation step in mu from hover", &kPositive},
      Option{"tolerance", &O::tolerance, "-", "tolerance on mu_c", &kPositive},
      Option{"zeta_threshold", &O::zeta_threshold, "per rev",
             "unstable means zeta > zeta_threshold", &O::kZetaThresholdRange},
      Option{"periodic_omega_tolerance", &O::periodic_omega_tolerance, "per rev",
             "|omega - k/2| below which a crossing is periodic", &O::kOmegaToleranceRange},
      Option{"scan_zeta_tolerance", &O::scan_zeta_tolerance, "per rev",
             "exponent accuracy asked of the scan", &kPositive},
      Option{"all_intervals", &O::all_intervals, "",
             "scan to mu_max and report every interval of instability"});
}

// One interval of instability in mu: max zeta > zeta_threshold for onset < mu < end.
struct InstabilityInterval {
  double onset = 0.0;
  std::optional<double> end;  // re-stabilization; nullopt: still unstable at mu_max
  std::optional<double> onset_error, end_error;  // as CriticalResult::mu_c_error
  std::string mode;                              // the mode that crosses at the onset
  double omega = 0.0;                            // its omega at the onset, per rev, >= 0
  InstabilityKind kind = InstabilityKind::Flutter;
};

constexpr auto describe(Tag<InstabilityInterval>) {
  return std::make_tuple(
      Field{"onset", &InstabilityInterval::onset, "-",
            "the advance ratio where the interval starts"},
      Field{"end", &InstabilityInterval::end, "-",
            "the advance ratio of re-stabilization; null: still unstable at mu_max"},
      Field{"onset_error", &InstabilityInterval::onset_error, "-", "estimated |onset error|"},
      Field{"end_error", &InstabilityInterval::end_error, "-", "estimated |end error|"},
      Field{"mode", &InstabilityInterval::mode, "", "the mode that crosses at the onset"},
      Field{"omega", &InstabilityInterval::omega, "per rev", "its omega at the onset, >= 0"},
      Field{"kind", &InstabilityInterval::kind, "",
            "flutter (omega not locked) or periodic (omega locked to 0, 1/2 or 1 per rev)"});
}

struct CriticalResult : Outcome {
  bool hover_unstable = false;       // true: unstable already at mu = 0 (no mu_c; see exponents)
  std::optional<double> mu_c;        // first mu in (0, mu_max] with zeta > zeta_threshold; nullopt:
                                     // stable up to mu_max, hover unstable, or the search failed
  std::optional<double> mu_c_error;  // estimated |mu_c error|: the Brent bracket plus the
                                     // exponent error over |d zeta/d mu| at the crossing (plus
                                     // basis_error with exact modes)
  std::string mode;                  // label of the mode that crossed ("" without mu_c)
  double omega = 0.0;  // its omega at mu_c, per rev, >= 0 (either member of a crossing pair)
  InstabilityKind kind = InstabilityKind::Flutter;
  double mu_max = 0.0;
  std::vector<LabelledExponent> exponents;  // at mu_c, at hover, or at the last mu scanned
  // The first interval starts at mu_c; with all_intervals, every interval up to mu_max.
  std::vector<InstabilityInterval> intervals;
  int evaluations = 0;  // calls of the FloquetFunction
  // Set by the analysis of a blade with exact modes: the cantilever functions of their Galerkin
  // basis, and the change of mu_c to a neighbouring basis (included in mu_c_error).
  std::optional<int> basis;
  std::optional<double> basis_error;
};

// mode, omega and kind are null without mu_c.
constexpr auto describe(Tag<CriticalResult>) {
  return std::tuple_cat(
      std::make_tuple(
          Field{"hover_unstable", &CriticalResult::hover_unstable, "",
                "unstable already in hover (then no mu_c; see exponents)"},
          Field{"mu_c", &CriticalResult::mu_c, "-",
                "the first mu in (0, mu_max] with zeta > zeta_threshold (0 unless asked); null: "
                "stable up to mu_max, unstable in hover, or the search failed"},
          Field{"mu_c_error", &CriticalResult::mu_c_error, "-",
                "estimated |mu_c error|: the bracket plus the exponent error over |d zeta/d mu|, "
                "plus basis_error with exact modes"},
          Computed{"omega",
                   +[](const CriticalResult& c) {
                     return c.mu_c ? std::optional<double>(c.omega) : std::nullopt;
                   },
                   "per rev", "omega of the mode that crosses at mu_c, >= 0; null without mu_c"},
          Computed{"mode",
                   +[](const CriticalResult& c) {
                     return c.mu_c ? std::optional<std::string>(c.mode) : std::nullopt;
                   },
                   "", "the mode that crosses at mu_c; null without mu_c"},
          Computed{"kind",
                   +[](const CriticalResult& c) {
                     return c.mu_c ? std::optional<InstabilityKind>(c.kind) : std::nullopt;
                   },
                   "",
                   "flutter (omega not locked) or periodic (omega locked to 0, 1/2 or 1 per "
                   "rev); null without mu_c"},
          Field{"mu_max", &CriticalResult::mu_max, "-", "the scan limit"},
          Field{"exponents", &CriticalResult::exponents, "",
                "the exponents at mu_c, at hover, or at the last mu scanned"},
          Field{"intervals", &CriticalResult::intervals, "",
                "the intervals of instability: the first starts at mu_c; every one up to mu_max "
                "when all intervals were asked for"},
          Field{"evaluations", &CriticalResult::evaluations, "", "Floquet analyses made"},
          Field{"basis", &CriticalResult::basis, "",
                "exact modes: the cantilever functions of the Galerkin basis used, -1 for finite "
                "elements; null for the assumed mode"},
          Field{"basis_error", &CriticalResult::basis_error, "-",
                "exact modes: |mu_c with the reference discretization - mu_c| (the neighbouring "
                "basis; finite elements for a blade table; included in mu_c_error and in the "
                "intervals' errors); null when not estimated"}),
      describe(Tag<Outcome>{}));
}

// Every number of a result is finite (the zeta of a zero multiplier excepted: -inf), and an
// optional diagnostic is absent rather than NaN.  The continuation and the search check it on
// every result they make: a value that breaks it makes the result Failed (an exponent, mu, mu_c
// or its omega, mu_max; stable and mu_c are then unknown) or Warning (the Liouville residual, an
// error estimate), with "non-finite <what> (not shown)" in its message, so that every front end
// reports the same status; front ends show such a value as absent.
void check_finite(PointResult& p);
void check_finite(CriticalResult& c);

// Scans mu = step, 2 step, ... up to mu_max, continuing the exponents from hover.  Where the
// sign of max_k zeta_k(mu) - zeta_threshold changes between grid points the crossing is refined
// by Brent's method, each trial advancing a copy of the tracker from the grid point below (so
// that labels and omega integers stay those of the continuation); the first onset is mu_c, and
// with all_intervals the scan goes on to mu_max.  A mode that turns unstable and stable again
// within one step is not seen.  Scan points far from the threshold only need their sign: when
// the FloquetFunction estimates errors they are asked for a looser tolerance (2 % of the
// previous margin, at most 1e-3 per rev) and kept only when the sign of max zeta -
// zeta_threshold survives moving every zeta by ten times its estimate; the two ends of a
// bracket and the last point of a stable scan are always evaluated at scan_zeta_tolerance, so
// the results are those of a scan at scan_zeta_tolerance throughout (evaluations counts every
// call).  A change of sign seen at the scan resolution that is gone at mu resolved can be a
// narrow interval next to the grid point: that grid interval and the next are searched at
// scan_step / 10, then / 100 (every point resolved) before the change is reported as vanished
// (status Warning).  Hover with its largest zeta within hover.zeta_rounding of the threshold
// is of unknown stability: status Warning, no search.  Options are checked (Check()).
CriticalResult find_critical(const HoverModes& hover, const FloquetFunction& floquet,
                             const CriticalOptions& opt = {});

// Labelled exponents at mu0, mu0 + step, ..., mu1 (mu1 always included).  The continuation
// starts in hover and reaches mu0 in equal steps of at most `step`.  0 <= mu0 <= mu1 <=
// kMaxAdvanceRatio, step > 0, and at most kMaxContinuationSteps steps in all (else
// InvalidInput).  A Failed step stops the sweep (points so far are kept, the failed one last,
// with stable = nullopt).  Each point is resolved to `zeta_tolerance` where the FloquetFunction
// can.
// Labelled exponents at the given advance ratios (nondecreasing, in [0, kMaxAdvanceRatio]),
// continued from hover in steps of at most max_step (intermediate steps are not reported).
// sweep_exponents is this on the grid mu0, mu0 + step, ..., mu1.  One FloquetFunction makes
// every evaluation, in order.
SweepResult track_exponents(const HoverModes& hover, const FloquetFunction& floquet,
                            const std::vector<double>& mus, double max_step,
                            double zeta_tolerance = 1e-5);

// Makes the FloquetFunction of one stretch of a continuation.  The functions it makes must be
// safe to call from different threads at once; the evaluations of one function may depend on
// each other (Analysis carries a steps hint along one function), never on another function's.
using FloquetFunctionFactory = std::function<FloquetFunction()>;

// The same continuation evaluated in stretches.  Stretch s holds the reported points
// s L .. (s + 1) L - 1, L = continuation_stretch(mus.size()), with the steps that lead to each;
// each stretch is evaluated in order by its own function from `make`, the stretches on
// min(thread_count(threads), stretches) threads (core/parallel.h: threads 0 = all cores, else
// 1..kMaxThreads), and then the exponents are identified along the whole continuation in
// order, as above.  The stretches depend only on the number of reported points, so the result
// is the same, bit for bit, for any number of threads, and for any max_step when the function
// keeps the evaluations of the reported points apart from the others (Analysis keys its warm
// start by tolerance): a map line that reaches its points in steps of scan_step equals the
// plain sweep over the same points.  It can differ from the single-function track_exponents
// within the error estimates, where a stretch starts without the history of the one before.
// A FloquetFunction that throws throws here, from the first evaluation in continuation order
// that threw, as the single-function form would (later evaluations may have been made; their
// results are dropped).  At most kStretchesInMemory stretches and kSamplesInMemory samples are
// held at a time (a longer stretch is evaluated and identified as it goes, on one thread).
SweepResult track_exponents(const HoverModes& hover, const FloquetFunctionFactory& make,
                            const std::vector<double>& mus, double max_step, double zeta_tolerance,
                            int threads);

// Reported points per stretch of a continuation of `points` reported points: split into
// kContinuationStretches nearly equal stretches, each of kMinStretch to kMaxStretch points.
inline constexpr std::size_t kContinuationStretches = 16;
inline constexpr std::size_t kMinStretch = 8, kMaxStretch = 128;
inline constexpr std::size_t kStretchesInMemory = 16, kSamplesInMemory = 4096;
std::size_t continuation_stretch(std::size_t points);

SweepResult sweep_exponents(const HoverModes& hover, const FloquetFunction& floquet, double mu0,
                            double mu1, double step, double zeta_tolerance = 1e-5);
// The grid of sweep_exponents (mu0, mu0 + step, ..., mu1; arguments checked the same way).
std::vector<double> sweep_grid(double mu0, double mu1, double step);

}  // namespace flaplag
