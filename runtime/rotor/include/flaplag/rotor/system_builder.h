// flaplag (internal) — from rotor parameters to the periodic system y' = A(psi) y + f(psi).
//
// Operating point: inflow (eq 2.24), mode shapes, spanwise integrals and generalized masses,
// elastic coupling, hover equilibrium (2.29-2.32).  For each mu: the generated coefficient
// functions evaluated with the normal-region integrals and with the reversed-sector integrals
// (Appendix D), assembled into harmonic matrices of A and f.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "flaplag/blade/aero_integrals.h"
#include "flaplag/blade/blade.h"
#include "flaplag/rotor/hover.h"
#include "flaplag/model_api.h"
#include "flaplag/rotor/parameters.h"
#include "flaplag/numerics/periodic_system.h"

namespace flaplag::detail {

// Half-angle sector of reversed flow (Appendix D): alpha = pi/2 for mu < 1, eq D.2 for mu >= 1.
double reversed_flow_sector_width(double mu);

class SystemBuilder {
 public:
  SystemBuilder(const RotorParameters& p, const model::ModelDescriptor& m);

  const RotorParameters& params() const { return p_; }
  const model::ModelDescriptor& model() const { return *model_; }
  const ModeSet& modes() const { return modes_; }
  const HoverResult& hover() const { return hover_; }
  int state_size() const { return 2 * n_; }

  PeriodicSystem system(double mu) const;
  // Aerodynamic integrals used inside the reversed sector at mu.
  std::vector<double> reversed_integrals(double mu) const;
  const std::vector<double>& normal_integrals() const { return aero_.normal(); }

  // The nonlinear generalized loads (model_api.h NonlinearOutputs) at mu with the aerodynamic
  // integrals `aero` of one flow region, at the full state y [2n]: force [H_nl*n] and
  // jacobian [H_nl*n*2n].  Only for models with nonlinear loads (model().nonlinear != nullptr).
  void nonlinear_loads(double mu, const std::vector<double>& aero, const double* y, double* force,
                       double* jacobian) const;
  // generalized mass^-1 [n x n]
  const Eigen::MatrixXd& mass_inverse() const { return mass_inverse_; }
  const std::vector<double>& structural_values() const { return structural_; }

 private:
  model::CoefficientInputs inputs(double mu, const double* aero) const;
  void assemble(double mu, const std::vector<double>& aero, HarmonicSet& out) const;

  RotorParameters p_;
  const model::ModelDescriptor* model_;
  int M_, N_, n_, H_;
  ModeSet modes_;
  SpanGeometry geometry_;
  double inflow_ = 0.0, cdo_a_ = 0.0;
  ElasticCoupling coupling_;
  std::vector<double> es_flap_, es_lag_, ecs_flap_lag_, ecs_lag_flap_;  // row-major copies
  std::vector<double> structural_;
  AeroIntegrals aero_;
  std::vector<double> g0_, h0_;
  std::vector<double> damping_flap_, damping_lag_;  // per mode [M], [N]
  Eigen::VectorXd hover_forcing_;         // forcing[0] at mu = 0, normal flow, at the equilibrium
  Eigen::MatrixXd mass_inverse_;  // generalized mass^-1, factored once in the constructor
  HoverResult hover_;
};

}  // namespace flaplag::detail
