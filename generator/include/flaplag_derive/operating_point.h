// flaplag-derive — numbers for the audit report: every derived term evaluated at one stated
// operating point, so that an auditor can check magnitudes as well as forms.
//
// The point is the paper's typical case (Sec. 4.1 and Figs 3-5, 13): gamma = 10, theta = 0.15,
// lambda from eq 2.24 with sigma = 0.05 and a = 2 pi, C_Do = 0.01, omega_F1 = 1.175,
// omega_L1 = 1.28303, mu = 0.5; beta_P = beta_D = 0 and no structural damping (the paper's
// defaults); l/R = 1, A = 0, B = 1, e1 = 0 (Sec. 4.1); uniform blade (mbar = 3) with the assumed
// mode of eq 4.1 for flap and lag, and hence no elastic coupling (Sec. 4.1(a)).  The spanwise
// integrals of the assumed-mode polynomials are evaluated exactly (GiNaC, rational arithmetic);
// the hover equilibrium g0, h0 solves the derived S q0 = c at that point.  Only models with one
// flap and one lag mode have values: the others need the exact rotating modes of the runtime.
#pragma once

#include <ginac/ginac.h>

#include <string>
#include <vector>

#include "flaplag_derive/derive.h"

namespace flaplag::derive {

struct OperatingPoint {
  double lock = 10.0;                     // gamma
  double theta = 0.15;                    // collective pitch [rad]
  double solidity = 0.05;                 // sigma, eq 2.24
  double lift_slope = 6.283185307179586;  // a = 2 pi
  double cdo = 0.01;                      // C_Do
  double omega_flap = 1.175, omega_lag = 1.28303;
  double mu = 0.5;
  double inflow() const;  // lambda, eq 2.24
};

struct PointValues {
  bool available = false;
  std::string reason;  // why there are no values (available == false)
  OperatingPoint point;
  std::vector<double> scalar;              // by scalar index of the model (g0, h0 solved)
  std::vector<GiNaC::numeric> aero;        // exact assumed-mode integrals, int_0^1
  std::vector<GiNaC::numeric> structural;  // exact generalized masses (mbar = 3)

  // Value of a term (its coefficient, scalars and integral).
  double value(const Term& t) const;
  // Value of a slot (sum of its terms).
  double value(const Slot& s) const;
};

// The values of every input of m at the typical case (see above).
PointValues typical_case_values(const DerivedModel& m);

// Exact integrals of the assumed mode of eq 4.1 (eta = gamma = -(1/3)[1 - 4 x0 - (1 - x0)^4])
// for l/R = 1, e1 = 0, A = 0, B = 1 and mbar = 3.
GiNaC::numeric assumed_mode_integral(const AeroIntegralKey& k);
GiNaC::numeric assumed_mode_integral(const StructuralIntegralKey& k);

}  // namespace flaplag::derive
