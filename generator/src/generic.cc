// Extraction of the mode-generic model from concrete derivations (see generic.h).
//
// A term is handled as a "labelled term": every place that carries a mode (indexed scalars,
// integral factors, state factors, and the slot's equation and column) holds either a concrete
// mode (a derivation's term) or a variable (a pattern).  key() is its canonical text without
// the coefficient; substituting values for the variables of a pattern gives concrete terms.
#include "flaplag_derive/generic.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "flaplag_derive/paper_names.h"

namespace flaplag::derive {

namespace {

using GiNaC::numeric;

ModeDir dir_of(FactorKind k) {
  return k == FactorKind::Gamma || k == FactorKind::GammaPrime ? ModeDir::Lag : ModeDir::Flap;
}
bool has_mode(FactorKind k) { return model::has_mode(static_cast<model::Factor>(k)); }

// Families of indexed scalars, the directions of their indices (derive.cc's names) and the
// per-direction input they read (model_api.h CoefficientInputs).
struct Family {
  const char* name;
  std::vector<ModeDir> dirs;
  const char* array;
};
const std::vector<Family>& families() {
  static const std::vector<Family> f = {
      {"g0", {ModeDir::Flap}, "q0"},
      {"h0", {ModeDir::Lag}, "q0"},
      {"omega_flap", {ModeDir::Flap}, "omega"},
      {"damping_flap", {ModeDir::Flap}, "damping"},
      {"omega_lag", {ModeDir::Lag}, "omega"},
      {"damping_lag", {ModeDir::Lag}, "damping"},
      {"es_flap", {ModeDir::Flap, ModeDir::Flap}, "elastic"},
      {"ecs_flap_lag", {ModeDir::Flap, ModeDir::Lag}, "elastic"},
      {"es_lag", {ModeDir::Lag, ModeDir::Lag}, "elastic"},
      {"ecs_lag_flap", {ModeDir::Lag, ModeDir::Flap}, "elastic"},
  };
  return f;
}
const Family* family_of(const std::string& name) {
  for (const auto& f : families())
    if (name == f.name) return &f;
  return nullptr;
}

// A labelled term.  Modes: concrete values or pattern variables; -1 = no mode (X0, Arm, Twist).
struct Lab {
  numeric coef = 1;
  std::vector<std::pair<std::string, int>> scalars;
  std::vector<IndexedScalar> indexed;
  IntegralRef ref = IntegralRef::None;
  int x_power = 0, outer_mass = 0, inner_mass = 0;
  InnerKind inner = InnerKind::None;
  std::vector<TemplateFactor> outer, inner_f;
  std::vector<StateFactor> states;
  int eps = 0;
  std::string origin;
  bool radial = false;
};

void sort_lab(Lab& t) {
  std::sort(t.outer.begin(), t.outer.end());
  std::sort(t.inner_f.begin(), t.inner_f.end());
  std::sort(t.indexed.begin(), t.indexed.end(), [](const IndexedScalar& a, const IndexedScalar& b) {
    return std::tie(a.family, a.args, a.power) < std::tie(b.family, b.args, b.power);
  });
  std::sort(t.states.begin(), t.states.end(), [](const StateFactor& a, const StateFactor& b) {
    return std::tie(a.dir, a.rate, a.var, a.power) < std::tie(b.dir, b.rate, b.var, b.power);
  });
  // equal indexed scalars (a pattern's g0_k g0_l at k = l): one with the summed power
  std::vector<IndexedScalar> idx;
  for (const auto& x : t.indexed) {
    if (!idx.empty() && idx.back().family == x.family && idx.back().args == x.args) {
      idx.back().power += x.power;
    } else {
      idx.push_back(x);
    }
  }
  t.indexed = idx;
  // equal state factors: one with the summed power
  std::vector<StateFactor> merged;
  for (const auto& s : t.states) {
    if (!merged.empty() && merged.back().dir == s.dir && merged.back().rate == s.rate &&
        merged.back().var == s.var) {
      merged.back().power += s.power;
    } else {
      merged.push_back(s);
    }
  }
  t.states = merged;
}

std::string factors_text(const std::vector<TemplateFactor>& f) {
  std::ostringstream os;
  for (const auto& x : f) os << static_cast<int>(x.kind) << ":" << x.var << ",";
  return os.str();
}

// Canonical text without the coefficient (lists must be sorted: sort_lab).
std::string key(const Lab& t) {
  std::ostringstream os;
  for (const auto& [n, p] : t.scalars) os << n << "^" << p << " ";
  os << "|";
  for (const auto& s : t.indexed) {
    os << s.family << "(";
    for (int a : s.args) os << a << ",";
    os << ")^" << s.power << " ";
  }
  os << "|" << static_cast<int>(t.ref) << " x" << t.x_power << " m" << t.outer_mass << " ["
     << factors_text(t.outer) << "] " << static_cast<int>(t.inner) << " mi" << t.inner_mass << " ["
     << factors_text(t.inner_f) << "]|";
  for (const auto& s : t.states)
    os << static_cast<int>(s.dir) << (s.rate ? "'" : "") << s.var << "^" << s.power << " ";
  os << "|" << t.eps << "|" << t.origin << "|" << t.radial;
  return os.str();
}

// Applies f to every mode place.
void for_each_mode(Lab& t, const std::function<void(ModeDir, int&)>& f) {
  for (auto& s : t.indexed) {
    const Family* fam = family_of(s.family);
    for (size_t a = 0; a < s.args.size(); ++a) f(fam->dirs[a], s.args[a]);
  }
  for (auto& x : t.outer)
    if (has_mode(x.kind)) f(dir_of(x.kind), x.var);
  for (auto& x : t.inner_f)
    if (has_mode(x.kind)) f(dir_of(x.kind), x.var);
  for (auto& s : t.states) f(s.dir, s.var);
}

Lab substitute(const Lab& g, const std::vector<int>& values) {
  Lab t = g;
  for_each_mode(t, [&](ModeDir, int& m) { m = values.at(static_cast<size_t>(m)); });
  sort_lab(t);
  return t;
}

// ----- slots --------------------------------------------------------------------------------

struct ClassKey {
  SlotKind kind;
  int harmonic;
  ModeDir eq, col;
  bool rate;
  bool operator<(const ClassKey& o) const {
    return std::tie(kind, harmonic, eq, col, rate) <
           std::tie(o.kind, o.harmonic, o.eq, o.col, o.rate);
  }
};

bool kind_has_eq(SlotKind k) {
  return k != SlotKind::ThrustForce && k != SlotKind::ThrustForcing &&
         k != SlotKind::NonlinearThrust;
}
bool kind_has_col(SlotKind k) {
  return k == SlotKind::Mass || k == SlotKind::Force || k == SlotKind::HoverStiffness ||
         k == SlotKind::ThrustForce || k == SlotKind::Absorbed;
}

// Bound values of one concrete slot: (equation mode, column mode), -1 when absent.
using Bound = std::pair<int, int>;

// Every concrete term of a derivation, by slot class and bound values, merged by key.
using SlotTerms = std::map<std::string, Lab>;
using Concrete = std::map<ClassKey, std::map<Bound, SlotTerms>>;

struct Coord {
  ModeDir dir;
  int mode;
};
Coord coord(int j, int M) { return j < M ? Coord{ModeDir::Flap, j} : Coord{ModeDir::Lag, j - M}; }

class Collector {
 public:
  explicit Collector(const DerivedModel& m) : m_(m) {}

  Lab label(const Term& t) const {
    Lab l;
    l.coef = t.coef;
    for (const auto& [idx, p] : t.scalars) {
      const std::string& name = m_.scalars[static_cast<size_t>(idx)].name;
      // indexed names: <family>_<a> or <family>_<a>_<b>, 1-based
      bool found = false;
      for (const auto& fam : families()) {
        const std::string prefix = std::string(fam.name) + "_";
        if (name.rfind(prefix, 0) != 0) continue;
        std::vector<int> args;
        std::stringstream rest(name.substr(prefix.size()));
        std::string part;
        bool ok = true;
        while (std::getline(rest, part, '_')) {
          if (part.empty() || part.find_first_not_of("0123456789") != std::string::npos) {
            ok = false;
            break;
          }
          args.push_back(std::stoi(part) - 1);
        }
        if (!ok || args.size() != fam.dirs.size()) continue;
        l.indexed.push_back({fam.name, args, p});
        found = true;
        break;
      }
      if (!found) l.scalars.emplace_back(name, p);
    }
    std::sort(l.scalars.begin(), l.scalars.end());
    l.ref = t.ref;
    auto conv = [](const std::vector<ShapeFactor>& f) {
      std::vector<TemplateFactor> out;
      for (const auto& x : f) out.push_back({x.kind, has_mode(x.kind) ? x.mode : -1});
      return out;
    };
    if (t.ref == IntegralRef::Aero) {
      const AeroIntegralKey& k = m_.aero_keys[static_cast<size_t>(t.integral)];
      l.x_power = k.x_power;
      l.outer = conv(k.factors);
    } else if (t.ref == IntegralRef::Structural) {
      const StructuralIntegralKey& k = m_.structural_keys[static_cast<size_t>(t.integral)];
      l.outer_mass = k.outer_mass;
      l.outer = conv(k.outer);
      l.inner = k.inner;
      l.inner_mass = k.inner_mass;
      l.inner_f = conv(k.inner_factors);
    }
    l.eps = t.eps_order;
    l.origin = t.origin;
    l.radial = t.radial_flow;
    sort_lab(l);
    return l;
  }

  void add(Concrete& c, const ClassKey& k, Bound b, const Lab& l) const {
    SlotTerms& s = c[k][b];
    const std::string kk = key(l);
    auto it = s.find(kk);
    if (it == s.end()) {
      s.emplace(kk, l);
    } else {
      it->second.coef += l.coef;
    }
  }

  void add_slot(Concrete& c, const ClassKey& k, Bound b, const Slot& s,
                const std::vector<StateFactor>& states = {}) const {
    for (const auto& t : s.terms) {
      Lab l = label(t);
      l.states = states;
      sort_lab(l);
      add(c, k, b, l);
    }
  }

  Concrete collect() const {
    Concrete c;
    const int M = m_.M, N = m_.N, n = M + N;
    for (int r = 0; r < n; ++r) {
      const Coord e = coord(r, M);
      for (int q = 0; q < n; ++q) {
        const Coord a = coord(q, M);
        add_slot(c, {SlotKind::Mass, 0, e.dir, a.dir, false}, {e.mode, a.mode},
                 m_.mass[static_cast<size_t>(r * n + q)]);
        add_slot(c, {SlotKind::HoverStiffness, 0, e.dir, a.dir, false}, {e.mode, a.mode},
                 m_.S[static_cast<size_t>(r * n + q)]);
      }
      add_slot(c, {SlotKind::HoverLoad, 0, e.dir, ModeDir::Flap, false}, {e.mode, -1},
               m_.c[static_cast<size_t>(r)]);
      for (int h = 0; h < m_.H; ++h) {
        for (int col = 0; col < 2 * n; ++col) {
          const model::StateRef s = model::state_ref(col, M, N);
          const ModeDir d = s.direction == model::Direction::Flap ? ModeDir::Flap : ModeDir::Lag;
          add_slot(c, {SlotKind::Force, h, e.dir, d, s.rate}, {e.mode, s.mode},
                   m_.force[static_cast<size_t>((h * n + r) * 2 * n + col)]);
        }
        add_slot(c, {SlotKind::Forcing, h, e.dir, ModeDir::Flap, false}, {e.mode, -1},
                 m_.forcing[static_cast<size_t>(h * n + r)]);
      }
    }
    if (!m_.thrust_forcing.empty()) {
      for (int h = 0; h < m_.H; ++h) {
        for (int col = 0; col < 2 * n; ++col) {
          const model::StateRef s = model::state_ref(col, M, N);
          const ModeDir d = s.direction == model::Direction::Flap ? ModeDir::Flap : ModeDir::Lag;
          add_slot(c, {SlotKind::ThrustForce, h, ModeDir::Flap, d, s.rate}, {-1, s.mode},
                   m_.thrust_force[static_cast<size_t>(h * 2 * n + col)]);
        }
        add_slot(c, {SlotKind::ThrustForcing, h, ModeDir::Flap, ModeDir::Flap, false}, {-1, -1},
                 m_.thrust_forcing[static_cast<size_t>(h)]);
      }
    }
    auto states_of = [&](const std::vector<int>& powers) {
      std::vector<StateFactor> st;
      for (int col = 0; col < 2 * n; ++col) {
        if (powers[static_cast<size_t>(col)] == 0) continue;
        const model::StateRef s = model::state_ref(col, M, N);
        st.push_back({s.direction == model::Direction::Flap ? ModeDir::Flap : ModeDir::Lag, s.rate,
                      s.mode, powers[static_cast<size_t>(col)]});
      }
      return st;
    };
    for (const auto& s : m_.nonlinear) {
      const Coord e = coord(s.equation, M);
      add_slot(c, {SlotKind::Nonlinear, s.harmonic, e.dir, ModeDir::Flap, false}, {e.mode, -1},
               s.slot, states_of(s.powers));
    }
    for (const auto& s : m_.nonlinear_thrust) {
      add_slot(c, {SlotKind::NonlinearThrust, s.harmonic, ModeDir::Flap, ModeDir::Flap, false},
               {-1, -1}, s.slot, states_of(s.powers));
    }
    for (const auto& a : m_.absorbed) {
      const Coord e = coord(a.equation, M);
      const model::StateRef s = model::state_ref(a.state, M, N);
      const ModeDir d = s.direction == model::Direction::Flap ? ModeDir::Flap : ModeDir::Lag;
      Lab l = label(a.term);
      add(c, {SlotKind::Absorbed, 0, e.dir, d, s.rate}, {e.mode, s.mode}, l);
    }
    // drop terms that cancelled
    for (auto& [k, by_bound] : c) {
      for (auto& [b, terms] : by_bound) {
        for (auto it = terms.begin(); it != terms.end();) {
          it = it->second.coef.is_zero() ? terms.erase(it) : std::next(it);
        }
      }
    }
    return c;
  }

 private:
  const DerivedModel& m_;
};

// ----- patterns -------------------------------------------------------------------------------

// A pattern: a labelled term in variables, the directions of its variables, how many are bound.
struct Pattern {
  Lab lab;
  std::vector<ModeDir> vars;
  bool diagonal = false;
};

// Bound variables of a class for given bound values: 0 = equation, 1 = column (unless the
// column's mode is the equation's in the same direction: diagonal, the column is variable 0).
struct Binding {
  std::vector<ModeDir> dirs;  // of the bound variables
  std::vector<int> values;
  bool diagonal = false;
};
Binding binding(const ClassKey& k, Bound b) {
  Binding r;
  if (kind_has_eq(k.kind)) {
    r.dirs.push_back(k.eq);
    r.values.push_back(b.first);
  }
  if (kind_has_col(k.kind)) {
    if (kind_has_eq(k.kind) && k.col == k.eq && b.second == b.first) {
      r.diagonal = true;
    } else {
      r.dirs.push_back(k.col);
      r.values.push_back(b.second);
    }
  }
  return r;
}

// Every assignment of the free variables (modes 0..count-1 of their direction), with the bound
// ones fixed: calls f(values).
void assignments(const std::vector<ModeDir>& vars, const std::vector<int>& bound, int M, int N,
                 const std::function<void(const std::vector<int>&)>& f) {
  std::vector<int> v(vars.size(), 0);
  for (size_t j = 0; j < bound.size(); ++j) v[j] = bound[j];
  std::function<void(size_t)> rec = [&](size_t j) {
    if (j == vars.size()) {
      f(v);
      return;
    }
    const int count = vars[j] == ModeDir::Flap ? M : N;
    for (int m = 0; m < count; ++m) {
      v[j] = m;
      rec(j + 1);
    }
  };
  rec(bound.size());
}

// The concrete terms a pattern produces in the slot with the given bound values.
std::map<std::string, std::pair<numeric, Lab>> expand(const Pattern& p,
                                                      const std::vector<int>& bound, int M, int N) {
  std::map<std::string, std::pair<numeric, Lab>> out;
  assignments(p.vars, bound, M, N, [&](const std::vector<int>& v) {
    Lab t = substitute(p.lab, v);
    const std::string k = key(t);
    auto it = out.find(k);
    if (it == out.end()) {
      out.emplace(k, std::make_pair(p.lab.coef, t));
    } else {
      it->second.first += p.lab.coef;
    }
  });
  return out;
}

// Renumbers the free variables (those from `bound` on) to the permutation with the smallest key.
void canonical_vars(Pattern& p, size_t bound) {
  const size_t nfree = p.vars.size() - bound;
  if (nfree < 2) return;
  std::vector<int> perm(nfree);
  std::iota(perm.begin(), perm.end(), 0);
  std::string best;
  Pattern best_p = p;
  do {
    bool ok = true;
    for (size_t j = 0; j < nfree; ++j) {
      if (p.vars[bound + j] != p.vars[bound + static_cast<size_t>(perm[j])]) ok = false;
    }
    if (!ok) continue;
    std::vector<int> values(p.vars.size());
    for (size_t j = 0; j < bound; ++j) values[j] = static_cast<int>(j);
    for (size_t j = 0; j < nfree; ++j) values[bound + j] = static_cast<int>(bound) + perm[j];
    Lab t = substitute(p.lab, values);
    const std::string k = key(t);
    if (best.empty() || k < best) {
      best = k;
      best_p.lab = t;
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
  p = best_p;
}

// The pattern of a concrete term: bound values become the bound variables, every other
// distinct (direction, mode) a new variable.
Pattern generalize(const Lab& c, const Binding& b) {
  Pattern p;
  p.vars = b.dirs;
  p.diagonal = b.diagonal;
  std::map<std::pair<ModeDir, int>, int> var_of;
  for (size_t j = 0; j < b.dirs.size(); ++j) var_of[{b.dirs[j], b.values[j]}] = static_cast<int>(j);
  p.lab = c;
  for_each_mode(p.lab, [&](ModeDir d, int& m) {
    auto it = var_of.find({d, m});
    if (it == var_of.end()) {
      it = var_of.emplace(std::make_pair(d, m), static_cast<int>(p.vars.size())).first;
      p.vars.push_back(d);
    }
    m = it->second;
  });
  sort_lab(p.lab);
  canonical_vars(p, b.dirs.size());
  return p;
}

int distinct_modes(const Lab& c, const Binding& b) {
  std::vector<std::pair<ModeDir, int>> seen;
  for (size_t j = 0; j < b.dirs.size(); ++j) seen.emplace_back(b.dirs[j], b.values[j]);
  Lab t = c;
  for_each_mode(t, [&](ModeDir d, int& m) { seen.emplace_back(d, m); });
  std::sort(seen.begin(), seen.end());
  return static_cast<int>(std::unique(seen.begin(), seen.end()) - seen.begin());
}

// The patterns of one slot class: inclusion-exclusion over the concrete slot with distinct
// bound modes, then over the diagonal slot (same direction, equal modes).
std::vector<Pattern> extract_class(const ClassKey& k, const std::map<Bound, SlotTerms>& slots,
                                   int M, int N) {
  std::vector<Pattern> patterns;
  std::vector<Bound> reps;
  const bool eq = kind_has_eq(k.kind), col = kind_has_col(k.kind);
  if (eq && col && k.eq == k.col) {
    reps = {{0, 1}, {0, 0}};
  } else {
    reps = {{eq ? 0 : -1, col ? 0 : -1}};
  }
  for (const Bound& rep : reps) {
    const Binding b = binding(k, rep);
    auto found = slots.find(rep);
    if (found == slots.end()) continue;
    std::map<std::string, numeric> predicted;
    for (const Pattern& p : patterns) {
      // earlier (non-diagonal) patterns evaluated at this slot's bound values
      std::vector<int> bv = b.values;
      if (b.diagonal) bv.push_back(b.values[0]);
      for (const auto& [kk, v] : expand(p, bv, M, N)) predicted[kk] += v.first;
    }
    std::vector<const std::pair<const std::string, Lab>*> order;
    for (const auto& e : found->second) order.push_back(&e);
    std::stable_sort(order.begin(), order.end(), [&](const auto* a, const auto* c) {
      return distinct_modes(a->second, b) > distinct_modes(c->second, b);
    });
    for (const auto* e : order) {
      const numeric residual = e->second.coef - predicted[e->first];
      if (residual.is_zero()) continue;
      Pattern p = generalize(e->second, b);
      p.lab.coef = 1;
      const auto ex = expand(p, b.values, M, N);
      const numeric mult = ex.at(e->first).first;
      p.lab.coef = residual / mult;
      for (const auto& [kk, v] : ex) predicted[kk] += v.first * p.lab.coef;
      patterns.push_back(p);
    }
  }
  return patterns;
}

// What the patterns of a class produce in the concrete slot with bound values b.
std::map<std::string, std::pair<numeric, Lab>> evaluate(const ClassKey& k,
                                                        const std::vector<Pattern>& patterns,
                                                        Bound bound, int M, int N) {
  const Binding b = binding(k, bound);
  std::map<std::string, std::pair<numeric, Lab>> out;
  for (const Pattern& p : patterns) {
    if (p.diagonal && !b.diagonal) continue;
    std::vector<int> bv = b.values;
    if (b.diagonal && !p.diagonal) bv.push_back(b.values[0]);
    for (const auto& [kk, v] : expand(p, bv, M, N)) {
      auto it = out.find(kk);
      if (it == out.end()) {
        out.emplace(kk, v);
      } else {
        it->second.first += v.first;
      }
    }
  }
  for (auto it = out.begin(); it != out.end();) {
    it = it->second.first.is_zero() ? out.erase(it) : std::next(it);
  }
  return out;
}

std::vector<Bound> bounds_of(const ClassKey& k, int M, int N) {
  const int ce = k.eq == ModeDir::Flap ? M : N, cc = k.col == ModeDir::Flap ? M : N;
  std::vector<Bound> out;
  const bool eq = kind_has_eq(k.kind), col = kind_has_col(k.kind);
  for (int i = 0; i < (eq ? ce : 1); ++i)
    for (int j = 0; j < (col ? cc : 1); ++j) out.emplace_back(eq ? i : -1, col ? j : -1);
  return out;
}

std::string class_text(const ClassKey& k, Bound b) {
  std::ostringstream os;
  os << static_cast<int>(k.kind) << " h" << k.harmonic << " " << static_cast<int>(k.eq) << ":"
     << b.first << " " << static_cast<int>(k.col) << (k.rate ? "'" : "") << ":" << b.second;
  return os.str();
}

std::string coef_text(const numeric& c) {
  std::ostringstream os;
  os << c;
  return os.str();
}

// ----- from patterns to the GenericModel ------------------------------------------------------

const char kTermLetters[] = "ijklpqrstuvw";
const char kTemplateLetters[] = "abcdefgh";

std::string factor_text(const TemplateFactor& f, const char* letters) {
  switch (f.kind) {
    case FactorKind::Eta:
      return std::string("eta_") + letters[f.var];
    case FactorKind::EtaPrime:
      return std::string("eta_") + letters[f.var] + "'";
    case FactorKind::Gamma:
      return std::string("gamma_") + letters[f.var];
    case FactorKind::GammaPrime:
      return std::string("gamma_") + letters[f.var] + "'";
    case FactorKind::X0:
      return "x0";
    case FactorKind::Arm:
      return "(x0+e1/l)";
    case FactorKind::Twist:
      return "tw";
  }
  return "";
}
std::string factor_id(const TemplateFactor& f) {
  switch (f.kind) {
    case FactorKind::Eta:
      return std::string("eta") + kTemplateLetters[f.var];
    case FactorKind::EtaPrime:
      return std::string("deta") + kTemplateLetters[f.var];
    case FactorKind::Gamma:
      return std::string("gam") + kTemplateLetters[f.var];
    case FactorKind::GammaPrime:
      return std::string("dgam") + kTemplateLetters[f.var];
    case FactorKind::X0:
      return "x0";
    case FactorKind::Arm:
      return "arm";
    case FactorKind::Twist:
      return "tw";
  }
  return "";
}

void name_template(IntegralTemplate& t) {
  std::ostringstream name, id;
  if (t.ref == IntegralRef::Aero) {
    if (t.x_power > 0) {
      name << (t.x_power == 1 ? "x" : "x^" + std::to_string(t.x_power));
      id << "x" << t.x_power;
    }
    // the twist, a weight on the span like x^p, is written next to it: "x^2 tw eta_a"
    for (const bool twist : {true, false}) {
      for (const auto& f : t.factors) {
        if ((f.kind == FactorKind::Twist) != twist) continue;
        name << (name.tellp() > 0 ? " " : "") << factor_text(f, kTemplateLetters);
        id << (id.tellp() > 0 ? "_" : "") << factor_id(f);
      }
    }
    t.name = name.str().empty() ? "1" : name.str();
    t.ident = id.str().empty() ? "one" : id.str();
    return;
  }
  if (t.outer_mass > 0) {
    name << "m";
    id << "m";
  }
  for (const auto& f : t.factors) {
    name << (name.tellp() > 0 ? " " : "") << factor_text(f, kTemplateLetters);
    id << (id.tellp() > 0 ? "_" : "") << factor_id(f);
  }
  if (t.inner != InnerKind::None) {
    name << (t.inner == InnerKind::Tail ? " [int_x^1 " : " [int_0^x ");
    id << (t.inner == InnerKind::Tail ? "__tail" : "__head");
    bool first = true;
    if (t.inner_mass > 0) {
      name << "m";
      id << "_m";
      first = false;
    }
    for (const auto& f : t.inner_factors) {
      name << (first ? "" : " ") << factor_text(f, kTemplateLetters);
      id << "_" << factor_id(f);
      first = false;
    }
    name << " dx1]";
  }
  t.name = name.str();
  t.ident = id.str();
}

// Replaces the trailing mode digits of each '/'-separated paper name: digit d -> letters[d-1].
std::string letter_name(const std::string& concrete, const char* letters,
                        const std::vector<int>& digit_to_index) {
  std::stringstream in(concrete);
  std::string part, out;
  while (std::getline(in, part, '/')) {
    size_t e = part.size();
    while (e > 0 && std::isdigit(static_cast<unsigned char>(part[e - 1]))) --e;
    std::string s = part.substr(0, e);
    bool ok = true;
    for (size_t j = e; j < part.size(); ++j) {
      const int d = part[j] - '1';
      if (d < 0 || d >= static_cast<int>(digit_to_index.size()) || digit_to_index[d] < 0) {
        ok = false;
        break;
      }
      s += letters[digit_to_index[static_cast<size_t>(d)]];
    }
    if (!ok) continue;
    out += (out.empty() ? "" : "/") + s;
  }
  return out;
}

class Builder {
 public:
  explicit Builder(GenericModel& g) : g_(g) {}

  GenericTerm term(const ClassKey& k, const Pattern& p) {
    GenericTerm t;
    t.coef = p.lab.coef;
    t.vars = p.vars;
    t.diagonal = p.diagonal;
    t.scalars = p.lab.scalars;
    t.indexed = p.lab.indexed;
    t.states = p.lab.states;
    t.eps_order = p.lab.eps;
    t.origin = p.lab.origin;
    t.radial_flow = p.lab.radial;
    if (p.lab.ref != IntegralRef::None) {
      place_integral(p.lab, t);
      t.paper_name = paper_name(k, p);
    }
    return t;
  }

 private:
  // The term's integral as a template (its variables renumbered canonically) and arguments.
  void place_integral(const Lab& l, GenericTerm& t) {
    std::vector<int> used;  // term variables in the integral, in order of appearance
    auto note = [&](const std::vector<TemplateFactor>& f) {
      for (const auto& x : f)
        if (x.var >= 0 && std::find(used.begin(), used.end(), x.var) == used.end())
          used.push_back(x.var);
    };
    note(l.outer);
    note(l.inner_f);
    std::sort(used.begin(), used.end());
    std::string best;
    IntegralTemplate best_t;
    std::vector<int> best_args;
    std::vector<int> perm(used.size());
    std::iota(perm.begin(), perm.end(), 0);
    do {
      // template variable perm[j] <- term variable used[j]
      bool ok = true;
      std::vector<int> args(used.size());
      for (size_t j = 0; j < used.size(); ++j) args[static_cast<size_t>(perm[j])] = used[j];
      IntegralTemplate tp;
      tp.ref = l.ref;
      tp.x_power = l.x_power;
      tp.outer_mass = l.outer_mass;
      tp.inner = l.inner;
      tp.inner_mass = l.inner_mass;
      auto map_f = [&](const std::vector<TemplateFactor>& f) {
        std::vector<TemplateFactor> out;
        for (const auto& x : f) {
          int v = -1;
          if (x.var >= 0) {
            const auto it = std::find(used.begin(), used.end(), x.var);
            v = perm[static_cast<size_t>(it - used.begin())];
          }
          out.push_back({x.kind, v});
        }
        std::sort(out.begin(), out.end());
        return out;
      };
      tp.factors = map_f(l.outer);
      tp.inner_factors = map_f(l.inner_f);
      tp.vars.resize(used.size());
      for (size_t j = 0; j < used.size(); ++j) {
        tp.vars[static_cast<size_t>(perm[j])] = t.vars[static_cast<size_t>(used[j])];
      }
      // variables numbered flap before lag keeps the letters readable; the key decides
      for (size_t j = 0; j + 1 < tp.vars.size(); ++j) {
        if (tp.vars[j] > tp.vars[j + 1]) ok = false;
      }
      if (!ok) continue;
      const std::string k = tp.key();
      if (best.empty() || k < best) {
        best = k;
        best_t = tp;
        best_args = args;
      }
    } while (std::next_permutation(perm.begin(), perm.end()));
    auto it = index_.find(best);
    if (it == index_.end()) {
      name_template(best_t);
      it = index_.emplace(best, static_cast<int>(g_.integrals.size())).first;
      g_.integrals.push_back(best_t);
    }
    t.integral = it->second;
    t.integral_args = best_args;
  }

  // Role-aware paper name: the concrete name with every variable a distinct mode, its digits
  // turned back into the term's letters.
  std::string paper_name(const ClassKey& k, const Pattern& p) const {
    if (!kind_has_eq(k.kind)) return "";
    std::vector<int> values(p.vars.size());
    std::iota(values.begin(), values.end(), 0);
    Lab c = substitute(p.lab, values);
    const bool flap_eq = k.eq == ModeDir::Flap;
    std::vector<ShapeFactor> outer, inner;
    for (const auto& f : c.outer) outer.push_back({f.kind, std::max(f.var, 0)});
    for (const auto& f : c.inner_f) inner.push_back({f.kind, std::max(f.var, 0)});
    std::string name;
    if (c.ref == IntegralRef::Aero) {
      name = paper_aero_name(flap_eq, 0, AeroIntegralKey{c.x_power, outer});
    } else if (c.ref == IntegralRef::Structural) {
      name = paper_structural_name(
          flap_eq, 0, StructuralIntegralKey{c.outer_mass, outer, c.inner, c.inner_mass, inner});
    }
    std::vector<int> digit_to_index(values.size());
    std::iota(digit_to_index.begin(), digit_to_index.end(), 0);
    return letter_name(name, kTermLetters, digit_to_index);
  }

  GenericModel& g_;
  std::map<std::string, int> index_;
};

// Template paper names: the term names whose letters all belong to the integral, in template
// letters.
void template_paper_names(GenericModel& g) {
  for (const auto& s : g.slots) {
    for (const auto& t : s.terms) {
      if (t.integral < 0 || t.paper_name.empty()) continue;
      std::vector<int> to_template(t.vars.size(), -1);
      for (size_t a = 0; a < t.integral_args.size(); ++a)
        to_template[static_cast<size_t>(t.integral_args[a])] = static_cast<int>(a);
      std::stringstream in(t.paper_name);
      std::string part;
      IntegralTemplate& tp = g.integrals[static_cast<size_t>(t.integral)];
      while (std::getline(in, part, '/')) {
        size_t e = part.size();
        while (e > 0 && std::islower(static_cast<unsigned char>(part[e - 1])) &&
               std::string(kTermLetters).find(part[e - 1]) != std::string::npos)
          --e;
        std::string sub = part.substr(0, e);
        bool ok = e < part.size() || part.find('_') == std::string::npos;
        for (size_t j = e; j < part.size() && ok; ++j) {
          const int v = static_cast<int>(std::string(kTermLetters).find(part[j]));
          if (to_template[static_cast<size_t>(v)] < 0)
            ok = false;
          else
            sub += kTemplateLetters[to_template[static_cast<size_t>(v)]];
        }
        if (!ok) continue;
        if (("/" + tp.paper_name + "/").find("/" + sub + "/") == std::string::npos) {
          tp.paper_name += (tp.paper_name.empty() ? "" : "/") + sub;
        }
      }
    }
  }
  for (const auto& s : g.slots) {
    if (s.kind != SlotKind::Absorbed) continue;
    for (const auto& t : s.terms) {
      if (t.integral >= 0 && g.integrals[static_cast<size_t>(t.integral)].paper_name.empty())
        g.integrals[static_cast<size_t>(t.integral)].paper_name =
            "centrifugal stiffness (absorbed)";
    }
  }
}

std::string lab_text(const ClassKey& k, Bound b, const numeric& c, const std::string& key) {
  return class_text(k, b) + " | " + key + " | " + coef_text(c);
}

}  // namespace

std::string IntegralTemplate::key() const {
  std::ostringstream os;
  os << static_cast<int>(ref) << " v";
  for (auto d : vars) os << static_cast<int>(d);
  os << " x" << x_power << " m" << outer_mass << " [" << factors_text(factors) << "] "
     << static_cast<int>(inner) << " mi" << inner_mass << " [" << factors_text(inner_factors)
     << "]";
  return os.str();
}

bool GenericSlot::has_eq() const { return kind_has_eq(kind); }
bool GenericSlot::has_col() const { return kind_has_col(kind); }

GenericModel extract_generic_from(const DerivedModel& m) {
  const Concrete concrete = Collector(m).collect();
  GenericModel g;
  g.spec = m.spec;
  g.H = m.H;
  g.H_nonlinear = m.H_nonlinear;
  g.P = std::min(m.M, m.N);
  for (const auto& s : m.scalars) {
    bool indexed = false;
    for (const auto& fam : families())
      if (s.name.rfind(std::string(fam.name) + "_", 0) == 0) indexed = true;
    if (!indexed) g.scalar_names.push_back(s.name);
  }
  Builder builder(g);
  for (const auto& [k, slots] : concrete) {
    const std::vector<Pattern> patterns = extract_class(k, slots, m.M, m.N);
    // The patterns must reproduce every concrete slot of the class exactly.
    for (const Bound& b : bounds_of(k, m.M, m.N)) {
      const auto got = evaluate(k, patterns, b, m.M, m.N);
      static const SlotTerms kEmpty;
      const auto want_it = slots.find(b);
      const SlotTerms& want = want_it == slots.end() ? kEmpty : want_it->second;
      bool same = got.size() == want.size();
      for (const auto& [kk, l] : want) {
        const auto it = got.find(kk);
        if (it == got.end() || it->second.first != l.coef) same = false;
      }
      if (!same) {
        if (std::getenv("FLAPLAG_GENERIC_DEBUG")) {
          for (const auto& [kk, l] : want) {
            const auto it = got.find(kk);
            if (it == got.end() || it->second.first != l.coef)
              fprintf(stderr, "want %s : %s got %s\n", kk.c_str(), coef_text(l.coef).c_str(),
                      it == got.end() ? "-" : coef_text(it->second.first).c_str());
          }
          for (const auto& [kk, v] : got)
            if (!want.count(kk))
              fprintf(stderr, "extra %s : %s\n", kk.c_str(), coef_text(v.first).c_str());
        }
        throw std::logic_error("generic extraction does not reproduce slot " + class_text(k, b) +
                               " of the " + std::to_string(m.M) + "x" + std::to_string(m.N) +
                               " derivation");
      }
    }
    if (patterns.empty()) continue;
    GenericSlot slot;
    slot.kind = k.kind;
    slot.harmonic = k.harmonic;
    slot.eq = k.eq;
    slot.col = k.col;
    slot.rate = k.rate;
    for (const Pattern& p : patterns) slot.terms.push_back(builder.term(k, p));
    g.slots.push_back(slot);
  }
  template_paper_names(g);
  return g;
}

GenericModel extract_generic(const OrderingSpec& spec, int P) {
  auto at = [&](int p) {
    OrderingSpec s = spec;
    s.flap_modes = p;
    s.lag_modes = p;
    s.cyclic_pitch = true;
    s.nonlinear = true;
    return extract_generic_from(derive_model(s));
  };
  GenericModel g = at(P);
  const GenericModel bigger = at(P + 1);
  if (g.serialize() != bigger.serialize()) {
    throw std::logic_error("generic extraction of " + spec.name + " is not saturated at " +
                           std::to_string(P) + " modes per direction");
  }
  g.spec = spec;
  return g;
}

std::string GenericModel::serialize() const {
  std::ostringstream os;
  os << "H " << H << " Hnl " << H_nonlinear << "\n";
  for (const auto& s : scalar_names) os << "scalar " << s << "\n";
  for (size_t j = 0; j < integrals.size(); ++j)
    os << "integral " << j << " " << integrals[j].key() << " " << integrals[j].paper_name << "\n";
  for (const auto& s : slots) {
    os << "slot " << static_cast<int>(s.kind) << " h" << s.harmonic << " " << static_cast<int>(s.eq)
       << " " << static_cast<int>(s.col) << (s.rate ? "'" : "") << "\n";
    for (const auto& t : s.terms) {
      os << "  " << t.coef << " v";
      for (auto d : t.vars) os << static_cast<int>(d);
      os << (t.diagonal ? " diag" : "") << " |";
      for (const auto& [n, p] : t.scalars) os << " " << n << "^" << p;
      for (const auto& x : t.indexed) {
        os << " " << x.family << "(";
        for (int a : x.args) os << a << ",";
        os << ")^" << x.power;
      }
      os << " | I" << t.integral << "(";
      for (int a : t.integral_args) os << a << ",";
      os << ") |";
      for (const auto& st : t.states)
        os << " " << static_cast<int>(st.dir) << (st.rate ? "'" : "") << st.var << "^" << st.power;
      os << " | " << t.eps_order << " " << t.origin << " " << t.radial_flow << " " << t.paper_name
         << "\n";
    }
  }
  return os.str();
}

std::vector<std::string> concrete_terms(const DerivedModel& m) {
  std::vector<std::string> out;
  for (const auto& [k, slots] : Collector(m).collect()) {
    for (const auto& [b, terms] : slots) {
      for (const auto& [kk, l] : terms) out.push_back(lab_text(k, b, l.coef, kk));
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

int index_among_kind(const GenericModel& g, int integral) {
  const IntegralRef ref = g.integrals[static_cast<size_t>(integral)].ref;
  int idx = 0;
  for (int j = 0; j < integral; ++j)
    if (g.integrals[static_cast<size_t>(j)].ref == ref) ++idx;
  return idx;
}

int linear_aero_templates(const GenericModel& g) {
  int count = 0;
  for (const GenericSlot& s : g.slots) {
    const bool linear = s.kind == SlotKind::Mass || s.kind == SlotKind::Force ||
                        s.kind == SlotKind::Forcing || s.kind == SlotKind::HoverStiffness ||
                        s.kind == SlotKind::HoverLoad;
    if (!linear) continue;
    for (const GenericTerm& t : s.terms) {
      if (t.integral < 0 || g.integrals[static_cast<size_t>(t.integral)].ref != IntegralRef::Aero)
        continue;
      count = std::max(count, index_among_kind(g, t.integral) + 1);
    }
  }
  return count;
}

std::vector<std::string> expand_generic(const GenericModel& g, int M, int N) {
  std::vector<std::string> out;
  for (const auto& s : g.slots) {
    const ClassKey k{s.kind, s.harmonic, s.eq, s.col, s.rate};
    std::vector<Pattern> patterns;
    for (const auto& t : s.terms) {
      Pattern p;
      p.vars = t.vars;
      p.diagonal = t.diagonal;
      p.lab.coef = t.coef;
      p.lab.scalars = t.scalars;
      p.lab.indexed = t.indexed;
      p.lab.states = t.states;
      p.lab.eps = t.eps_order;
      p.lab.origin = t.origin;
      p.lab.radial = t.radial_flow;
      if (t.integral >= 0) {
        const IntegralTemplate& tp = g.integrals[static_cast<size_t>(t.integral)];
        p.lab.ref = tp.ref;
        p.lab.x_power = tp.x_power;
        p.lab.outer_mass = tp.outer_mass;
        p.lab.inner = tp.inner;
        p.lab.inner_mass = tp.inner_mass;
        auto map_f = [&](const std::vector<TemplateFactor>& f) {
          std::vector<TemplateFactor> o;
          for (const auto& x : f)
            o.push_back({x.kind, x.var < 0 ? -1 : t.integral_args[static_cast<size_t>(x.var)]});
          return o;
        };
        p.lab.outer = map_f(tp.factors);
        p.lab.inner_f = map_f(tp.inner_factors);
      }
      sort_lab(p.lab);
      patterns.push_back(p);
    }
    for (const Bound& b : bounds_of(k, M, N)) {
      for (const auto& [kk, v] : evaluate(k, patterns, b, M, N))
        out.push_back(lab_text(k, b, v.first, kk));
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

FamilyInput family_input(const std::string& family) {
  const Family* f = family_of(family);
  if (f == nullptr) throw std::logic_error("no model input is named " + family);
  return {f->array, f->dirs};
}

}  // namespace flaplag::derive
