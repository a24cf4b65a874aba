// Monomial analysis and slot placement: an expanded residual is split into harmonics (powers of
// z), each monomial is taken apart by the roles of its symbols (deriver.h) into a Term with its
// spanwise integral, eps order, origin and radial-flow flag, and filed under its slot (mass,
// force, forcing) or, for the linear centrifugal stiffness, under the absorbed terms.
#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "deriver.h"
#include "flaplag_derive/paper_names.h"

namespace flaplag::derive::detail {

using GiNaC::ex;
using GiNaC::exvector;
using GiNaC::numeric;
using GiNaC::symbol;

namespace {

// Factor name used in canonical integral names.
std::string factor_name(const ShapeFactor& f) {
  const std::string m = std::to_string(f.mode + 1);
  switch (f.kind) {
    case FactorKind::Eta:
      return "eta" + m;
    case FactorKind::EtaPrime:
      return "eta" + m + "'";
    case FactorKind::Gamma:
      return "gamma" + m;
    case FactorKind::GammaPrime:
      return "gamma" + m + "'";
    case FactorKind::X0:
      return "x0";
    case FactorKind::Arm:
      return "(x0+e1/l)";
    case FactorKind::Twist:
      return "tw";
  }
  return "?";
}

std::string factor_ident(const ShapeFactor& f) {
  const std::string m = std::to_string(f.mode + 1);
  switch (f.kind) {
    case FactorKind::Eta:
      return "eta" + m;
    case FactorKind::EtaPrime:
      return "deta" + m;
    case FactorKind::Gamma:
      return "gam" + m;
    case FactorKind::GammaPrime:
      return "dgam" + m;
    case FactorKind::X0:
      return "x0";
    case FactorKind::Arm:
      return "arm";
    case FactorKind::Twist:
      return "tw";
  }
  return "q";
}

}  // namespace

Mono Deriver::analyse(const ex& t) const {
  Mono m;
  auto take = [&](const ex& f) {
    if (GiNaC::is_a<numeric>(f)) {
      m.coef *= GiNaC::ex_to<numeric>(f);
      return;
    }
    ex base = f;
    int p = 1;
    if (GiNaC::is_a<GiNaC::power>(f)) {
      base = f.op(0);
      const ex e = f.op(1);
      if (!GiNaC::is_a<numeric>(e) || !GiNaC::ex_to<numeric>(e).is_integer()) {
        throw std::logic_error("non-integer power in monomial");
      }
      p = GiNaC::ex_to<numeric>(e).to_int();
    }
    if (!GiNaC::is_a<symbol>(base)) {
      std::ostringstream os;
      os << "unexpected factor in monomial: " << f;
      throw std::logic_error(os.str());
    }
    const SymRole& r = roles_.at(GiNaC::ex_to<symbol>(base).get_name());
    switch (r.role) {
      case Role::Eps:
        m.eps += p;
        break;
      case Role::Dlt:
        m.dlt += p;
        break;
      case Role::Radial:
        m.radial += p;
        break;
      case Role::Z:
        m.z += p;
        break;
      case Role::Tag:
        m.origin = r.tag;
        break;
      case Role::Scalar:
        m.scalars.emplace_back(r.index, p);
        break;
      case Role::State:
        m.state = r.index;
        m.states.emplace_back(r.index, p);
        break;
      case Role::Accel:
        m.accel = r.index;
        break;
      case Role::Shape:
        for (int j = 0; j < p; ++j) m.outer.push_back({r.kind, r.index});
        break;
      case Role::InnerShape:
        for (int j = 0; j < p; ++j) m.inner.push_back({r.kind, r.index});
        break;
      case Role::X:
        m.x_power += p;
        break;
      case Role::MassOuter:
        m.mass_outer += p;
        break;
      case Role::MassInner:
        m.mass_inner += p;
        break;
      case Role::Tail:
        m.inner_kind = InnerKind::Tail;
        break;
      case Role::Head:
        m.inner_kind = InnerKind::Head;
        break;
    }
  };
  if (GiNaC::is_a<GiNaC::mul>(t)) {
    for (const auto& f : t) take(f);
  } else {
    take(t);
  }
  std::sort(m.scalars.begin(), m.scalars.end());
  std::sort(m.states.begin(), m.states.end());
  std::sort(m.outer.begin(), m.outer.end());
  std::sort(m.inner.begin(), m.inner.end());
  return m;
}

namespace {

// Name ("x eta1 gamma1'", "x^2 tw eta1") and C identifier ("x1_eta1_dgam1", "x2_tw_eta1") of
// an aerodynamic integral: the twist, a weight on the span like x^p, is written next to it.
IntegralInfo aero_info(const AeroIntegralKey& k) {
  IntegralInfo info;
  std::ostringstream name, id;
  if (k.x_power > 0) {
    name << (k.x_power == 1 ? "x" : "x^" + std::to_string(k.x_power));
    id << "x" << k.x_power;
  }
  for (const bool twist : {true, false}) {
    for (const auto& f : k.factors) {
      if ((f.kind == FactorKind::Twist) != twist) continue;
      if (name.tellp() > 0) name << " ";
      if (id.tellp() > 0) id << "_";
      name << factor_name(f);
      id << factor_ident(f);
    }
  }
  info.name = name.str().empty() ? "1" : name.str();
  info.ident = id.str().empty() ? "one" : id.str();
  return info;
}

}  // namespace

int Deriver::aero_index(const AeroIntegralKey& k) {
  auto it = aero_index_.find(k);
  if (it != aero_index_.end()) return it->second;
  const int idx = static_cast<int>(model_.aero_keys.size());
  aero_index_.emplace(k, idx);
  model_.aero_keys.push_back(k);
  const IntegralInfo info = aero_info(k);
  model_.aero.push_back(info);
  model_.aero_syms.push_back(symbol("A_" + info.ident));
  return idx;
}

int Deriver::structural_index(const StructuralIntegralKey& k) {
  auto it = structural_index_.find(k);
  if (it != structural_index_.end()) return it->second;
  const int idx = static_cast<int>(model_.structural_keys.size());
  structural_index_.emplace(k, idx);
  model_.structural_keys.push_back(k);
  IntegralInfo info;
  std::ostringstream name, id;
  if (k.outer_mass > 0) {
    name << "m";
    id << "m";
  }
  for (const auto& f : k.outer) {
    if (name.tellp() > 0) name << " ";
    if (id.tellp() > 0) id << "_";
    name << factor_name(f);
    id << factor_ident(f);
  }
  if (k.inner != InnerKind::None) {
    name << (k.inner == InnerKind::Tail ? " [int_x^1 " : " [int_0^x ");
    id << (k.inner == InnerKind::Tail ? "__tail" : "__head");
    bool first = true;
    if (k.inner_mass > 0) {
      name << "m";
      id << "_m";
      first = false;
    }
    for (const auto& f : k.inner_factors) {
      name << (first ? "" : " ") << factor_name(f);
      id << "_" << factor_ident(f);
      first = false;
    }
    name << " dx1]";
  }
  info.name = name.str();
  info.ident = id.str();
  model_.structural.push_back(info);
  model_.structural_syms.push_back(symbol("S_" + info.ident));
  return idx;
}

Term Deriver::make_term(const Mono& m, bool aero, int eq) {
  Term t;
  t.coef = m.coef;
  t.scalars = m.scalars;
  t.eps_order = m.eps;
  t.origin = m.origin;
  t.radial_flow = m.radial > 0;
  const bool flap_eq = model::is_flap_coordinate(eq, M_);
  const int eq_mode = flap_eq ? eq : eq - M_;
  if (aero) {
    AeroIntegralKey k{m.x_power, m.outer};
    t.ref = IntegralRef::Aero;
    t.integral = aero_index(k);
    // The thrust (cyclic-pitch models) is no equation of the paper: no paper names.
    if (eq < M_ + N_) t.paper_name = paper_aero_name(flap_eq, eq_mode, k);
  } else if (m.outer.empty() && m.inner_kind == InnerKind::None && m.mass_outer == 0) {
    t.ref = IntegralRef::None;  // elastic coupling, modal stiffness inputs carry no integral
  } else {
    StructuralIntegralKey k{m.mass_outer, m.outer, m.inner_kind, m.mass_inner, m.inner};
    t.ref = IntegralRef::Structural;
    t.integral = structural_index(k);
    t.paper_name = paper_structural_name(flap_eq, eq_mode, k);
  }
  return t;
}

std::string Deriver::spec_drops(const Mono& m, bool aero, int eq) const {
  if (!aero) return "";
  const bool thrust = eq == M_ + N_;
  const bool flap = thrust || model::is_flap_coordinate(eq, M_);
  const std::string where = flap ? "flap" : "lag";
  if (m.radial > 0 && !spec_.radial_flow_in(flap)) {
    return "radial flow off in the " + where + " equation";
  }
  const int kept = flap ? spec_.kept_flap : spec_.kept_lag;
  if (spec_.damping_only_at_top_order(flap) && m.eps >= kept) {
    bool rate = false;
    if (nonlinear_) {
      for (const auto& [col, p] : m.states) rate = rate || model::state_ref(col, M_, N_).rate;
    } else {
      rate = m.dlt == 1 && m.state >= 0 && model::state_ref(m.state, M_, N_).rate;
    }
    if (!rate) return "O(eps^" + std::to_string(kept) + ") without a state rate (" + where + ")";
  }
  if (!thrust && !spec_.excluded.empty()) {
    const int eq_mode = flap ? eq : eq - M_;
    const std::string name =
        paper_base_name(paper_aero_name(flap, eq_mode, AeroIntegralKey{m.x_power, m.outer}));
    if (!name.empty() &&
        std::find(spec_.excluded.begin(), spec_.excluded.end(), name) != spec_.excluded.end()) {
      return "excluded: " + name;
    }
  }
  return "";
}

void Deriver::record_dropped(const Mono& m, int eq, int h, const std::string& reason) {
  DroppedTerm d;
  d.equation = eq;
  d.harmonic = h;
  d.state = m.dlt == 0 ? -1 : m.state;
  d.term.coef = m.coef;
  d.term.scalars = m.scalars;
  d.term.eps_order = m.eps;
  d.term.origin = m.origin;
  d.term.radial_flow = m.radial > 0;
  d.term.ref = IntegralRef::Aero;
  const AeroIntegralKey k{m.x_power, m.outer};
  const bool flap = model::is_flap_coordinate(eq, M_);
  if (eq < M_ + N_) d.term.paper_name = paper_aero_name(flap, flap ? eq : eq - M_, k);
  d.integral = aero_info(k).name;
  d.reason = reason;
  model_.dropped.push_back(std::move(d));
}

void Deriver::add_term(Slot& s, const Term& t) {
  ex v = t.coef;
  for (const auto& [idx, p] : t.scalars) v *= GiNaC::pow(model_.scalars[idx].sym, p);
  if (t.ref == IntegralRef::Aero) v *= model_.aero_syms[t.integral];
  if (t.ref == IntegralRef::Structural) v *= model_.structural_syms[t.integral];
  s.terms.push_back(t);
  s.value = s.value + v;
}

std::map<int, exvector> Deriver::harmonics(const ex& expr) const {
  std::map<int, exvector> buckets;  // harmonic index -> terms
  const ex e = expr.expand();
  auto bucket = [&](const ex& t) {
    const int zp = t.degree(z_) > 0 ? t.degree(z_) : t.ldegree(z_);
    const ex rest = t.subs(z_ == 1);
    if (zp == 0) {
      buckets[0].push_back(rest);
    } else {
      const int k = std::abs(zp);
      // a z^k + a_ z^-k = (a + a_) cos k psi + i (a - a_) sin k psi
      buckets[2 * k - 1].push_back(rest);
      buckets[2 * k].push_back((zp > 0 ? GiNaC::I : -GiNaC::I) * rest);
    }
  };
  if (GiNaC::is_a<GiNaC::add>(e)) {
    for (const auto& t : e) bucket(t);
  } else if (!e.is_zero()) {
    bucket(e);
  }
  std::map<int, exvector> out;
  for (auto& [h, terms] : buckets) {
    const ex sum = ex(GiNaC::add(terms)).expand();
    if (sum.is_zero()) continue;
    exvector& monos = out[h];
    if (GiNaC::is_a<GiNaC::add>(sum)) {
      for (const auto& t : sum) monos.push_back(t);
    } else {
      monos.push_back(sum);
    }
  }
  return out;
}

// Splits an expanded residual of equation eq into harmonics and slots.
void Deriver::place(const ex& expr, bool aero, int eq) {
  if (nonlinear_) {
    place_nonlinear(expr, aero, eq);
    return;
  }
  for (const auto& [h, monos] : harmonics(expr)) {
    for (const auto& t : monos) {
      Mono m = analyse(t);
      if (!m.coef.is_real()) throw std::logic_error("complex coefficient after harmonic split");
      const std::string dropped = spec_drops(m, aero, eq);
      if (!dropped.empty()) {
        record_dropped(m, eq, h, dropped);
        continue;
      }
      if (h + 1 > model_.H) model_.H = h + 1;
      if (!aero && absorbed_origins_.count(m.origin) > 0) {
        // Linear rotating-beam stiffness: replaced by M w^2 through the orthogonality
        // relations (A.2, A.4), which define the rotating frequencies.
        int col = -1;
        if (m.dlt == 1 && m.scalars.empty() && m.accel < 0 && m.state >= 0 &&
            !model::state_ref(m.state, M_, N_).rate) {
          col = m.state;
        } else if (m.dlt == 0 && m.scalars.size() == 1 && m.scalars[0].second == 1) {
          const int si = m.scalars[0].first;
          for (int k = 0; k < M_; ++k)
            if (si == g0_[k]) col = model::flap_displacement_index(k, M_, N_);
          for (int r = 0; r < N_; ++r)
            if (si == h0_[r]) col = model::lag_displacement_index(r, M_, N_);
        }
        if (col >= 0) {
          if (m.dlt == 1) {  // record once, for the perturbation
            model_.absorbed.push_back({eq, col, make_term(m, aero, eq)});
          }
          continue;
        }
      }
      if (m.dlt == 0) {
        pending_forcing_[{h, eq}].push_back(make_term(m, aero, eq));
      } else if (m.accel >= 0) {
        // mass * q'' appears on the right-hand side with a minus sign
        m.coef = -m.coef;
        Term tt = make_term(m, aero, eq);
        pending_mass_[{eq, m.accel}].push_back(tt);
      } else if (m.state >= 0) {
        pending_force_[{h, eq, m.state}].push_back(make_term(m, aero, eq));
      } else {
        throw std::logic_error("perturbation term without a state");
      }
    }
  }
}

}  // namespace flaplag::derive::detail
