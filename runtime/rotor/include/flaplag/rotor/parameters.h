// flaplag — rotor parameters: one source of truth for names, defaults and validation.
//
// All quantities nondimensional as in the paper (angles in radians, frequencies by Omega).
// Defaults are the paper's constants and its "typical case" (Fig. 3): omega_F1 = 1.175,
// omega_L1 = 1.28303, gamma = 10, theta = 0.15 (the collective pitch appears only on the plots).
#pragma once

#include <memory>
#include <string>

#include "flaplag/blade/blade_properties.h"

namespace flaplag {

enum class ModeKind { Assumed, Exact };

struct ImportedModes;  // flaplag/blade/imported_modes.h

// The Galerkin basis of the exact rotating modes (RotorParameters::basis): kConvergedBasis (the
// default) is the largest basis, kMaxBasisFunctions, whose error is estimated against the next
// smaller one and included in every error estimate; kPaperBasis is the paper's five functions
// (4.1(b)), for reproducing it; 1..12 is that many functions (an error estimate against the next
// larger basis, or 11 for 12).  kElementBasis: cubic finite elements instead of the Galerkin basis
// (blade/blade_elements.h), their error estimated against the largest Galerkin basis.  The
// Galerkin modes of a blade table are checked against the finite elements (not the next basis:
// a table's corners and tip mass make the basis converge slowly and not alternately).
inline constexpr int kConvergedBasis = 0;
inline constexpr int kPaperBasis = 5;
inline constexpr int kElementBasis = -1;

struct RotorParameters {
  std::string model = "paper";            // compiled ordering model (see `flaplag models`)
  double gamma = 10.0;                    // Lock number based on normal flow, (0, 1e4]
  double sigma = 0.05;                    // rotor solidity, (0, 1], used by the inflow, eq 2.24
  double lift_slope = 6.283185307179586;  // a [1/rad], (0, 100]
  double cdo = 0.01;                      // profile drag coefficient C_Do, [0, 1]
  double theta = 0.15;                    // collective pitch [rad], (-pi/2, pi/2)
  double theta1c = 0.0;                   // cyclic pitch, cos psi [rad], (-pi/2, pi/2) (*)
  double theta1s = 0.0;                   // cyclic pitch, sin psi [rad], (-pi/2, pi/2) (*)
  double precone = 0.0;                   // beta_P [rad], (-pi/2, pi/2)
  double droop = 0.0;                     // beta_D [rad], (-pi/2, pi/2)
  double omega_flap = 1.175;              // first rotating flap frequency by Omega, (0, 1000]
  double omega_lag = 1.28303;             // first rotating lag frequency by Omega, (0, 1000]
  double damping_flap = 0.0;              // eta_SF, viscous structural damping ratio, [0, 10]
  double damping_lag = 0.0;               // eta_SL, [0, 10]
  double length_ratio = 1.0;              // l / R, (0, 1]
  double tip_loss_a = 0.0;                // A-bar, inner aerodynamic limit in x0bar, [0, 1)
  double tip_loss_b = 1.0;                // B-bar, outer aerodynamic limit in x0bar, (0, 1]
  double root_offset = 0.0;               // e1, root offset of the elastic blade by R, [0, 1)
  bool reversed_flow = true;              // reversed flow: the Appendix D sector model, or
  bool exact_reversed_flow = false;       // the exact circle x < -mu sin psi (needs reversed_flow)
  ModeKind modes = ModeKind::Assumed;
  int basis = kConvergedBasis;   // exact modes: cantilever functions per direction, 1..12,
                                 // kConvergedBasis (the largest, its error estimated) or
                                 // kElementBasis (finite elements)
  bool elastic_coupling = true;  // Appendix E; applies to exact modes only (paper 4.1(a))
  bool paper_1974_shapes =
      false;  // exact modes rebuilt with the 1974 sign slip (docs/validation.md)
  // A nonuniform blade (mass, stiffness shape, chord, twist, tip mass along the elastic span;
  // blade/blade_properties.h); null: the paper's uniform blade.  Needs `modes` = exact: its
  // stiffness columns are scaled so that the first rotating frequencies are omega_flap and
  // omega_lag.  Not a row of parameter_table.h (a table, not a number).
  std::shared_ptr<const BladeProperties> blade;
  // Mode shapes and rotating frequencies imported from a table (e.g. a finite-element model;
  // blade/imported_modes.h, parse_mode_table); null: the modes are computed (assumed or exact).
  // When set, `modes` must be exact, the model's M flap and N lag modes are the columns
  // flap1..flapM and lag1..lagN, their frequencies the table's (omega_flap and omega_lag are
  // then not used), and the stiffnesses of the elastic coupling are those of the uniform blade
  // with the first imported frequencies (with `basis` and root_offset / length_ratio as for
  // the exact modes).  Not a parameter_table row (no command-line option or case key).
  std::shared_ptr<const ImportedModes> mode_shapes;
};

// (*) theta(psi) = theta + theta1c cos psi + theta1s sin psi (every model has cyclic pitch).
//
// Throws InvalidInput naming the first offending field ("omega_lag") and its value; the
// admissible ranges are those of parameter_table.h (also noted above), with tip_loss_a <
// tip_loss_b and C_Do / a <= kMaxDragOverLiftSlope besides.
inline constexpr double kMaxDragOverLiftSlope = 1e300;
void validate(const RotorParameters& p);
// validate() without its last check (that eq 2.24 has a real inflow at theta): for an operating
// point whose inflow is given instead (a trim, eq 2.25).
void validate_except_inflow(const RotorParameters& p);

// The number of cantilever functions the exact modes of p use: p.basis, or kMaxBasisFunctions
// for kConvergedBasis; 0 for kElementBasis (no Galerkin basis).
int galerkin_basis(const RotorParameters& p);
// The basis the error of p's exact modes is estimated against, for a model of M flap and N lag
// modes: for the uniform blade's Galerkin modes the next larger basis (the next smaller for the
// largest), 0 when there is none that holds max(M, N) modes: they converge alternately in the
// basis size (the tip value of the cantilever functions alternates in sign), so that the limit
// lies between two neighbouring bases and their difference bounds the error of either.  For a
// blade table's Galerkin modes kElementBasis; for kElementBasis the largest Galerkin basis.
int reference_basis(const RotorParameters& p, int flap_modes, int lag_modes);
// "12 cantilever functions" or "cubic finite elements": the exact modes' discretization `basis`
// (a value of RotorParameters::basis), as results describe it.
std::string basis_description(int basis);

// Inflow ratio for hover, eq 2.24: lambda = sigma a / 16 [sqrt(1 + 24 theta/(sigma a)) - 1];
// with a blade table, sigma times its thrust-weighted chord 3 int (c/c_ref) x^2 dx and theta
// plus its thrust-weighted twist (x = r/R from the centre, the root values held inboard).
double hover_inflow(const RotorParameters& p);

}  // namespace flaplag
