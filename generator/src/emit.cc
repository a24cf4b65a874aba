#include "flaplag_derive/emit.h"

#include <algorithm>
#include <set>
#include <sstream>
#include <stdexcept>

#include "emit_text.h"
#include "flaplag_derive/paper_names.h"

namespace flaplag::derive {

namespace {

using detail::c_string;
using detail::factor_enum;
using detail::rational_cpp;

std::string factors_init(const std::vector<ShapeFactor>& f) {
  if (f.size() > static_cast<size_t>(model::kMaxFactors)) {
    throw std::logic_error("an integrand has more than model::kMaxFactors spanwise factors");
  }
  std::ostringstream os;
  os << "{";
  for (size_t j = 0; j < f.size(); ++j) {
    os << (j ? ", " : "") << "{" << factor_enum(f[j].kind) << ", " << f[j].mode << "}";
  }
  os << "}";
  return os.str();
}

// One term as C++; the named inputs are members of `prefix` ("s." = the Symbols struct).
std::string term_cpp(const DerivedModel& m, const Term& t, const std::string& prefix) {
  std::ostringstream os;
  GiNaC::numeric c = t.coef;
  const bool neg = c < 0;
  if (neg) c = -c;
  std::vector<std::string> f;
  if (c != 1) f.push_back("(" + rational_cpp(c) + ")");
  for (const auto& [idx, p] : t.scalars) {
    for (int j = 0; j < p; ++j) f.push_back(prefix + m.scalars[idx].name);
  }
  if (t.ref == IntegralRef::Aero) f.push_back(prefix + "A_" + m.aero[t.integral].ident);
  if (t.ref == IntegralRef::Structural) {
    f.push_back(prefix + "S_" + m.structural[t.integral].ident);
  }
  if (f.empty()) f.push_back("1.0");
  os << (neg ? "- " : "+ ");
  for (size_t j = 0; j < f.size(); ++j) os << (j ? " * " : "") << f[j];
  return os.str();
}

std::string slot_cpp(const DerivedModel& m, const Slot& s, const std::string& indent,
                     const std::string& prefix = "s.") {
  if (s.terms.empty()) return "0.0";
  std::ostringstream os;
  for (size_t j = 0; j < s.terms.size(); ++j) {
    std::string t = term_cpp(m, s.terms[j], prefix);
    if (j == 0 && t.rfind("+ ", 0) == 0) t = t.substr(2);
    if (j == 0 && t.rfind("- ", 0) == 0) t = "-" + t.substr(2);
    os << (j ? "\n" + indent : "") << t;
  }
  return os.str();
}

// The named inputs (scalars, aerodynamic integrals A_*, generalized masses S_*), unpacked once
// for both generated functions.
void emit_symbols(std::ostringstream& os, const DerivedModel& m) {
  os << "// Named inputs: scalars, spanwise aerodynamic integrals (A_*), generalized masses "
        "(S_*).\n"
     << "struct Symbols {\n  explicit Symbols(const model::CoefficientInputs& in);\n";
  for (const auto& sc : m.scalars) os << "  double " << sc.name << ";\n";
  for (size_t j = 0; j < m.aero.size(); ++j) {
    os << "  double A_" << m.aero[j].ident << ";"
       << (m.aero[j].paper_name.empty() ? "" : "  // " + m.aero[j].paper_name) << "\n";
  }
  for (size_t j = 0; j < m.structural.size(); ++j) {
    os << "  double S_" << m.structural[j].ident << ";"
       << (m.structural[j].paper_name.empty() ? "" : "  // " + m.structural[j].paper_name) << "\n";
  }
  os << "};\n\nFLAPLAG_GENERATED_NO_UBSAN\nSymbols::Symbols(const model::CoefficientInputs& in) "
        "{\n";
  for (const auto& sc : m.scalars) os << "  " << sc.name << " = " << sc.cexpr << ";\n";
  for (size_t j = 0; j < m.aero.size(); ++j) {
    os << "  A_" << m.aero[j].ident << " = in.aero[" << j << "];\n";
  }
  for (size_t j = 0; j < m.structural.size(); ++j) {
    os << "  S_" << m.structural[j].ident << " = in.structural[" << j << "];\n";
  }
  os << "}\n\n";
}

// C++ name of full-state column c of the nonlinear loads: "q_g1_rate", "q_g1", "q_h1_rate".
std::string full_state_ident(const DerivedModel& m, int col) {
  const model::StateRef r = model::state_ref(col, m.M, m.N);
  return std::string("q_") + (r.direction == model::Direction::Flap ? "g" : "h") +
         std::to_string(r.mode + 1) + (r.rate ? "_rate" : "");
}

// The product of the columns in `powers` as C++ ("1.0" for degree 0).
std::string monomial_cpp(const DerivedModel& m, const std::vector<int>& powers) {
  std::string out;
  for (size_t c = 0; c < powers.size(); ++c) {
    for (int j = 0; j < powers[c]; ++j) {
      out += (out.empty() ? "" : " * ") + full_state_ident(m, static_cast<int>(c));
    }
  }
  return out.empty() ? "1.0" : out;
}

// Body of a polynomial function of the full state y: `rows` values per harmonic (the slots'
// equation, or row 0 for the thrust) and their Jacobian.
void emit_polynomial(std::ostringstream& os, const DerivedModel& m,
                     const std::vector<NonlinearSlot>& slots, int rows, bool thrust) {
  const int ns = 2 * m.n(), H = m.H_nonlinear;
  const std::string ind = "        ";
  os << "  const Symbols s(in);\n";
  for (int c = 0; c < ns; ++c) {
    os << "  const double " << full_state_ident(m, c) << " = y[" << c << "];\n";
  }
  os << "  for (int k = 0; k < " << H * rows << "; ++k) out.force[k] = 0.0;\n"
     << "  for (int k = 0; k < " << H * rows * ns << "; ++k) out.jacobian[k] = 0.0;\n";
  for (const auto& nl : slots) {
    const int idx = nl.harmonic * rows + (thrust ? 0 : nl.equation);
    os << "  {  // "
       << (thrust ? std::string("thrust") : m.equation_name(nl.equation) + " equation") << ", "
       << DerivedModel::harmonic_name(nl.harmonic) << ": " << monomial_text(m, nl.powers) << "\n"
       << "    const double c =\n"
       << ind << slot_cpp(m, nl.slot, ind) << ";\n"
       << "    out.force[" << idx << "] += c * " << monomial_cpp(m, nl.powers) << ";\n";
    for (int c = 0; c < ns; ++c) {
      if (nl.powers[c] == 0) continue;
      std::vector<int> d = nl.powers;
      --d[c];
      os << "    out.jacobian[" << idx * ns + c
         << "] += " << (nl.powers[c] > 1 ? std::to_string(nl.powers[c]) + ".0 * " : "") << "c * "
         << monomial_cpp(m, d) << ";\n";
    }
    os << "  }\n";
  }
  os << "}\n\n";
}

// The nonlinear generalized loads and their Jacobian (model_api.h NonlinearOutputs).
void emit_nonlinear(std::ostringstream& os, const DerivedModel& m) {
  const int n = m.n(), H = m.H_nonlinear;
  os << "// Nonlinear generalized loads: mass * q'' = sum_h phi_h(psi) force[h](y), y the full "
        "state\n// (not a perturbation; in.q0 is not read), every product of the coordinates "
        "that the\n// ordering keeps; and d force / d y.  H_nl = "
     << H << ".\n"
     << "FLAPLAG_GENERATED_NO_UBSAN\n"
     << "void nonlinear(const model::CoefficientInputs& in, const double* y,\n"
     << "               const model::NonlinearOutputs& out) {\n";
  emit_polynomial(os, m, m.nonlinear, n, false);
}

// The rotor thrust as a polynomial in the full state (cyclic-pitch models with nonlinear
// loads; model_api.h ModelDescriptor::nonlinear_thrust): one row per harmonic.
void emit_nonlinear_thrust(std::ostringstream& os, const DerivedModel& m) {
  os << "// Rotor thrust of one blade at the full state y: T(psi) = sum_h phi_h(psi) force[h](y),\n"
        "// the load of `thrust` without its degree-1 cut; and d force / d y.  H_nl = "
     << m.H_nonlinear << ".\n"
     << "FLAPLAG_GENERATED_NO_UBSAN\n"
     << "void nonlinear_thrust(const model::CoefficientInputs& in, const double* y,\n"
     << "                      const model::NonlinearOutputs& out) {\n";
  emit_polynomial(os, m, m.nonlinear_thrust, 1, true);
}

// Indent of a slot's continuation lines in the straight-line functions.
constexpr char kSlotIndent[] = "      ";

// The file header and the UBSan opt-out macro every generated function carries.
void emit_preamble(std::ostringstream& os, const DerivedModel& m) {
  os << generated_header(m, "//");
  os << "// NASA CR-132431 flap-lag equations: harmonic coefficients of the generalized forces.\n"
     << "// See " << m.spec.name << ".md (same directory) for the term-by-term audit.\n\n";
  os << "#include \"flaplag/model_api.h\"\n\n";
  // UBSan would check every one of the thousands of array accesses of the straight-line code
  // below for alignment and pointer overflow; those checks cannot fire on arrays the runtime
  // sizes from this descriptor (ASan still checks the bounds), and the extra basic blocks make
  // GCC's variable tracking of a -g build superlinear in the function size (paper-3x3: 82 s
  // instead of 2.5 s with -O1 -g -fsanitize=address,undefined).
  os << "// UBSan's per-access checks add nothing to straight-line arithmetic on arrays sized by "
        "this\n// descriptor (ASan still checks the bounds) and make -g sanitizer builds of the "
        "larger\n// models take minutes (variable tracking).\n"
     << "#if defined(__GNUC__) || defined(__clang__)\n"
     << "#define FLAPLAG_GENERATED_NO_UBSAN __attribute__((no_sanitize(\"undefined\")))\n"
     << "#else\n#define FLAPLAG_GENERATED_NO_UBSAN\n#endif\n\n";
}

// The tables the descriptor points to: the spanwise integrals the runtime evaluates (their
// order is the order of in.aero and in.structural) and the canonical spec text.
void emit_tables(std::ostringstream& os, const DerivedModel& m) {
  os << "using model::Factor;\nusing model::Inner;\n\n";
  os << "// The directions' places in the per-direction inputs (CoefficientInputs).\n"
     << "constexpr int kFlap = model::index(model::Direction::Flap);\n"
     << "constexpr int kLag = model::index(model::Direction::Lag);\n\n";
  os << "const model::AeroIntegral kAero[] = {\n";
  for (size_t j = 0; j < m.aero.size(); ++j) {
    const auto& k = m.aero_keys[j];
    os << "    {" << c_string(m.aero[j].name) << ", " << c_string(m.aero[j].ident) << ", "
       << k.x_power << ", " << k.factors.size() << ", " << factors_init(k.factors) << ", "
       << c_string(m.aero[j].paper_name) << "},\n";
  }
  os << "};\n\n";
  os << "const model::StructuralIntegral kStructural[] = {\n";
  for (size_t j = 0; j < m.structural.size(); ++j) {
    const auto& k = m.structural_keys[j];
    const char* inner = k.inner == InnerKind::None   ? "Inner::None"
                        : k.inner == InnerKind::Tail ? "Inner::Tail"
                                                     : "Inner::Head";
    os << "    {" << c_string(m.structural[j].name) << ", " << c_string(m.structural[j].ident)
       << ", " << k.outer_mass << ", " << k.outer.size() << ", " << factors_init(k.outer) << ", "
       << inner << ", " << k.inner_mass << ", " << k.inner_factors.size() << ", "
       << factors_init(k.inner_factors) << ", " << c_string(m.structural[j].paper_name) << "},\n";
  }
  os << "};\n\n";
  os << "const char kSpecText[] = " << c_string(m.spec.canonical_text()) << ";\n\n";
}

// The generalized mass.  Emitted before the Symbols struct and without it: the runtime
// evaluates the mass once per blade, so it reads only the structural integrals it needs
// (model_api.h).
void emit_mass(std::ostringstream& os, const DerivedModel& m) {
  const int n = m.n();
  os << "// Generalized mass: coefficient of the accelerations q'' = [dg1''..dgM'', dh1''..dhN''] "
        "in\n// each equation (inertia terms of eqs 2.16-2.17).  Structural integrals only: "
        "independent\n// of mu and of the hover state.\n"
     << "FLAPLAG_GENERATED_NO_UBSAN\nvoid mass(const model::CoefficientInputs& in, double* out) "
        "{\n";
  std::set<int> mass_integrals;
  for (const auto& slot : m.mass) {
    for (const auto& t : slot.terms) mass_integrals.insert(t.integral);
  }
  for (int j : mass_integrals) {
    os << "  const double S_" << m.structural[j].ident << " = in.structural[" << j << "];"
       << (m.structural[j].paper_name.empty() ? "" : "  // " + m.structural[j].paper_name) << "\n";
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      // the mass multiplies the acceleration of coordinate j: q_j'' = (displacement j)''
      os << "  // mass: " << m.equation_name(i) << " equation, coefficient of "
         << m.state_name(model::displacement_index(j, m.M, m.N)) << "''\n";
      os << "  out[" << i * n + j << "] =\n"
         << kSlotIndent << slot_cpp(m, m.mass[i * n + j], kSlotIndent, "") << ";\n";
    }
  }
  os << "}\n\n";
}

// The linearized equations: force (the entries of A) and forcing (of f) by harmonic, each
// slot labelled with the Appendix C entry it feeds.
void emit_coefficients(std::ostringstream& os, const DerivedModel& m) {
  const int n = m.n();
  os << "// mass * q'' = sum_h phi_h(psi) (force[h] y + forcing[h]);  n = " << n
     << ", states 2n = " << 2 * n << ", harmonics H = " << m.H << ".\n"
     << "// Each slot is labelled with the entry of the first-order form y' = A(psi) y + f(psi) "
        "it\n"
     << "// feeds (A = mass^-1 force, f = mass^-1 forcing; eqs 2.36-2.37) and the harmonic it\n"
     << "// multiplies.  Row i of A is the row of the equation's rate (flap k -> k, lag m -> 2M + "
        "m),\n"
     << "// column j the state column; for M = N = 1 these are A11..A14, A31..A34 (Appendix C.2)\n"
     << "// and f1, f3 (Appendix C.3), and A_ij = force / M_F1 (flap) or / M_L1 (lag).\n";
  os << "FLAPLAG_GENERATED_NO_UBSAN\n"
     << "void coefficients(const model::CoefficientInputs& in, const model::CoefficientOutputs& "
        "out) {\n";
  os << "  const Symbols s(in);\n";
  for (int h = 0; h < m.H; ++h) {
    for (int i = 0; i < n; ++i) {
      for (int col = 0; col < 2 * n; ++col) {
        const int idx = (h * n + i) * 2 * n + col;
        os << "  // " << a_entry_name(i, col, m.M, m.N) << ", " << DerivedModel::harmonic_name(h)
           << ": " << m.equation_name(i) << " equation, coefficient of " << m.state_name(col)
           << "\n";
        os << "  out.force[" << idx << "] =\n"
           << kSlotIndent << slot_cpp(m, m.force[idx], kSlotIndent) << ";\n";
      }
    }
    for (int i = 0; i < n; ++i) {
      os << "  // " << f_entry_name(i, m.M, m.N) << ", " << DerivedModel::harmonic_name(h) << ": "
         << m.equation_name(i) << " equation, state-independent\n";
      os << "  out.forcing[" << h * n + i << "] =\n"
         << kSlotIndent << slot_cpp(m, m.forcing[h * n + i], kSlotIndent) << ";\n";
    }
  }
  os << "}\n\n";
}

// The hover static equilibrium S q0 = c, row by row.
void emit_equilibrium(std::ostringstream& os, const DerivedModel& m) {
  const int n = m.n();
  os << "// Hover static equilibrium S q0 = c (eqs 2.27-2.32).\n";
  os << "FLAPLAG_GENERATED_NO_UBSAN\n"
     << "void equilibrium(const model::CoefficientInputs& in, const model::EquilibriumOutputs& "
        "out) {\n";
  os << "  const Symbols s(in);\n";
  for (int i = 0; i < n; ++i) {
    const std::string row = std::to_string(i + 1);
    for (int j = 0; j < n; ++j) {
      const std::string q0 = model::is_flap_coordinate(j, m.M)
                                 ? "g0_" + std::to_string(j + 1)
                                 : "h0_" + std::to_string(j - m.M + 1);
      os << "  // S[" << row << "," << j + 1 << "]: " << m.equation_name(i)
         << " equation, coefficient of " << q0 << "\n";
      os << "  out.S[" << i * n + j << "] =\n"
         << kSlotIndent << slot_cpp(m, m.S[i * n + j], kSlotIndent) << ";\n";
    }
    os << "  // c[" << row << "]: " << m.equation_name(i) << " equation, hover load\n";
    os << "  out.c[" << i << "] =\n" << kSlotIndent << slot_cpp(m, m.c[i], kSlotIndent) << ";\n";
  }
  os << "}\n\n";
}

// The rotor thrust, linear in the state like the coefficients (cyclic-pitch models only).
void emit_thrust(std::ostringstream& os, const DerivedModel& m) {
  const int n = m.n();
  os << "// Rotor thrust of one blade, lr int L_z dx0 (the flap load of eq 2.20 with the same\n"
     << "// truncation), by harmonic h: out.forcing[h] + out.force[h*2n .. h*2n+2n) . y.\n"
     << "// C_T = (sigma a / 2) times its azimuth average.\n";
  os << "FLAPLAG_GENERATED_NO_UBSAN\n"
     << "void thrust(const model::CoefficientInputs& in, const model::CoefficientOutputs& "
        "out) {\n";
  os << "  const Symbols s(in);\n";
  for (int h = 0; h < m.H; ++h) {
    for (int col = 0; col < 2 * n; ++col) {
      const int idx = h * 2 * n + col;
      os << "  // thrust, " << DerivedModel::harmonic_name(h) << ": coefficient of "
         << m.state_name(col) << "\n";
      os << "  out.force[" << idx << "] =\n"
         << kSlotIndent << slot_cpp(m, m.thrust_force[idx], kSlotIndent) << ";\n";
    }
    os << "  // thrust, " << DerivedModel::harmonic_name(h) << ": state-independent\n";
    os << "  out.forcing[" << h << "] =\n"
       << kSlotIndent << slot_cpp(m, m.thrust_forcing[h], kSlotIndent) << ";\n";
  }
  os << "}\n\n";
}

// The accessor flaplag_model_<id>() of the model's descriptor (model_api.h ModelDescriptor).
void emit_descriptor(std::ostringstream& os, const DerivedModel& m, const std::string& id) {
  os << "const flaplag::model::ModelDescriptor& flaplag_model_" << id << "() {\n";
  os << "  namespace g = flaplag::generated::" << id << ";\n";
  os << "  static const flaplag::model::ModelDescriptor d = {\n"
     << "      " << c_string(m.spec.name) << ",\n"
     << "      " << c_string(m.spec.family) << ",\n"
     << "      " << c_string(m.spec.file) << ",\n"
     << "      g::kSpecText,\n"
     << "      " << c_string(m.spec.summary()) << ",\n"
     << "      " << m.M << ", " << m.N << ", " << m.H << ",\n"
     << "      " << m.aero.size() << ", g::kAero,\n"
     << "      " << m.structural.size() << ", g::kStructural,\n"
     << "      &g::mass,\n"
     << "      &g::coefficients,\n"
     << "      &g::equilibrium";
  // Trailing members of the descriptor (model_api.h), written only when they differ from
  // their defaults: the models without cyclic pitch or nonlinear loads stay byte-identical.
  if (m.spec.cyclic_pitch || m.spec.nonlinear)
    os << ",\n      " << (m.spec.cyclic_pitch ? "true" : "false") << ",\n      "
       << (m.spec.cyclic_pitch ? "&g::thrust" : "nullptr");
  if (m.spec.nonlinear) os << ",\n      " << m.H_nonlinear << ", &g::nonlinear";
  if (m.spec.nonlinear && m.spec.cyclic_pitch) os << ",\n      &g::nonlinear_thrust";
  os << "};\n";
  os << "  return d;\n}\n";
}

}  // namespace

std::string monomial_text(const DerivedModel& m, const std::vector<int>& powers) {
  std::string out;
  for (size_t c = 0; c < powers.size(); ++c) {
    if (powers[c] == 0) continue;
    std::string name = model::state_name(static_cast<int>(c), m.M, m.N).substr(1);  // no "d"
    if (powers[c] > 1) name += "^" + std::to_string(powers[c]);
    out += (out.empty() ? "" : " ") + name;
  }
  return out.empty() ? "1" : out;
}

std::string generated_header(const DerivedModel& m, const std::string& comment) {
  std::ostringstream os;
  os << comment << " Generated by flaplag-derive (generator/) from the ordering spec "
     << m.spec.file << " -- do not edit.\n"
     << comment << " Model " << m.spec.summary() << ".\n"
     << comment
     << " Refresh the checked-in copy with: cmake --build build --target refresh-generated\n";
  return os.str();
}

std::string model_ident(const std::string& name) {
  std::string id;
  for (char ch : name) id += (std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_');
  if (!id.empty() && std::isdigit(static_cast<unsigned char>(id[0]))) id = "m_" + id;
  return id;
}

std::string emit_cpp(const DerivedModel& m) {
  const std::string id = model_ident(m.spec.name);
  std::ostringstream os;
  emit_preamble(os, m);
  os << "namespace flaplag::generated::" << id << " {\nnamespace {\n\n";
  emit_tables(os, m);
  emit_mass(os, m);
  emit_symbols(os, m);
  emit_coefficients(os, m);
  emit_equilibrium(os, m);
  if (m.spec.cyclic_pitch) emit_thrust(os, m);
  if (m.spec.nonlinear) emit_nonlinear(os, m);
  if (m.spec.nonlinear && m.spec.cyclic_pitch) emit_nonlinear_thrust(os, m);
  os << "}  // namespace\n}  // namespace flaplag::generated::" << id << "\n\n";
  emit_descriptor(os, m, id);
  return os.str();
}

}  // namespace flaplag::derive
