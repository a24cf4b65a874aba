#include "flaplag_derive/spec.h"

#include <toml++/toml.h>

#include <fstream>
#include <sstream>

namespace flaplag::derive {

namespace {

// Canonical order of the small quantities (Appendix C.1).
const char* const kOrderKeys[] = {"g",      "h",       "g_dot", "h_dot", "theta",
                                  "inflow", "precone", "droop", "cdo_a"};

std::string node_text(const toml::node& n) {
  std::ostringstream os;
  if (const auto* s = n.as_string()) {
    os << '"' << s->get() << '"';
  } else if (const auto* i = n.as_integer()) {
    os << i->get();
  } else if (const auto* f = n.as_floating_point()) {
    os << f->get();
  } else if (const auto* b = n.as_boolean()) {
    os << (b->get() ? "true" : "false");
  } else if (n.is_table()) {
    os << "(table)";
  } else if (n.is_array()) {
    os << "(array)";
  } else {
    os << "(value)";
  }
  return os.str();
}

std::string stem_of(const std::string& file) {
  std::string base = file;
  if (auto slash = base.find_last_of('/'); slash != std::string::npos)
    base = base.substr(slash + 1);
  if (base.size() > 5 && base.compare(base.size() - 5, 5, ".toml") == 0) {
    base = base.substr(0, base.size() - 5);
  }
  return base;
}

int read_int(const toml::node& n, const std::string& file, const std::string& key, int min_value) {
  const auto* i = n.as_integer();
  if (i == nullptr) {
    throw SpecError(file, key, node_text(n), "must be an integer");
  }
  const int64_t v = i->get();
  if (v < min_value) {
    throw SpecError(file, key, node_text(n), "must be >= " + std::to_string(min_value));
  }
  if (v > 99) throw SpecError(file, key, node_text(n), "must be <= 99");
  return static_cast<int>(v);
}

bool read_bool(const toml::node& n, const std::string& file, const std::string& key) {
  const auto* b = n.as_boolean();
  if (b == nullptr) throw SpecError(file, key, node_text(n), "must be true or false");
  return b->get();
}

const toml::table& read_table(const toml::node& n, const std::string& file,
                              const std::string& key) {
  const auto* t = n.as_table();
  if (t == nullptr) throw SpecError(file, key, node_text(n), "must be a table");
  return *t;
}

}  // namespace

const std::map<std::string, int>& default_orders() {
  static const std::map<std::string, int> m = {{"g", 1},       {"h", 1},     {"g_dot", 1},
                                               {"h_dot", 1},   {"theta", 1}, {"inflow", 1},
                                               {"precone", 1}, {"droop", 1}, {"cdo_a", 2}};
  return m;
}

OrderingSpec parse_spec(const std::string& text, const std::string& file_label) {
  OrderingSpec spec;
  spec.file = file_label;
  if (auto slash = spec.file.find_last_of('/'); slash != std::string::npos) {
    spec.file = spec.file.substr(slash + 1);
  }
  spec.name = stem_of(file_label);
  spec.orders = default_orders();
  const std::string& f = spec.file;

  toml::table root;
  try {
    root = toml::parse(text, file_label);
  } catch (const toml::parse_error& e) {
    std::ostringstream where;
    where << "line " << e.source().begin.line;
    throw SpecError(f, where.str(), "?",
                    std::string("malformed TOML: ") + std::string(e.description()));
  }

  for (const auto& [k, v] : root) {
    const std::string key(k.str());
    if (key == "description") {
      const auto* s = v.as_string();
      if (s == nullptr) throw SpecError(f, key, node_text(v), "must be a string");
      spec.description = s->get();
    } else if (key == "modes") {
      for (const auto& [mk, mv] : read_table(v, f, key)) {
        const std::string k2 = "modes." + std::string(mk.str());
        if (mk.str() == "flap") {
          spec.flap_modes = read_int(mv, f, k2, 1);
        } else if (mk.str() == "lag") {
          spec.lag_modes = read_int(mv, f, k2, 1);
        } else {
          throw SpecError(f, k2, node_text(mv), "unknown key (expected flap, lag)");
        }
      }
    } else if (key == "orders") {
      for (const auto& [ok, ov] : read_table(v, f, key)) {
        const std::string name(ok.str());
        const std::string k2 = "orders." + name;
        if (spec.orders.count(name) == 0) {
          throw SpecError(f, k2, node_text(ov),
                          "unknown symbol (expected g, h, g_dot, h_dot, theta, inflow, precone, "
                          "droop, cdo_a)");
        }
        spec.orders[name] = read_int(ov, f, k2, 0);
      }
    } else if (key == "kept") {
      for (const auto& [kk, kv] : read_table(v, f, key)) {
        const std::string k2 = "kept." + std::string(kk.str());
        if (kk.str() == "flap") {
          spec.kept_flap = read_int(kv, f, k2, 0);
        } else if (kk.str() == "lag") {
          spec.kept_lag = read_int(kv, f, k2, 0);
        } else {
          throw SpecError(f, k2, node_text(kv), "unknown key (expected flap, lag)");
        }
      }
    } else if (key == "terms") {
      for (const auto& [tk, tv] : read_table(v, f, key)) {
        const std::string k2 = "terms." + std::string(tk.str());
        if (tk.str() == "radial_flow") {
          spec.radial_flow = read_bool(tv, f, k2);
        } else {
          throw SpecError(f, k2, node_text(tv), "unknown term class (expected radial_flow)");
        }
      }
    } else {
      throw SpecError(f, key, node_text(v),
                      "unknown key (expected description, modes, orders, kept, terms)");
    }
  }
  // Displacements and their rates must be small, or the linearization is meaningless.
  for (const char* k : {"g", "h", "g_dot", "h_dot"}) {
    if (spec.orders[k] < 1) {
      throw SpecError(f, std::string("orders.") + k, std::to_string(spec.orders[k]),
                      "generalized coordinates must be at least O(eps)");
    }
  }
  return spec;
}

OrderingSpec load_spec(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw SpecError(path, "file", "?", "cannot be read");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_spec(ss.str(), path);
}

std::string OrderingSpec::canonical_text() const {
  std::ostringstream os;
  os << "description = \"" << description << "\"\n";
  os << "[modes]\nflap = " << flap_modes << "\nlag = " << lag_modes << "\n";
  os << "[orders]\n";
  for (const char* k : kOrderKeys) os << k << " = " << orders.at(k) << "\n";
  os << "[kept]\nflap = " << kept_flap << "\nlag = " << kept_lag << "\n";
  os << "[terms]\nradial_flow = " << (radial_flow ? "true" : "false") << "\n";
  return os.str();
}

std::string OrderingSpec::summary() const {
  std::ostringstream os;
  os << name << ": " << flap_modes << " flap x " << lag_modes << " lag modes; flap loads to O(eps^"
     << kept_flap << "), lag loads to O(eps^" << kept_lag << "); radial flow "
     << (radial_flow ? "on" : "off");
  return os.str();
}

}  // namespace flaplag::derive
