// flaplag-derive (internal) — the Deriver: GiNaC symbols, their bookkeeping roles and the steps
// of the derivation.  Shared by derive.cc (set-up, assembly of the slots, hover equilibrium),
// physics.cc (kinematics, loads, ordering truncation) and monomials.cc (taking expanded
// monomials apart and placing them into slots).
//
// Every intermediate expression is a polynomial in GiNaC symbols.  Besides the physical inputs,
// the polynomials carry *bookkeeping* symbols that are never given a value; a monomial is taken
// apart by looking up the role of each of its symbols (SymRole) and each bookkeeping symbol
// becomes a field of the resulting Term:
//
//   symbol     role        meaning
//   eps        Eps         ordering parameter eps_D (Appendix C.1): every small quantity q enters
//                          as eps^order(q) q, so a monomial's eps degree is its order
//   dlt        Dlt         perturbation marker: Delta g, Delta h (eq 2.26) enter as dlt * dg ...;
//                          degree 0 = forcing, 1 = linear in the state, >= 2 dropped (linearized)
//   rf         Radial      radial-flow marker: multiplies the mu cos(psi) dv/dx0 term of U_T
//                          (eq 2.23), so every term it produces is flagged `radial` in the report
//   tagN       Tag         origin tag: one symbol per load product or structural mechanism (e.g.
//                          "L_z: -U_T U_P", "tension, Coriolis 2v' (2.4)"); each monomial carries
//                          exactly one, which becomes Term::origin
//   z          Z           z = exp(i psi): cos psi = (z + 1/z)/2, sin psi = (z - 1/z)/(2i); the
//                          z power of a monomial is its harmonic
//   x          X           station radius by R in the aerodynamic integrals, x = e1/R + (l/R) x0
//   eta1, etap1, gam1, gamp1, x0, arm, tw
//              Shape       outer spanwise factors eta_k, eta_k', gamma_m, gamma_m', x0, the
//                          centrifugal arm x0 + e1/l and the built-in twist theta_tw(x0) (in the
//                          aerodynamic pitch only): together they name the integral
//   ieta1, ietap1, igam1, igamp1, iarm
//              InnerShape  the same factors at the inner station x1 of a nested integral
//   m          MassOuter   mass marker: mbar (= m l^3/I_b) in the outer integrand
//   mi         MassInner   mass marker: mbar in the inner integrand
//   TAIL       Tail        the inner factors form int_x^1 ... dx1 (tension integral, eq 2.10)
//   HEAD       Head        the inner factors form int_0^x ... dx1 (foreshortening u, eq 2.8)
//   dgd1, dg1, dhd1, dh1
//              State       state components dg'_k, dg_k, dh'_m, dh_m (index = state column)
//   dgdd1, dhdd1
//              Accel       accelerations g_k'', h_m'' (index = coordinate, i.e. mass column)
//   lock, lr, theta, ..., g0_1, es_flap_1_1, ...
//              Scalar      the named inputs of the generated code (index into the scalar list)
//
// Beware of two gammas: the paper writes both the Lock number and the lag mode shape as gamma.
// Here the Lock number is the scalar `lock` and the lag shape is `gam` (integral names spell it
// "gamma1"); there is no symbol called gamma.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "flaplag_derive/derive.h"

namespace flaplag::derive::detail {

// No truncation of the structural loads: their products are exact to second order in the
// displacements (eqs 2.2-2.10); only the perturbation-degree cut applies.  Any bound above the
// highest eps order that occurs would do.
constexpr int kUntruncated = 1000;

enum class Role {
  Eps,
  Dlt,
  Radial,
  Tag,
  Z,
  Scalar,
  State,
  Accel,
  Shape,
  InnerShape,
  X,
  MassOuter,
  MassInner,
  Tail,
  Head
};

struct SymRole {
  SymRole(Role r, int i = 0, FactorKind k = FactorKind::Eta, std::string t = {})
      : role(r), index(i), kind(k), tag(std::move(t)) {}
  Role role;
  int index;  // scalar index, state column, coordinate, or mode
  FactorKind kind;
  std::string tag;  // origin text for Role::Tag
};

// One expanded monomial, taken apart by its symbols' roles.
struct Mono {
  GiNaC::numeric coef = 1;
  std::vector<std::pair<int, int>> scalars;  // (scalar index, power)
  int eps = 0, dlt = 0, radial = 0, z = 0;   // powers of eps, dlt, rf, z
  std::string origin;                        // from the tag
  int state = -1;                            // state column of a perturbation (power 1)
  std::vector<std::pair<int, int>> states;   // (state column, power), sorted (nonlinear pass)
  int accel = -1;                            // coordinate of an acceleration (power 1)
  int x_power = 0;
  std::vector<ShapeFactor> outer, inner;
  int mass_outer = 0, mass_inner = 0;
  InnerKind inner_kind = InnerKind::None;
};

// Canonical order of terms inside a slot (GiNaC's own order is address dependent).
bool term_less(const Term& a, const Term& b);

class Deriver {
 public:
  explicit Deriver(const OrderingSpec& spec);
  DerivedModel run();

 private:
  // ----- symbols (derive.cc) ---------------------------------------------------------------
  GiNaC::symbol sym(const std::string& name, SymRole role) {
    GiNaC::symbol s(name);
    roles_.emplace(name, std::move(role));
    return s;
  }
  int add_scalar(const std::string& name, const std::string& cexpr);
  GiNaC::ex scalar(int idx) const { return model_.scalars[idx].sym; }
  GiNaC::ex eps_pow(const std::string& key) const { return GiNaC::pow(eps_, spec_.order(key)); }
  GiNaC::symbol tag(const std::string& origin);
  void make_symbols();

  // ----- ordering truncation (physics.cc) --------------------------------------------------
  // Keeps the monomials with eps order <= max_eps and perturbation degree <= 1.
  GiNaC::ex trunc(const GiNaC::ex& e, int max_eps) const;
  // Every product is truncated at once, which keeps GiNaC's expression swell bounded.
  GiNaC::ex mul(const GiNaC::ex& a, const GiNaC::ex& b, int max_eps) const {
    return trunc(a * b, max_eps);
  }

  // ----- physics (physics.cc) --------------------------------------------------------------
  void aerodynamic_loads();
  void structural_loads();

  // ----- monomial analysis and slot placement (monomials.cc) -------------------------------
  Mono analyse(const GiNaC::ex& t) const;
  Term make_term(const Mono& m, bool aero, int eq);
  // Why the spec drops this monomial of equation eq ([terms.flap], [terms.lag], [exclude]);
  // "" when it is kept.  The rotor thrust (eq = M + N) follows the flap equation's classes.
  std::string spec_drops(const Mono& m, bool aero, int eq) const;
  // Records a dropped monomial of the linear pass (harmonic h) for the report.
  void record_dropped(const Mono& m, int eq, int h, const std::string& reason);
  int aero_index(const AeroIntegralKey& k);
  int structural_index(const StructuralIntegralKey& k);
  // Splits the expanded residual of equation eq into harmonics and pending slots (the
  // nonlinear pending slots in the nonlinear pass).
  void place(const GiNaC::ex& expr, bool aero, int eq);
  // The monomials of each harmonic index of an expanded residual (z powers to cos/sin).
  std::map<int, GiNaC::exvector> harmonics(const GiNaC::ex& expr) const;

  // ----- nonlinear loads (nonlinear.cc; spec [emit] nonlinear) -----------------------------
  // Runs the physics again with nonlinear_ set: the hover amplitudes g0, h0 are zero (the
  // state is the full coordinate) and trunc() keeps every perturbation degree.
  void nonlinear_pass();
  void place_nonlinear(const GiNaC::ex& expr, bool aero, int eq);
  void assemble_nonlinear();
  void add_term(Slot& s, const Term& t);

  // ----- assembly (derive.cc) --------------------------------------------------------------
  // GiNaC visits terms in an address-dependent order: renumber the integrals by their keys and
  // sort every term list so that the output is byte-identical from run to run.
  void canonicalize();
  // Sizes the model's slots (DerivedModel layout) with value 0; the thrust rows only with
  // cyclic pitch.
  void allocate_slots();
  // The pending acceleration terms into the generalized mass.
  void assemble_mass();
  // The pending perturbation terms into force and forcing, the thrust pseudo-equation's into
  // thrust_force and thrust_forcing.
  void assemble_linear();
  // The hover static equilibrium S q0 = c (eqs 2.27-2.32) from the constant harmonic of the
  // forcing: the perturbation-free residual at mu = 0 is c - S q0.
  void assemble_hover_equilibrium();
  // One term of that residual: into c (free of q0) or -S[eq, j] (linear in q0_j); q0_scalar
  // holds the scalar indices of g0_1..g0_M, h0_1..h0_N.
  void place_hover_term(const Term& t, int eq, const std::vector<int>& q0_scalar);
  // Each integral's paper name: the distinct names of all the terms that use it.
  void name_integrals();
  void add_paper_names(const Slot& slot);

  const OrderingSpec& spec_;
  bool nonlinear_ = false;   // inside nonlinear_pass()
  GiNaC::exmap hover_zero_;  // g0, h0 -> 0 (nonlinear pass)
  int M_, N_;
  DerivedModel model_;
  std::map<std::string, SymRole> roles_;

  GiNaC::symbol eps_, dlt_, radial_, z_;
  GiNaC::symbol x_;                                         // aerodynamic station radius by R
  std::vector<GiNaC::symbol> eta_, etap_, gam_, gamp_;      // outer shapes
  std::vector<GiNaC::symbol> ieta_, ietap_, igam_, igamp_;  // inner shapes (at x1)
  GiNaC::symbol x0_, arm_, iarm_, tw_, mo_, mi_, tail_, head_;
  std::vector<GiNaC::symbol> dg_, dgd_, dgdd_, dh_, dhd_, dhdd_;
  // scalar indices
  int lock_ = -1, lr_ = -1, theta_ = -1, inflow_ = -1, precone_ = -1, droop_ = -1, cdo_ = -1,
      mu_ = -1;
  int theta1c_ = -1, theta1s_ = -1;  // cyclic pitch (spec.cyclic_pitch only)
  std::vector<int> g0_, h0_, wf_, wl_, zf_, zl_;
  std::vector<std::vector<int>> esf_, esl_, ecsfl_, ecslf_;
  std::map<std::string, GiNaC::symbol> tags_;

  std::map<AeroIntegralKey, int> aero_index_;
  std::map<StructuralIntegralKey, int> structural_index_;

  std::map<std::pair<int, int>, std::vector<Term>> pending_forcing_;      // (h, eq)
  std::map<std::pair<int, int>, std::vector<Term>> pending_mass_;         // (eq, accel)
  std::map<std::tuple<int, int, int>, std::vector<Term>> pending_force_;  // (h, eq, state)
  // (h, eq, powers) -> terms of the nonlinear generalized force.
  std::map<std::tuple<int, int, std::vector<int>>, std::vector<Term>> pending_nonlinear_;
  // Origins of the linear centrifugal stiffness, replaced by the modal stiffness (A.2, A.4).
  std::set<std::string> absorbed_origins_;
};

}  // namespace flaplag::derive::detail
