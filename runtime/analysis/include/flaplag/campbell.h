// flaplag — the Campbell (fan) diagram: the frequency of every mode of the blade against the
// rotor speed Omega / Omega_0, with the integer per-rev lines n Omega / Omega_0 it crosses.
//
// The blade is the one the rotor parameters describe at the nominal speed Omega_0: its first
// rotating frequencies omega_F1, omega_L1 (by Omega_0) fix the nonrotating bending stiffness of
// the uniform cantilever (Fig 9, blade/rotating_modes.h), which does not change with the speed.
// At speed s = Omega / Omega_0 the stiffness by Omega^2 is k / s^2, so the blade's first rotating
// frequencies by Omega are those of the uniform cantilever with that stiffness (centrifugal
// stiffening), and the aeroelastic exponents at the advance ratio mu follow from the same
// nondimensional equations with those frequencies (gamma, sigma, theta and mu unchanged: the
// aerodynamic loads scale with Omega^2 as the inertial ones do).  A mode's frequency by Omega_0
// is s omega, with omega its exponent's imaginary part per rev at speed s, continued from
// hover (analysis.h, point).  At s = 0 nothing rotates and no air flows: the frequencies are the
// nonrotating structural ones, sqrt(k / mbar) beta_k^2 for mode k.
//
// A blade table (RotorParameters::blade) is handled the same way with the scale of its stiffness
// columns in place of k (rotating_modes.h): s0 = stiffness_for_frequency of omega_F1, omega_L1
// with the table, the table's rotating frequencies at scale s0 / s^2 at speed s (the analysis
// there solves the scale back from its first frequencies), and its k-th nonrotating Galerkin
// frequency at scale s0 at rest.  A dimensional table's columns are absolute (s0 = 1 to
// rounding).  Imported mode shapes (RotorParameters::mode_shapes) hold at one rotor speed only
// and are refused (InvalidInput "mode_shapes").
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "flaplag/analysis.h"
#include "flaplag/core/outcome.h"
#include "flaplag/core/validation.h"

namespace flaplag {

inline constexpr Range kCampbellSpeedRange{{0.0, 10.0, true, false}, "in (0, 10]"};
inline constexpr Range kCampbellMuRange{{0.0, kMaxAdvanceRatio, false, false}, "in [0, 1000]"};
inline constexpr Range kCampbellPointsRange{{2.0, 10001.0, false, false}, "2..10001"};
inline constexpr Range kCampbellHarmonicsRange{{1.0, 100.0, false, false}, "1..100"};

struct CampbellOptions {
  double speed_max = 1.5;   // the largest Omega / Omega_0; the speeds are 0 .. speed_max
  int points = 31;          // speeds, evenly spaced, 0 and speed_max included
  double mu = 0.0;          // the advance ratio at every speed (0: hover)
  double scan_step = 0.01;  // continuation step from hover to mu (analysis.h, point)
  int harmonics = 6;        // the per-rev lines n Omega, n = 1 .. harmonics
  int threads = 0;          // 0: as many as the hardware has (core/parallel.h)

  std::optional<InvalidInput> Validate() const;
  bool IsValid(std::string* error) const { return IsValidReport(Validate(), error); }
  void Check() const { ThrowIfInvalid(Validate()); }
};

constexpr auto describe(Tag<CampbellOptions>) {
  using O = CampbellOptions;
  return std::make_tuple(
      Option{"speed_max", &O::speed_max, "-",
             "the largest rotor speed Omega/Omega_0; the speeds run from 0", &kCampbellSpeedRange},
      Option{"points", &O::points, "", "rotor speeds, evenly spaced from 0 to the largest speed",
             &kCampbellPointsRange},
      Option{"mu", &O::mu, "-", "advance ratio at every speed (0: hover)", &kCampbellMuRange},
      Option{"scan_step", &O::scan_step, "-", "continuation step in mu from hover", &kPositive},
      Option{"harmonics", &O::harmonics, "",
             "the per-rev lines n Omega drawn and crossed, n = 1 up to this number",
             &kCampbellHarmonicsRange},
      Option{"threads", &O::threads, "",
             "worker threads (0: all cores; the answer does not depend on it)"});
}

// One mode at one speed.
struct CampbellFrequency {
  std::string label;       // the mode, as the analysis labels it (flap, lag; flap1, lag2, ...)
  double frequency = 0.0;  // omega Omega / Omega_0: the frequency by the nominal speed
  double omega = 0.0;      // per rev at this speed (frequency / speed; the nonrotating at s = 0)
  // -zeta/|lambda| (numerics/continuation.h); null at s = 0 (no aerodynamic damping there).
  std::optional<double> damping_ratio;
};

constexpr auto describe(Tag<CampbellFrequency>) {
  return std::make_tuple(
      Field{"label", &CampbellFrequency::label, "", "the mode"},
      Field{"frequency", &CampbellFrequency::frequency, "per rev at Omega_0",
            "the mode's frequency by the nominal rotor speed, omega Omega / Omega_0"},
      Field{"omega", &CampbellFrequency::omega, "per rev",
            "the imaginary part of the exponent at this speed, continued from hover (at "
            "Omega = 0: the nonrotating frequency by Omega_0)"},
      Field{"damping_ratio", &CampbellFrequency::damping_ratio, "- (fraction of critical)",
            "-zeta/|lambda| at this speed; null at Omega = 0"});
}

// The modes at one speed.
struct CampbellPoint : Outcome {
  double speed = 0.0;  // Omega / Omega_0
  // The blade's first rotating frequencies by Omega at this speed (at s = 0: the nonrotating
  // ones by Omega_0).
  double omega_flap = 0.0, omega_lag = 0.0;
  std::vector<CampbellFrequency> modes;  // in the order of the result's labels
};

constexpr auto describe(Tag<CampbellPoint>) {
  return std::tuple_cat(
      std::make_tuple(
          Field{"speed", &CampbellPoint::speed, "-", "the rotor speed Omega / Omega_0"},
          Field{"omega_flap", &CampbellPoint::omega_flap, "per rev",
                "the blade's first rotating flap frequency by Omega at this speed (centrifugal "
                "stiffening of the fixed bending stiffness); at Omega = 0 the nonrotating one "
                "by Omega_0"},
          Field{"omega_lag", &CampbellPoint::omega_lag, "per rev",
                "the same for the first lag mode"},
          Field{"modes", &CampbellPoint::modes, "", "every mode's frequency at this speed"}),
      describe(Tag<Outcome>{}));
}

// Where a mode's frequency meets the line n Omega (resonance with the n-th harmonic of the
// rotor speed): linear interpolation of frequency - n speed between the two speeds around it.
struct CampbellCrossing {
  std::string label;
  int harmonic = 1;        // n
  double speed = 0.0;      // Omega / Omega_0 at the crossing
  double frequency = 0.0;  // n speed
};

constexpr auto describe(Tag<CampbellCrossing>) {
  return std::make_tuple(
      Field{"label", &CampbellCrossing::label, "", "the mode"},
      Field{"harmonic", &CampbellCrossing::harmonic, "", "n of the per-rev line n Omega"},
      Field{"speed", &CampbellCrossing::speed, "-",
            "Omega / Omega_0 where the mode's frequency equals n Omega (linear interpolation "
            "between the speeds around it)"},
      Field{"frequency", &CampbellCrossing::frequency, "per rev at Omega_0",
            "the frequency there, n times the speed"});
}

struct CampbellResult : Outcome {
  double mu = 0.0;
  int harmonics = 0;
  std::vector<std::string> labels;          // the modes, in the analysis' order
  std::vector<CampbellPoint> points;        // speeds 0 .. speed_max
  std::vector<CampbellCrossing> crossings;  // by label, then harmonic, then speed
};

constexpr auto describe(Tag<CampbellResult>) {
  return std::tuple_cat(
      std::make_tuple(Field{"mu", &CampbellResult::mu, "-", "the advance ratio at every speed"},
                      Field{"harmonics", &CampbellResult::harmonics, "",
                            "the per-rev lines n Omega drawn and crossed, n = 1 .. harmonics"},
                      Field{"labels", &CampbellResult::labels, "", "the modes"},
                      Field{"points", &CampbellResult::points, "", "the modes at each speed"},
                      Field{"crossings", &CampbellResult::crossings, "",
                            "every crossing of a mode's frequency with a per-rev line"}),
      describe(Tag<Outcome>{}));
}

// The Campbell diagram of the blade `params` describes at Omega_0 (with its model, modes and
// structural damping).  Checks options (InvalidInput naming the field) and the parameters at
// Omega_0.  A speed whose analysis fails (or throws InvalidInput) is a point with status Failed
// and no modes; the result is as bad as its worst point (Outcome::Include).
CampbellResult campbell_diagram(const RotorParameters& params, const TransitionOptions& transition,
                                const CampbellOptions& options);

}  // namespace flaplag
