// flaplag — a blade property table (CSV) and what it sets in RotorParameters.
//
// The file: `#` comment lines and blank lines are skipped; the first other line names the
// columns, every following line is a station, except lines whose first cell is a keyword.
//   x            station by R from the hub centre (nondimensional table), or
//   r [m]        station radius (dimensional table: SI units throughout);
//                the first station is the root of the elastic blade (e1), the last the tip
//                (x = 1, or r = R);
//   m            mass per length (any unit; kg/m in a dimensional table);
//   EI_flap, EI_lag   bending stiffness out of / in the plane of rotation (any unit, scaled to
//                the first rotating frequencies omega_flap, omega_lag; N m^2 in a dimensional
//                table, where the frequencies are results);
//   chord        optional: chord (any unit, taken relative to its value at x = 0.75, the
//                reference chord of gamma and sigma; m in a dimensional table);
//   twist_deg    optional: built-in twist [deg], added to the collective pitch theta (theta is
//                the pitch where the twist is 0).
// Keyword lines (`name,value`):
//   tip_mass        a point mass at the tip: a fraction of the elastic blade's mass (kg in a
//                   dimensional table);
//   rotor_speed_rpm, air_density [kg/m^3], blades    the rotor (dimensional tables only, all
//                   three required there).
// Between stations every column is linear.  A dimensional table determines the paper's
// nondimensional groups: gamma = rho a c_ref R^4 / I_b, sigma = b c_ref / (pi R), e1 = r_root/R,
// l/R, mbar = m l^3 / I_b, k = EI / (Omega^2 l I_b), with I_b = int_0^l m r0^2 dr0 + M_tip l^2.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "flaplag/rotor/parameters.h"

namespace flaplag {

struct BladeTable {
  std::string source;  // file name (or "Python") for messages
  bool dimensional = false;
  std::vector<double> station;                                  // x by R, or r [m]
  std::vector<double> mass, ei_flap, ei_lag, chord, twist_deg;  // chord, twist: empty if absent
  std::vector<int> line;                                        // the file line of each station
  double tip_mass = 0.0;
  double rotor_speed_rpm = 0.0, air_density = 0.0;
  int blades = 0;
};

// Parses the text of a table.  Throws InvalidInput whose name is "<source>:<line>: <column>"
// for a cell that is not a number, a missing or extra cell, an unknown column or keyword,
// stations that do not increase, a non-positive m, EI or chord, more than 100000 stations.
BladeTable parse_blade_table(std::string_view text, std::string source);

// Sets p.blade, p.modes = exact, p.root_offset and p.length_ratio from the table; a dimensional
// table also sets gamma, sigma, omega_flap and omega_lag (the first rotating frequencies of its
// stiffness, with p.basis); the groups are also kept in p.blade->origin.  Throws InvalidInput
// naming the table for a blade the model cannot take (a root at or beyond the tip, c_ref outside
// the blade, no rotating frequency).
BladeOrigin apply_blade_table(const BladeTable& table, RotorParameters& p);

// The first rotating frequencies (flap, lag) of `blade` with its stiffness columns taken as
// absolute k (a dimensional table), with p's exact-mode discretization (p.basis: the Galerkin
// basis or finite elements) and root offset.  What apply_blade_table sets omega_flap and
// omega_lag to; the reference of an error estimate recomputes them with its own discretization.
std::pair<double, double> stiffness_frequencies(const RotorParameters& p,
                                                std::shared_ptr<const BladeProperties> blade);

// The fields apply_blade_table sets, by table kind (to refuse the same field given twice).
std::vector<std::string> blade_table_fields(bool dimensional);

}  // namespace flaplag
