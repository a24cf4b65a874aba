// flaplag — blade mode shapes, spanwise integrals and generalized masses.
//
// Uniform mass and stiffness along the span (paper 4.1).  x0 = x0bar in [0, 1] is the elastic
// span coordinate by l; derivatives are d/dx0bar.  Mass is nondimensionalised by I_b (inertia of
// the elastic part about its root, Appendix B), so the uniform mass per unit length is
// mbar = m l^3 / I_b = 3.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "flaplag/blade/blade_properties.h"
#include "flaplag/model_api.h"

namespace flaplag {

// One mode shape with its first three derivatives on [0, 1].
class ModeShape {
 public:
  virtual ~ModeShape() = default;
  // derivative order d in 0..3
  virtual double value(int d, double x0) const = 0;
};

// Eq 4.1: eta = gamma = -(1/3) [1 - 4 x0 - (1 - x0)^4], eta(1) = 1.  Satisfies all cantilever
// boundary conditions.  It is the first nonrotating *assumed* mode, used for flap and lag.
std::shared_ptr<const ModeShape> assumed_mode_shape();

// Nonrotating clamped-free uniform cantilever mode j (1-based; 1 <= j <= 100, accurate to
// ~1e-13 relative for j <= 12), in the classical normalisation:
//   phi_j = cosh(b x0) - cos(b x0) - sigma_j (sinh(b x0) - sin(b x0)),  b = beta_j,
//   sigma_j = (cosh b + cos b) / (sinh b + sin b),
//   int_0^1 phi_i phi_j dx0 = delta_ij,  int_0^1 phi_i'' phi_j'' dx0 = beta_j^4 delta_ij,
//   phi_j(1) = 2 (-1)^(j+1)  (the even-numbered functions have a negative tip).
// Evaluated in a form without cosh/sinh cancellation (blade.cc).  Throws InvalidInput for j out
// of range or a derivative order outside 0..3.
std::shared_ptr<const ModeShape> cantilever_mode(int j);
// beta_j, roots of 1 + cos(beta) cosh(beta) = 0 (1.8751, 4.6941, 7.8548, ...), to full precision.
double cantilever_root(int j);

// The modes of one bending direction (model_api.h Direction): flap (eta_k, (EI)_y) or lag
// (gamma_m, (EI)_z).
struct DirectionModes {
  std::vector<std::shared_ptr<const ModeShape>> shapes;  // mode k = 0..count()-1
  std::vector<double> omega;                             // rotating frequencies by Omega, per shape
  // Nondimensional bending stiffness k = EI / (Omega^2 l I_b); 0 when not known (assumed modes).
  // With a blade table, k(x0) = stiffness times the table's column of the direction at x0.
  double stiffness = 0.0;
  int count() const { return static_cast<int>(shapes.size()); }
};

struct ModeSet {
  // Per direction, indexed by model::index(d): eta_k (k = 0..M-1), gamma_m (m = 0..N-1).
  std::array<DirectionModes, model::kDirectionCount> directions;
  DirectionModes& operator[](model::Direction d) { return directions[model::index(d)]; }
  const DirectionModes& operator[](model::Direction d) const { return directions[model::index(d)]; }
  // The shapes of direction d.
  const std::vector<std::shared_ptr<const ModeShape>>& shapes(model::Direction d) const {
    return (*this)[d].shapes;
  }
  std::string kind;  // "assumed" or "exact"
  // The blade's spanwise distributions; null for the paper's uniform blade (mbar = 3, chord 1,
  // no twist, no tip mass).  Every integral of blade.h and aero_integrals.h weights by them.
  std::shared_ptr<const BladeProperties> blade;
  // Interior nodes where the shapes themselves are only piecewise smooth (finite-element modes,
  // blade_elements.h); empty for shapes smooth on [0, 1].  Quadrature panels end there too.
  std::vector<double> mesh;
};

// The paper's assumed-mode blade: one flap and one lag mode (eq 4.1) with the given rotating
// frequencies; no stiffness information (elastic coupling is neglected with assumed modes).
ModeSet assumed_modes(double omega_flap, double omega_lag);

// Geometry of the aerodynamic span: x = e1 + lr * x0 by R, tip-loss limits A <= x0 <= B.
struct SpanGeometry {
  double e1 = 0.0;  // hinge offset by R
  double lr = 1.0;  // l / R
  double tip_loss_a = 0.0;
  double tip_loss_b = 1.0;
};

// Throws InvalidInput unless e1 >= 0, lr > 0 and A <= B, all finite.
void validate(const SpanGeometry& g);

// The quadrature behind every spanwise integral: composite Gauss-Legendre, 8 equal panels of
// 20 points on [a, b].  Exact for polynomials of degree <= 39 (the assumed-mode integrands) and
// accurate to ~1e-14 relative for products of up to four exact modes built from <= 8 cantilever
// functions.
struct SpanRule {
  std::vector<double> x0;      // nodes
  std::vector<double> weight;  // weights, sum = b - a
};
SpanRule span_rule(double a, double b);
// The same with the panels that hold a corner (a station of a blade table, where the
// distributions are not smooth) split there, so that every panel integrand is smooth.
SpanRule span_rule(double a, double b, const std::vector<double>& corners);
// The panel edges of that rule: a, the 8 equal panels' edges, the corners inside (a, b), b.
std::vector<double> panel_edges(double a, double b, const std::vector<double>& corners);
// The corners of the blade's distributions and the mesh of its shapes, ascending (none for the
// uniform blade's smooth modes).
std::vector<double> blade_corners(const ModeSet& modes);

// int_{x0_lo}^{x0_hi} x^p prod(factors) dx0  (Gauss quadrature, exact for the polynomial modes).
// The reference for the production integrals of aero_integrals.h.
// X0 factors are x0bar; Arm factors are x0bar + e1/l with e1/l = g.e1 / g.lr; Twist factors are
// modes.blade->twist_at(x0bar) (0 without a blade table).
double aero_integral(const model::AeroIntegral& spec, const ModeSet& modes, const SpanGeometry& g,
                     double x0_lo, double x0_hi);

// Values of every aerodynamic integrand of model m,  x^p prod(factors),  at the stations x0
// (out[j][q] for integral j at station q).  Shared by the Gauss quadrature above and the
// production integrals of aero_integrals.h.  Throws InvalidInput for an invalid geometry or a
// factor naming a mode the set does not have.
std::vector<std::vector<double>> aero_integrands(const model::ModelDescriptor& m,
                                                 const ModeSet& modes, const SpanGeometry& g,
                                                 const std::vector<double>& x0);

// Structural generalized masses (see model_api.h); mbar = 3, e1_over_l = e1 / l.  The inner
// integral is evaluated by Gauss quadrature on [x, end of x's panel] plus whole-panel sums, so
// nested integrals are as accurate as single ones (exact for the assumed mode).
double structural_integral(const model::StructuralIntegral& spec, const ModeSet& modes,
                           double e1_over_l, double mbar = 3.0);
std::vector<double> structural_integrals(const model::ModelDescriptor& m, const ModeSet& modes,
                                         double e1_over_l, double mbar = 3.0);

// Elastic coupling (Appendix E, eqs E.3-E.8) for collective pitch theta, one block per pair of
// directions (row: the equation's direction, column: the coordinate's):
//   (flap, flap) Es_F[i][k]  = (k_z - k_y) sin^2(theta)         int eta_i'' eta_k''
//   (lag, lag)   Es_L[i][m]  = (k_z - k_y) sin^2(theta)         int gamma_i'' gamma_m''
//   (flap, lag)  Ecs_FL[i][m] = (k_z - k_y) sin(theta)cos(theta) int eta_i'' gamma_m''
//   (lag, flap)  Ecs_LF[i][k] = (k_z - k_y) sin(theta)cos(theta) int gamma_i'' eta_k''
// with k = EI / (Omega^2 l I_b).  All zero when the ModeSet carries no stiffness.
struct ElasticCoupling {
  // blocks[index(row)][index(column)]: count(row) x count(column)
  std::array<std::array<Eigen::MatrixXd, model::kDirectionCount>, model::kDirectionCount> blocks;
  const Eigen::MatrixXd& block(model::Direction row, model::Direction column) const {
    return blocks[model::index(row)][model::index(column)];
  }
};
ElasticCoupling elastic_coupling(const ModeSet& modes, double theta);
ElasticCoupling no_elastic_coupling(const ModeSet& modes);

}  // namespace flaplag
