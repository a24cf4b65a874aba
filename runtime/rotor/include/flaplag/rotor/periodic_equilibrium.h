// flaplag — the periodic equilibrium q°(psi) of the nonlinear flap-lag equations at advance
// ratio mu, and the linearization about it.
//
// Equations: mass q'' = G(q, q', psi) = sum_h phi_h(psi) force_h(q, q'), the nonlinear loads of
// the model (model_api.h NonlinearOutputs), with the aerodynamic
// integrals of the normal region or, inside the reversed-flow sector (Appendix D), of the sector.
// In first-order form y' = F(y, psi), y = [g', g, h', h] the full state (model_api.h ordering).
//
// Method: harmonic balance + Newton.  q°(psi) = sum_{c <= 2K} X_c phi_c(psi); the Fourier
// coefficients (c < 2K+1) of the residual q'' - mass^-1 G are set to zero; each Newton step
// solves with the exact Jacobian of those coefficients (from the generated dG/dy).  Why not
// shooting: harmonic balance gives q° as a finite Fourier series, so the linearization
// A(psi) = dF/dy(q°(psi), psi) is again a finite Fourier series in each flow region (the model's
// harmonics times those of q°).  The existing PeriodicSystem of harmonic sets, the transition
// methods (Hsu's exact interval means included), their automatic step choice and error estimates,
// and the continuation then work unchanged; shooting would give q° only point-wise and need a
// point-wise evaluation path of A(psi).  The price is the truncation at K harmonics: with the
// reversed-flow sector q°'' jumps at the sector edges, so the coefficients of q° fall like
// k^-3; by default K is chosen by doubling until two K agree (harmonics_error), and the result
// also reports the size of the last harmonic (docs/validation.md gives mu_c against K).  The
// projections are integrals over each smooth piece (split at the sector edges) by composite 8-point
// Gauss-Legendre rules fine enough for the trigonometric degree of the integrand (converged to
// rounding).
#pragma once

#include <Eigen/Dense>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "flaplag/core/outcome.h"
#include "flaplag/core/validation.h"
#include "flaplag/numerics/periodic_system.h"

namespace flaplag {

namespace detail {
class SystemBuilder;  // flaplag/rotor/system_builder.h (internal)
}

// y' = F(y, psi) of the nonlinear equations at one mu (full state y, size 2n).  Holds a reference
// to the builder: must not outlive it.
class NonlinearSystem {
 public:
  // InvalidInput("model", ...) when the model has no nonlinear loads; ("mu", ...) when mu is
  // not finite and >= 0.
  NonlinearSystem(const detail::SystemBuilder& builder, double mu);

  int size() const { return ns_; }  // 2n
  double mu() const { return mu_; }
  // The reversed-flow sector [begin, end) of the linear system at mu (has_sector false: none).
  const PeriodicSystem& sector() const { return sector_; }
  bool reversed(double psi) const;

  // F(y, psi) and, when J is not null, dF/dy [2n x 2n]; in_sector selects the region (callers
  // on a sector edge choose the side).
  void evaluate(double psi, bool in_sector, const Eigen::VectorXd& y, Eigen::VectorXd* F,
                Eigen::MatrixXd* J) const;
  void evaluate(double psi, const Eigen::VectorXd& y, Eigen::VectorXd* F,
                Eigen::MatrixXd* J) const {
    evaluate(psi, reversed(psi), y, F, J);
  }
  // The rotor thrust of one blade T(y, psi) (ModelDescriptor::nonlinear_thrust, the load of
  // trim.h's thrust at the full state y) in the region in_sector selects; models with cyclic
  // pitch and nonlinear loads only (else std::logic_error).
  double thrust(double psi, bool in_sector, const Eigen::VectorXd& y) const;

  // Classical RK4 from (psi0, y0) over `revolutions` revolutions with `steps_per_rev` equal
  // steps per revolution, each split at the sector edges.  Returns the state at the end of each
  // revolution (revolutions entries).  For checks against the periodic equilibrium.
  std::vector<Eigen::VectorXd> integrate(const Eigen::VectorXd& y0, int revolutions,
                                         int steps_per_rev) const;

 private:
  const detail::SystemBuilder* builder_;
  double mu_;
  int n_, ns_, H_;
  std::vector<double> normal_, reversed_;  // aerodynamic integrals of the two regions
  PeriodicSystem sector_;
};

struct PeriodicEquilibriumOptions {
  // harmonics = kAutomaticHarmonics: K chosen by doubling (see periodic_equilibrium below).
  static constexpr int kAutomaticHarmonics = -1;
  static constexpr int kFirstHarmonics = 8;  // the automatic K starts here without a start
  static constexpr int kMaxHarmonics = 64;   // and doubles up to this cap
  static constexpr Range kHarmonicsRange{{1, 128, false, false}, "1..128, or -1 (automatic)"};
  static constexpr Range kToleranceRange{{0.0, 1e-2, true, false}, "in (0, 1e-2]"};
  static constexpr Range kIterationsRange{{1, 1000, false, false}, "1..1000"};
  static constexpr Range kMinStepRange{{0.0, 0.1, true, false}, "in (0, 0.1]"};
  int harmonics = kAutomaticHarmonics;  // K, harmonics of q°: 1..128 fixed, or automatic
  // Automatic K: accepted when the estimate of the relative error of the coefficients of q°
  // (harmonics_error of the result) is at most this, (0, 1e-2].  1e-4: in the typical case
  // (paper, mu = 0.6) the coefficients of K = 8, 16, 32 differ by 9e-5 and 1.3e-5
  // while the largest zeta of the linearization agrees to 1e-7, far below the analysis's
  // zeta tolerance 1e-5 (TransitionOptions); the K is then 16 (8 near hover, 32 near the fold).
  double harmonics_tolerance = 1e-4;
  int max_iterations = 30;      // Newton iterations, 1..1000
  double tolerance = 1e-12;     // on max |Newton step| / max(1, max |X|), (0, 1e-2]
  bool check_stability = true;  // Floquet multipliers of the linearization (RK4, 4096 steps)
  // The continuation in mu gives up when its step falls below this (near a fold), (0, 0.1].
  double min_continuation_step = 1e-5;
  std::optional<InvalidInput> Validate() const;
  bool IsValid(std::string* error) const { return IsValidReport(Validate(), error); }
  void Check() const { ThrowIfInvalid(Validate()); }
};

// harmonics: kHarmonicsRange or kAutomaticHarmonics, checked by hand.
constexpr auto describe(Tag<PeriodicEquilibriumOptions>) {
  using O = PeriodicEquilibriumOptions;
  return std::make_tuple(
      Option{"harmonics", &O::harmonics, "", "harmonics K of q°: 1..128, or -1 (automatic)"},
      Option{"harmonics_tolerance", &O::harmonics_tolerance, "-",
             "automatic K: the relative error of the coefficients accepted", &O::kToleranceRange},
      Option{"max_iterations", &O::max_iterations, "", "Newton iterations", &O::kIterationsRange},
      Option{"tolerance", &O::tolerance, "-", "on the Newton step, relative", &O::kToleranceRange},
      Option{"check_stability", &O::check_stability, "",
             "Floquet multipliers of the linearization"},
      Option{"min_continuation_step", &O::min_continuation_step, "-",
             "the continuation in mu gives up below this step", &O::kMinStepRange});
}

struct PeriodicEquilibrium : Outcome {
  double mu = 0.0;
  int harmonics = 0;   // K
  int flap_modes = 0;  // M (the coordinates are M flap, then N lag amplitudes)
  // Fourier coefficients of the coordinates q° = [g°_1..g°_M, h°_1..h°_N]: n x (2K+1), column c
  // the harmonic index of periodic_system.h (0 const, 2k-1 cos k psi, 2k sin k psi).
  Eigen::MatrixXd coefficients;
  // The full state y°(psi) = [g°', g°, h°', h°] (model_api.h ordering).
  Eigen::VectorXd state(double psi) const;
  // y' = A(psi) y about y°: A = dF/dy(y°(psi), psi) as harmonic sets of the normal region and
  // the sector (f = 0: y is the perturbation about the equilibrium).
  PeriodicSystem linearization;
  double continued_to = 0.0;  // the mu nearest `mu` that the continuation reached
  int iterations = 0;
  double step = 0.0;        // last Newton step, max norm, relative
  double residual = 0.0;    // max |projected residual| (generalized coordinates per rev^2)
  double truncation = 0.0;  // amplitude of harmonic K of q° relative to max |q°| coefficient
  // Error estimate of q° in K: max_c |X_c(K) - X_c(K/2)| / max |X(K)| over the coefficients,
  // the difference to the solution with half the harmonics (a conservative estimate of the
  // error of the K solution, which converges like K^-2.7 in the typical case).  Automatic K
  // only (else NaN).
  double harmonics_error = std::numeric_limits<double>::quiet_NaN();
  // Models with cyclic pitch and nonlinear loads (ModelDescriptor::nonlinear_thrust): the
  // azimuth mean of the thrust of one blade along q°, (1/2 pi) int T(y°(psi), psi) dpsi (the
  // sector's integrals inside it), so that C_T = (sigma a / 2) mean_thrust (trim.h); NaN for
  // the other models or when the equilibrium failed.
  double mean_thrust = std::numeric_limits<double>::quiet_NaN();
  // With check_stability: Floquet multipliers of the linearization (modulus sorted descending)
  // and min_k |Lambda_k - 1|.
  std::vector<double> multiplier_moduli;
  double min_distance_to_one = 0.0;
  // Failed: no convergence, a singular Newton matrix (a multiplier at 1: no unique periodic
  // equilibrium) or overflow; Warning: unstable (the blade does not settle onto it), or a
  // multiplier near 1, or the last harmonic is not small (increase `harmonics`), or the
  // automatic K reached kMaxHarmonics with harmonics_error above `harmonics_tolerance`.
};

// The table of an equilibrium: its numbers, not the coefficients or the linearization (which a
// front end writes as arrays of its own).
constexpr auto describe(Tag<PeriodicEquilibrium>) {
  return std::tuple_cat(
      std::make_tuple(
          Field{"mu", &PeriodicEquilibrium::mu, "-", "the advance ratio"},
          Field{"harmonics", &PeriodicEquilibrium::harmonics, "", "K, the harmonics of q°"},
          Field{"flap_modes", &PeriodicEquilibrium::flap_modes, "",
                "M: the coordinates are M flap, then N lag amplitudes"},
          Field{"continued_to", &PeriodicEquilibrium::continued_to, "-",
                "the advance ratio nearest mu that the continuation from hover reached"},
          Field{"iterations", &PeriodicEquilibrium::iterations, "",
                "Newton iterations of the last solve"},
          Field{"step", &PeriodicEquilibrium::step, "-",
                "the last Newton step, max norm, relative"},
          Field{"residual", &PeriodicEquilibrium::residual, "-",
                "max |projected residual| (generalized coordinates per rev^2)"},
          Field{"truncation", &PeriodicEquilibrium::truncation, "-",
                "amplitude of harmonic K of q° relative to its largest coefficient"},
          Field{"harmonics_error", &PeriodicEquilibrium::harmonics_error, "-",
                "automatic K: the largest coefficient change from K/2 to K, relative to the "
                "largest coefficient; not a number (null) for a fixed K"},
          Field{"mean_thrust", &PeriodicEquilibrium::mean_thrust, "-",
                "azimuth mean of one blade's thrust along q° (C_T = sigma a / 2 times it); not a "
                "number (null) for a model without nonlinear thrust"},
          Field{"multiplier_moduli", &PeriodicEquilibrium::multiplier_moduli, "-",
                "|Floquet multipliers| of the linearization about q°, descending (with the "
                "stability check; empty otherwise)"},
          Computed{"min_distance_to_one",
                   +[](const PeriodicEquilibrium& e) {
                     return e.multiplier_moduli.empty()
                                ? std::optional<double>()
                                : std::optional<double>(e.min_distance_to_one);
                   },
                   "-", "min |multiplier - 1|; null without the stability check"}),
      describe(Tag<Outcome>{}));
}

// opt.Check() first (InvalidInput).  The equilibrium on the branch through the hover
// equilibrium (which solves the equations at mu = 0): continuation in mu from hover in steps of
// at most 0.1 that move no coefficient by more than 0.01, halved otherwise.  Where that branch
// folds (a real multiplier reaches 1 and the branch turns back) there is no equilibrium beyond it:
// status Failed, continued_to says where.
// Automatic K (opt.harmonics = kAutomaticHarmonics): the continuation runs at K0 (start's K / 2
// from a start of automatic K, else kFirstHarmonics), then Newton at mu alone at 2 K0, 4 K0, ...
// (each started from the previous solution padded with zero harmonics) until harmonics_error
// <= opt.harmonics_tolerance or K = kMaxHarmonics; the result is the last, finest solution.
// `start` (optional): an equilibrium at start->mu <= mu + 0.1 (its coefficients truncated or
// padded to the K of the continuation), itself from this
// function, of this builder or of one with slightly different parameters (a neighbouring trim
// iterate): it is corrected by Newton at start->mu, and the continuation then starts there
// (upwards or downwards) instead of at hover (same branch, fewer steps).  Ignored when it does
// not fit, when that correction fails or when it moves a coefficient by more than 0.01.
PeriodicEquilibrium periodic_equilibrium(const detail::SystemBuilder& builder, double mu,
                                         const PeriodicEquilibriumOptions& opt = {},
                                         const PeriodicEquilibrium* start = nullptr);

}  // namespace flaplag
