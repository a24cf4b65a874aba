// flaplag — the contract between generated model code and the runtime.
//
// The generator (generator/, GiNaC, build time) writes one translation unit per ordering spec
// that fills a ModelFamily (any M x N; instantiate() makes its ModelDescriptor for given mode
// counts).  Everything the generated code needs comes in through
// CoefficientInputs; everything it computes goes out through plain arrays, so the generated
// code depends on nothing but this header.
//
// Nondimensionalisation (paper, list of symbols): lengths associated with aerodynamics by R,
// elastic ones by l; frequencies by Omega; masses by I_b (blade inertia about the root);
// psi = Omega t, period 2*pi.  Generalized coordinates g_k (flap), h_m (lag) are the modal
// amplitudes of eqs 2.11-2.12 (w_e = l eta_k g_k, v_e = -l gamma_m h_m: h > 0 is lag).
//
// State ordering (eq 2.36 generalised to M flap and N lag modes):
//   y = [dg'_1..dg'_M, dg_1..dg_M, dh'_1..dh'_N, dh_1..dh_N]     (' = d/dpsi, d = Delta)
// Equation ordering (rows of the generalized force): flap 1..M, then lag 1..N.
// The functions below are the one place this ordering is written down.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace flaplag::model {

// ----- state and equation ordering (all indices 0-based; k: flap mode, m: lag mode) ----------

constexpr int state_count(int M, int N) { return 2 * (M + N); }
constexpr int flap_rate_index(int k, int /*M*/, int /*N*/) { return k; }             // dg'_k
constexpr int flap_displacement_index(int k, int M, int /*N*/) { return M + k; }     // dg_k
constexpr int lag_rate_index(int m, int M, int /*N*/) { return 2 * M + m; }          // dh'_m
constexpr int lag_displacement_index(int m, int M, int N) { return 2 * M + N + m; }  // dh_m

// Generalized coordinate j of q = [g_1..g_M, h_1..h_N] (also the equation / mass row j).
constexpr bool is_flap_coordinate(int j, int M) { return j < M; }
constexpr int rate_index(int j, int M, int N) {
  return j < M ? flap_rate_index(j, M, N) : lag_rate_index(j - M, M, N);
}
constexpr int displacement_index(int j, int M, int N) {
  return j < M ? flap_displacement_index(j, M, N) : lag_displacement_index(j - M, M, N);
}
constexpr int flap_equation_index(int k, int /*M*/) { return k; }
constexpr int lag_equation_index(int m, int M) { return M + m; }

// What state column col holds.
enum class Direction : int { Flap = 0, Lag = 1 };
// The directions, in state order; per-direction data (CoefficientInputs, ModeSet) is indexed by
// index(d).
inline constexpr int kDirectionCount = 2;
inline constexpr Direction kDirections[kDirectionCount] = {Direction::Flap, Direction::Lag};
constexpr int index(Direction d) { return static_cast<int>(d); }
struct StateRef {
  Direction direction;
  int mode;   // 0-based mode of that direction
  bool rate;  // true: dg'_k / dh'_m, false: dg_k / dh_m
};
constexpr StateRef state_ref(int col, int M, int N) {
  return col < M           ? StateRef{Direction::Flap, col, true}
         : col < 2 * M     ? StateRef{Direction::Flap, col - M, false}
         : col < 2 * M + N ? StateRef{Direction::Lag, col - 2 * M, true}
                           : StateRef{Direction::Lag, col - 2 * M - N, false};
}
// The coordinate (equation row) a state column belongs to.
constexpr int coordinate_of_state(int col, int M, int N) {
  return state_ref(col, M, N).direction == Direction::Flap ? state_ref(col, M, N).mode
                                                           : M + state_ref(col, M, N).mode;
}

// The blade directions of the state, in state order, as data: the state is, direction after
// direction, its mode rates and then its mode displacements (eq 2.36 for one mode each).  Code
// that handles every direction alike loops over these instead of naming flap and lag.
struct DirectionBlock {
  Direction direction;
  const char* name;        // "flap", "lag": mode labels and result keys
  const char* coordinate;  // "g", "h": the generalized coordinates (eqs 2.13-2.15)
  const char* deflection;  // "w", "v": the displacement it bends the blade by (eq 2.12)
  const char* shape;       // "eta", "gamma": its mode shapes (eqs 2.11-2.12)
  int modes;               // M, N
  int first_state;         // the state column of its first rate
  int first_coordinate;    // its first coordinate j of q (and equation row)
  int rate_index(int k) const { return first_state + k; }
  int displacement_index(int k) const { return first_state + modes + k; }
};
// The directions' names, in state order.
inline constexpr const char* kDirectionNames[] = {"flap", "lag"};
inline std::vector<DirectionBlock> direction_blocks(int M, int N) {
  return {{Direction::Flap, kDirectionNames[0], "g", "w", "eta", M, flap_rate_index(0, M, N), 0},
          {Direction::Lag, kDirectionNames[1], "h", "v", "gamma", N, lag_rate_index(0, M, N), M}};
}

// The label of mode k (1-based) of a direction, one scheme for every model: the first mode is the
// direction's name ("flap", "lag"), mode k > 1 adds its number ("flap2").  A 1 x 1 model's "lag"
// and a 3 x 3 model's "lag" are the same mode.
inline std::string mode_label(const std::string& direction, int k) {
  return k == 1 ? direction : direction + std::to_string(k);
}
// The direction name and mode number of a label: "lag" -> ("lag", 1), "flap2" -> ("flap", 2);
// "lag1" (the spelling of result files written before the one scheme) is mode 1 too.  False when
// the label is none of these (a name that is no direction, a number 0, leading zeros or more
// than three digits).
inline bool parse_mode_label(const std::string& label, std::string* direction, int* k) {
  for (const char* name : kDirectionNames) {
    const std::string base = name;
    if (label.compare(0, base.size(), base) != 0) continue;
    const std::string digits = label.substr(base.size());
    if (digits.empty()) {
      *direction = base;
      *k = 1;
      return true;
    }
    if (digits.size() > 3 || digits[0] == '0') return false;
    for (char c : digits)
      if (c < '0' || c > '9') return false;
    *direction = base;
    *k = std::stoi(digits);
    return true;
  }
  return false;
}

// Name of state column col: "dg1'", "dg1", "dh1'", "dh1" (1-based mode numbers).
inline std::string state_name(int col, int M, int N) {
  const StateRef s = state_ref(col, M, N);
  return std::string(s.direction == Direction::Flap ? "dg" : "dh") + std::to_string(s.mode + 1) +
         (s.rate ? "'" : "");
}

// Spanwise functions that can appear in an integrand.  Derivatives are d/d(x0bar).
enum class Factor : int {
  Eta = 0,         // eta_k(x0)          flap mode shape
  EtaPrime = 1,    // eta_k'(x0)
  Gamma = 2,       // gamma_m(x0)        lag mode shape
  GammaPrime = 3,  // gamma_m'(x0)
  X0 = 4,          // x0bar              (structural integrals only; mode ignored)
  Arm = 5,         // x0bar + e1/l       centrifugal arm (structural integrals only; mode ignored)
  Twist = 6,       // theta_tw(x0) [rad] built-in twist (aerodynamic integrals only; mode ignored):
                   // the section pitch of eqs 2.20-2.21 is theta + theta_tw(x0) (+ cyclic), so
                   // every theta term has a twin with theta replaced by this factor; 0 for the
                   // paper's untwisted blade (ModeSet::blade null)
};

// Whether a factor is a mode shape (its FactorRef::mode counts) or a function of x0 alone.
constexpr bool has_mode(Factor k) {
  return k != Factor::X0 && k != Factor::Arm && k != Factor::Twist;
}

// Largest number of spanwise factors in one integrand (outer or inner): the generator stops
// with an error if a derivation needs more.
constexpr int kMaxFactors = 4;

struct FactorRef {
  Factor kind;
  int mode;  // 0-based mode index (flap mode for Eta*, lag mode for Gamma*), 0 for X0/Arm/Twist
};

// Aerodynamic spanwise integral  I = int x^p * prod(factors) dx0bar  over the aerodynamic span
// (tip-loss limits A..B, split at x = mu in the reversed-flow sector, Appendix D), where
// x = e1/R + (l/R) x0bar is the station radius by R.
struct AeroIntegral {
  const char* name;   // canonical, e.g. "x^2 eta1 eta1'"
  const char* ident;  // C identifier form, e.g. "x2_eta1_deta1"
  int x_power;
  int n_factors;
  FactorRef factors[kMaxFactors];
  const char* paper_name;  // Appendix B name, e.g. "F6_11", or "" when the paper has none
};

// Structural (inertial) generalized mass, nondimensionalised by I_b:
//   I = int_0^1 mbar^outer_mass * prod(outer)(x) * J(x) dx0bar,
//   J(x) = 1                                              (inner == None)
//        = int_x^1 mbar^inner_mass * prod(inner)(x1) dx1   (inner == Tail: tension integrals)
//        = int_0^x mbar^inner_mass * prod(inner)(x1) dx1   (inner == Head: foreshortening u)
// mbar = m l^3 / I_b (= 3 for a uniform blade with e1 = 0).
enum class Inner : int { None = 0, Tail = 1, Head = 2 };

struct StructuralIntegral {
  const char* name;   // canonical, e.g. "int eta1' eta1' [int_x^1 m gamma1]"
  const char* ident;  // C identifier form
  int outer_mass;
  int n_outer;
  FactorRef outer[kMaxFactors];
  Inner inner;
  int inner_mass;
  int n_inner;
  FactorRef inner_factors[kMaxFactors];
  const char* paper_name;  // Appendix B name ("B3_11", "P_111", "M_F1", ...) or ""
};

// Inputs of the generated coefficient functions.  Arrays are row-major.  The data of the blade
// directions is given per direction, indexed by index(d) (state order: flap, lag), each with
// modes[index(d)] entries (M, N).
struct CoefficientInputs {
  double lock;     // gamma, Lock number (normal flow)
  double lr;       // l/R
  double theta;    // collective pitch [rad]
  double inflow;   // lambda, positive down, by Omega R
  double precone;  // beta_P [rad]
  double droop;    // beta_D [rad]
  double cdo_a;    // C_Do / a
  double mu;       // advance ratio
  // Per direction: hover static amplitudes (g0, h0), rotating frequencies by Omega, viscous
  // structural damping ratios (eta_SF, eta_SL).
  const double* q0[kDirectionCount];
  const double* omega[kDirectionCount];
  const double* damping[kDirectionCount];
  // Elastic coupling (Appendix E) per pair of directions: elastic[r][c], [modes[r] * modes[c]],
  // row: a mode of direction r's equations, column: a mode of direction c.  (flap, flap)
  // Ebar^s_ik (eq E.5), (flap, lag) Ebar^cs_im (eq E.6), (lag, flap) Ebar^cs_ik (eq E.8),
  // (lag, lag) Ebar^s_im (eq E.7).
  const double* elastic[kDirectionCount][kDirectionCount];
  const double* aero;        // [n_aero] values of the AeroIntegral list, for one flow region
  const double* structural;  // [n_structural] values of the StructuralIntegral list
  // Cyclic pitch [rad]: theta(psi) = theta + theta1c cos psi + theta1s sin psi.
  double theta1c;
  double theta1s;
  // Mode counts per direction (M, N): read by the functions of a ModelFamily (instantiate()
  // descriptors).
  int modes[kDirectionCount];
  // The model's ModelDescriptor::context (SystemBuilder copies it): the data of a family made at
  // run time, nullptr for a compiled one (which never reads it).
  const void* context = nullptr;
};

// Outputs.  n = M + N equations, 2n states, H harmonics.
// Harmonic index h: 0 -> 1 (constant), 2k-1 -> cos(k psi), 2k -> sin(k psi).
// The equations of motion are  mass * q'' = sum_h phi_h(psi) (force[h] * y + forcing[h]),
// with the generalized mass from ModelDescriptor::mass.  A function writes every entry of its
// outputs (the caller need not clear them).
struct CoefficientOutputs {
  double* force;    // [H*n*2n]  linear coefficient of the state y in the generalized force
  double* forcing;  // [H*n]     state-independent part (evaluated at g0, h0; includes hover load)
};

// Hover static equilibrium (eqs 2.27-2.32): S * q0 = c, q0 = [g0_1..g0_M, h0_1..h0_N].
struct EquilibriumOutputs {
  double* S;  // [n*n]
  double* c;  // [n]
};

// Nonlinear generalized loads.  The
// argument y is the *full* state [g'_1..g'_M, g_1..g_M, h'_1..h'_N, h_1..h_N] (the ordering
// above, but absolute values: the hover amplitudes in.q0 are not read), and
//   mass * q'' = sum_h phi_h(psi) force[h](y)
// with the same mass, harmonics and flow-region integrals (in.aero) as the linear functions.
// The polynomials keep every product of the coordinates that the ordering keeps (the eps_D
// truncation of each load product), so that their Jacobian at y = (0, q0) equals the linear
// `force` and their value there the linear `forcing`.
struct NonlinearOutputs {
  double* force;     // [H_nl*n]     generalized force at y, per harmonic and equation
  double* jacobian;  // [H_nl*n*2n]  d force / d y (row-major per harmonic: equation, state)
};

// One model: a family (below) instantiated for M x N modes (instantiate()).  Every function is
// set: each model has cyclic pitch, the rotor thrust and the nonlinear loads.
struct ModelDescriptor {
  const char* name;  // model name, e.g. "paper" or "paper-2x2"
  // Model family (ordering spec), e.g. "paper" for paper, paper-2x1, paper-2x2: the models of
  // one family differ only in their mode counts, so a model is (base, flap_modes, lag_modes).
  const char* base;
  const char* spec_file;  // spec file name, e.g. "paper.toml"
  const char* spec_text;  // the resolved spec (canonical TOML; a comment line names its base)
  const char* summary;    // one line: orders, term classes, modes
  int flap_modes;         // M
  int lag_modes;          // N
  int n_harmonics;        // H
  int n_aero;
  const AeroIntegral* aero;
  int n_structural;
  const StructuralIntegral* structural;
  // Generalized mass matrix [n*n], row-major (equation row, coordinate column of q''): the
  // inertia of the modal accelerations.  Reads in.structural only (no mu, no hover state), so
  // the runtime evaluates and factors it once per blade.
  void (*mass)(const CoefficientInputs& in, double* mass);
  void (*coefficients)(const CoefficientInputs&, const CoefficientOutputs&);
  void (*equilibrium)(const CoefficientInputs&, const EquilibriumOutputs&);
  // Rotor thrust of one blade, T = (l/R) int L_z dx0 over the aerodynamic span with the flap
  // load L_z of the derivation (eq 2.20, same eps truncation, linear in the state), as
  // harmonics: T(psi) = sum_h phi_h(psi) (out.forcing[h] + sum_c out.force[h*2n + c] y_c).
  // out.forcing has H entries, out.force H*2n.  C_T = (sigma a / 2) * mean over psi of T.
  void (*thrust)(const CoefficientInputs&, const CoefficientOutputs&);
  // Nonlinear loads (see NonlinearOutputs), H_nl harmonics.
  int n_nonlinear_harmonics;
  void (*nonlinear)(const CoefficientInputs& in, const double* y, const NonlinearOutputs& out);
  // The rotor thrust of one blade (`thrust`'s load, without its linearization) at the full
  // state y, T(psi) = sum_h phi_h(psi) out.force[h](y), H_nl harmonics; out.force has H_nl
  // entries, out.jacobian H_nl*2n.  For the trim about the periodic equilibrium.
  void (*nonlinear_thrust)(const CoefficientInputs& in, const double* y,
                           const NonlinearOutputs& out);
  // ModelFamily::context: every caller of the functions above passes it in
  // CoefficientInputs::context.
  const void* context = nullptr;
  // The first n_linear_aero entries of `aero` hold every integral that mass, coefficients and
  // equilibrium read (ModelFamily::n_linear_aero); 0: not known, all of them.
  int n_linear_aero = 0;
};

// ----- model families: one per ordering spec, for any number of modes ----------------------
//
// The generator derives a spec once with variable mode indices (a term of the flap equation of
// mode i is a coefficient times an integral such as int eta_i eta_k' gamma_j' dx0, summed over
// k).  A family's functions assemble the outputs above for the M x N given in
// CoefficientInputs::modes from integral *tensors*: each template below is
// evaluated for every assignment of its mode variables, and instantiate() lists those concrete
// integrals in the order the functions read them (template by template, each row-major over
// its variables, variable 0 slowest, a flap variable ranging over M modes and a lag one over N).

// A spanwise integral whose factors carry template variables (FactorRef::mode = variable,
// 0 for X0/Arm/Twist).  Aerodynamic: x^x_power prod(factors).  Structural: as StructuralIntegral,
// with factors the outer factors.
struct IntegralTemplate {
  const char* name;   // e.g. "x eta_a eta_b'" (letters a, b, c, d name the variables)
  const char* ident;  // C identifier form
  int n_vars;
  Direction var_dirs[kMaxFactors];
  int x_power;
  int outer_mass;
  int n_factors;
  FactorRef factors[kMaxFactors];
  Inner inner;
  int inner_mass;
  int n_inner;
  FactorRef inner_factors[kMaxFactors];
  const char* paper_name;  // Appendix B name with the letters, e.g. "F6_ab", or ""
};

// Concrete integrals of a template: prod over its variables of M or N.
inline int template_size(const IntegralTemplate& t, int M, int N) {
  int size = 1;
  for (int v = 0; v < t.n_vars; ++v) size *= t.var_dirs[v] == Direction::Flap ? M : N;
  return size;
}

// Read access to the integral tensors of a list of templates (what the generated code uses).
class TemplateTensors {
 public:
  TemplateTensors(const IntegralTemplate* t, int count, const double* values, int M, int N)
      : values_(values), entries_(static_cast<std::size_t>(count)) {
    int offset = 0;
    for (int j = 0; j < count; ++j) {
      Entry& e = entries_[static_cast<std::size_t>(j)];
      e.offset = offset;
      int stride = 1;
      for (int v = t[j].n_vars - 1; v >= 0; --v) {
        e.stride[v] = stride;
        stride *= t[j].var_dirs[v] == Direction::Flap ? M : N;
      }
      offset += stride;
    }
  }
  double operator()(int t, int a = 0, int b = 0, int c = 0, int d = 0) const {
    const Entry& e = entries_[static_cast<std::size_t>(t)];
    return values_[e.offset + a * e.stride[0] + b * e.stride[1] + c * e.stride[2] +
                   d * e.stride[3]];
  }

 private:
  struct Entry {
    int offset = 0;
    int stride[kMaxFactors] = {0, 0, 0, 0};
  };
  const double* values_;
  std::vector<Entry> entries_;
};

// The same read access for the 1 x 1 blade, where every template has one entry, at its own
// index (the strides and offsets of TemplateTensors are not needed): the generated code's
// compile-time 1 x 1 instance reads the same values without computing them on every call.
class UnitTensors {
 public:
  UnitTensors(const IntegralTemplate*, int, const double* values, int M, int N) : values_(values) {
    if (M != 1 || N != 1) throw std::logic_error("UnitTensors: a 1 x 1 blade only");
  }
  double operator()(int t, int = 0, int = 0, int = 0, int = 0) const { return values_[t]; }

 private:
  const double* values_;
};

struct ModelFamily {
  const char* name;        // spec name, e.g. "paper"
  const char* spec_file;   // e.g. "paper.toml"
  const char* spec_text;   // the resolved spec (canonical TOML)
  const char* summary;     // orders and term classes (no mode counts)
  int default_flap_modes;  // the spec's [modes]
  int default_lag_modes;
  int n_harmonics;            // H
  int n_nonlinear_harmonics;  // H_nl
  int n_aero;
  const IntegralTemplate* aero;
  int n_structural;
  const IntegralTemplate* structural;
  // As in ModelDescriptor, for the M x N of in.modes.
  void (*mass)(const CoefficientInputs& in, double* mass);
  void (*coefficients)(const CoefficientInputs&, const CoefficientOutputs&);
  void (*equilibrium)(const CoefficientInputs&, const EquilibriumOutputs&);
  void (*thrust)(const CoefficientInputs&, const CoefficientOutputs&);
  void (*nonlinear)(const CoefficientInputs& in, const double* y, const NonlinearOutputs& out);
  void (*nonlinear_thrust)(const CoefficientInputs& in, const double* y,
                           const NonlinearOutputs& out);
  // What the functions of a family made at run time read (they are plain function pointers):
  // instantiate() copies it into ModelDescriptor::context, the caller into
  // CoefficientInputs::context.  nullptr for a compiled family.
  const void* context = nullptr;
  // The first n_linear_aero templates of `aero` hold every integral that mass, coefficients and
  // equilibrium read (thrust and the nonlinear loads read the rest): a caller that builds only
  // the linear system may leave the others out.
  int n_linear_aero = 0;
};

// The largest mode count per direction a family is instantiated for (the Galerkin basis of the
// exact rotating modes).
constexpr int kMaxModes = 12;

// All model families compiled into this build (generated registry), in spec-file order.
std::vector<const ModelFamily*> compiled_families();

// Adds a family made at run time (an ordering spec derived in-process by the CLI's or the
// Python module's --spec): registered_families() lists it after the compiled ones.  f must live
// for the rest of the program.  Throws std::invalid_argument when a family of that name exists.
// Thread-safe.
void register_family(const ModelFamily& f);

// The compiled families, then those registered at run time (in registration order).
std::vector<const ModelFamily*> registered_families();

// The descriptor of family f for M flap x N lag modes (1 <= M, N <= kMaxModes): named f.name
// when M x N is the spec's [modes], else "<name>-<M>x<N>"; its integral lists are the templates'
// concrete integrals.  Made once per (family, M, N) and kept for the life of the program;
// thread-safe.  Throws std::invalid_argument for mode counts out of range.
const ModelDescriptor& instantiate(const ModelFamily& f, int M, int N);

// All models compiled into this build (generated registry), in spec-file order: each compiled
// family at its spec's mode counts.
std::vector<const ModelDescriptor*> registered_models();

}  // namespace flaplag::model
