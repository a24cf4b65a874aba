// flaplag-derive — the ordering spec: which small quantities have which eps_D order, which order
// is kept in each equation, which term classes are switched on, how many modes.
//
// One spec file = one model.  The model name is the file name without ".toml".  A spec may
// inherit from another spec (`base = "paper"`, looked up in the spec's own directory, then among
// the shipped specs, shipped_spec_dir()): it starts from the resolved base spec and overrides
// the keys it gives, so that variants (e.g. the paper ordering with more modes) cannot drift
// from their base.  Every key is declared once, in spec_keys().
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace flaplag::derive {

// A bad spec: carries file, key and value so the build log points at the offending line.
class SpecError : public std::runtime_error {
 public:
  SpecError(const std::string& file, const std::string& key, const std::string& value,
            const std::string& reason)
      : std::runtime_error(file + ": " + key + " = " + value + ": " + reason) {}
};

// Construct with default_spec(), load_spec() or parse_spec(): the defaults live in spec_keys().
struct OrderingSpec {
  std::string name;  // model name (file stem)
  std::string file;  // file name (no directory: generated output must not embed paths)
  std::string base;  // the spec this one inherits from (`base` key), "" when none
  // Model family: specs that differ only in their mode counts (and description) form one family,
  // named after its root spec.  = base's family when this spec changes nothing but [modes] and
  // description; otherwise its own name.  The runtime looks models up by (family, M, N).
  std::string family;
  std::string description;
  int flap_modes = 0;  // M
  int lag_modes = 0;   // N
  // eps_D order of each small quantity (paper Appendix C.1); keys as in spec_keys() ([orders]).
  std::map<std::string, int> orders;
  int kept_flap = 0;         // highest eps order kept in the flap aerodynamic load
  int kept_lag = 0;          // ... in the lag aerodynamic load
  bool radial_flow = false;  // the mu cos(psi) dv/dx0 term of U_T (eq 2.23), both equations
  // Term classes of one equation's aerodynamic load ([terms.flap], [terms.lag]).  A class is
  // kept in an equation when it is on both for the spec ([terms]) and for that equation.
  struct EquationTerms {
    bool radial_flow = true;
    // Of the terms of the equation's highest kept order (O(eps^kept)): "all", or "damping" =
    // only those that multiply a state rate g'_k or h'_m (the aerodynamic damping).
    std::string top_order = "all";
  };
  EquationTerms flap_terms, lag_terms;
  // Appendix B names (without mode subscripts, e.g. "F23", "L13") of the aerodynamic terms
  // dropped from the equations ([exclude] terms); in the order of paper_aero_names(), no repeats.
  std::vector<std::string> excluded;
  // Derivation switches (not spec keys: every model family has both, extract_generic() and
  // the generator turn them on).  cyclic_pitch: theta(psi) = theta + theta1c cos psi +
  // theta1s sin psi in the aerodynamic loads (eqs 2.20-2.21), theta1c and theta1s of theta's
  // eps order, and the rotor thrust.  nonlinear: also the nonlinear generalized loads as
  // polynomials in the full state (not linearized about hover), for the periodic equilibrium.
  bool cyclic_pitch = false;
  bool nonlinear = false;

  int order(const std::string& key) const { return orders.at(key); }
  // Radial flow and the top-order rule of the flap (flap = true) or lag equation's load.
  bool radial_flow_in(bool flap) const {
    return radial_flow && (flap ? flap_terms : lag_terms).radial_flow;
  }
  bool damping_only_at_top_order(bool flap) const {
    return (flap ? flap_terms : lag_terms).top_order == "damping";
  }
  // Canonical TOML text of the resolved spec (what the generated code records).
  std::string canonical_text() const;
  // One-line summary.
  std::string summary() const;
};

// One key of the spec format.  spec_keys() is the single list: parsing, defaults, the "expected
// ..." lists of error messages, the family rule and the canonical text all read it.
struct SpecKey {
  enum class Type { Text, Integer, Boolean, TextList };
  const char* table;  // "" for a top-level key, else the [table] it belongs to
  const char* name;
  Type type;
  int default_value;       // Integer and Boolean (0/1) keys
  int min_value;           // Integer keys: smallest accepted value (the largest is 99)
  const char* min_reason;  // why min_value (nullptr: none given)
  bool physics;            // part of the equations (false: description, mode counts)
  // Where the value lives (the one matching `type` is set; the key name is passed in).
  std::string* (*text)(OrderingSpec&, const char* name);
  int* (*integer)(OrderingSpec&, const char* name);
  bool* (*boolean)(OrderingSpec&, const char* name);
  // Keys added after models were shipped: written into the canonical text only when they
  // differ from their default, so the recorded text (and generated code) of every older spec
  // stays byte-identical.
  bool omit_at_default = false;
  std::vector<std::string>* (*list)(OrderingSpec&, const char* name) = nullptr;  // TextList
  // The accepted values of a Text key (the first is its default) or of the items of a TextList
  // key (default: empty list); nullptr: any text.
  const std::vector<std::string>& (*choices)() = nullptr;
};
const std::vector<SpecKey>& spec_keys();

// A spec with every key at its default (the paper's ordering, one mode each).
OrderingSpec default_spec();

// The directory of the shipped specs (generator/orderings of the source tree), where a `base`
// not found next to the spec is looked up.
std::string shipped_spec_dir();

// Parse a spec file; throws SpecError.  A `base` is looked up in the same directory, then in
// shipped_spec_dir().
OrderingSpec load_spec(const std::string& path);
// Parse spec text (file_label is used in messages and as OrderingSpec::file; a `base` is looked
// up in file_label's directory, then in shipped_spec_dir()).
OrderingSpec parse_spec(const std::string& text, const std::string& file_label);

}  // namespace flaplag::derive
