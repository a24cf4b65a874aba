// flaplag — exact rotating mode shapes of a cantilevered blade (paper 4.1(b), App. A): the
// uniform blade below, or a blade table (ExactModeOptions::blade).
//
// Galerkin's method on n_basis nonrotating clamped-free cantilever functions phi_j per bending
// direction (blade.h, classical normalisation int phi_i phi_j = delta_ij).  Nondimensional as in
// the paper: span coordinate x0 = x0bar in [0, 1] by l, frequencies by Omega, masses by I_b,
//   mbar = m l^3 / I_b               (= 3 for a uniform blade: I_b = l^3 int_0^1 m x0^2 dx0),
//   k    = EI / (Omega^2 l I_b)      (stiffness_flap = (EI)_y, stiffness_lag = (EI)_z),
//   T(x) = int_x^1 mbar (x1 + e1/l) dx1   (centrifugal tension by Omega^2 I_b / l).
// Eqs A.1-A.2 (flap) and A.3-A.4 (lag) give the symmetric eigenproblems
//   flap:  [k B + G] c = wbar^2 M c,
//   lag:   [k B + G - M] c = wbar^2 M c,
//   B_ij = int phi_i'' phi_j'' = beta_j^4 delta_ij,  G_ij = int phi_i' phi_j' T,
//   M_ij = mbar int phi_i phi_j = mbar delta_ij.
// The nonrotating first frequency is wbar_1N = sqrt(k / mbar) beta_1^2 (k beta^4 = mbar wbar^2).
// The user specifies the first rotating frequencies; k_y and k_z are solved for.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <memory>
#include <vector>

#include "flaplag/blade/blade.h"

namespace flaplag {

// The bending directions are the model's (model_api.h): flap and lag.
using BendingDirection = model::Direction;

// The largest Galerkin basis: the cantilever functions are verified to ~1e-13 for j <= 12
// (blade.h).
inline constexpr int kMaxBasisFunctions = 12;

struct ExactModeOptions {
  int n_basis = 5;     // cantilever functions per direction (paper: 5); 1..kMaxBasisFunctions
  int flap_modes = 1;  // M rotating flap modes returned, 1..n_basis
  int lag_modes = 1;   // N rotating lag modes returned, 1..n_basis
  // The modes returned in direction d: flap_modes or lag_modes.
  int modes(model::Direction d) const {
    return d == model::Direction::Flap ? flap_modes : lag_modes;
  }
  double e1_over_l = 0.0;  // root offset from the rotation axis by l, >= 0 (centrifugal arm)
  double mbar = 3.0;       // m l^3 / I_b (frequencies depend on k / mbar only)
  // Compatibility with the 1974 program (docs/validation.md, "1974 shapes"):
  // rebuild the shapes from the correct Galerkin coefficients c_j with the even-numbered basis
  // functions sign-flipped, eta = sum (-1)^(j+1) c_j phi_j.  Frequencies and stiffnesses are
  // unchanged; the shapes are NOT modes of the blade.  Off by default.
  bool paper_1974_shapes = false;
  // A nonuniform blade (blade_properties.h); null: the uniform blade of mass mbar.  With a
  // blade, the Galerkin matrices are integrals of its distributions (its tip mass included) and
  // `mbar` is not used.
  std::shared_ptr<const BladeProperties> blade;
};

// A linear combination sum_j c_j phi_j of basis shapes (derivatives 0..3 by linearity).
class ModalCombination final : public ModeShape {
 public:
  ModalCombination(std::vector<std::shared_ptr<const ModeShape>> basis,
                   Eigen::VectorXd coefficients);
  double value(int d, double x0) const override;
  const Eigen::VectorXd& coefficients() const { return coefficients_; }

 private:
  std::vector<std::shared_ptr<const ModeShape>> basis_;
  Eigen::VectorXd coefficients_;
};

// The Galerkin solution of one direction beyond the modes it returns.
struct ExactDirection {
  double omega_nonrotating = 0.0;  // first nonrotating frequency, sqrt(k / mbar) beta_1^2
  std::vector<double> omega_all;   // all n_basis rotating frequencies, ascending
  // Coefficients of the returned shapes on phi_1..phi_n (n_basis x count), as used in the
  // ModeSet (i.e. including the 1974 sign flip when that option is set).
  Eigen::MatrixXd coefficients;
};

struct ExactModes {
  // Per direction: tip-normalised rotating modes (eta(1) = gamma(1) = +1, like eq 4.1), kind
  // "exact", their rotating frequencies and the stiffnesses k_y, k_z.
  ModeSet modes;
  std::array<ExactDirection, model::kDirectionCount> directions;  // indexed by model::index(d)
  ExactDirection& operator[](model::Direction d) { return directions[model::index(d)]; }
  const ExactDirection& operator[](model::Direction d) const { return directions[model::index(d)]; }
};

// Exact rotating modes with first rotating frequencies omega_flap = wbar_F1 and omega_lag =
// wbar_L1 (by Omega).  Throws InvalidInput naming "omega_flap" / "omega_lag" when a frequency is
// non-finite, <= 0, or not above the k -> 0 limit of the basis (centrifugal_limit); and naming
// the option for out-of-range options.
ExactModes exact_rotating_modes(double omega_flap, double omega_lag,
                                const ExactModeOptions& options = {});
// With options.blade: the table's stiffness columns scaled so that the first rotating
// frequencies are omega_flap and omega_lag (the returned stiffness_* are the scales).
//
// The modes of options.blade with its stiffness columns taken as absolute k = EI/(Omega^2 l
// I_b) (dimensional input): the frequencies are results.  Throws InvalidInput without a blade.
ExactModes blade_stiffness_modes(const ExactModeOptions& options);
// The ModeSet part of exact_rotating_modes.
ModeSet exact_modes(double omega_flap, double omega_lag, const ExactModeOptions& options = {});

// With a blade table (options.blade) every function below takes and returns the scale s of the
// table's stiffness column in place of k: the blade's stiffness is k(x0) = s column(x0) (a
// dimensional table's columns are absolute, s = 1 at the table's rotor speed; at speed
// Omega = r Omega_0 the same blade has s = 1 / r^2).  The frequencies are those of the
// table's Galerkin matrices (its mass, stiffness, tip mass and centrifugal tension, as
// exact_rotating_modes), and `mbar` is not used.  The blade is checked (validate(), InvalidInput
// naming its column and station).

// All n_basis rotating frequencies (ascending) for stiffness k = EI / (Omega^2 l I_b) >= 0
// (a table: the scale s >= 0).  Throws InvalidInput "stiffness_flap" / "stiffness_lag" for a
// negative or non-finite stiffness.
std::vector<double> rotating_frequencies(BendingDirection direction, double stiffness,
                                         const ExactModeOptions& options = {});
// All n_basis nonrotating frequencies (ascending, by the Omega of the stiffness) for stiffness k
// >= 0: the cantilever's sqrt(k / mbar) beta_j^2, j = 1..n_basis (exact for the uniform blade);
// a table: the square roots of the eigenvalues of (s B, M) (Galerkin, no tension, no -M term).
std::vector<double> nonrotating_frequencies(BendingDirection direction, double stiffness,
                                            const ExactModeOptions& options = {});
// The first rotating frequency as k -> 0 (pure centrifugal stiffening in the basis): flap just
// above 1 for e1 = 0 (1 exactly only for the rigid hinged blade), lag = sqrt(flap^2 - 1).
// Requested first frequencies must exceed it.  A table: its s -> 0 limit (its mass and tip
// mass decide it).
double centrifugal_limit(BendingDirection direction, const ExactModeOptions& options = {});
// k whose first rotating frequency is omega_rotating (bracketed, safeguarded Newton on the
// concave, increasing lambda_1(k)).  Throws as exact_rotating_modes.  A table: the scale s,
// the same number as exact_rotating_modes' stiffness_flap / stiffness_lag.
double stiffness_for_frequency(BendingDirection direction, double omega_rotating,
                               const ExactModeOptions& options = {});

// Fig. 9: first rotating <-> first nonrotating frequency (both by Omega).  A table: the
// nonrotating first frequency is linear in the scale, wn^2 = s lambda_N1(1) (lambda_N1(1) the
// first eigenvalue of (B, M)), so s = wn^2 / lambda_N1(1) and the rotating frequency is the
// first at that scale.
double nonrotating_frequency(BendingDirection direction, double omega_rotating,
                             const ExactModeOptions& options = {});
double rotating_frequency(BendingDirection direction, double omega_nonrotating,
                          const ExactModeOptions& options = {});
struct FrequencyPair {
  double nonrotating;
  double rotating;
};
// n_points >= 2 equally spaced nonrotating frequencies on [lo, hi] (0 <= lo <= hi) with their
// rotating first frequencies: the curves of Fig. 9 (of the table's blade with options.blade).
std::vector<FrequencyPair> fig9_table(BendingDirection direction, double omega_nonrotating_lo,
                                      double omega_nonrotating_hi, int n_points,
                                      const ExactModeOptions& options = {});

// Rayleigh quotient sqrt(R) of any shape, by quadrature:
//   flap: R = [k int eta''^2 + int eta'^2 T] / int mbar eta^2;  lag: R_flap - 1 (eq A.4).
// For an exact mode it returns its frequency; for a wrong shape it shows how wrong.
double rayleigh_frequency(BendingDirection direction, const ModeShape& shape, double stiffness,
                          double e1_over_l = 0.0, double mbar = 3.0);
// The same for a blade table with its stiffness column scaled by `scale` (quadrature panels
// ending at its stations):
//   flap: R = [s int column eta''^2 + int T eta'^2] / [int mbar eta^2 + tip eta(1)^2],
//   lag:  R_flap - 1,   T(x) = int_x^1 mbar (x1 + e1/l) dx1 + tip (1 + e1/l).
// For the table's exact modes (exact_rotating_modes) it returns their frequencies.
double rayleigh_frequency(BendingDirection direction, const ModeShape& shape, double scale,
                          double e1_over_l, const BladeProperties& blade);

}  // namespace flaplag
