// flaplag-derive — symbolic derivation of the linearized flap-lag equations (NASA CR-132431).
//
// Pipeline: displacement field (2.13-2.15) and velocities (2.22-2.23) -> loads L_z, L_y
// (2.20-2.21) truncated by eps_D order after every product -> Galerkin projection (2.18-2.19)
// -> structural/inertial residuals from the loads P_x, P_y, P_z (2.4-2.6) with tension by parts
// -> linearization about the hover equilibrium (2.26) -> harmonic form in psi.
//
// The result is a list of terms per output slot, each a rational factor times powers of named
// scalars times one spanwise integral.  Terms carry their eps order, origin and radial-flow flag
// for the audit report.
//
// Implementation: src/physics.cc (kinematics, loads, ordering truncation), src/monomials.cc
// (monomials to terms and slots), src/derive.cc (set-up, assembly, hover equilibrium); the
// bookkeeping symbols (eps, dlt, rf, origin tags, TAIL/HEAD, mass markers) are explained at the
// top of src/deriver.h; paper names in paper_names.h.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <string>
#include <vector>

#include "flaplag/model_api.h"
#include "flaplag_derive/spec.h"

namespace flaplag::derive {

// The values of model::Factor (the run-time interpreter converts by value).
enum class FactorKind {
  Eta = 0,
  EtaPrime = 1,
  Gamma = 2,
  GammaPrime = 3,
  X0 = 4,
  Arm = 5,
  Twist = 6
};
static_assert(static_cast<int>(FactorKind::Twist) == static_cast<int>(model::Factor::Twist));

struct ShapeFactor {
  FactorKind kind;
  int mode;  // 0-based
  bool operator<(const ShapeFactor& o) const {
    return kind != o.kind ? kind < o.kind : mode < o.mode;
  }
  bool operator==(const ShapeFactor& o) const { return kind == o.kind && mode == o.mode; }
};

struct AeroIntegralKey {
  int x_power = 0;
  std::vector<ShapeFactor> factors;  // sorted
  bool operator<(const AeroIntegralKey& o) const {
    return x_power != o.x_power ? x_power < o.x_power : factors < o.factors;
  }
};

enum class InnerKind { None = 0, Tail = 1, Head = 2 };

struct StructuralIntegralKey {
  int outer_mass = 0;
  std::vector<ShapeFactor> outer;  // sorted
  InnerKind inner = InnerKind::None;
  int inner_mass = 0;
  std::vector<ShapeFactor> inner_factors;  // sorted
  bool operator<(const StructuralIntegralKey& o) const;
};

struct IntegralInfo {
  std::string name;        // human: "x^2 eta1 eta1'"
  std::string ident;       // C identifier
  std::string paper_name;  // Appendix B name(s) or ""
};

// Named scalar inputs of the generated functions.
struct ScalarInfo {
  std::string name;   // e.g. "theta", "g0_1", "es_flap_1_1"
  std::string cexpr;  // e.g. "in.theta", "in.q0[kFlap][0]"
  GiNaC::symbol sym;
};

enum class IntegralRef { None, Aero, Structural };

struct Term {
  GiNaC::numeric coef;                       // exact rational
  std::vector<std::pair<int, int>> scalars;  // (scalar index, power), sorted by index
  IntegralRef ref = IntegralRef::None;
  int integral = -1;  // index into aero or structural list
  int eps_order = 0;
  std::string origin;  // load product or structural mechanism
  bool radial_flow = false;
  std::string paper_name;  // paper coefficient for this term (role-aware)
};

// A linear centrifugal stiffness term absorbed into the modal stiffness.
struct AbsorbedTerm {
  int equation;  // row (flap 1..M, lag 1..N)
  int state;     // state column of the displacement it multiplies
  Term term;
};

// An aerodynamic term the spec dropped from an equation by its per-equation term classes or
// its exclusions ([terms.flap], [terms.lag], [exclude]): listed in the report.
struct DroppedTerm {
  int equation;          // row (flap 1..M, lag 1..N); M + N: the rotor thrust
  int harmonic;          // as in the slots
  int state;             // state column it multiplies, -1: forcing
  Term term;             // ref = Aero, integral = -1 (dropped terms add no integral)
  std::string integral;  // the integral's name, e.g. "x eta1 gamma1'"
  std::string reason;
};

struct Slot {
  std::vector<Term> terms;
  GiNaC::ex value;  // sum of the terms, in scalar symbols and integral symbols
};

// One slot of the nonlinear generalized force (spec [emit] nonlinear): the coefficient of the
// monomial prod_c y_c^powers[c] of the *full* state y = [g'_1..g'_M, g_1..g_M, h'_1..h'_N,
// h_1..h_N] (model_api.h ordering, not a perturbation) in equation eq, harmonic h.
struct NonlinearSlot {
  int harmonic = 0;
  int equation = 0;
  std::vector<int> powers;  // [2n], total degree >= 0
  Slot slot;
  int degree() const;
};

struct DerivedModel {
  OrderingSpec spec;
  int M = 1, N = 1, H = 1;  // modes, harmonics
  int n() const { return M + N; }
  std::vector<ScalarInfo> scalars;
  std::vector<AeroIntegralKey> aero_keys;
  std::vector<IntegralInfo> aero;
  std::vector<GiNaC::symbol> aero_syms;
  std::vector<StructuralIntegralKey> structural_keys;
  std::vector<IntegralInfo> structural;
  std::vector<GiNaC::symbol> structural_syms;

  std::vector<Slot> mass;     // [n*n]
  std::vector<Slot> force;    // [H*n*2n]
  std::vector<Slot> forcing;  // [H*n]
  std::vector<Slot> S;        // [n*n]
  std::vector<Slot> c;        // [n]
  // Cyclic-pitch models only (spec.cyclic_pitch; empty otherwise): the rotor thrust of one
  // blade, lr int L_z dx0 with the flap load L_z of the derivation (eq 2.20, the same
  // truncation), as harmonics of its state-independent part [H] and of its linear coefficient
  // of the state [H*2n].  C_T = (sigma a / 2) times its azimuth average.
  std::vector<Slot> thrust_forcing;              // [H]
  std::vector<Slot> thrust_force;                // [H*2n]
  int thrust_equation() const { return M + N; }  // pseudo-equation index used while placing
  // Centrifugal stiffness terms replaced by the modal stiffness M w^2 (orthogonality, eqs A.2,
  // A.4), listed in the report so that nothing derived disappears silently.
  std::vector<AbsorbedTerm> absorbed;
  // Terms dropped by the spec's per-equation term classes and exclusions (linear model),
  // sorted by (equation, state, harmonic, integral, term).  Empty at the paper's defaults.
  std::vector<DroppedTerm> dropped;
  // Nonlinear generalized loads (empty unless spec.nonlinear): the same derivation and eps
  // truncation without the degree-1 cut in the perturbation, about q = 0 instead of the hover
  // equilibrium; sorted by (harmonic, equation, powers).  mass q'' = sum_h phi_h(psi) sum over
  // the slots of harmonic h of slot * y^powers.  Its Jacobian at y = (0, q0) is `force`, its
  // value there `forcing` (tests/generator_test.cpp).
  std::vector<NonlinearSlot> nonlinear;
  // Cyclic-pitch models with nonlinear loads: the rotor thrust of one blade (thrust_force's
  // load) as the same kind of polynomial in the full state; equation = thrust_equation().
  // Its Jacobian at (0, q0) is thrust_force, its value thrust_forcing.
  std::vector<NonlinearSlot> nonlinear_thrust;
  int H_nonlinear = 0;  // harmonics of the nonlinear slots (loads and thrust)

  std::string state_name(int col) const;     // "dg1'", "dg1", "dh1'", "dh1"
  std::string equation_name(int row) const;  // "flap 1", "lag 1"
  static std::string harmonic_name(int h);   // "const", "cos psi", "sin psi", "cos 2psi", ...
};

// Derive the model for a spec.  Deterministic.
DerivedModel derive_model(const OrderingSpec& spec);

}  // namespace flaplag::derive
