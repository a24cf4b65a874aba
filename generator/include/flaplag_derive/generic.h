// flaplag-derive — the model of one ordering spec for any number of modes.
//
// The derivation (derive.h) is concrete: it expands the displacement sums w = l eta_k g_k,
// v = -l gamma_m h_m over a given M x N and names every term with concrete modes.  Every load
// is a polynomial in those sums, so the coefficient of state j in equation i is a sum over
// index patterns: a rational times scalars times one spanwise integral whose modes are i, j and
// summed indices (e.g. sum_k  eta_i eta_k' gamma_j' g0_k).  extract_generic() recovers these
// patterns from concrete derivations at P x P modes by inclusion-exclusion over coinciding
// indices (finest pattern first; a coarser concrete term keeps only what the finer patterns do
// not already produce, e.g. the modal stiffness that exists only for j = i), then checks that
// the patterns reproduce every concrete slot of the P x P derivation exactly and that a
// derivation at (P+1) x (P+1) gives the same patterns.
//
// Index variables: every term numbers its variables 0, 1, ...; the first are bound by the slot
// (the equation's mode, then the state's or coordinate's mode, unless `diagonal`, when the
// state's mode is the equation's), the rest are summed over all modes of their direction.
#pragma once

#include <ginac/ginac.h>

#include <string>
#include <vector>

#include "flaplag_derive/derive.h"

namespace flaplag::derive {

enum class ModeDir { Flap = 0, Lag = 1 };

// A spanwise factor of an integral template: kind and the template's variable (-1 for X0, Arm,
// Twist).
struct TemplateFactor {
  FactorKind kind;
  int var;
  bool operator<(const TemplateFactor& o) const {
    return kind != o.kind ? kind < o.kind : var < o.var;
  }
  bool operator==(const TemplateFactor& o) const { return kind == o.kind && var == o.var; }
};

// A spanwise integral with variable modes.  Its variables 0..vars.size()-1 are numbered
// canonically; a term passes its own variables as arguments.  The runtime evaluates a template
// for every assignment of its variables (row-major, variable 0 slowest) into one tensor.
struct IntegralTemplate {
  IntegralRef ref = IntegralRef::None;
  std::vector<ModeDir> vars;
  int x_power = 0;                      // aero
  std::vector<TemplateFactor> factors;  // aero factors, or structural outer factors
  int outer_mass = 0;                   // structural
  InnerKind inner = InnerKind::None;
  int inner_mass = 0;
  std::vector<TemplateFactor> inner_factors;
  std::string name;        // "x eta_a eta_b'" (template letters a, b, c, ...)
  std::string ident;       // C identifier
  std::string paper_name;  // Appendix B name with index letters, or ""
  std::string key() const;
};

// A scalar input with modes: family (g0, h0, omega_flap, damping_flap, omega_lag, damping_lag,
// es_flap, ecs_flap_lag, es_lag, ecs_lag_flap) and the term variables of its indices.
struct IndexedScalar {
  std::string family;
  std::vector<int> args;
  int power = 1;
};

// The per-direction input of model_api.h's CoefficientInputs a family reads: `array` "q0",
// "omega", "damping" (one index, a mode of direction dirs[0]) or "elastic" (two indices, the
// block elastic[dirs[0]][dirs[1]], row-major).  Throws std::logic_error for an unknown family.
struct FamilyInput {
  std::string array;
  std::vector<ModeDir> dirs;
};
FamilyInput family_input(const std::string& family);

// A state factor of a nonlinear load: coordinate direction, rate or displacement, variable.
struct StateFactor {
  ModeDir dir;
  bool rate;
  int var;
  int power = 1;
};

struct GenericTerm {
  GiNaC::numeric coef;
  std::vector<ModeDir> vars;                         // direction of each variable
  bool diagonal = false;                             // the slot's state mode == equation mode
  std::vector<std::pair<std::string, int>> scalars;  // (plain scalar name, power), sorted
  std::vector<IndexedScalar> indexed;                // sorted
  int integral = -1;                                 // index into GenericModel::integrals
  std::vector<int> integral_args;                    // term variable of each template variable
  std::vector<StateFactor> states;                   // nonlinear loads only
  int eps_order = 0;
  std::string origin;
  bool radial_flow = false;
  std::string paper_name;  // role-aware paper name with index letters, or ""
};

enum class SlotKind {
  Mass,             // eq i, acceleration of coordinate j
  Force,            // harmonic, eq i, state column (direction, rate, mode j)
  Forcing,          // harmonic, eq i
  HoverStiffness,   // S: eq i, coordinate j   (hover equilibrium S q0 = c)
  HoverLoad,        // c: eq i
  ThrustForce,      // harmonic, state column j
  ThrustForcing,    // harmonic
  Nonlinear,        // harmonic, eq i; terms carry their states
  NonlinearThrust,  // harmonic; terms carry their states
  Absorbed,         // report only: centrifugal stiffness replaced by the modal stiffness
};

struct GenericSlot {
  SlotKind kind;
  int harmonic = 0;
  ModeDir eq = ModeDir::Flap;   // equation direction (kinds with an equation)
  ModeDir col = ModeDir::Flap;  // column direction (Mass, Force, HoverStiffness, ThrustForce,
                                // Absorbed)
  bool rate = false;            // Force, ThrustForce, Absorbed: rate column
  std::vector<GenericTerm> terms;
  bool has_eq() const;
  bool has_col() const;
};

struct GenericModel {
  OrderingSpec spec;  // as given (its [modes] are the shipped default)
  int H = 1;          // harmonics of the linear coefficients
  int H_nonlinear = 0;
  std::vector<std::string> scalar_names;  // plain scalars, in CoefficientInputs order
  std::vector<IntegralTemplate> integrals;
  std::vector<GenericSlot> slots;  // sorted by (kind, harmonic, eq, col, rate)
  int P = 0;                       // modes per direction of the derivation it was extracted from
  std::string serialize() const;   // canonical text (tests, the saturation check)
};

// Derives `spec` at P x P and (P+1) x (P+1) modes with every feature on (cyclic pitch, thrust,
// nonlinear loads) and extracts the patterns; throws std::logic_error when the patterns do not
// reproduce the concrete derivation or are not saturated at P.
GenericModel extract_generic(const OrderingSpec& spec, int P = 4);

// The index of g.integrals[integral] among the templates of its kind (aerodynamic or
// structural), in order: its index in the emitted kAero or kStructural list.
int index_among_kind(const GenericModel& g, int integral);

// The aerodynamic templates (counted among those of their kind, in order) that the linear
// functions read, as a prefix: 1 + the largest index a Mass, Force, Forcing, HoverStiffness or
// HoverLoad term reads (0 when none does).  A system A(psi), f(psi) needs only these integrals of
// a flow region; the thrust and the nonlinear loads read the rest.
int linear_aero_templates(const GenericModel& g);

// Patterns from one concrete derivation (no saturation check): for tests.
GenericModel extract_generic_from(const DerivedModel& concrete);

// Expands the patterns for M flap x N lag modes into the concrete slots of that size, as a
// canonical multiset of (slot, term) texts with exact coefficients: equal to the same text of
// derive_model() at M x N when the extraction is right (tests/generator_test.cpp).
std::vector<std::string> expand_generic(const GenericModel& g, int M, int N);
std::vector<std::string> concrete_terms(const DerivedModel& m);

}  // namespace flaplag::derive
