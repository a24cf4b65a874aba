// Symbolic derivation of the flap-lag equations: set-up of the symbols, assembly of the slots
// and the hover equilibrium.  See derive.h for the pipeline, deriver.h for the bookkeeping
// symbols, physics.cc for the loads and monomials.cc for the slot placement.
#include "flaplag_derive/derive.h"

#include <algorithm>
#include <stdexcept>
#include <tuple>

#include "deriver.h"

namespace flaplag::derive {

bool StructuralIntegralKey::operator<(const StructuralIntegralKey& o) const {
  if (outer_mass != o.outer_mass) return outer_mass < o.outer_mass;
  if (outer != o.outer) return outer < o.outer;
  if (inner != o.inner) return inner < o.inner;
  if (inner_mass != o.inner_mass) return inner_mass < o.inner_mass;
  return inner_factors < o.inner_factors;
}

std::string DerivedModel::state_name(int col) const { return model::state_name(col, M, N); }

std::string DerivedModel::equation_name(int row) const {
  return model::is_flap_coordinate(row, M) ? "flap " + std::to_string(row + 1)
                                           : "lag " + std::to_string(row - M + 1);
}

std::string DerivedModel::harmonic_name(int h) {
  if (h == 0) return "const";
  const int k = (h + 1) / 2;
  const std::string arg = k == 1 ? "psi" : std::to_string(k) + "psi";
  return (h % 2 == 1 ? "cos " : "sin ") + arg;
}

namespace detail {

using GiNaC::ex;
using GiNaC::exvector;
using GiNaC::numeric;
using GiNaC::symbol;

bool term_less(const Term& a, const Term& b) {
  if (a.ref != b.ref) return a.ref < b.ref;
  if (a.integral != b.integral) return a.integral < b.integral;
  if (a.scalars != b.scalars) return a.scalars < b.scalars;
  if (a.origin != b.origin) return a.origin < b.origin;
  if (a.radial_flow != b.radial_flow) return a.radial_flow < b.radial_flow;
  return a.coef < b.coef;
}

Deriver::Deriver(const OrderingSpec& spec) : spec_(spec), M_(spec.flap_modes), N_(spec.lag_modes) {
  model_.spec = spec;
  model_.M = M_;
  model_.N = N_;
  make_symbols();
}

int Deriver::add_scalar(const std::string& name, const std::string& cexpr) {
  const int idx = static_cast<int>(model_.scalars.size());
  symbol s = sym(name, {Role::Scalar, idx});
  model_.scalars.push_back({name, cexpr, s});
  return idx;
}

symbol Deriver::tag(const std::string& origin) {
  auto it = tags_.find(origin);
  if (it != tags_.end()) return it->second;
  const std::string name = "tag" + std::to_string(tags_.size());
  symbol s = sym(name, {Role::Tag, 0, FactorKind::Eta, origin});
  tags_.emplace(origin, s);
  return s;
}

void Deriver::make_symbols() {
  eps_ = sym("eps", {Role::Eps});
  dlt_ = sym("dlt", {Role::Dlt});
  radial_ = sym("rf", {Role::Radial});
  z_ = sym("z", {Role::Z});
  x_ = sym("x", {Role::X});
  x0_ = sym("x0", {Role::Shape, 0, FactorKind::X0});
  arm_ = sym("arm", {Role::Shape, 0, FactorKind::Arm});
  iarm_ = sym("iarm", {Role::InnerShape, 0, FactorKind::Arm});
  tw_ = sym("tw", {Role::Shape, 0, FactorKind::Twist});
  mo_ = sym("m", {Role::MassOuter});
  mi_ = sym("mi", {Role::MassInner});
  tail_ = sym("TAIL", {Role::Tail});
  head_ = sym("HEAD", {Role::Head});
  for (int k = 0; k < M_; ++k) {
    const std::string s = std::to_string(k + 1);
    eta_.push_back(sym("eta" + s, {Role::Shape, k, FactorKind::Eta}));
    etap_.push_back(sym("etap" + s, {Role::Shape, k, FactorKind::EtaPrime}));
    ieta_.push_back(sym("ieta" + s, {Role::InnerShape, k, FactorKind::Eta}));
    ietap_.push_back(sym("ietap" + s, {Role::InnerShape, k, FactorKind::EtaPrime}));
    dgd_.push_back(sym("dgd" + s, {Role::State, model::flap_rate_index(k, M_, N_)}));
    dg_.push_back(sym("dg" + s, {Role::State, model::flap_displacement_index(k, M_, N_)}));
    dgdd_.push_back(sym("dgdd" + s, {Role::Accel, model::flap_equation_index(k, M_)}));
  }
  for (int m = 0; m < N_; ++m) {
    const std::string s = std::to_string(m + 1);
    gam_.push_back(sym("gam" + s, {Role::Shape, m, FactorKind::Gamma}));
    gamp_.push_back(sym("gamp" + s, {Role::Shape, m, FactorKind::GammaPrime}));
    igam_.push_back(sym("igam" + s, {Role::InnerShape, m, FactorKind::Gamma}));
    igamp_.push_back(sym("igamp" + s, {Role::InnerShape, m, FactorKind::GammaPrime}));
    dhd_.push_back(sym("dhd" + s, {Role::State, model::lag_rate_index(m, M_, N_)}));
    dh_.push_back(sym("dh" + s, {Role::State, model::lag_displacement_index(m, M_, N_)}));
    dhdd_.push_back(sym("dhdd" + s, {Role::Accel, model::lag_equation_index(m, M_)}));
  }
  // Scalars, in the order the generated code reads them.
  lock_ = add_scalar("lock", "in.lock");
  lr_ = add_scalar("lr", "in.lr");
  theta_ = add_scalar("theta", "in.theta");
  inflow_ = add_scalar("inflow", "in.inflow");
  precone_ = add_scalar("precone", "in.precone");
  droop_ = add_scalar("droop", "in.droop");
  cdo_ = add_scalar("cdo_a", "in.cdo_a");
  mu_ = add_scalar("mu", "in.mu");
  auto idx1 = [](int i) { return std::to_string(i + 1); };
  // The per-direction inputs of model_api.h: in.omega[kFlap][k], in.elastic[kFlap][kLag][i].
  auto input = [](const char* array, const char* dirs, int i) {
    return std::string("in.") + array + dirs + "[" + std::to_string(i) + "]";
  };
  for (int k = 0; k < M_; ++k)
    g0_.push_back(add_scalar("g0_" + idx1(k), input("q0", "[kFlap]", k)));
  for (int m = 0; m < N_; ++m) h0_.push_back(add_scalar("h0_" + idx1(m), input("q0", "[kLag]", m)));
  for (int k = 0; k < M_; ++k) {
    wf_.push_back(add_scalar("omega_flap_" + idx1(k), input("omega", "[kFlap]", k)));
    zf_.push_back(add_scalar("damping_flap_" + idx1(k), input("damping", "[kFlap]", k)));
  }
  for (int m = 0; m < N_; ++m) {
    wl_.push_back(add_scalar("omega_lag_" + idx1(m), input("omega", "[kLag]", m)));
    zl_.push_back(add_scalar("damping_lag_" + idx1(m), input("damping", "[kLag]", m)));
  }
  esf_.assign(M_, std::vector<int>(M_));
  ecsfl_.assign(M_, std::vector<int>(N_));
  esl_.assign(N_, std::vector<int>(N_));
  ecslf_.assign(N_, std::vector<int>(M_));
  for (int i = 0; i < M_; ++i) {
    for (int k = 0; k < M_; ++k)
      esf_[i][k] = add_scalar("es_flap_" + idx1(i) + "_" + idx1(k),
                              input("elastic", "[kFlap][kFlap]", i * M_ + k));
    for (int m = 0; m < N_; ++m)
      ecsfl_[i][m] = add_scalar("ecs_flap_lag_" + idx1(i) + "_" + idx1(m),
                                input("elastic", "[kFlap][kLag]", i * N_ + m));
  }
  for (int i = 0; i < N_; ++i) {
    for (int m = 0; m < N_; ++m)
      esl_[i][m] = add_scalar("es_lag_" + idx1(i) + "_" + idx1(m),
                              input("elastic", "[kLag][kLag]", i * N_ + m));
    for (int k = 0; k < M_; ++k)
      ecslf_[i][k] = add_scalar("ecs_lag_flap_" + idx1(i) + "_" + idx1(k),
                                input("elastic", "[kLag][kFlap]", i * M_ + k));
  }
  // Appended last, and only when switched on, so that the models without cyclic pitch keep
  // their scalar list (and generated code) unchanged.
  if (spec_.cyclic_pitch) {
    theta1c_ = add_scalar("theta1c", "in.theta1c");
    theta1s_ = add_scalar("theta1s", "in.theta1s");
  }
}

void Deriver::canonicalize() {
  std::vector<int> aero_map(model_.aero_keys.size()), struct_map(model_.structural_keys.size());
  {
    int next = 0;
    for (const auto& [key, old] : aero_index_) aero_map[old] = next++;
    std::vector<AeroIntegralKey> keys(aero_map.size());
    std::vector<IntegralInfo> info(aero_map.size());
    std::vector<symbol> syms(aero_map.size());
    for (size_t old = 0; old < aero_map.size(); ++old) {
      keys[aero_map[old]] = model_.aero_keys[old];
      info[aero_map[old]] = model_.aero[old];
      syms[aero_map[old]] = model_.aero_syms[old];
    }
    model_.aero_keys = keys;
    model_.aero = info;
    model_.aero_syms = syms;
    for (auto& [key, idx] : aero_index_) idx = aero_map[idx];
  }
  {
    int next = 0;
    for (const auto& [key, old] : structural_index_) struct_map[old] = next++;
    std::vector<StructuralIntegralKey> keys(struct_map.size());
    std::vector<IntegralInfo> info(struct_map.size());
    std::vector<symbol> syms(struct_map.size());
    for (size_t old = 0; old < struct_map.size(); ++old) {
      keys[struct_map[old]] = model_.structural_keys[old];
      info[struct_map[old]] = model_.structural[old];
      syms[struct_map[old]] = model_.structural_syms[old];
    }
    model_.structural_keys = keys;
    model_.structural = info;
    model_.structural_syms = syms;
    for (auto& [key, idx] : structural_index_) idx = struct_map[idx];
  }
  auto remap = [&](Term& t) {
    if (t.ref == IntegralRef::Aero) t.integral = aero_map[t.integral];
    if (t.ref == IntegralRef::Structural) t.integral = struct_map[t.integral];
  };
  auto fix = [&](std::vector<Term>& v) {
    for (auto& t : v) remap(t);
    std::sort(v.begin(), v.end(), term_less);
  };
  for (auto& [k, v] : pending_forcing_) fix(v);
  for (auto& [k, v] : pending_mass_) fix(v);
  for (auto& [k, v] : pending_force_) fix(v);
  for (auto& [k, v] : pending_nonlinear_) fix(v);
  std::sort(model_.dropped.begin(), model_.dropped.end(),
            [](const DroppedTerm& a, const DroppedTerm& b) {
              return std::tie(a.equation, a.state, a.harmonic, a.integral) <
                         std::tie(b.equation, b.state, b.harmonic, b.integral) ||
                     (std::tie(a.equation, a.state, a.harmonic, a.integral) ==
                          std::tie(b.equation, b.state, b.harmonic, b.integral) &&
                      term_less(a.term, b.term));
            });
  // absorbed terms: sort by (equation, state, term)
  for (auto& a : model_.absorbed) remap(a.term);
  std::sort(model_.absorbed.begin(), model_.absorbed.end(),
            [](const AbsorbedTerm& a, const AbsorbedTerm& b) {
              if (a.equation != b.equation) return a.equation < b.equation;
              if (a.state != b.state) return a.state < b.state;
              return term_less(a.term, b.term);
            });
}

namespace {

// `count` empty slots; their value is the sum add_term() accumulates.
std::vector<Slot> zero_slots(int count) {
  std::vector<Slot> slots(static_cast<size_t>(count));
  for (auto& s : slots) s.value = 0;
  return slots;
}

}  // namespace

void Deriver::allocate_slots() {
  const int n = M_ + N_;
  const int H = model_.H;
  model_.mass = zero_slots(n * n);
  model_.force = zero_slots(H * n * 2 * n);
  model_.forcing = zero_slots(H * n);
  model_.S = zero_slots(n * n);
  model_.c = zero_slots(n);
  if (spec_.cyclic_pitch) {
    model_.thrust_force = zero_slots(H * 2 * n);
    model_.thrust_forcing = zero_slots(H);
  }
}

void Deriver::assemble_mass() {
  const int n = M_ + N_;
  for (const auto& [key, terms] : pending_mass_) {
    for (const auto& t : terms) {
      // The runtime evaluates and factors the mass once per blade (model_api.h): it must be a
      // pure structural integral, free of mu and of the hover state.
      if (!t.scalars.empty() || t.ref != IntegralRef::Structural) {
        throw std::logic_error("generalized mass term with scalar inputs (" + t.origin + ")");
      }
      add_term(model_.mass[key.first * n + key.second], t);
    }
  }
}

void Deriver::assemble_linear() {
  const int n = M_ + N_;
  const int thrust_eq = model_.thrust_equation();
  for (const auto& [key, terms] : pending_force_) {
    const auto [h, eq, col] = key;
    for (const auto& t : terms) {
      add_term(eq == thrust_eq ? model_.thrust_force[h * 2 * n + col]
                               : model_.force[(h * n + eq) * 2 * n + col],
               t);
    }
  }
  for (const auto& [key, terms] : pending_forcing_) {
    const auto [h, eq] = key;
    for (const auto& t : terms) {
      add_term(eq == thrust_eq ? model_.thrust_forcing[h] : model_.forcing[h * n + eq], t);
    }
  }
}

void Deriver::assemble_hover_equilibrium() {
  std::vector<int> q0_scalar(g0_);
  q0_scalar.insert(q0_scalar.end(), h0_.begin(), h0_.end());
  for (int eq = 0; eq < M_ + N_; ++eq) {
    auto it = pending_forcing_.find({0, eq});
    if (it == pending_forcing_.end()) continue;
    for (const auto& t : it->second) place_hover_term(t, eq, q0_scalar);
  }
}

void Deriver::place_hover_term(const Term& t, int eq, const std::vector<int>& q0_scalar) {
  const int n = M_ + N_;
  bool has_mu = false;
  int q_index = -1, q_count = 0;
  for (const auto& [si, p] : t.scalars) {
    if (si == mu_) has_mu = true;
    for (int j = 0; j < n; ++j) {
      if (q0_scalar[j] == si) {
        q_index = j;
        q_count += p;
      }
    }
  }
  if (has_mu) return;
  if (q_count > 1) throw std::logic_error("hover equilibrium is nonlinear in q0");
  if (q_count == 0) {
    add_term(model_.c[eq], t);
    return;
  }
  Term s = t;
  s.coef = -s.coef;
  s.scalars.erase(
      std::remove_if(s.scalars.begin(), s.scalars.end(),
                     [&](const std::pair<int, int>& sp) { return sp.first == q0_scalar[q_index]; }),
      s.scalars.end());
  add_term(model_.S[eq * n + q_index], s);
}

void Deriver::add_paper_names(const Slot& slot) {
  for (const auto& t : slot.terms) {
    if (t.paper_name.empty() || t.integral < 0) continue;
    auto& info =
        t.ref == IntegralRef::Aero ? model_.aero[t.integral] : model_.structural[t.integral];
    if (info.paper_name.find(t.paper_name) == std::string::npos) {
      info.paper_name += (info.paper_name.empty() ? "" : "/") + t.paper_name;
    }
  }
}

void Deriver::name_integrals() {
  for (const auto& s : model_.mass) add_paper_names(s);
  for (const auto& s : model_.force) add_paper_names(s);
  for (const auto& s : model_.forcing) add_paper_names(s);
  for (const auto& s : model_.nonlinear) add_paper_names(s.slot);
  // An integral that only absorbed terms use still needs a name in the tables and the report.
  for (const auto& a : model_.absorbed) {
    const Term& t = a.term;
    if (t.ref == IntegralRef::Structural && model_.structural[t.integral].paper_name.empty()) {
      model_.structural[t.integral].paper_name = "centrifugal stiffness (absorbed)";
    }
  }
}

DerivedModel Deriver::run() {
  aerodynamic_loads();  // physics.cc
  structural_loads();
  if (spec_.nonlinear) nonlinear_pass();  // nonlinear.cc
  canonicalize();
  allocate_slots();
  assemble_mass();
  assemble_linear();
  assemble_hover_equilibrium();
  assemble_nonlinear();  // nonlinear.cc
  name_integrals();
  return model_;
}

}  // namespace detail

DerivedModel derive_model(const OrderingSpec& spec) { return detail::Deriver(spec).run(); }

}  // namespace flaplag::derive
