#include "flaplag_derive/operating_point.h"

#include <cmath>
#include <stdexcept>

namespace flaplag::derive {

namespace {

using GiNaC::ex;
using GiNaC::numeric;
using GiNaC::symbol;

constexpr int kUniformMass = 3;  // mbar = m l^3 / I_b for a uniform blade with e1 = 0

// Eq 4.1 and its slope; x0 itself for the X0 factor and the centrifugal arm x0 + e1/l (e1 = 0);
// no built-in twist.
ex shape(FactorKind k, const symbol& x) {
  const ex eta = -numeric(1, 3) * (1 - 4 * x - GiNaC::pow(1 - x, 4));
  switch (k) {
    case FactorKind::Eta:
    case FactorKind::Gamma:
      return eta;
    case FactorKind::EtaPrime:
    case FactorKind::GammaPrime:
      return eta.diff(x);
    case FactorKind::X0:
    case FactorKind::Arm:
      return x;
    case FactorKind::Twist:
      return 0;  // the paper's blade is untwisted
  }
  return 0;
}

ex product(const std::vector<ShapeFactor>& f, const symbol& x) {
  ex p = 1;
  for (const auto& s : f) {
    if (s.mode != 0) throw std::logic_error("the assumed mode set has one mode per direction");
    p *= shape(s.kind, x);
  }
  return p;
}

// Antiderivative of a polynomial in x, vanishing at 0.
ex antiderivative(const ex& poly, const symbol& x) {
  const ex p = poly.expand();
  ex r = 0;
  for (int k = p.ldegree(x); k <= p.degree(x); ++k)
    r += p.coeff(x, k) * GiNaC::pow(x, k + 1) / (k + 1);
  return r;
}

numeric definite(const ex& poly, const symbol& x) {
  const ex F = antiderivative(poly, x);
  return GiNaC::ex_to<numeric>((F.subs(x == 1) - F.subs(x == 0)).expand());
}

}  // namespace

double OperatingPoint::inflow() const {
  const double sa = solidity * lift_slope;
  return sa / 16.0 * (std::sqrt(1.0 + 24.0 * theta / sa) - 1.0);  // eq 2.24
}

numeric assumed_mode_integral(const AeroIntegralKey& k) {
  const symbol x("x");  // x = e1/R + (l/R) x0 = x0
  return definite(GiNaC::pow(x, k.x_power) * product(k.factors, x), x);
}

numeric assumed_mode_integral(const StructuralIntegralKey& k) {
  const symbol x("x");
  const ex outer = GiNaC::pow(kUniformMass, k.outer_mass) * product(k.outer, x);
  ex inner = 1;
  if (k.inner != InnerKind::None) {
    const ex G =
        antiderivative(GiNaC::pow(kUniformMass, k.inner_mass) * product(k.inner_factors, x), x);
    inner = k.inner == InnerKind::Tail ? G.subs(x == 1) - G  // int_x^1
                                       : G;                  // int_0^x (G(0) = 0)
  }
  return definite(outer * inner, x);
}

double PointValues::value(const Term& t) const {
  double v = t.coef.to_double();
  for (const auto& [idx, p] : t.scalars) v *= std::pow(scalar[idx], p);
  if (t.ref == IntegralRef::Aero) v *= aero[t.integral].to_double();
  if (t.ref == IntegralRef::Structural) v *= structural[t.integral].to_double();
  return v;
}

double PointValues::value(const Slot& s) const {
  double v = 0.0;
  for (const auto& t : s.terms) v += value(t);
  return v;
}

PointValues typical_case_values(const DerivedModel& m) {
  PointValues r;
  if (m.M != 1 || m.N != 1) {
    r.reason =
        "this model has " + std::to_string(m.M) + " flap x " + std::to_string(m.N) +
        " lag modes: its integrals need the exact rotating modes, which the runtime computes "
        "(the `system` command of the CLI prints their values)";
    return r;
  }
  for (const auto& k : m.aero_keys) r.aero.push_back(assumed_mode_integral(k));
  for (const auto& k : m.structural_keys) r.structural.push_back(assumed_mode_integral(k));
  const OperatingPoint& p = r.point;
  r.scalar.assign(m.scalars.size(), 0.0);  // beta_P, beta_D, damping, E^s, E^cs: 0
  int g0 = -1, h0 = -1;
  for (size_t j = 0; j < m.scalars.size(); ++j) {
    const std::string& n = m.scalars[j].name;
    double& v = r.scalar[j];
    if (n == "lock") v = p.lock;
    if (n == "lr") v = 1.0;
    if (n == "theta") v = p.theta;
    if (n == "inflow") v = p.inflow();
    if (n == "cdo_a") v = p.cdo / p.lift_slope;
    if (n == "mu") v = p.mu;
    if (n == "omega_flap_1") v = p.omega_flap;
    if (n == "omega_lag_1") v = p.omega_lag;
    if (n == "g0_1") g0 = static_cast<int>(j);
    if (n == "h0_1") h0 = static_cast<int>(j);
  }
  // Hover equilibrium S q0 = c (eqs 2.29-2.32); S and c do not contain q0.
  const double S11 = r.value(m.S[0]), S12 = r.value(m.S[1]), S21 = r.value(m.S[2]),
               S22 = r.value(m.S[3]), c1 = r.value(m.c[0]), c2 = r.value(m.c[1]);
  const double det = S11 * S22 - S12 * S21;
  if (det == 0.0) {
    r.reason = "the hover equilibrium matrix S is singular at the typical case";
    return r;
  }
  r.scalar[g0] = (c1 * S22 - S12 * c2) / det;
  r.scalar[h0] = (S11 * c2 - S21 * c1) / det;
  r.available = true;
  return r;
}

}  // namespace flaplag::derive
