// flaplag — rotating modes by cubic finite elements: the second discretization of the exact
// modes (RotorParameters::basis = elements), independent of the Galerkin basis of
// rotating_modes.h, and the reference the Galerkin modes of a blade table are checked against.
//
// The same equations as rotating_modes.h (eqs A.1-A.4 with the blade's distributions):
//   flap:  [s B + G] q = wbar^2 M q,   lag:  [s B + G - M] q = wbar^2 M q,
//   M = int mbar N N + tip N(1) N(1),  B = int kshape N'' N'',  G = int T N' N',
// on C1 Hermite elements (deflection and slope at each node, cubic between), clamped at x0 = 0.
// The nodes are the blade's stations, each interval divided into equal elements no longer than
// 1 / kElementsPerSpan; the element integrals are exact (5-point Gauss on polynomials).  The
// frequencies converge as h^4 for any table (corners at the stations, a tip mass): relative
// error about (beta h)^4 / 720 for a mode of wavenumber beta, below 1e-9 for the first three
// modes of the paper's blade.
#pragma once

#include <vector>

#include "flaplag/blade/rotating_modes.h"

namespace flaplag {

inline constexpr int kElementsPerSpan = 96;

// A mode on the element mesh: nodal deflections and slopes, Hermite-cubic between; the second
// derivative is linear and the third constant on each element.
class ElementModeShape final : public ModeShape {
 public:
  ElementModeShape(std::vector<double> nodes, std::vector<double> deflection,
                   std::vector<double> slope);
  double value(int d, double x0) const override;

 private:
  std::vector<double> nodes_, w_, dw_;
};

// The element nodes of the mesh described above for the blade's stations (0 and 1 for the
// uniform blade), ascending, first 0 and last 1.
std::vector<double> element_nodes(const BladeProperties* blade);

// The exact modes of options.blade (the uniform blade of mass options.mbar when null) with first
// rotating frequencies omega_flap and omega_lag, as exact_rotating_modes does with the Galerkin
// basis: stiffness_* are the scales of the table's columns (k itself for the uniform blade),
// omega_*_all the first kMaxBasisFunctions frequencies, the shapes tip-normalised
// ElementModeShapes, modes.mesh the interior nodes.  options.n_basis is not used;
// *_coefficients are empty.  Throws InvalidInput as exact_rotating_modes, and for
// paper_1974_shapes (a property of the Galerkin basis).
ExactModes element_rotating_modes(double omega_flap, double omega_lag,
                                  const ExactModeOptions& options);
// With the table's stiffness columns as absolute k (as blade_stiffness_modes).  Throws
// InvalidInput without a blade.
ExactModes element_stiffness_modes(const ExactModeOptions& options);

}  // namespace flaplag
