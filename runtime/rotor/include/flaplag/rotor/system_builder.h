// flaplag (internal) — from rotor parameters to the periodic system y' = A(psi) y + f(psi).
//
// Operating point: inflow (eq 2.24), mode shapes, spanwise integrals and generalized masses,
// elastic coupling, hover equilibrium (2.29-2.32).  For each mu: the generated coefficient
// functions evaluated with the normal-region integrals and with the reversed-sector integrals
// (Appendix D), assembled into harmonic matrices of A and f.  With exact_reversed_flow the
// sector is replaced by the exact circle: on the retreating side the integrals are split at
// the station where the flow reverses at that psi, so A and f come from a psi-dependent
// evaluator piece of the PeriodicSystem there.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "flaplag/blade/aero_integrals.h"
#include "flaplag/blade/blade.h"
#include "flaplag/model_api.h"
#include "flaplag/numerics/periodic_system.h"
#include "flaplag/rotor/hover.h"
#include "flaplag/rotor/inflow.h"
#include "flaplag/rotor/parameters.h"

namespace flaplag::detail {

// Half-angle sector of reversed flow (Appendix D): alpha = pi/2 for mu < 1, eq D.2 for mu >= 1.
double reversed_flow_sector_width(double mu);

// The exact circular region of reversed flow at mu: the blade stations x = r/R < -mu sin psi
// (the circle of diameter mu on the retreating side).  On the aerodynamic span
// x in [x_A, x_B] = [e1 + (l/R) A, e1 + (l/R) B] the reversed part is non-empty for psi in
// (begin, end) = (pi + asin(x_A/mu), 2 pi - asin(x_A/mu)) when mu > x_A; the whole span is
// reversed between the breaks pi + asin(x_B/mu) and 2 pi - asin(x_B/mu) when mu > x_B.  The
// split station moves smoothly with psi between these points and is clipped at them, so they
// are where A(psi) is not smooth.
struct ExactReversedRegion {
  bool exists = false;
  double begin = 0.0, end = 0.0;  // radians, pi <= begin < end <= 2 pi
  std::vector<double> breaks;     // inside (begin, end), sorted
};
ExactReversedRegion exact_reversed_region(double mu, const RotorParameters& p);
// The rotor thrust of one blade, T(psi) = sum_h phi_h(psi) (t[h] + tau[h] . y) for one flow
// region (ModelDescriptor::thrust; y the perturbation state about the hover equilibrium).
struct ThrustHarmonics {
  std::vector<double> t;                // [H]
  std::vector<Eigen::RowVectorXd> tau;  // [H] each 1 x 2n
};
struct ThrustSystem {
  ThrustHarmonics normal, reversed;  // reversed: used inside the sector of system(mu)
};

class SystemBuilder {
 public:
  // inflow: the inflow model (inflow.h; the default: eq 2.24).  The hover equilibrium is at its
  // lambda at mu = 0, the system at mu at its lambda at mu.  Throws InvalidInput for a bad
  // model, and InvalidInput("theta1c"/"theta1s", ...) when cyclic pitch is asked of a model
  // without it.
  SystemBuilder(const RotorParameters& p, const model::ModelDescriptor& m,
                const InflowModel& inflow = {});

  const RotorParameters& params() const { return p_; }
  const model::ModelDescriptor& model() const { return *model_; }
  const ModeSet& modes() const { return modes_; }
  const HoverResult& hover() const { return hover_; }
  int state_size() const { return 2 * n_; }

  PeriodicSystem system(double mu) const;
  // The same into *out, reusing its storage: along a continuation the harmonic matrices have
  // the same sizes at every mu, so nothing is allocated after the first call.
  void system(double mu, PeriodicSystem* out) const;
  // Thrust harmonics at mu (models with ModelDescriptor::thrust only; else std::logic_error).
  ThrustSystem thrust(double mu) const;
  // lambda in hover (the hover equilibrium's) and at mu.
  double inflow() const { return inflow_; }
  double inflow(double mu) const {
    return inflow_model_.varies_with_mu() ? inflow_model_.lambda(p_, mu) : inflow_;
  }
  const InflowModel& inflow_model() const { return inflow_model_; }
  // Aerodynamic integrals used inside the reversed sector at mu.
  std::vector<double> reversed_integrals(double mu) const;
  // Aerodynamic integrals of the exact region at (mu, psi): -int_A^{x0} + int_{x0}^B with
  // x0 = (-mu sin psi - e1)/(l/R) clipped to [A, B] (the sector's rule with its fixed station
  // x = mu replaced by x = -mu sin psi); the normal values where x0 <= A.
  std::vector<double> exact_integrals(double mu, double psi) const;
  // Harmonic matrices of A and f at mu for a given set of aerodynamic integrals (in the exact
  // region, system(mu).A(psi) is harmonics(mu, exact_integrals(mu, psi)) summed at psi).
  HarmonicSet harmonics(double mu, const std::vector<double>& aero) const;
  const std::vector<double>& normal_integrals() const { return aero_.normal(); }

  // The nonlinear generalized loads (model_api.h NonlinearOutputs) at mu with the aerodynamic
  // integrals `aero` of one flow region, at the full state y [2n]: force [H_nl*n] and
  // jacobian [H_nl*n*2n].  Only for models with nonlinear loads (model().nonlinear != nullptr).
  void nonlinear_loads(double mu, const std::vector<double>& aero, const double* y, double* force,
                       double* jacobian) const;
  // The rotor thrust of one blade at the full state y [2n] (ModelDescriptor::nonlinear_thrust):
  // thrust [H_nl] and jacobian [H_nl*2n] (jacobian may be null).  Only for models with both
  // cyclic pitch and nonlinear loads (else std::logic_error).
  void nonlinear_thrust(double mu, const std::vector<double>& aero, const double* y, double* thrust,
                        double* jacobian) const;
  // generalized mass^-1 [n x n]
  const Eigen::MatrixXd& mass_inverse() const { return mass_inverse_; }
  const std::vector<double>& structural_values() const { return structural_; }

 private:
  class ExactTable;  // the exact region's A, f as Chebyshev series in the split station

  model::CoefficientInputs inputs(double mu, const double* aero) const;
  // Which harmonics assemble() writes: all H, or without the trailing ones whose coefficients
  // the model gives as exactly zero (the 3/rev terms of a zero cyclic pitch), which would cost
  // every evaluation of A(psi) and add nothing.
  enum class ZeroTail { Keep, Drop };
  void assemble(double mu, const std::vector<double>& aero, HarmonicSet& out,
                ZeroTail tail = ZeroTail::Keep) const;

  template <class T>
  using PerDirection = std::array<T, model::kDirectionCount>;  // indexed by model::index(d)

  RotorParameters p_;
  const model::ModelDescriptor* model_;
  std::vector<model::DirectionBlock> directions_;  // the model's, in state order
  int n_, H_;
  InflowModel inflow_model_;
  ModeSet modes_;
  SpanGeometry geometry_;
  double inflow_ = 0.0, cdo_a_ = 0.0;
  ElasticCoupling coupling_;
  PerDirection<PerDirection<std::vector<double>>> elastic_;  // row-major copies of its blocks
  std::vector<double> structural_;
  AeroIntegrals aero_;
  PerDirection<std::vector<double>> q0_;          // hover static amplitudes per mode
  PerDirection<std::vector<double>> damping_;     // structural damping ratio per mode
  std::vector<int> rate_col_, displacement_col_;  // the state columns of coordinate j
  Eigen::VectorXd hover_forcing_;  // forcing[0] at mu = 0, normal flow, at the equilibrium
  Eigen::MatrixXd mass_inverse_;   // generalized mass^-1, factored once in the constructor
  HoverResult hover_;
};

}  // namespace flaplag::detail
