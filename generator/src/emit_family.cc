// Emission of a model family (generic.h): C++ that assembles the outputs of model_api.h for any
// M x N with loops over the mode indices.  Deterministic.
#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "emit_text.h"
#include "flaplag_derive/emit.h"
#include "flaplag_derive/generic.h"

namespace flaplag::derive {

namespace {

using detail::c_string;
using detail::factor_enum;
using detail::rational_cpp;

const char kLetters[] = "ijklpqrstuvw";

std::string var_name(int v) { return std::string(1, kLetters[v]); }

std::string factors_init(const std::vector<TemplateFactor>& f) {
  if (f.size() > static_cast<size_t>(model::kMaxFactors)) {
    throw std::logic_error("an integrand has more than model::kMaxFactors spanwise factors");
  }
  std::ostringstream os;
  os << "{";
  for (size_t j = 0; j < f.size(); ++j)
    os << (j ? ", " : "") << "{" << factor_enum(f[j].kind) << ", " << std::max(f[j].var, 0) << "}";
  os << "}";
  return os.str();
}

std::string dir_text(ModeDir d) { return d == ModeDir::Flap ? "flap" : "lag"; }
std::string count_of(ModeDir d) { return d == ModeDir::Flap ? "M" : "N"; }

// Equation row of mode variable v of direction d.
std::string row_cpp(ModeDir d, const std::string& v) { return d == ModeDir::Flap ? v : "M + " + v; }
// State column: rate or displacement of mode v.
std::string col_cpp(ModeDir d, bool rate, const std::string& v) {
  if (d == ModeDir::Flap) return rate ? v : "M + " + v;
  return rate ? "2 * M + " + v : "2 * M + N + " + v;
}
std::string state_text(ModeDir d, bool rate, const std::string& v) {
  return std::string(d == ModeDir::Flap ? "g_" : "h_") + v + (rate ? "'" : "");
}

// The index of a direction in the per-direction inputs (the constants the emitted file defines).
std::string direction_cpp(ModeDir d) { return d == ModeDir::Flap ? "kFlap" : "kLag"; }

// Array element of an indexed scalar: in.omega[kFlap][i], in.elastic[kFlap][kLag][i * N + j].
std::string indexed_cpp(const IndexedScalar& s) {
  auto v = [&](size_t a) { return var_name(s.args[a]); };
  const FamilyInput input = family_input(s.family);
  std::string base = "in." + input.array;
  for (ModeDir d : input.dirs) base += "[" + direction_cpp(d) + "]";
  if (s.args.size() == 1) {
    base += "[" + v(0) + "]";
  } else {
    const bool second_flap = input.dirs.at(1) == ModeDir::Flap;
    base += "[" + v(0) + " * " + (second_flap ? "M" : "N") + " + " + v(1) + "]";
  }
  std::string out = base;
  for (int p = 1; p < s.power; ++p) out += " * " + base;
  return out;
}

std::string term_cpp(const GenericModel& g, const GenericTerm& t) {
  std::vector<std::string> f;
  GiNaC::numeric c = t.coef;
  const bool neg = c < 0;
  if (neg) c = -c;
  if (c != 1) f.push_back("(" + rational_cpp(c) + ")");
  for (const auto& [name, p] : t.scalars)
    for (int j = 0; j < p; ++j) f.push_back("s." + name);
  for (const auto& x : t.indexed) f.push_back(indexed_cpp(x));
  if (t.integral >= 0) {
    const IntegralTemplate& tp = g.integrals[static_cast<size_t>(t.integral)];
    std::string call = std::string(tp.ref == IntegralRef::Aero ? "A" : "S") + "(" +
                       std::to_string(index_among_kind(g, t.integral));
    for (int a : t.integral_args) call += ", " + var_name(a);
    f.push_back(call + ")");
  }
  if (f.empty()) f.push_back("1.0");
  std::string out = neg ? "-" : "";
  for (size_t j = 0; j < f.size(); ++j) out += (j ? " * " : "") + f[j];
  return out;
}

std::string term_comment(const GenericTerm& t) {
  std::ostringstream os;
  os << "eps^" << t.eps_order << ", " << t.origin << (t.radial_flow ? ", radial" : "");
  if (!t.paper_name.empty()) os << ", " << t.paper_name;
  return os.str();
}

// Loops over the free variables of a term (those after the bound ones).
std::string open_loops(const GenericTerm& t, int bound, const std::string& indent) {
  std::string out;
  for (size_t v = static_cast<size_t>(bound); v < t.vars.size(); ++v) {
    const std::string n = var_name(static_cast<int>(v));
    out += indent + std::string(2 * (v - static_cast<size_t>(bound)), ' ') + "for (int " + n +
           " = 0; " + n + " < " + count_of(t.vars[v]) + "; ++" + n + ")\n";
  }
  return out;
}
std::string loop_indent(const GenericTerm& t, int bound, const std::string& indent) {
  return indent + std::string(2 * (t.vars.size() - static_cast<size_t>(bound)), ' ');
}

int bound_count(const GenericSlot& s, const GenericTerm& t) {
  return (s.has_eq() ? 1 : 0) + (s.has_col() && !t.diagonal ? 1 : 0);
}

// The linear terms of one slot class, accumulated into `target` (a C++ lvalue in i, j).
void emit_linear_slot(std::ostringstream& os, const GenericModel& g, const GenericSlot& s,
                      const std::string& what, const std::string& target,
                      const std::string& diag_target) {
  bool any = false, any_diag = false;
  for (const auto& t : s.terms) (t.diagonal ? any_diag : any) = true;
  const std::string ind = "  ";
  auto emit_terms = [&](bool diagonal, const std::string& tgt, int depth) {
    const std::string in2 = ind + std::string(2 * static_cast<size_t>(depth), ' ');
    os << in2 << "double v = 0.0;\n";
    for (const auto& t : s.terms) {
      if (t.diagonal != diagonal) continue;
      const int b = bound_count(s, t);
      os << in2 << "// " << term_comment(t) << "\n";
      os << open_loops(t, b, in2);
      os << loop_indent(t, b, in2) << "v += " << term_cpp(g, t) << ";\n";
    }
    os << in2 << tgt << " += v;\n";
  };
  os << "  // " << what << "\n";
  if (any) {
    int depth = 0;
    if (s.has_eq()) {
      os << ind << "for (int i = 0; i < " << count_of(s.eq) << "; ++i) {\n";
      ++depth;
    }
    if (s.has_col()) {
      const std::string jv = s.has_eq() ? "j" : "i";
      os << ind << std::string(2 * static_cast<size_t>(depth), ' ') << "for (int " << jv << " = 0; "
         << jv << " < " << count_of(s.col) << "; ++" << jv << ") {\n";
      ++depth;
    }
    if (depth == 0) os << ind << "{\n";
    emit_terms(false, target, std::max(depth, 1));
    for (int d = std::max(depth, 1) - 1; d >= 0; --d)
      os << ind << std::string(2 * static_cast<size_t>(d), ' ') << "}\n";
  }
  if (any_diag) {
    os << "  // " << what << ": terms of the diagonal (state mode = equation mode) only\n";
    os << ind << "for (int i = 0; i < " << count_of(s.eq) << "; ++i) {\n";
    emit_terms(true, diag_target, 1);
    os << ind << "}\n";
  }
}

std::string harmonic_name(int h) { return DerivedModel::harmonic_name(h); }

// Slots of one kind.
std::vector<const GenericSlot*> slots_of(const GenericModel& g, SlotKind k) {
  std::vector<const GenericSlot*> out;
  for (const auto& s : g.slots)
    if (s.kind == k) out.push_back(&s);
  return out;
}

void emit_mass(std::ostringstream& os, const GenericModel& g) {
  os << "// Generalized mass [n*n]: coefficient of the acceleration of coordinate j in the "
        "equation of\n// coordinate i (inertia terms of eqs 2.16-2.17); structural integrals "
        "only.\n"
     << "FLAPLAG_GENERATED_NO_UBSAN\nvoid mass(const model::CoefficientInputs& in, double* out) "
        "{\n"
     << "  const Tensors T(in);\n  const int M = T.M, N = T.N, n = M + N;\n"
     << "  (void)M;\n  (void)N;\n  const model::TemplateTensors& S = T.S;\n"
     << "  std::fill(out, out + n * n, 0.0);\n";
  for (const GenericSlot* s : slots_of(g, SlotKind::Mass)) {
    const std::string what = dir_text(s->eq) + " equation i, acceleration of " +
                             (s->col == ModeDir::Flap ? "g_j''" : "h_j''");
    emit_linear_slot(os, g, *s, what,
                     "out[(" + row_cpp(s->eq, "i") + ") * n + " + row_cpp(s->col, "j") + "]",
                     "out[(" + row_cpp(s->eq, "i") + ") * n + " + row_cpp(s->col, "i") + "]");
  }
  os << "}\n\n";
}

void emit_coefficients(std::ostringstream& os, const GenericModel& g) {
  os << "// mass * q'' = sum_h phi_h(psi) (force[h] y + forcing[h]), H = " << g.H
     << " harmonics, n = M + N\n// equations, 2n states (model_api.h ordering).  A = mass^-1 "
        "force, f = mass^-1 forcing (eqs 2.36-2.37).\n"
     << "// kM, kN: the mode counts when known at compile time (the 1 x 1 blade, so that its "
        "loops\n"
     << "// unroll and its indices fold), 0: in.modes; the same operations in the same order.\n"
     << "template <int kM, int kN>\n"
     << "FLAPLAG_GENERATED_NO_UBSAN\n"
     << "void coefficients_of(const model::CoefficientInputs& in, const model::CoefficientOutputs& "
        "out) {\n"
     << "  using Tensor = std::conditional_t<kM == 1 && kN == 1, model::UnitTensors, "
        "model::TemplateTensors>;\n"
     << "  const TensorsOf<Tensor> T(in);\n  const Symbols s(in);\n"
     << "  const int M = kM > 0 ? kM : T.M, N = kN > 0 ? kN : T.N, n = M + N;\n"
     << "  const Tensor& A = T.A;\n  const Tensor& S = T.S;\n"
     << "  (void)A;\n  (void)S;\n  (void)M;\n  (void)N;\n"
     << "  std::fill(out.force, out.force + " << g.H << " * n * 2 * n, 0.0);\n"
     << "  std::fill(out.forcing, out.forcing + " << g.H << " * n, 0.0);\n";
  for (const GenericSlot* s : slots_of(g, SlotKind::Force)) {
    const std::string h = std::to_string(s->harmonic);
    const std::string what = harmonic_name(s->harmonic) + ": " + dir_text(s->eq) +
                             " equation i, coefficient of " + state_text(s->col, s->rate, "j");
    auto tgt = [&](const std::string& j) {
      return "out.force[(" + h + " * n + " + row_cpp(s->eq, "i") + ") * 2 * n + " +
             col_cpp(s->col, s->rate, j) + "]";
    };
    emit_linear_slot(os, g, *s, what, tgt("j"), tgt("i"));
  }
  for (const GenericSlot* s : slots_of(g, SlotKind::Forcing)) {
    const std::string h = std::to_string(s->harmonic);
    const std::string what =
        harmonic_name(s->harmonic) + ": " + dir_text(s->eq) + " equation i, state-independent";
    const std::string t = "out.forcing[" + h + " * n + " + row_cpp(s->eq, "i") + "]";
    emit_linear_slot(os, g, *s, what, t, t);
  }
  os << "}\n\n"
     << "void coefficients(const model::CoefficientInputs& in, const model::CoefficientOutputs& "
        "out) {\n"
     << "  if (in.modes[kFlap] == 1 && in.modes[kLag] == 1)\n"
     << "    coefficients_of<1, 1>(in, out);\n"
     << "  else\n"
     << "    coefficients_of<0, 0>(in, out);\n"
     << "}\n\n";
}

void emit_equilibrium(std::ostringstream& os, const GenericModel& g) {
  os << "// Hover static equilibrium S q0 = c (eqs 2.27-2.32).\n"
     << "FLAPLAG_GENERATED_NO_UBSAN\n"
     << "void equilibrium(const model::CoefficientInputs& in, const model::EquilibriumOutputs& "
        "out) {\n"
     << "  const Tensors T(in);\n  const Symbols s(in);\n"
     << "  const int M = T.M, N = T.N, n = M + N;\n"
     << "  const model::TemplateTensors& A = T.A;\n  const model::TemplateTensors& S = T.S;\n"
     << "  (void)A;\n  (void)S;\n  (void)M;\n  (void)N;\n"
     << "  std::fill(out.S, out.S + n * n, 0.0);\n  std::fill(out.c, out.c + n, 0.0);\n";
  for (const GenericSlot* s : slots_of(g, SlotKind::HoverStiffness)) {
    const std::string what = dir_text(s->eq) + " equation i, coefficient of " +
                             (s->col == ModeDir::Flap ? "g0_j" : "h0_j");
    emit_linear_slot(os, g, *s, what,
                     "out.S[(" + row_cpp(s->eq, "i") + ") * n + " + row_cpp(s->col, "j") + "]",
                     "out.S[(" + row_cpp(s->eq, "i") + ") * n + " + row_cpp(s->col, "i") + "]");
  }
  for (const GenericSlot* s : slots_of(g, SlotKind::HoverLoad)) {
    const std::string t = "out.c[" + row_cpp(s->eq, "i") + "]";
    emit_linear_slot(os, g, *s, dir_text(s->eq) + " equation i, hover load", t, t);
  }
  os << "}\n\n";
}

void emit_thrust(std::ostringstream& os, const GenericModel& g) {
  os << "// Rotor thrust of one blade, lr int L_z dx0 (the flap load of eq 2.20 with the same\n"
     << "// truncation), by harmonic h: out.forcing[h] + out.force[h*2n .. h*2n+2n) . y.\n"
     << "// C_T = (sigma a / 2) times its azimuth average.\n"
     << "FLAPLAG_GENERATED_NO_UBSAN\n"
     << "void thrust(const model::CoefficientInputs& in, const model::CoefficientOutputs& out) "
        "{\n"
     << "  const Tensors T(in);\n  const Symbols s(in);\n"
     << "  const int M = T.M, N = T.N, n = M + N;\n"
     << "  const model::TemplateTensors& A = T.A;\n  (void)A;\n  (void)M;\n  (void)N;\n"
     << "  std::fill(out.force, out.force + " << g.H << " * 2 * n, 0.0);\n"
     << "  std::fill(out.forcing, out.forcing + " << g.H << ", 0.0);\n";
  for (const GenericSlot* s : slots_of(g, SlotKind::ThrustForce)) {
    const std::string h = std::to_string(s->harmonic);
    emit_linear_slot(os, g, *s,
                     "thrust, " + harmonic_name(s->harmonic) + ": coefficient of " +
                         state_text(s->col, s->rate, "i"),
                     "out.force[" + h + " * 2 * n + " + col_cpp(s->col, s->rate, "i") + "]", "");
  }
  for (const GenericSlot* s : slots_of(g, SlotKind::ThrustForcing)) {
    const std::string t = "out.forcing[" + std::to_string(s->harmonic) + "]";
    emit_linear_slot(os, g, *s, "thrust, " + harmonic_name(s->harmonic) + ": state-independent", t,
                     t);
  }
  os << "}\n\n";
}

// Nonlinear loads: every term is c * prod(states); the Jacobian by the product rule.
void emit_polynomial(std::ostringstream& os, const GenericModel& g, SlotKind kind) {
  const bool thrust = kind == SlotKind::NonlinearThrust;
  os << "  const Tensors T(in);\n  const Symbols s(in);\n"
     << "  const int M = T.M, N = T.N, n = M + N;\n"
     << "  const model::TemplateTensors& A = T.A;\n  const model::TemplateTensors& S = T.S;\n"
     << "  (void)A;\n  (void)S;\n  (void)M;\n  (void)N;\n"
     << "  const int rows = " << (thrust ? "1" : "n") << ";\n"
     << "  std::fill(out.force, out.force + " << g.H_nonlinear << " * rows, 0.0);\n"
     << "  std::fill(out.jacobian, out.jacobian + " << g.H_nonlinear << " * rows * 2 * n, 0.0);\n";
  for (const GenericSlot* s : slots_of(g, kind)) {
    const std::string h = std::to_string(s->harmonic);
    const std::string row = thrust ? "0" : row_cpp(s->eq, "i");
    os << "  // " << (thrust ? std::string("thrust") : dir_text(s->eq) + " equation i") << ", "
       << harmonic_name(s->harmonic) << "\n";
    std::string ind = "  ";
    if (!thrust) {
      os << ind << "for (int i = 0; i < " << count_of(s->eq) << "; ++i) {\n";
      ind += "  ";
    } else {
      os << ind << "{\n";
      ind += "  ";
    }
    os << ind << "double* f = out.force + " << h << " * rows + " << row << ";\n"
       << ind << "double* jac = out.jacobian + (" << h << " * rows + " << row << ") * 2 * n;\n"
       << ind << "(void)f;\n"
       << ind << "(void)jac;\n";
    for (const auto& t : s->terms) {
      const int b = thrust ? 0 : 1;
      os << ind << "// " << term_comment(t) << "\n" << open_loops(t, b, ind);
      const std::string in2 = loop_indent(t, b, ind);
      os << in2 << "{\n";
      os << in2 << "  const double c = " << term_cpp(g, t) << ";\n";
      std::vector<std::string> ys;  // one entry per unit power
      for (const auto& st : t.states)
        for (int p = 0; p < st.power; ++p)
          ys.push_back("y[" + col_cpp(st.dir, st.rate, var_name(st.var)) + "]");
      std::string prod = "c";
      for (const auto& y : ys) prod += " * " + y;
      os << in2 << "  *f += " << prod << ";\n";
      for (size_t a = 0; a < t.states.size(); ++a) {
        const auto& st = t.states[a];
        std::string d = (st.power > 1 ? std::to_string(st.power) + ".0 * " : "") + std::string("c");
        for (size_t b2 = 0; b2 < t.states.size(); ++b2) {
          const int p = t.states[b2].power - (b2 == a ? 1 : 0);
          const std::string y =
              "y[" + col_cpp(t.states[b2].dir, t.states[b2].rate, var_name(t.states[b2].var)) + "]";
          for (int q = 0; q < p; ++q) d += " * " + y;
        }
        os << in2 << "  jac[" << col_cpp(st.dir, st.rate, var_name(st.var)) << "] += " << d
           << ";\n";
      }
      os << in2 << "}\n";
    }
    os << "  }\n";
  }
  os << "}\n\n";
}

std::string family_summary(const GenericModel& g) {
  // OrderingSpec::summary() names the mode counts first ("paper: 1 flap x 1 lag modes; ...").
  const std::string s = g.spec.summary();
  const auto semi = s.find("; ");
  return semi == std::string::npos ? s : s.substr(semi + 2);
}

std::string factor_md(const GenericModel& g, const GenericTerm& t) {
  std::ostringstream os;
  os << t.coef;
  for (const auto& [name, p] : t.scalars)
    os << " " << name << (p > 1 ? "^" + std::to_string(p) : "");
  for (const auto& x : t.indexed) {
    os << " " << x.family << "_";
    for (int a : x.args) os << var_name(a);
    if (x.power > 1) os << "^" << x.power;
  }
  for (const auto& st : t.states) {
    os << " " << state_text(st.dir, st.rate, var_name(st.var));
    if (st.power > 1) os << "^" << st.power;
  }
  (void)g;
  return os.str();
}

std::string integral_md(const GenericModel& g, const GenericTerm& t) {
  if (t.integral < 0) return "-";
  std::string name = g.integrals[static_cast<size_t>(t.integral)].name;
  // template letters a, b, ... -> the term's letters
  std::string out;
  for (size_t j = 0; j < name.size(); ++j) {
    if (name[j] == '_' && j + 1 < name.size() && name[j + 1] >= 'a' &&
        name[j + 1] < 'a' + static_cast<char>(t.integral_args.size())) {
      out += "_" + var_name(t.integral_args[static_cast<size_t>(name[j + 1] - 'a')]);
      ++j;
    } else {
      out += name[j];
    }
  }
  return "int " + out;
}

std::string slot_title(const GenericSlot& s) {
  const std::string h = harmonic_name(s.harmonic);
  switch (s.kind) {
    case SlotKind::Mass:
      return dir_text(s.eq) + " equation i: mass, acceleration of " +
             (s.col == ModeDir::Flap ? "g_j''" : "h_j''");
    case SlotKind::Force:
      return dir_text(s.eq) + " equation i, " + h + ": coefficient of " +
             state_text(s.col, s.rate, "j");
    case SlotKind::Forcing:
      return dir_text(s.eq) + " equation i, " + h + ": state-independent";
    case SlotKind::HoverStiffness:
      return dir_text(s.eq) + " equation i: hover equilibrium, coefficient of " +
             (s.col == ModeDir::Flap ? "g0_j" : "h0_j");
    case SlotKind::HoverLoad:
      return dir_text(s.eq) + " equation i: hover equilibrium, load";
    case SlotKind::ThrustForce:
      return "thrust, " + h + ": coefficient of " + state_text(s.col, s.rate, "i");
    case SlotKind::ThrustForcing:
      return "thrust, " + h + ": state-independent";
    case SlotKind::Nonlinear:
      return dir_text(s.eq) + " equation i, " + h + ": nonlinear load";
    case SlotKind::NonlinearThrust:
      return "thrust, " + h + ": nonlinear load";
    case SlotKind::Absorbed:
      return dir_text(s.eq) +
             " equation i: centrifugal stiffness absorbed into the modal "
             "stiffness, coefficient of " +
             state_text(s.col, s.rate, "j");
  }
  return "";
}

}  // namespace

std::string emit_family_report(const GenericModel& g) {
  std::ostringstream os;
  os << "\n## Every term, for any number of modes\n\n"
     << "The code in `" << g.spec.name
     << ".cc` assembles the equations for any M flap x N lag "
        "modes from the terms below (extracted from the derivation at "
     << g.P << " x " << g.P << " modes, checked to reproduce it exactly and to be the same at "
     << g.P + 1 << " x " << g.P + 1
     << ").  Letters: i = the equation's mode, j = the "
        "state's or coordinate's mode, k, l, p = modes summed over all modes of their "
        "direction (flap: 1..M for eta, g; lag: 1..N for gamma, h).  A term marked `j = i` "
        "exists only on the diagonal.  Factors: `g0_k`, `h0_k` hover amplitudes, "
        "`es_*_ik`, `ecs_*_ik` Appendix E couplings, `omega_*_i`, `damping_*_i` modal "
        "frequency and damping; aerodynamic factors include (gamma/2)(l/R)^2.\n\n";
  os << "### Integral templates\n\n| # | integral | paper |\n|---|---|---|\n";
  for (IntegralRef ref : {IntegralRef::Aero, IntegralRef::Structural}) {
    int idx = 0;
    for (const auto& t : g.integrals) {
      if (t.ref != ref) continue;
      os << "| " << (ref == IntegralRef::Aero ? "A" : "S") << idx++ << " | int " << t.name << " | "
         << (t.paper_name.empty() ? "-" : t.paper_name) << " |\n";
    }
  }
  for (const auto& s : g.slots) {
    os << "\n### " << slot_title(s) << "\n\n| factor | integral | eps | origin | paper |\n"
       << "|---|---|---|---|---|\n";
    for (const auto& t : s.terms) {
      os << "| " << factor_md(g, t) << (t.diagonal ? " (j = i)" : "") << " | " << integral_md(g, t)
         << " | " << t.eps_order << " | " << t.origin << (t.radial_flow ? " (radial)" : "") << " | "
         << (t.paper_name.empty() ? "-" : t.paper_name) << " |\n";
    }
  }
  return os.str();
}

std::string emit_family_cpp(const GenericModel& g) {
  const std::string id = model_ident(g.spec.name);
  std::ostringstream os;
  os << "// Generated by flaplag-derive (generator/) from the ordering spec " << g.spec.file
     << " -- do not edit.\n"
     << "// Model family " << g.spec.name << " (any M flap x N lag modes): " << family_summary(g)
     << ".\n"
     << "// Refresh the checked-in copy with: cmake --build build --target refresh-generated\n"
     << "// NASA CR-132431 flap-lag equations for any number of modes: loops over the mode "
        "indices\n// (i: equation, j: state or coordinate, k, l, ...: summed) and integral "
        "tensors (model_api.h).\n// See "
     << g.spec.name << ".md (same directory) for the term-by-term audit.\n\n"
     << "#include <algorithm>\n#include <type_traits>\n\n#include \"flaplag/model_api.h\"\n\n"
     << "#if defined(__GNUC__) || defined(__clang__)\n"
     << "#define FLAPLAG_GENERATED_NO_UBSAN __attribute__((no_sanitize(\"undefined\")))\n"
     << "#else\n#define FLAPLAG_GENERATED_NO_UBSAN\n#endif\n\n"
     << "namespace flaplag::generated::" << id << " {\nnamespace {\n\n"
     << "using model::Direction;\nusing model::Factor;\nusing model::Inner;\n\n"
     << "// The directions' places in the per-direction inputs (CoefficientInputs).\n"
     << "constexpr int kFlap = model::index(Direction::Flap);\n"
     << "constexpr int kLag = model::index(Direction::Lag);\n\n";
  for (IntegralRef ref : {IntegralRef::Aero, IntegralRef::Structural}) {
    os << "// " << (ref == IntegralRef::Aero ? "Aerodynamic" : "Structural")
       << " integral templates (letters a, b, c: the template's mode variables).\n"
       << "const model::IntegralTemplate k" << (ref == IntegralRef::Aero ? "Aero" : "Structural")
       << "[] = {\n";
    int idx = 0;
    for (const auto& t : g.integrals) {
      if (t.ref != ref) continue;
      const char* inner = t.inner == InnerKind::None   ? "Inner::None"
                          : t.inner == InnerKind::Tail ? "Inner::Tail"
                                                       : "Inner::Head";
      os << "    /* " << idx++ << " */ {" << c_string(t.name) << ", " << c_string(t.ident) << ", "
         << t.vars.size() << ", {";
      for (size_t v = 0; v < t.vars.size(); ++v)
        os << (v ? ", " : "")
           << (t.vars[v] == ModeDir::Flap ? "Direction::Flap" : "Direction::Lag");
      os << "}, " << t.x_power << ", " << t.outer_mass << ", " << t.factors.size() << ", "
         << factors_init(t.factors) << ", " << inner << ", " << t.inner_mass << ", "
         << t.inner_factors.size() << ", " << factors_init(t.inner_factors) << ", "
         << c_string(t.paper_name) << "},\n";
    }
    os << "};\n\n";
  }
  os << "const char kSpecText[] = " << c_string(g.spec.canonical_text()) << ";\n\n";
  os << "// The integral tensors of in.aero, in.structural and the mode counts (Tensor:\n"
     << "// model::TemplateTensors, or model::UnitTensors for the 1 x 1 blade).\n"
     << "template <class Tensor>\n"
     << "struct TensorsOf {\n"
     << "  explicit TensorsOf(const model::CoefficientInputs& in)\n"
     << "      : M(in.modes[kFlap]),\n        N(in.modes[kLag]),\n"
     << "        A(kAero, static_cast<int>(std::size(kAero)), in.aero, M, N),\n"
     << "        S(kStructural, static_cast<int>(std::size(kStructural)), in.structural, M, N) "
        "{}\n"
     << "  int M, N;\n  Tensor A, S;\n};\nusing Tensors = TensorsOf<model::TemplateTensors>;\n\n";
  os << "// The scalar inputs without mode indices.\n"
     << "struct Symbols {\n  explicit Symbols(const model::CoefficientInputs& in)\n      : ";
  for (size_t j = 0; j < g.scalar_names.size(); ++j)
    os << (j ? ",\n        " : "") << g.scalar_names[j] << "(in." << g.scalar_names[j] << ")";
  os << " {}\n";
  for (const auto& n : g.scalar_names) os << "  double " << n << ";\n";
  os << "};\n\n";
  emit_mass(os, g);
  emit_coefficients(os, g);
  emit_equilibrium(os, g);
  emit_thrust(os, g);
  os << "// Nonlinear generalized loads: mass * q'' = sum_h phi_h(psi) force[h](y), y the full "
        "state\n// (not a perturbation; in.q0 is not read), every product of the coordinates "
        "that the\n// ordering keeps; and d force / d y.  H_nl = "
     << g.H_nonlinear << ".\n"
     << "FLAPLAG_GENERATED_NO_UBSAN\n"
     << "void nonlinear(const model::CoefficientInputs& in, const double* y,\n"
     << "               const model::NonlinearOutputs& out) {\n";
  emit_polynomial(os, g, SlotKind::Nonlinear);
  os << "// Rotor thrust of one blade at the full state y: T(psi) = sum_h phi_h(psi) "
        "force[h](y),\n// the load of `thrust` without its degree-1 cut; and d force / d y.\n"
     << "FLAPLAG_GENERATED_NO_UBSAN\n"
     << "void nonlinear_thrust(const model::CoefficientInputs& in, const double* y,\n"
     << "                      const model::NonlinearOutputs& out) {\n";
  emit_polynomial(os, g, SlotKind::NonlinearThrust);
  os << "}  // namespace\n}  // namespace flaplag::generated::" << id << "\n\n";
  os << "const flaplag::model::ModelFamily& flaplag_family_" << id << "() {\n"
     << "  namespace g = flaplag::generated::" << id << ";\n"
     << "  static const flaplag::model::ModelFamily f = {\n"
     << "      " << c_string(g.spec.name) << ",\n"
     << "      " << c_string(g.spec.file) << ",\n"
     << "      g::kSpecText,\n"
     << "      " << c_string(family_summary(g)) << ",\n"
     << "      " << g.spec.flap_modes << ", " << g.spec.lag_modes << ",\n"
     << "      " << g.H << ", " << g.H_nonlinear << ",\n"
     << "      static_cast<int>(std::size(g::kAero)), g::kAero,\n"
     << "      static_cast<int>(std::size(g::kStructural)), g::kStructural,\n"
     << "      &g::mass,\n      &g::coefficients,\n      &g::equilibrium,\n      &g::thrust,\n"
     << "      &g::nonlinear,\n      &g::nonlinear_thrust,\n"
     << "      nullptr,\n"
     << "      " << linear_aero_templates(g) << "};\n"
     << "  return f;\n}\n";
  return os.str();
}

}  // namespace flaplag::derive
