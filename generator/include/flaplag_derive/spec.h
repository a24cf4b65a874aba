// flaplag-derive — the ordering spec: which small quantities have which eps_D order, which order
// is kept in each equation, which term classes are switched on, how many modes.
//
// One spec file = one model.  The model name is the file name without ".toml".
#pragma once

#include <map>
#include <stdexcept>
#include <string>

namespace flaplag::derive {

// A bad spec: carries file, key and value so the build log points at the offending line.
class SpecError : public std::runtime_error {
 public:
  SpecError(const std::string& file, const std::string& key, const std::string& value,
            const std::string& reason)
      : std::runtime_error(file + ": " + key + " = " + value + ": " + reason) {}
};

struct OrderingSpec {
  std::string name;  // model name (file stem)
  std::string file;  // file name (no directory: generated output must not embed paths)
  std::string description;
  int flap_modes = 1;  // M
  int lag_modes = 1;   // N
  // eps_D order of each small quantity (paper Appendix C.1).  Keys: g, h, g_dot, h_dot, theta,
  // inflow, precone, droop, cdo_a.
  std::map<std::string, int> orders;
  int kept_flap = 2;        // highest eps order kept in the flap aerodynamic load
  int kept_lag = 3;         // ... in the lag aerodynamic load
  bool radial_flow = true;  // the mu cos(psi) dv/dx0 term of U_T (eq 2.23)

  int order(const std::string& key) const { return orders.at(key); }
  // Canonical TOML text of the spec (what the generated code records).
  std::string canonical_text() const;
  // One-line summary.
  std::string summary() const;
};

// The small quantities and their paper orders, in canonical order.
const std::map<std::string, int>& default_orders();

// Parse a spec file; throws SpecError.
OrderingSpec load_spec(const std::string& path);
// Parse spec text (file_label is used in messages and as OrderingSpec::file).
OrderingSpec parse_spec(const std::string& text, const std::string& file_label);

}  // namespace flaplag::derive
