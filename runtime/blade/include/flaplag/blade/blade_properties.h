// flaplag — the spanwise distributions of a nonuniform blade (mass, stiffness, chord, twist, a
// tip mass), nondimensional as in the paper.
//
// Stations x0 = x0bar in [0, 1] along the elastic span (0 at its root, at e1 from the hub
// centre; 1 at the tip); every distribution is linear between stations.  Scaling:
//   mass(x0)      mbar = m l^3 / I_b, with I_b = int_0^l m r0^2 dr0 + M_tip l^2 the inertia of the
//                 elastic blade about its root (Appendix B), so int_0^1 mbar x0^2 dx0 +
//                 tip_mass = 1 (a uniform blade without tip mass: mbar = 3);
//   tip_mass      M_tip l^2 / I_b, a point mass at x0 = 1;
//   stiffness_*   k = EI / (Omega^2 l I_b) (EI_y flap, EI_z lag): absolute when given
//                 dimensionally; a shape scaled to a first rotating frequency otherwise
//                 (rotating_modes.h);
//   chord(x0)     c / c_ref, c_ref the chord the Lock number and solidity are based on;
//   twist(x0)     built-in twist theta_tw [rad], added to the collective pitch theta in the
//                 aerodynamic integrals and in the elastic coupling (Appendix E) at each station.
// A uniform blade is the paper's (mass 3, chord 1, twist 0, no tip mass).
#pragma once

#include <string>
#include <vector>

namespace flaplag {

// Where a blade came from: the nondimensional groups its table gave and, for a dimensional
// table, the dimensional data behind them (what outputs print; not used by the analysis).
struct BladeOrigin {
  double root_offset = 0.0, length_ratio = 1.0;  // e1, l/R
  double tip_mass = 0.0;                         // M_tip l^2 / I_b
  bool dimensional = false;
  double radius = 0.0, rotor_speed = 0.0, air_density = 0.0;  // R [m], Omega [rad/s], rho
  int blades = 0;
  double inertia = 0.0, reference_chord = 0.0;  // I_b [kg m^2], c_ref [m]
  double gamma = 0.0, sigma = 0.0, omega_flap = 0.0, omega_lag = 0.0;
};

struct BladeProperties {
  std::vector<double> x0;              // >= 2 stations, strictly increasing, first 0, last 1
  std::vector<double> mass;            // mbar > 0 per station
  std::vector<double> stiffness_flap;  // k_y > 0 per station (or a shape, see above)
  std::vector<double> stiffness_lag;   // k_z > 0 per station
  std::vector<double> chord;           // c / c_ref > 0 per station
  std::vector<double> twist;           // theta_tw [rad] per station, |theta_tw| < pi/2
  double tip_mass = 0.0;               // M_tip l^2 / I_b >= 0
  // Where the numbers came from ("blade.csv", "Python"), for messages; not part of the blade.
  std::string source;
  BladeOrigin origin;

  // Linear interpolation of a per-station column at s (clamped to [0, 1]).
  double at(const std::vector<double>& column, double x0) const;
  double mass_at(double s) const { return at(mass, s); }
  double chord_at(double s) const { return at(chord, s); }
  double twist_at(double s) const { return at(twist, s); }
  // The interior stations 0 < x0 < 1, where the distributions have corners: quadrature
  // panels end there.
  std::vector<double> corners() const;
};

// Throws InvalidInput naming the first offending column and station ("mass at x0 = 0.5") unless
// the blade is as documented above (sizes, order, signs, finiteness; the mass normalisation to
// 1e-12).
void validate(const BladeProperties& b);

// The blade with its mass and tip mass scaled so that int mbar x0^2 + tip_mass = 1 (what a
// table in arbitrary mass units becomes); throws InvalidInput as validate() for the rest.
BladeProperties normalised_mass(BladeProperties b);

// The paper's uniform blade on two stations (for tests and comparisons).
BladeProperties uniform_blade(double stiffness_flap = 1.0, double stiffness_lag = 1.0);

}  // namespace flaplag
