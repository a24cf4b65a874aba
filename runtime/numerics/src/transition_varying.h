// flaplag (internal) — transition matrices of a PeriodicSystem with a varying region
// (periodic_system.h), where A(psi) is evaluated point by point instead of from harmonics.
//
// Kept apart from the fixed-size harmonic kernels of transition.cc (whose hot path is
// unchanged): transition.cc dispatches here when sys.has_evaluator().  Same grid rule (equal steps,
// a step split at every breakpoint), same methods and orders.
#pragma once

#include <Eigen/Dense>

#include "flaplag/numerics/floquet.h"
#include "flaplag/numerics/periodic_system.h"

namespace flaplag::detail {

Eigen::MatrixXd varying_rk4(const PeriodicSystem& sys, int steps);
Eigen::MatrixXd varying_hsu(const PeriodicSystem& sys, int intervals, int terms);
TransitionResult varying_magnus4(const PeriodicSystem& sys, int steps);

}  // namespace flaplag::detail
