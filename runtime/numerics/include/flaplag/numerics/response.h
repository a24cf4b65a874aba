// flaplag — the periodic forced response of y' = A(psi) y + f(psi) and time-domain simulation.
//
// The periodic response is the Floquet particular solution: with Phi = Phi(2 pi, 0) and g the
// state at 2 pi of the solution that starts from y(0) = 0,  (I - Phi) y0 = g  gives the unique
// 2 pi-periodic solution when no multiplier equals 1.  Both Phi and g come from one RK4
// integration of the augmented system z = [y; 1], z' = [[A, f], [0, 0]] z, on the grid of
// transition.cc (equal steps, split at the reversed-flow sector edges, each substep in the
// harmonics of its own region).
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "flaplag/core/outcome.h"
#include "flaplag/core/validation.h"
#include "flaplag/numerics/periodic_system.h"

namespace flaplag {

struct ResponseOptions {
  static constexpr Range kStepsRange{{0, 1 << 20, false, false}, "0 (automatic) or 1..1048576"};
  static constexpr Range kSamplesRange{{2, 100000, false, false}, "2..100000"};
  int steps = 0;             // RK4 steps per period; 0: automatic (|lambda| h <= 1/2, >= 200,
                             // doubled until the periodic state agrees to `tolerance`)
  int samples = 72;          // points of y(psi) reported over one period (>= 2), psi_k = 2 pi k / n
  double tolerance = 1e-10;  // on max |y0(N) - y0(N/2)| relative to max |y0| (automatic steps)
  std::optional<InvalidInput> Validate() const;
  bool IsValid(std::string* error) const { return IsValidReport(Validate(), error); }
  void Check() const { ThrowIfInvalid(Validate()); }
};

constexpr auto describe(Tag<ResponseOptions>) {
  using O = ResponseOptions;
  return std::make_tuple(
      Option{"steps", &O::steps, "", "RK4 steps per period; 0: automatic", &O::kStepsRange},
      Option{"samples", &O::samples, "", "azimuth samples over one period", &O::kSamplesRange},
      Option{"tolerance", &O::tolerance, "-", "automatic steps: on the periodic state, relative",
             &kPositive});
}

struct PeriodicResponse : Outcome {
  Eigen::VectorXd y0;                // the periodic state at psi = 0
  std::vector<double> psi;           // sample azimuths [rad], [0, 2 pi)
  std::vector<Eigen::VectorXd> y;    // y(psi_k)
  double closure = 0.0;              // |y(2 pi) - y(0)| / max(1, |y0|): periodicity check
  std::optional<double> error;       // estimated error of y0 (max norm, relative)
  double min_distance_to_one = 0.0;  // min_k |Lambda_k - 1| (near 0: no unique solution)
  int steps = 0;
  // Outcome: Failed: a multiplier at 1 (singular I - Phi) or overflow
};

// sys.validate() and options.Check() first (InvalidInput).  An unstable system still has a
// periodic solution (status Warning: it is not what the blade settles to).
PeriodicResponse periodic_response(const PeriodicSystem& sys, const ResponseOptions& options = {});

struct SimulationOptions {
  static constexpr Range kRevolutionsRange{{0.0, 1e5, true, false}, "in (0, 1e5]"};
  static constexpr Range kStepsRange = ResponseOptions::kStepsRange;
  static constexpr Range kSamplesRange{{1, 10000, false, false}, "1..10000"};
  double revolutions = 20.0;  // > 0, at most 1e5
  int steps_per_rev = 0;      // RK4 steps per revolution; 0: automatic (|lambda| h <= 1/2, >= 200)
  int samples_per_rev = 36;   // reported points per revolution (>= 1)
  // For front ends that own a nonlinear system (Analysis::simulate): integrate the nonlinear
  // equations instead of the linear ones.  The numerics do not read it: simulate() integrates
  // the linear PeriodicSystem it is given, simulate_nonlinear() the callback it is given.
  bool nonlinear = false;
  std::optional<InvalidInput> Validate() const;
  bool IsValid(std::string* error) const { return IsValidReport(Validate(), error); }
  void Check() const { ThrowIfInvalid(Validate()); }
};

constexpr auto describe(Tag<SimulationOptions>) {
  using O = SimulationOptions;
  return std::make_tuple(
      Option{"revolutions", &O::revolutions, "-", "revolutions simulated", &O::kRevolutionsRange},
      Option{"steps_per_rev", &O::steps_per_rev, "", "RK4 steps per revolution; 0: automatic",
             &O::kStepsRange},
      Option{"samples_per_rev", &O::samples_per_rev, "", "reported points per revolution",
             &O::kSamplesRange},
      Option{"nonlinear", &O::nonlinear, "",
             "integrate the nonlinear equations instead of the linear ones"});
}

struct Simulation : Outcome {
  std::vector<double> psi;         // [rad] from 0
  std::vector<Eigen::VectorXd> y;  // y(psi)
  int steps_per_rev = 0;
  // Outcome: Failed on overflow (the state is kept up to there)
};

// Integrates y' = A y + (forced ? f : 0) from y(0) = y0 (size sys.n).
Simulation simulate(const PeriodicSystem& sys, const Eigen::VectorXd& y0, bool forced,
                    const SimulationOptions& options = {});

// y' = F(psi, y) of a nonlinear system (no rotor knowledge here: the caller's model).  F gets
// the size of y.  `reversed`: the step lies in the reversed-flow region of the grid system (its
// sector, or its point-wise region), so that one RK4 step uses one side of a sector edge only.
using NonlinearRhs =
    std::function<void(double psi, bool reversed, const Eigen::VectorXd& y, Eigen::VectorXd& F)>;

// Integrates y' = F(psi, y) by classical RK4 on the grid of simulate(): `grid` (typically the
// linearization of F about an equilibrium, size grid.n = y0.size()) supplies the sector edges
// at which steps are split and, with steps_per_rev = 0, the automatic step count (|lambda| h
// <= 1/2 for its A(psi)).  grid.validate() and options.Check() first (InvalidInput); y0 finite
// (InvalidInput "y0").  Status Failed on overflow, the state kept up to there.
Simulation simulate_nonlinear(const PeriodicSystem& grid, const NonlinearRhs& rhs,
                              const Eigen::VectorXd& y0, const SimulationOptions& options = {});

// A quantity T(psi, reversed, y) along the linear solution: `reversed` as for NonlinearRhs.
using PeriodicQuantity = std::function<double(double psi, bool reversed, const Eigen::VectorXd& y)>;

// (1/2 pi) int_0^2pi T(psi, y(psi)) dpsi along y' = A(psi) y + f(psi) from y(0) = y0 over one
// revolution: classical RK4 on the augmented system [y; int T], on the grid of the periodic
// response's monodromy (`steps` equal steps, split at the sector edges), so that y(psi) is the
// one periodic_response integrates.  sys.validate() first; steps >= 1 and y0 of size sys.n,
// finite (InvalidInput); NaN on overflow.
double periodic_mean(const PeriodicSystem& sys, const Eigen::VectorXd& y0, int steps,
                     const PeriodicQuantity& quantity);

// The growth rate of a simulated signal per rev: the slope of ln max_{rev k} |s| over the
// revolutions from `skip_revs` on, by least squares over whole revolutions (the envelope of
// a Floquet solution grows like exp(zeta psi)).  nullopt with fewer than 3 revolutions left.
std::optional<double> envelope_growth_rate(const std::vector<double>& psi,
                                           const std::vector<double>& signal, double skip_revs);

}  // namespace flaplag
