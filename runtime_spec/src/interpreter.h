// flaplag — evaluation of a model family (generic.h) without compiling it: the functions of a
// ModelFamily (model_api.h) as loops over plain run-time data.
//
// A Program is the GenericModel with its exact rational coefficients turned into doubles the way
// the emitted C++ writes them ("(1.0 / 4.0)") and every term a list of factors in the emitted
// multiplication order; run() walks the slots, terms and mode loops in the order of
// emit_family.cc.  Same operations in the same order: the same numbers as the compiled family
// of the same spec, to the last bit (no FMA contraction in either).
#pragma once

#include <deque>
#include <string>
#include <vector>

#include "flaplag/model_api.h"
#include "flaplag_derive/generic.h"

namespace flaplag::spec {

class Program {
 public:
  explicit Program(const derive::GenericModel& g);

  void mass(const model::CoefficientInputs& in, double* out) const;
  void coefficients(const model::CoefficientInputs& in, const model::CoefficientOutputs& out) const;
  void equilibrium(const model::CoefficientInputs& in, const model::EquilibriumOutputs& out) const;
  void thrust(const model::CoefficientInputs& in, const model::CoefficientOutputs& out) const;
  void nonlinear(const model::CoefficientInputs& in, const double* y,
                 const model::NonlinearOutputs& out) const;
  void nonlinear_thrust(const model::CoefficientInputs& in, const double* y,
                        const model::NonlinearOutputs& out) const;

  // The integral templates of the family (ModelFamily::aero, ::structural).
  const std::vector<model::IntegralTemplate>& aero() const { return aero_; }
  const std::vector<model::IntegralTemplate>& structural() const { return structural_; }

 private:
  // One factor of a term's product.
  struct Factor {
    enum class Kind { Scalar, Indexed, Aero, Structural } kind;
    double model::CoefficientInputs::*scalar = nullptr;  // Scalar
    // Indexed: the per-direction input it reads (derive::FamilyInput), in.q0[dirs[0]], ...,
    // in.elastic[dirs[0]][dirs[1]].
    enum class Input { Q0, Omega, Damping, Elastic } input = Input::Q0;
    int dirs[2] = {0, 0};      // model::index() of the directions of its indices
    bool second_flap = false;  // Indexed with two indices: the second is a flap mode
    int index = 0;             // Aero, Structural: template among its kind
    int n_args = 0;
    int args[model::kMaxFactors] = {0, 0, 0, 0};  // term variables of the indices
  };
  // The Indexed factor of a family's scalar, and the array it reads in `in`.
  static Factor indexed_factor(const std::string& family);
  static const double* indexed_array(const model::CoefficientInputs& in, const Factor& f);
  struct State {
    derive::ModeDir dir;
    bool rate;
    int var;
    int power;
  };
  struct Term {
    bool negative = false;
    bool has_coef = false;
    double coef = 1.0;
    std::vector<Factor> factors;  // the plain scalars first (n_scalars of them)
    std::size_t n_scalars = 0;
    std::vector<derive::ModeDir> vars;
    bool diagonal = false;
    std::vector<State> states;
  };
  struct Slot {
    derive::SlotKind kind;
    int harmonic;
    derive::ModeDir eq, col;
    bool rate;
    std::vector<Term> terms;
    bool has_eq, has_col;
  };
  struct Context;  // the inputs of one call: tensors, mode counts, variable values

  // The product so far: its value and whether it has a factor yet.
  struct Partial {
    double value;
    bool started;
  };
  // The coefficient times the plain scalars: the same for every mode of a call, so computed
  // once per call (the left end of the product, so the result is the same to the bit).
  static Partial prefix(const Term& t, const Context& c);
  // The term's value for the variables in c.
  double value(const Term& t, const Context& c, Partial prefix) const;
  // Calls f() for every value of the term's variables from `first` on (first slowest).
  template <class F>
  static void for_free(const Term& t, int first, Context& c, F f);
  // Accumulates the slots of `kind` as the emitted code does; target(i, j) is the element.
  template <class Target>
  void linear(derive::SlotKind kind, Context& c, Target target) const;
  void polynomial(derive::SlotKind kind, const model::CoefficientInputs& in, const double* y,
                  const model::NonlinearOutputs& out) const;

  int H_ = 1, H_nonlinear_ = 0;
  std::vector<Slot> slots_;
  std::vector<model::IntegralTemplate> aero_, structural_;
  std::deque<std::string> texts_;  // storage of the templates' names (stable addresses)
};

}  // namespace flaplag::spec
