// Symbolic derivation of the flap-lag equations.  See derive.h for the pipeline and
// generator/README.md for the conventions.  Every product is truncated immediately (eps order
// and degree in the perturbation), which keeps GiNaC's expression swell bounded.
#include "flaplag_derive/derive.h"

#include <algorithm>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace flaplag::derive {

using GiNaC::ex;
using GiNaC::exvector;
using GiNaC::numeric;
using GiNaC::symbol;

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
  if (h == 0) return "1";
  const int k = (h + 1) / 2;
  const std::string arg = k == 1 ? "psi" : std::to_string(k) + "psi";
  return (h % 2 == 1 ? "cos " : "sin ") + arg;
}

namespace {

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
  int index;  // scalar index, state column, equation, or mode
  FactorKind kind;
  std::string tag;  // origin text for Role::Tag
};

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
  }
  return "q";
}

// One expanded monomial, taken apart.
struct Mono {
  numeric coef = 1;
  std::vector<std::pair<int, int>> scalars;
  int eps = 0, dlt = 0, radial = 0, z = 0;
  std::string origin;
  int state = -1;  // state column of a perturbation (power 1)
  int accel = -1;  // equation index of an acceleration (power 1)
  int x_power = 0;
  std::vector<ShapeFactor> outer, inner;
  int mass_outer = 0, mass_inner = 0;
  InnerKind inner_kind = InnerKind::None;
};

// Paper coefficient names (Appendix B), with the definitions the derivation produces.  Kinds
// are listed in the order of the paper's indices after the equation index i.
struct PaperAero {
  const char* name;
  bool flap;  // weight eta_i (flap) or gamma_i (lag)
  int x_power;
  std::vector<FactorKind> kinds;
};

const std::vector<PaperAero>& paper_aero_table() {
  using K = FactorKind;
  static const std::vector<PaperAero> t = {
      {"F1", true, 2, {}},
      {"F2", true, 1, {}},
      {"F3", true, 0, {}},
      {"F6", true, 1, {K::EtaPrime}},
      {"F7", true, 0, {K::EtaPrime}},
      {"F8", true, 1, {K::Eta}},
      {"F9", true, 0, {K::Eta}},
      {"F10", true, 1, {K::Gamma}},
      {"F11", true, 0, {K::Gamma}},
      {"F14", true, 0, {K::EtaPrime, K::Gamma}},
      {"F15", true, 0, {K::Eta, K::Gamma}},
      {"F21", true, 1, {K::GammaPrime}},
      {"F22", true, 0, {K::GammaPrime}},
      {"F23", true, 0, {K::EtaPrime, K::GammaPrime}},
      {"F24", true, 0, {K::Eta, K::GammaPrime}},
      {"L1", false, 1, {}},
      {"L2", false, 0, {}},
      {"L4", false, 2, {}},
      {"L7", false, 1, {K::Eta}},
      {"L8", false, 0, {K::Eta}},
      {"L10", false, 1, {K::EtaPrime}},
      {"L11", false, 0, {K::EtaPrime}},
      {"L13", false, 0, {K::Gamma}},
      {"L14", false, 1, {K::Gamma}},
      {"L16", false, 0, {K::EtaPrime, K::Gamma}},
      {"L17", false, 0, {K::EtaPrime, K::Eta}},
      {"L18", false, 0, {K::Eta, K::Eta}},
      {"L20", false, 0, {K::GammaPrime}},
      {"L21", false, 0, {K::EtaPrime, K::GammaPrime}},
      {"L22", false, 0, {K::Eta, K::GammaPrime}},
      {"L23", false, 1, {K::GammaPrime}},
      {"L24", false, 0, {K::EtaPrime, K::EtaPrime}},
  };
  return t;
}

// Assigns modes of `rest` to the kinds in paper order; "" when no entry matches.
std::string indexed_name(const char* base, int eq_mode, const std::vector<FactorKind>& kinds,
                         std::vector<ShapeFactor> rest) {
  std::ostringstream os;
  os << base << "_" << eq_mode + 1;
  for (FactorKind k : kinds) {
    auto it =
        std::find_if(rest.begin(), rest.end(), [k](const ShapeFactor& f) { return f.kind == k; });
    if (it == rest.end()) return "";
    os << it->mode + 1;
    rest.erase(it);
  }
  return rest.empty() ? os.str() : "";
}

std::string paper_aero_name(bool flap_eq, int eq_mode, const AeroIntegralKey& key) {
  const ShapeFactor weight{flap_eq ? FactorKind::Eta : FactorKind::Gamma, eq_mode};
  std::vector<ShapeFactor> rest = key.factors;
  auto w = std::find(rest.begin(), rest.end(), weight);
  if (w == rest.end()) return "";
  rest.erase(w);
  for (const auto& e : paper_aero_table()) {
    if (e.flap != flap_eq || e.x_power != key.x_power || e.kinds.size() != rest.size()) continue;
    std::vector<FactorKind> a = e.kinds, b;
    for (const auto& f : rest) b.push_back(f.kind);
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    if (a == b) return indexed_name(e.name, eq_mode, e.kinds, rest);
  }
  return "";
}

// Structural generalized masses (Appendix B) as derived.  Signature: weight-free outer kinds |
// inner kind | inner kinds, with mass flags.
std::string paper_structural_name(bool flap_eq, int eq_mode, const StructuralIntegralKey& k) {
  using K = FactorKind;
  std::vector<ShapeFactor> outer = k.outer;
  // The Galerkin weight is eta_i / gamma_i (local terms) or its slope (tension terms).
  const ShapeFactor w0{flap_eq ? K::Eta : K::Gamma, eq_mode};
  const ShapeFactor w1{flap_eq ? K::EtaPrime : K::GammaPrime, eq_mode};
  bool slope_weight = false;
  auto it = std::find(outer.begin(), outer.end(), w0);
  if (k.inner == InnerKind::Tail) {
    it = std::find(outer.begin(), outer.end(), w1);
    slope_weight = true;
  }
  if (it == outer.end()) return "";
  outer.erase(it);
  const std::string i = std::to_string(eq_mode + 1);
  auto kinds_are = [](const std::vector<ShapeFactor>& v, std::vector<K> want) {
    if (v.size() != want.size()) return false;
    for (size_t j = 0; j < v.size(); ++j) {
      if (v[j].kind != want[j]) return false;
    }
    return true;
  };
  auto idx = [](const std::vector<ShapeFactor>& v) {
    std::string s;
    for (const auto& f : v) s += std::to_string(f.mode + 1);
    return s;
  };
  if (k.inner == InnerKind::None && k.outer_mass == 1) {
    if (flap_eq && kinds_are(outer, {K::Eta})) return "M_F" + i + idx(outer);
    if (!flap_eq && kinds_are(outer, {K::Gamma})) return "M_L" + i + idx(outer);
    if (!flap_eq && kinds_are(outer, {K::Eta})) return "B7_" + i + idx(outer);
    if (!flap_eq && kinds_are(outer, {K::X0})) return "B11_" + i;
  }
  if (k.inner == InnerKind::Tail && slope_weight && k.inner_mass == 1) {
    const bool arm = kinds_are(k.inner_factors, {K::Arm});
    if (flap_eq && outer.empty() && arm) return "B1_" + i;
    if (!flap_eq && outer.empty() && arm) return "B10_" + i;
    if (flap_eq && outer.empty() && kinds_are(k.inner_factors, {K::Gamma}))
      return "B3_" + i + idx(k.inner_factors);
    if (!flap_eq && outer.empty() && kinds_are(k.inner_factors, {K::Gamma}))
      return "B8_" + i + idx(k.inner_factors);
    if (flap_eq && kinds_are(outer, {K::EtaPrime}) && kinds_are(k.inner_factors, {K::Gamma}))
      return "P_" + i + idx(outer) + idx(k.inner_factors);
    if (!flap_eq && kinds_are(outer, {K::GammaPrime}) && kinds_are(k.inner_factors, {K::Gamma}))
      return "S_" + i + idx(outer) + idx(k.inner_factors);
  }
  if (k.inner == InnerKind::Head && k.outer_mass == 1 && outer.empty() && !flap_eq) {
    if (kinds_are(k.inner_factors, {K::EtaPrime, K::EtaPrime}))
      return "Meta_" + i + idx(k.inner_factors);
    if (kinds_are(k.inner_factors, {K::GammaPrime, K::GammaPrime}))
      return "Mgamma_" + i + idx(k.inner_factors);
  }
  return "";
}

class Deriver {
 public:
  explicit Deriver(const OrderingSpec& spec)
      : spec_(spec), M_(spec.flap_modes), N_(spec.lag_modes) {
    model_.spec = spec;
    model_.M = M_;
    model_.N = N_;
    make_symbols();
  }

  DerivedModel run();

 private:
  // ----- symbols -------------------------------------------------------------------------
  symbol sym(const std::string& name, SymRole role) {
    symbol s(name);
    roles_.emplace(name, std::move(role));
    return s;
  }
  int add_scalar(const std::string& name, const std::string& cexpr) {
    const int idx = static_cast<int>(model_.scalars.size());
    symbol s = sym(name, {Role::Scalar, idx});
    model_.scalars.push_back({name, cexpr, s});
    return idx;
  }
  ex scalar(int idx) const { return model_.scalars[idx].sym; }
  ex eps_pow(const std::string& key) const { return GiNaC::pow(eps_, spec_.order(key)); }

  void make_symbols();

  // ----- truncation ------------------------------------------------------------------------
  // Keeps monomials with eps order <= max_eps and perturbation degree <= 1.
  ex trunc(const ex& e, int max_eps) const {
    const ex x = e.expand();
    exvector keep;
    auto consider = [&](const ex& t) {
      if (t.degree(dlt_) <= 1 && t.degree(eps_) <= max_eps) keep.push_back(t);
    };
    if (GiNaC::is_a<GiNaC::add>(x)) {
      for (const auto& t : x) consider(t);
    } else {
      consider(x);
    }
    return ex(GiNaC::add(keep));
  }
  ex mul(const ex& a, const ex& b, int max_eps) const { return trunc(a * b, max_eps); }

  // ----- monomial analysis ---------------------------------------------------------------
  Mono analyse(const ex& t) const;
  Term make_term(const Mono& m, bool aero, int eq);
  int aero_index(const AeroIntegralKey& k);
  int structural_index(const StructuralIntegralKey& k);
  void place(const ex& expr, bool aero, int eq);
  void add_term(Slot& s, const Term& t);

  // ----- physics ---------------------------------------------------------------------------
  void aerodynamic_loads();
  void structural_loads();

  const OrderingSpec& spec_;
  int M_, N_;
  DerivedModel model_;
  std::map<std::string, SymRole> roles_;

  symbol eps_, dlt_, radial_, z_;
  symbol x_;                                         // aerodynamic station radius by R
  std::vector<symbol> eta_, etap_, gam_, gamp_;      // outer shapes
  std::vector<symbol> ieta_, ietap_, igam_, igamp_;  // inner shapes (at x1)
  symbol x0_, arm_, iarm_, mo_, mi_, tail_, head_;
  std::vector<symbol> dg_, dgd_, dgdd_, dh_, dhd_, dhdd_;
  int lock_, lr_, theta_, inflow_, precone_, droop_, cdo_, mu_;
  std::vector<int> g0_, h0_, wf_, wl_, zf_, zl_;
  std::vector<std::vector<int>> esf_, esl_, ecsfl_, ecslf_;
  std::map<std::string, symbol> tags_;
  symbol tag(const std::string& origin) {
    auto it = tags_.find(origin);
    if (it != tags_.end()) return it->second;
    const std::string name = "tag" + std::to_string(tags_.size());
    symbol s = sym(name, {Role::Tag, 0, FactorKind::Eta, origin});
    tags_.emplace(origin, s);
    return s;
  }

  std::map<AeroIntegralKey, int> aero_index_;
  std::map<StructuralIntegralKey, int> structural_index_;

  std::map<std::pair<int, int>, std::vector<Term>> pending_forcing_;      // (h, eq)
  std::map<std::pair<int, int>, std::vector<Term>> pending_mass_;         // (eq, accel)
  std::map<std::tuple<int, int, int>, std::vector<Term>> pending_force_;  // (h, eq, state)
  std::set<std::string> absorbed_origins_;

  // GiNaC visits terms in an address-dependent order: renumber the integrals by their keys and
  // sort every term list so that the output is byte-identical from run to run.
  void canonicalize();
};

bool term_less(const Term& a, const Term& b) {
  if (a.ref != b.ref) return a.ref < b.ref;
  if (a.integral != b.integral) return a.integral < b.integral;
  if (a.scalars != b.scalars) return a.scalars < b.scalars;
  if (a.origin != b.origin) return a.origin < b.origin;
  if (a.radial_flow != b.radial_flow) return a.radial_flow < b.radial_flow;
  return a.coef < b.coef;
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
  for (int k = 0; k < M_; ++k)
    g0_.push_back(add_scalar("g0_" + idx1(k), "in.g0[" + std::to_string(k) + "]"));
  for (int m = 0; m < N_; ++m)
    h0_.push_back(add_scalar("h0_" + idx1(m), "in.h0[" + std::to_string(m) + "]"));
  for (int k = 0; k < M_; ++k) {
    wf_.push_back(add_scalar("omega_flap_" + idx1(k), "in.omega_flap[" + std::to_string(k) + "]"));
    zf_.push_back(
        add_scalar("damping_flap_" + idx1(k), "in.damping_flap[" + std::to_string(k) + "]"));
  }
  for (int m = 0; m < N_; ++m) {
    wl_.push_back(add_scalar("omega_lag_" + idx1(m), "in.omega_lag[" + std::to_string(m) + "]"));
    zl_.push_back(
        add_scalar("damping_lag_" + idx1(m), "in.damping_lag[" + std::to_string(m) + "]"));
  }
  auto flat = [](int r, int c, int cols) { return std::to_string(r * cols + c); };
  esf_.assign(M_, std::vector<int>(M_));
  ecsfl_.assign(M_, std::vector<int>(N_));
  esl_.assign(N_, std::vector<int>(N_));
  ecslf_.assign(N_, std::vector<int>(M_));
  for (int i = 0; i < M_; ++i) {
    for (int k = 0; k < M_; ++k)
      esf_[i][k] =
          add_scalar("es_flap_" + idx1(i) + "_" + idx1(k), "in.es_flap[" + flat(i, k, M_) + "]");
    for (int m = 0; m < N_; ++m)
      ecsfl_[i][m] = add_scalar("ecs_flap_lag_" + idx1(i) + "_" + idx1(m),
                                "in.ecs_flap_lag[" + flat(i, m, N_) + "]");
  }
  for (int i = 0; i < N_; ++i) {
    for (int m = 0; m < N_; ++m)
      esl_[i][m] =
          add_scalar("es_lag_" + idx1(i) + "_" + idx1(m), "in.es_lag[" + flat(i, m, N_) + "]");
    for (int k = 0; k < M_; ++k)
      ecslf_[i][k] = add_scalar("ecs_lag_flap_" + idx1(i) + "_" + idx1(k),
                                "in.ecs_lag_flap[" + flat(i, k, M_) + "]");
  }
}

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
  std::sort(m.outer.begin(), m.outer.end());
  std::sort(m.inner.begin(), m.inner.end());
  return m;
}

int Deriver::aero_index(const AeroIntegralKey& k) {
  auto it = aero_index_.find(k);
  if (it != aero_index_.end()) return it->second;
  const int idx = static_cast<int>(model_.aero_keys.size());
  aero_index_.emplace(k, idx);
  model_.aero_keys.push_back(k);
  IntegralInfo info;
  std::ostringstream name, id;
  if (k.x_power > 0) {
    name << (k.x_power == 1 ? "x" : "x^" + std::to_string(k.x_power));
    id << "x" << k.x_power;
  }
  for (const auto& f : k.factors) {
    if (name.tellp() > 0) name << " ";
    if (id.tellp() > 0) id << "_";
    name << factor_name(f);
    id << factor_ident(f);
  }
  info.name = name.str().empty() ? "1" : name.str();
  info.ident = id.str().empty() ? "one" : id.str();
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
    t.paper_name = paper_aero_name(flap_eq, eq_mode, k);
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

void Deriver::add_term(Slot& s, const Term& t) {
  ex v = t.coef;
  for (const auto& [idx, p] : t.scalars) v *= GiNaC::pow(model_.scalars[idx].sym, p);
  if (t.ref == IntegralRef::Aero) v *= model_.aero_syms[t.integral];
  if (t.ref == IntegralRef::Structural) v *= model_.structural_syms[t.integral];
  s.terms.push_back(t);
  s.value = s.value + v;
}

// Splits an expanded residual of equation eq into harmonics and slots.
void Deriver::place(const ex& expr, bool aero, int eq) {
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
  for (auto& [h, terms] : buckets) {
    const ex sum = ex(GiNaC::add(terms)).expand();
    if (sum.is_zero()) continue;
    exvector monos;
    if (GiNaC::is_a<GiNaC::add>(sum)) {
      for (const auto& t : sum) monos.push_back(t);
    } else {
      monos.push_back(sum);
    }
    if (h + 1 > model_.H) model_.H = h + 1;
    for (const auto& t : monos) {
      Mono m = analyse(t);
      if (!m.coef.is_real()) throw std::logic_error("complex coefficient after harmonic split");
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
            model_.absorbed.push_back(make_term(m, aero, eq));
            model_.absorbed_equation.push_back(eq);
            model_.absorbed_state.push_back(col);
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

// Generalized aerodynamic loads, eqs 2.18-2.23, nondimensionalised so that
//   A_Fi = (gamma/2)(l/R)^2 int u_T (u_T theta - u_P) eta_i dx0
//   A_Li = (gamma/2)(l/R)^2 int [u_P (u_T theta - u_P) + (C_Do/a) u_T^2] gamma_i dx0
// with u_T = U_T/(Omega R), u_P = U_P/(Omega R).  A_Li carries the sign of eq 2.19 (v_e = -l
// gamma h, so the lag coordinate is positive against the rotation).
void Deriver::aerodynamic_loads() {
  const ex c = (z_ + 1 / z_) / 2;               // cos psi
  const ex s = (z_ - 1 / z_) / (2 * GiNaC::I);  // sin psi
  const ex theta = eps_pow("theta") * scalar(theta_);
  const ex lambda = eps_pow("inflow") * scalar(inflow_);
  const ex beta = eps_pow("precone") * scalar(precone_) + eps_pow("droop") * scalar(droop_);
  const ex beta_d = eps_pow("droop") * scalar(droop_);
  const ex cdo = eps_pow("cdo_a") * scalar(cdo_);
  const ex mu = scalar(mu_), lr = scalar(lr_);
  const int kf = spec_.kept_flap, kl = spec_.kept_lag;
  const int kmax = std::max(kf, kl);

  // Slopes and rates of the displacement field (2.13-2.15), linearized about hover (2.26):
  // g = g0 + dg, h = h0 + dh.
  ex w_slope = beta, v_slope = -beta_d * theta, w_rate = 0, v_rate = 0;
  for (int k = 0; k < M_; ++k) {
    w_slope += etap_[k] * eps_pow("g") * (scalar(g0_[k]) + dlt_ * dg_[k]);
    w_rate += eta_[k] * eps_pow("g_dot") * dlt_ * dgd_[k];
  }
  for (int m = 0; m < N_; ++m) {
    v_slope -= gamp_[m] * eps_pow("h") * (scalar(h0_[m]) + dlt_ * dh_[m]);
    v_rate -= gam_[m] * eps_pow("h_dot") * dlt_ * dhd_[m];
  }
  // Eq 2.23; the last term is the radial-flow term, tagged rf.
  const ex radial = spec_.radial_flow ? ex(radial_) : ex(0);
  const ex uT = trunc(x_ + mu * s + radial * mu * c * v_slope + lr * v_rate, kmax);
  // Eq 2.22.
  const ex uP = trunc(lambda + mu * c * w_slope + lr * w_rate, kmax);

  const ex uT2 = mul(uT, uT, kmax);
  const ex uTuP = mul(uT, uP, kmax);
  const ex uP2 = mul(uP, uP, kmax);

  // Eq 2.20 as u_T (u_T theta - u_P), by load product.
  const ex lz = trunc(tag("L_z: theta U_T^2") * theta * uT2 - tag("L_z: -U_T U_P") * uTuP, kf);
  // Eq 2.21 as -(L_y) = u_P (u_T theta - u_P) + (C_Do/a) u_T^2.
  const ex ly = trunc(tag("L_y: theta U_P U_T") * theta * uTuP - tag("L_y: -U_P^2") * uP2 +
                          tag("L_y: (C_Do/a) U_T^2") * cdo * uT2,
                      kl);
  const ex scale = scalar(lock_) / 2 * GiNaC::pow(lr, 2);
  for (int i = 0; i < M_; ++i) place(scale * lz * eta_[i], true, i);
  for (int i = 0; i < N_; ++i) place(scale * ly * gam_[i], true, model::lag_equation_index(i, M_));
}

// Structural and inertial generalized forces from eqs 2.2-2.10, Galerkin-weighted (2.16-2.17)
// and divided by Omega^2 I_b.  Loads (2.4-2.6) with the terms the paper marks small (u'' and
// u in P_x) neglected:
//   P_x = m (x0 + e1 + 2 v'),  P_y = L_y - m (v'' - v + 2 u'),  P_z = L_z - m w''
//   T(x) = int_x^1 P_x dx1 (free tip).
// Flap residual i:  int eta_i P_z dx0 - int eta_i' T w_x dx0      (tension by parts)
// Lag residual i:   int (-gamma_i) P_y dx0 + int gamma_i' T v_x dx0 (weight -gamma_i: v_e = -l
// gamma h)
void Deriver::structural_loads() {
  const int big = 1000;  // structural terms are exact to second order in displacement: no cut
  const ex theta = eps_pow("theta") * scalar(theta_);
  const ex beta = eps_pow("precone") * scalar(precone_) + eps_pow("droop") * scalar(droop_);
  const ex beta_d = eps_pow("droop") * scalar(droop_);

  ex w_slope = beta, w_acc = 0, v = -x0_ * beta_d * theta, v_slope = -beta_d * theta, v_acc = 0;
  ex u_rate = 0;                // u' (eq 2.8 differentiated; beta and theta constant)
  ex inner_v_rate = 0;          // v'(x1) inside the tension integral
  ex head_ww = 0, head_vv = 0;  // int_0^x w_e'^2 and v_e'^2 products, differentiated
  std::vector<ex> G, Gd, H, Hd;
  for (int k = 0; k < M_; ++k) {
    G.push_back(eps_pow("g") * (scalar(g0_[k]) + dlt_ * dg_[k]));
    Gd.push_back(eps_pow("g_dot") * dlt_ * dgd_[k]);
    w_slope += etap_[k] * G[k];
    w_acc += eta_[k] * eps_pow("g_dot") * dlt_ * dgdd_[k];
    u_rate -= beta * eta_[k] * Gd[k];  // -(beta_P + beta_D) w_e'
  }
  for (int m = 0; m < N_; ++m) {
    H.push_back(eps_pow("h") * (scalar(h0_[m]) + dlt_ * dh_[m]));
    Hd.push_back(eps_pow("h_dot") * dlt_ * dhd_[m]);
    v -= gam_[m] * H[m];
    v_slope -= gamp_[m] * H[m];
    v_acc -= gam_[m] * eps_pow("h_dot") * dlt_ * dhdd_[m];
    inner_v_rate -= igam_[m] * Hd[m];
  }
  // d/dpsi of -1/2 int_0^x (w_e'^2 + v_e'^2) dx1 = -int_0^x (w_e' w_e'' + v_e' v_e'') dx1
  for (int k = 0; k < M_; ++k)
    for (int l = 0; l < M_; ++l) head_ww += ietap_[k] * ietap_[l] * G[k] * Gd[l];
  for (int m = 0; m < N_; ++m)
    for (int r = 0; r < N_; ++r) head_vv += igamp_[m] * igamp_[r] * H[m] * Hd[r];
  u_rate = trunc(u_rate - head_ * (head_ww + head_vv), big);

  // Tension: centrifugal part and the Coriolis part 2 v' of P_x.
  const ex tension = tail_ * mi_ *
                     (tag("tension, centrifugal (2.4)") * iarm_ +
                      tag("tension, Coriolis 2v' (2.4)") * 2 * inner_v_rate);
  absorbed_origins_ = {"tension, centrifugal (2.4)", "in-plane centrifugal -v (2.5)"};

  for (int i = 0; i < M_; ++i) {
    ex r = -tag("flap inertia w'' (2.6)") * mo_ * eta_[i] * w_acc;
    r -= mul(etap_[i] * w_slope, tension, big);
    place(trunc(r, big), false, i);
  }
  for (int i = 0; i < N_; ++i) {
    ex r = mo_ * gam_[i] *
           (tag("lag inertia v'' (2.5)") * v_acc - tag("in-plane centrifugal -v (2.5)") * v +
            tag("Coriolis 2u' (2.5)") * 2 * u_rate);
    r += mul(gamp_[i] * v_slope, tension, big);
    place(trunc(r, big), false, model::lag_equation_index(i, M_));
  }

  // Modal stiffness and damping (orthogonality, A.2 and A.4; damping as in 2.16-2.17) and the
  // elastic coupling of Appendix E (E.5-E.8), which enter as inputs.
  const ex es_w = GiNaC::pow(eps_, 2 * spec_.order("theta"));  // sin^2 theta
  const ex ecs_w = eps_pow("theta");                           // sin theta cos theta
  for (int i = 0; i < M_; ++i) {
    const ex mass = mo_ * eta_[i] * eta_[i];
    ex r = -tag("modal stiffness (A.2)") * GiNaC::pow(scalar(wf_[i]), 2) * mass * G[i] -
           tag("structural damping (2.16)") * 2 * scalar(wf_[i]) * scalar(zf_[i]) * mass * Gd[i];
    for (int k = 0; k < M_; ++k)
      r -= tag("elastic coupling E^s (E.5)") * es_w * scalar(esf_[i][k]) * G[k];
    for (int m = 0; m < N_; ++m)
      r += tag("elastic coupling E^cs (E.6)") * ecs_w * scalar(ecsfl_[i][m]) * H[m];
    place(trunc(r, big), false, i);
  }
  for (int i = 0; i < N_; ++i) {
    const ex mass = mo_ * gam_[i] * gam_[i];
    ex r = -tag("modal stiffness (A.4)") * GiNaC::pow(scalar(wl_[i]), 2) * mass * H[i] -
           tag("structural damping (2.17)") * 2 * scalar(wl_[i]) * scalar(zl_[i]) * mass * Hd[i];
    for (int m = 0; m < N_; ++m)
      r += tag("elastic coupling E^s (E.7)") * es_w * scalar(esl_[i][m]) * H[m];
    for (int k = 0; k < M_; ++k)
      r += tag("elastic coupling E^cs (E.8)") * ecs_w * scalar(ecslf_[i][k]) * G[k];
    place(trunc(r, big), false, model::lag_equation_index(i, M_));
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
  // absorbed terms: sort by (equation, state, term)
  std::vector<size_t> order(model_.absorbed.size());
  for (size_t j = 0; j < order.size(); ++j) {
    order[j] = j;
    remap(model_.absorbed[j]);
  }
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    if (model_.absorbed_equation[a] != model_.absorbed_equation[b])
      return model_.absorbed_equation[a] < model_.absorbed_equation[b];
    if (model_.absorbed_state[a] != model_.absorbed_state[b])
      return model_.absorbed_state[a] < model_.absorbed_state[b];
    return term_less(model_.absorbed[a], model_.absorbed[b]);
  });
  std::vector<Term> t2;
  std::vector<int> e2, s2;
  for (size_t j : order) {
    t2.push_back(model_.absorbed[j]);
    e2.push_back(model_.absorbed_equation[j]);
    s2.push_back(model_.absorbed_state[j]);
  }
  model_.absorbed = t2;
  model_.absorbed_equation = e2;
  model_.absorbed_state = s2;
}

DerivedModel Deriver::run() {
  aerodynamic_loads();
  structural_loads();
  canonicalize();
  const int n = M_ + N_;
  const int H = model_.H;
  model_.mass.assign(n * n, Slot{});
  model_.force.assign(H * n * 2 * n, Slot{});
  model_.forcing.assign(H * n, Slot{});
  model_.S.assign(n * n, Slot{});
  model_.c.assign(n, Slot{});
  for (auto& s : model_.mass) s.value = 0;
  for (auto& s : model_.force) s.value = 0;
  for (auto& s : model_.forcing) s.value = 0;
  for (auto& s : model_.S) s.value = 0;
  for (auto& s : model_.c) s.value = 0;
  for (const auto& [key, terms] : pending_mass_) {
    for (const auto& t : terms) add_term(model_.mass[key.first * n + key.second], t);
  }
  for (const auto& [key, terms] : pending_force_) {
    const auto [h, eq, col] = key;
    for (const auto& t : terms) add_term(model_.force[(h * n + eq) * 2 * n + col], t);
  }
  for (const auto& [key, terms] : pending_forcing_) {
    const auto [h, eq] = key;
    for (const auto& t : terms) add_term(model_.forcing[h * n + eq], t);
  }
  // Hover static equilibrium, eqs 2.27-2.32: the perturbation-free residual at mu = 0 is
  // c - S q0 and must be linear in q0.
  std::vector<int> q0_scalar;
  for (int k = 0; k < M_; ++k) q0_scalar.push_back(g0_[k]);
  for (int m = 0; m < N_; ++m) q0_scalar.push_back(h0_[m]);
  for (int eq = 0; eq < n; ++eq) {
    auto it = pending_forcing_.find({0, eq});
    if (it == pending_forcing_.end()) continue;
    for (const auto& t : it->second) {
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
      if (has_mu) continue;
      if (q_count > 1) throw std::logic_error("hover equilibrium is nonlinear in q0");
      if (q_count == 0) {
        add_term(model_.c[eq], t);
      } else {
        Term s = t;
        s.coef = -s.coef;
        s.scalars.erase(std::remove_if(s.scalars.begin(), s.scalars.end(),
                                       [&](const std::pair<int, int>& sp) {
                                         return sp.first == q0_scalar[q_index];
                                       }),
                        s.scalars.end());
        add_term(model_.S[eq * n + q_index], s);
      }
    }
  }
  // Integral paper names: the distinct names of all terms that use each integral.
  auto collect = [&](const std::vector<Slot>& slots) {
    for (const auto& s : slots) {
      for (const auto& t : s.terms) {
        if (t.paper_name.empty() || t.integral < 0) continue;
        auto& info =
            t.ref == IntegralRef::Aero ? model_.aero[t.integral] : model_.structural[t.integral];
        if (info.paper_name.find(t.paper_name) == std::string::npos) {
          info.paper_name += (info.paper_name.empty() ? "" : "/") + t.paper_name;
        }
      }
    }
  };
  collect(model_.mass);
  collect(model_.force);
  collect(model_.forcing);
  for (const auto& t : model_.absorbed) {
    if (t.ref == IntegralRef::Structural && model_.structural[t.integral].paper_name.empty()) {
      model_.structural[t.integral].paper_name = "centrifugal stiffness (absorbed)";
    }
  }
  return model_;
}

}  // namespace

DerivedModel derive_model(const OrderingSpec& spec) { return Deriver(spec).run(); }

}  // namespace flaplag::derive
