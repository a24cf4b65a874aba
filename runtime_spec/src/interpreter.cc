// flaplag — the interpreter of a model family (interpreter.h).  Every loop below mirrors one of
// emit_family.cc: keep them in step.
#include "interpreter.h"

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>

namespace flaplag::spec {

namespace {

using derive::ModeDir;
using derive::SlotKind;
using model::CoefficientInputs;

// The double of an integer as the compiler reads the literal "<integer>.0" (correctly rounded).
double integer_double(const GiNaC::numeric& q) {
  std::ostringstream os;
  os << q;
  return std::strtod(os.str().c_str(), nullptr);
}

double CoefficientInputs::*plain_scalar(const std::string& name) {
  if (name == "lock") return &CoefficientInputs::lock;
  if (name == "lr") return &CoefficientInputs::lr;
  if (name == "theta") return &CoefficientInputs::theta;
  if (name == "inflow") return &CoefficientInputs::inflow;
  if (name == "precone") return &CoefficientInputs::precone;
  if (name == "droop") return &CoefficientInputs::droop;
  if (name == "cdo_a") return &CoefficientInputs::cdo_a;
  if (name == "mu") return &CoefficientInputs::mu;
  if (name == "theta1c") return &CoefficientInputs::theta1c;
  if (name == "theta1s") return &CoefficientInputs::theta1s;
  throw std::logic_error("the run-time model has no input named " + name);
}

model::Factor factor_kind(derive::FactorKind k) { return static_cast<model::Factor>(k); }

model::Direction direction(ModeDir d) {
  return d == ModeDir::Flap ? model::Direction::Flap : model::Direction::Lag;
}

bool has_eq(SlotKind k) {
  return k != SlotKind::ThrustForce && k != SlotKind::ThrustForcing &&
         k != SlotKind::NonlinearThrust;
}
bool has_col(SlotKind k) {
  return k == SlotKind::Mass || k == SlotKind::Force || k == SlotKind::HoverStiffness ||
         k == SlotKind::ThrustForce || k == SlotKind::Absorbed;
}

}  // namespace

struct Program::Context {
  Context(const Program& p, const CoefficientInputs& inputs)
      : in(inputs),
        M(inputs.modes[model::index(model::Direction::Flap)]),
        N(inputs.modes[model::index(model::Direction::Lag)]),
        A(p.aero_.data(), static_cast<int>(p.aero_.size()), inputs.aero, M, N),
        S(p.structural_.data(), static_cast<int>(p.structural_.size()), inputs.structural, M, N) {}
  const CoefficientInputs& in;
  int M, N;
  model::TemplateTensors A, S;
  int v[16] = {};  // values of the term variables
  int count(ModeDir d) const { return d == ModeDir::Flap ? M : N; }
  int row(ModeDir d, int k) const { return d == ModeDir::Flap ? k : M + k; }
  int col(ModeDir d, bool rate, int k) const {
    if (d == ModeDir::Flap) return rate ? k : M + k;
    return rate ? 2 * M + k : 2 * M + N + k;
  }
};

Program::Program(const derive::GenericModel& g) : H_(g.H), H_nonlinear_(g.H_nonlinear) {
  std::vector<int> index_of_kind(g.integrals.size(), 0);
  for (size_t j = 0; j < g.integrals.size(); ++j) {
    const derive::IntegralTemplate& t = g.integrals[j];
    auto& list = t.ref == derive::IntegralRef::Aero ? aero_ : structural_;
    index_of_kind[j] = static_cast<int>(list.size());
    if (t.vars.size() > static_cast<size_t>(model::kMaxFactors) ||
        t.factors.size() > static_cast<size_t>(model::kMaxFactors) ||
        t.inner_factors.size() > static_cast<size_t>(model::kMaxFactors))
      throw std::logic_error("an integrand has more than model::kMaxFactors spanwise factors");
    model::IntegralTemplate m{};
    texts_.push_back(t.name);
    m.name = texts_.back().c_str();
    texts_.push_back(t.ident);
    m.ident = texts_.back().c_str();
    texts_.push_back(t.paper_name);
    m.paper_name = texts_.back().c_str();
    m.n_vars = static_cast<int>(t.vars.size());
    for (size_t v = 0; v < t.vars.size(); ++v) m.var_dirs[v] = direction(t.vars[v]);
    m.x_power = t.x_power;
    m.outer_mass = t.outer_mass;
    m.n_factors = static_cast<int>(t.factors.size());
    for (size_t k = 0; k < t.factors.size(); ++k)
      m.factors[k] = {factor_kind(t.factors[k].kind), std::max(t.factors[k].var, 0)};
    m.inner = static_cast<model::Inner>(t.inner);
    m.inner_mass = t.inner_mass;
    m.n_inner = static_cast<int>(t.inner_factors.size());
    for (size_t k = 0; k < t.inner_factors.size(); ++k)
      m.inner_factors[k] = {factor_kind(t.inner_factors[k].kind),
                            std::max(t.inner_factors[k].var, 0)};
    list.push_back(m);
  }
  for (const derive::GenericSlot& s : g.slots) {
    if (s.kind == SlotKind::Absorbed) continue;  // the audit report's only
    Slot out{s.kind, s.harmonic, s.eq, s.col, s.rate, {}, has_eq(s.kind), has_col(s.kind)};
    for (const derive::GenericTerm& t : s.terms) {
      if (t.vars.size() > 16) throw std::logic_error("a term has more than 16 mode variables");
      Term r;
      GiNaC::numeric c = t.coef;
      r.negative = c < 0;
      if (r.negative) c = -c;
      r.has_coef = c != 1;
      // "(numer.0 / denom.0)"
      r.coef = c.denom() == 1 ? integer_double(c.numer())
                              : integer_double(c.numer()) / integer_double(c.denom());
      for (const auto& [name, power] : t.scalars) {
        for (int p = 0; p < power; ++p) {
          Factor f{Factor::Kind::Scalar};
          f.scalar = plain_scalar(name);
          r.factors.push_back(f);
        }
      }
      r.n_scalars = r.factors.size();
      for (const derive::IndexedScalar& x : t.indexed) {
        Factor f = indexed_factor(x.family);
        f.n_args = static_cast<int>(x.args.size());
        for (size_t a = 0; a < x.args.size() && a < 2; ++a) f.args[a] = x.args[a];
        for (int p = 0; p < x.power; ++p) r.factors.push_back(f);
      }
      if (t.integral >= 0) {
        const derive::IntegralTemplate& tp = g.integrals[static_cast<size_t>(t.integral)];
        Factor f{tp.ref == derive::IntegralRef::Aero ? Factor::Kind::Aero
                                                     : Factor::Kind::Structural};
        f.index = index_of_kind[static_cast<size_t>(t.integral)];
        f.n_args = static_cast<int>(t.integral_args.size());
        for (size_t a = 0; a < t.integral_args.size(); ++a) f.args[a] = t.integral_args[a];
        r.factors.push_back(f);
      }
      r.vars = t.vars;
      r.diagonal = t.diagonal;
      for (const derive::StateFactor& st : t.states)
        r.states.push_back({st.dir, st.rate, st.var, st.power});
      out.terms.push_back(std::move(r));
    }
    slots_.push_back(std::move(out));
  }
}

Program::Factor Program::indexed_factor(const std::string& family) {
  const derive::FamilyInput input = derive::family_input(family);
  Factor f{Factor::Kind::Indexed};
  if (input.array == "q0") {
    f.input = Factor::Input::Q0;
  } else if (input.array == "omega") {
    f.input = Factor::Input::Omega;
  } else if (input.array == "damping") {
    f.input = Factor::Input::Damping;
  } else if (input.array == "elastic") {
    f.input = Factor::Input::Elastic;
  } else {
    throw std::logic_error("the run-time model has no input named " + input.array);
  }
  for (std::size_t d = 0; d < input.dirs.size() && d < 2; ++d)
    f.dirs[d] = model::index(direction(input.dirs[d]));
  f.second_flap = input.dirs.size() == 2 && input.dirs[1] == ModeDir::Flap;
  return f;
}

const double* Program::indexed_array(const model::CoefficientInputs& in, const Factor& f) {
  switch (f.input) {
    case Factor::Input::Q0:
      return in.q0[f.dirs[0]];
    case Factor::Input::Omega:
      return in.omega[f.dirs[0]];
    case Factor::Input::Damping:
      return in.damping[f.dirs[0]];
    case Factor::Input::Elastic:
      return in.elastic[f.dirs[0]][f.dirs[1]];
  }
  return nullptr;
}

// The emitted product: [coefficient] * scalars * indexed * integral, left to right, the sign on
// the first factor (rounding is symmetric: -(a*b) == (-a)*b).
Program::Partial Program::prefix(const Term& t, const Context& c) {
  Partial p{t.has_coef ? t.coef : 1.0, t.has_coef};
  for (std::size_t k = 0; k < t.n_scalars; ++k) {
    const double x = c.in.*t.factors[k].scalar;
    p.value = p.started ? p.value * x : x;
    p.started = true;
  }
  return p;
}

double Program::value(const Term& t, const Context& c, Partial pre) const {
  double p = pre.value;
  bool first = !pre.started;
  auto times = [&](double x) {
    p = first ? x : p * x;
    first = false;
  };
  for (std::size_t k = t.n_scalars; k < t.factors.size(); ++k) {
    const Factor& f = t.factors[k];
    switch (f.kind) {
      case Factor::Kind::Scalar:
        times(c.in.*f.scalar);
        break;
      case Factor::Kind::Indexed: {
        const double* a = indexed_array(c.in, f);
        const int i = c.v[f.args[0]];
        times(f.n_args == 1 ? a[i] : a[i * (f.second_flap ? c.M : c.N) + c.v[f.args[1]]]);
        break;
      }
      case Factor::Kind::Aero:
      case Factor::Kind::Structural: {
        const model::TemplateTensors& T = f.kind == Factor::Kind::Aero ? c.A : c.S;
        int a[model::kMaxFactors] = {0, 0, 0, 0};
        for (int arg = 0; arg < f.n_args; ++arg) a[arg] = c.v[f.args[arg]];
        times(T(f.index, a[0], a[1], a[2], a[3]));
        break;
      }
    }
  }
  return t.negative ? -p : p;
}

template <class F>
void Program::for_free(const Term& t, int first, Context& c, F f) {
  const int n = static_cast<int>(t.vars.size());
  if (first >= n) {
    f();
    return;
  }
  const int count = c.count(t.vars[static_cast<size_t>(first)]);
  for (int k = 0; k < count; ++k) {
    c.v[first] = k;
    for_free(t, first + 1, c, f);
  }
}

template <class Target>
void Program::linear(SlotKind kind, Context& c, Target target) const {
  for (const Slot& s : slots_) {
    if (s.kind != kind) continue;
    bool any = false, any_diag = false;
    for (const Term& t : s.terms) (t.diagonal ? any_diag : any) = true;
    auto sum = [&](bool diagonal) {
      double v = 0.0;
      for (const Term& t : s.terms) {
        if (t.diagonal != diagonal) continue;
        const int bound = (s.has_eq ? 1 : 0) + (s.has_col && !t.diagonal ? 1 : 0);
        const Partial pre = prefix(t, c);
        for_free(t, bound, c, [&] { v += value(t, c, pre); });
      }
      return v;
    };
    if (any) {
      const int ni = s.has_eq ? c.count(s.eq) : 1;
      const int nj = s.has_col ? c.count(s.col) : 1;
      for (int i = 0; i < ni; ++i) {
        for (int j = 0; j < nj; ++j) {
          // the bound variables: the equation's mode, then the column's
          int b = 0;
          if (s.has_eq) c.v[b++] = i;
          if (s.has_col) c.v[b++] = j;
          const double v = sum(false);
          target(s, s.has_eq ? i : -1, s.has_col ? j : -1) += v;
        }
      }
    }
    if (any_diag) {
      for (int i = 0; i < c.count(s.eq); ++i) {
        c.v[0] = i;
        const double v = sum(true);
        target(s, i, i) += v;
      }
    }
  }
}

void Program::mass(const CoefficientInputs& in, double* out) const {
  Context c(*this, in);
  const int n = c.M + c.N;
  std::fill(out, out + n * n, 0.0);
  linear(SlotKind::Mass, c, [&](const Slot& s, int i, int j) -> double& {
    return out[c.row(s.eq, i) * n + c.row(s.col, j)];
  });
}

void Program::coefficients(const CoefficientInputs& in,
                           const model::CoefficientOutputs& out) const {
  Context c(*this, in);
  const int n = c.M + c.N;
  std::fill(out.force, out.force + H_ * n * 2 * n, 0.0);
  std::fill(out.forcing, out.forcing + H_ * n, 0.0);
  linear(SlotKind::Force, c, [&](const Slot& s, int i, int j) -> double& {
    return out.force[(s.harmonic * n + c.row(s.eq, i)) * 2 * n + c.col(s.col, s.rate, j)];
  });
  linear(SlotKind::Forcing, c, [&](const Slot& s, int i, int) -> double& {
    return out.forcing[s.harmonic * n + c.row(s.eq, i)];
  });
}

void Program::equilibrium(const CoefficientInputs& in, const model::EquilibriumOutputs& out) const {
  Context c(*this, in);
  const int n = c.M + c.N;
  std::fill(out.S, out.S + n * n, 0.0);
  std::fill(out.c, out.c + n, 0.0);
  linear(SlotKind::HoverStiffness, c, [&](const Slot& s, int i, int j) -> double& {
    return out.S[c.row(s.eq, i) * n + c.row(s.col, j)];
  });
  linear(SlotKind::HoverLoad, c,
         [&](const Slot& s, int i, int) -> double& { return out.c[c.row(s.eq, i)]; });
}

void Program::thrust(const CoefficientInputs& in, const model::CoefficientOutputs& out) const {
  Context c(*this, in);
  const int n = c.M + c.N;
  std::fill(out.force, out.force + H_ * 2 * n, 0.0);
  std::fill(out.forcing, out.forcing + H_, 0.0);
  // no equation: the column's mode is the slot's first variable
  linear(SlotKind::ThrustForce, c, [&](const Slot& s, int, int j) -> double& {
    return out.force[s.harmonic * 2 * n + c.col(s.col, s.rate, j)];
  });
  linear(SlotKind::ThrustForcing, c,
         [&](const Slot& s, int, int) -> double& { return out.forcing[s.harmonic]; });
}

void Program::polynomial(SlotKind kind, const CoefficientInputs& in, const double* y,
                         const model::NonlinearOutputs& out) const {
  Context c(*this, in);
  const bool thrust = kind == SlotKind::NonlinearThrust;
  const int n = c.M + c.N;
  const int rows = thrust ? 1 : n;
  std::fill(out.force, out.force + H_nonlinear_ * rows, 0.0);
  std::fill(out.jacobian, out.jacobian + H_nonlinear_ * rows * 2 * n, 0.0);
  for (const Slot& s : slots_) {
    if (s.kind != kind) continue;
    const int ni = thrust ? 1 : c.count(s.eq);
    for (int i = 0; i < ni; ++i) {
      const int row = thrust ? 0 : c.row(s.eq, i);
      double* f = out.force + s.harmonic * rows + row;
      double* jac = out.jacobian + (s.harmonic * rows + row) * 2 * n;
      if (!thrust) c.v[0] = i;
      for (const Term& t : s.terms) {
        const Partial pre = prefix(t, c);
        for_free(t, thrust ? 0 : 1, c, [&] {
          const double k = value(t, c, pre);
          auto y_of = [&](const State& st) { return y[c.col(st.dir, st.rate, c.v[st.var])]; };
          double prod = k;
          for (const State& st : t.states)
            for (int p = 0; p < st.power; ++p) prod = prod * y_of(st);
          *f += prod;
          for (size_t a = 0; a < t.states.size(); ++a) {
            const State& st = t.states[a];
            double d = st.power > 1 ? static_cast<double>(st.power) * k : k;
            for (size_t b = 0; b < t.states.size(); ++b) {
              const int p = t.states[b].power - (b == a ? 1 : 0);
              for (int q = 0; q < p; ++q) d = d * y_of(t.states[b]);
            }
            jac[c.col(st.dir, st.rate, c.v[st.var])] += d;
          }
        });
      }
    }
  }
}

void Program::nonlinear(const CoefficientInputs& in, const double* y,
                        const model::NonlinearOutputs& out) const {
  polynomial(SlotKind::Nonlinear, in, y, out);
}

void Program::nonlinear_thrust(const CoefficientInputs& in, const double* y,
                               const model::NonlinearOutputs& out) const {
  polynomial(SlotKind::NonlinearThrust, in, y, out);
}

}  // namespace flaplag::spec
