// The nonlinear generalized loads (spec [emit] nonlinear, issue 12 item 4): the same physics
// (physics.cc) and the same eps truncation of every product, but expanded about q = 0 with the
// full coordinates as the state and without the degree-1 cut in the perturbation.  What comes
// out are the products of the generalized coordinates that the ordering keeps, as polynomials
// in y = [g', g, h', h] with harmonic coefficients in psi.
//
// Why this is the model the linear slots are the linearization of: the eps truncation and the
// dlt-degree cut are both cuts by an additive degree, so truncating every product and cutting at
// the end commute; the linear pass is the nonlinear polynomial with g = g0 + dg, h = h0 + dh
// cut at degree 1 in (dg, dh).  Hence its Jacobian at y = (0, q0) is `force` and its value there
// is `forcing`, to rounding (tests/generator_test.cpp checks both).
#include <algorithm>
#include <stdexcept>

#include "deriver.h"

namespace flaplag::derive {

int NonlinearSlot::degree() const {
  int d = 0;
  for (int p : powers) d += p;
  return d;
}

namespace detail {

using GiNaC::ex;

void Deriver::nonlinear_pass() {
  hover_zero_.clear();
  for (int k = 0; k < M_; ++k) hover_zero_[scalar(g0_[k])] = 0;
  for (int r = 0; r < N_; ++r) hover_zero_[scalar(h0_[r])] = 0;
  nonlinear_ = true;
  aerodynamic_loads();
  structural_loads();
  nonlinear_ = false;
}

void Deriver::place_nonlinear(const ex& expr, bool aero, int eq) {
  const int ns = 2 * (M_ + N_);
  for (const auto& [h, monos] : harmonics(expr.subs(hover_zero_))) {
    for (const auto& t : monos) {
      Mono m = analyse(t);
      if (!m.coef.is_real()) throw std::logic_error("complex coefficient after harmonic split");
      // The spec's per-equation classes and exclusions, as in place() (linear pass).
      if (!spec_drops(m, aero, eq).empty()) continue;
      if (h + 1 > model_.H_nonlinear) model_.H_nonlinear = h + 1;
      int degree = 0;
      for (const auto& [col, p] : m.states) degree += p;
      if (degree != m.dlt - (m.accel >= 0 ? 1 : 0)) {
        throw std::logic_error("perturbation marker and state degree disagree");
      }
      if (m.accel >= 0) {
        // The generalized mass is the linear pass's (model_api.h): inertia is linear in q''.
        if (!m.states.empty()) throw std::logic_error("acceleration times a state");
        continue;
      }
      // The linear centrifugal stiffness is absorbed into M w^2 (A.2, A.4), as in place().
      if (!aero && absorbed_origins_.count(m.origin) > 0 && m.scalars.empty() && degree == 1 &&
          m.states[0].second == 1 && !model::state_ref(m.states[0].first, M_, N_).rate) {
        continue;
      }
      std::vector<int> powers(ns, 0);
      for (const auto& [col, p] : m.states) powers[col] = p;
      pending_nonlinear_[{h, eq, powers}].push_back(make_term(m, aero, eq));
    }
  }
}

void Deriver::assemble_nonlinear() {
  model_.nonlinear.clear();
  model_.nonlinear_thrust.clear();
  for (const auto& [key, terms] : pending_nonlinear_) {
    NonlinearSlot s;
    s.harmonic = std::get<0>(key);
    s.equation = std::get<1>(key);
    s.powers = std::get<2>(key);
    s.slot.value = 0;
    for (const auto& t : terms) add_term(s.slot, t);
    // The thrust pseudo-equation (cyclic-pitch models) is no generalized load: its own list.
    (s.equation == model_.thrust_equation() ? model_.nonlinear_thrust : model_.nonlinear)
        .push_back(std::move(s));
  }
}

}  // namespace detail
}  // namespace flaplag::derive
