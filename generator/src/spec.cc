#include "flaplag_derive/spec.h"

#include <toml++/toml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "flaplag_derive/paper_names.h"

namespace flaplag::derive {

namespace {

constexpr int kMaxInteger = 99;  // mode counts and orders: anything larger is a typo

std::string* description_of(OrderingSpec& s, const char*) { return &s.description; }
std::string* base_of(OrderingSpec& s, const char*) { return &s.base; }
int* modes_of(OrderingSpec& s, const char* key) {
  return std::string(key) == "flap" ? &s.flap_modes : &s.lag_modes;
}
int* order_of(OrderingSpec& s, const char* key) { return &s.orders[key]; }
int* kept_of(OrderingSpec& s, const char* key) {
  return std::string(key) == "flap" ? &s.kept_flap : &s.kept_lag;
}
bool* radial_flow_of(OrderingSpec& s, const char*) { return &s.radial_flow; }
bool* flap_radial_flow_of(OrderingSpec& s, const char*) { return &s.flap_terms.radial_flow; }
bool* lag_radial_flow_of(OrderingSpec& s, const char*) { return &s.lag_terms.radial_flow; }
std::string* flap_top_order_of(OrderingSpec& s, const char*) { return &s.flap_terms.top_order; }
std::string* lag_top_order_of(OrderingSpec& s, const char*) { return &s.lag_terms.top_order; }
std::vector<std::string>* excluded_of(OrderingSpec& s, const char*) { return &s.excluded; }
const std::vector<std::string>& top_order_choices() {
  static const std::vector<std::string> c = {"all", "damping"};
  return c;
}

std::string quoted_list(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + ('"' + x + '"');
  return s;
}

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
  std::string base = std::filesystem::path(file).filename().string();
  if (base.size() > 5 && base.compare(base.size() - 5, 5, ".toml") == 0) {
    base = base.substr(0, base.size() - 5);
  }
  return base;
}

std::string full_name(const SpecKey& k) {
  return *k.table ? std::string(k.table) + "." + k.name : std::string(k.name);
}

// Table names in the order of spec_keys(), "" (top level) first.
std::vector<std::string> tables() {
  std::vector<std::string> t;
  for (const auto& k : spec_keys()) {
    if (std::find(t.begin(), t.end(), k.table) == t.end()) t.emplace_back(k.table);
  }
  return t;
}

// "unknown key (expected a, b, c)" for one table, from spec_keys().
std::string unknown(const std::string& table) {
  const bool terms = table == "terms" || table.rfind("terms.", 0) == 0;
  const std::string what = table == "orders" ? "unknown symbol"
                           : terms           ? "unknown term class"
                                             : "unknown key";
  std::string expected;
  for (const auto& k : spec_keys()) {
    if (k.table != table) continue;
    expected += (expected.empty() ? "" : ", ") + std::string(k.name);
  }
  // the tables directly inside this one
  const std::string prefix = table.empty() ? "" : table + ".";
  for (const auto& t : tables()) {
    if (t.empty() || t.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string sub = t.substr(prefix.size());
    if (!sub.empty() && sub.find('.') == std::string::npos) {
      expected += (expected.empty() ? "" : ", ") + sub;
    }
  }
  return what + " (expected " + expected + ")";
}

const SpecKey* find_key(const std::string& table, const std::string& name) {
  for (const auto& k : spec_keys()) {
    if (k.table == table && k.name == name) return &k;
  }
  return nullptr;
}

void apply(const SpecKey& k, const toml::node& v, const std::string& file, OrderingSpec& spec) {
  const std::string key = full_name(k);
  switch (k.type) {
    case SpecKey::Type::Text: {
      const auto* s = v.as_string();
      if (s == nullptr) throw SpecError(file, key, node_text(v), "must be a string");
      if (k.choices != nullptr) {
        const auto& c = k.choices();
        if (std::find(c.begin(), c.end(), s->get()) == c.end()) {
          throw SpecError(file, key, node_text(v), "must be one of " + quoted_list(c));
        }
      }
      *k.text(spec, k.name) = s->get();
      return;
    }
    case SpecKey::Type::TextList: {
      const auto* a = v.as_array();
      if (a == nullptr) {
        throw SpecError(file, key, node_text(v), "must be a list of strings, e.g. [\"F23\"]");
      }
      std::vector<std::string> given;
      for (const auto& item : *a) {
        const auto* s = item.as_string();
        if (s == nullptr) throw SpecError(file, key, node_text(item), "must be a string");
        if (k.choices != nullptr) {
          const auto& c = k.choices();
          if (std::find(c.begin(), c.end(), s->get()) == c.end()) {
            std::string names;
            for (const auto& x : c) names += (names.empty() ? "" : ", ") + x;
            throw SpecError(file, key, node_text(item),
                            "no term of the derivation has this name (expected " + names + ")");
          }
        }
        given.push_back(s->get());
      }
      // Canonical: in the order of the accepted values, each once.
      std::vector<std::string> list;
      if (k.choices != nullptr) {
        for (const auto& x : k.choices()) {
          if (std::find(given.begin(), given.end(), x) != given.end()) list.push_back(x);
        }
      } else {
        list = given;
      }
      *k.list(spec, k.name) = list;
      return;
    }
    case SpecKey::Type::Integer: {
      const auto* i = v.as_integer();
      if (i == nullptr) throw SpecError(file, key, node_text(v), "must be an integer");
      const int64_t value = i->get();
      if (value < k.min_value) {
        std::string why = "must be >= " + std::to_string(k.min_value);
        if (k.min_reason != nullptr) why += " (" + std::string(k.min_reason) + ")";
        throw SpecError(file, key, node_text(v), why);
      }
      if (value > kMaxInteger) {
        throw SpecError(file, key, node_text(v), "must be <= " + std::to_string(kMaxInteger));
      }
      *k.integer(spec, k.name) = static_cast<int>(value);
      return;
    }
    case SpecKey::Type::Boolean: {
      const auto* b = v.as_boolean();
      if (b == nullptr) throw SpecError(file, key, node_text(v), "must be true or false");
      *k.boolean(spec, k.name) = b->get();
      return;
    }
  }
}

bool same_physics(OrderingSpec a, OrderingSpec b) {
  for (const auto& k : spec_keys()) {
    if (!k.physics) continue;
    switch (k.type) {
      case SpecKey::Type::Text:
        if (*k.text(a, k.name) != *k.text(b, k.name)) return false;
        break;
      case SpecKey::Type::Integer:
        if (*k.integer(a, k.name) != *k.integer(b, k.name)) return false;
        break;
      case SpecKey::Type::Boolean:
        if (*k.boolean(a, k.name) != *k.boolean(b, k.name)) return false;
        break;
      case SpecKey::Type::TextList:
        if (*k.list(a, k.name) != *k.list(b, k.name)) return false;
        break;
    }
  }
  return true;
}

bool plain_name(const std::string& s) {
  if (s.empty()) return false;
  return std::all_of(s.begin(), s.end(), [](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_';
  });
}

std::string read_text(const std::string& path, bool* ok) {
  std::ifstream in(path);
  *ok = static_cast<bool>(in);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The keys of [table] (and of the tables nested in it, e.g. [terms.lag]).
void apply_table(const std::string& table, const toml::node& v, const std::string& f,
                 OrderingSpec& spec) {
  const auto* t = v.as_table();
  if (t == nullptr) throw SpecError(f, table, node_text(v), "must be a table");
  const auto all = tables();
  for (const auto& [k2, v2] : *t) {
    const std::string name2(k2.str());
    const std::string full = table + "." + name2;
    if (table == "terms" && name2 == "cyclic_pitch") {
      throw SpecError(f, full, node_text(v2),
                      "no longer a spec key: every model has cyclic pitch and the rotor thrust");
    }
    if (const SpecKey* sk2 = find_key(table, name2)) {
      apply(*sk2, v2, f, spec);
    } else if (std::find(all.begin(), all.end(), full) != all.end()) {
      apply_table(full, v2, f, spec);
    } else {
      throw SpecError(f, full, node_text(v2), unknown(table));
    }
  }
}

// `chain`: the specs whose base is being resolved (leaf first), for the cycle check.
OrderingSpec parse_layer(const std::string& text, const std::string& file_label,
                         std::vector<std::string> chain) {
  const std::string f = std::filesystem::path(file_label).filename().string();
  const std::string name = stem_of(file_label);
  chain.push_back(name);

  toml::table root;
  try {
    root = toml::parse(text, file_label);
  } catch (const toml::parse_error& e) {
    std::ostringstream where;
    where << "line " << e.source().begin.line;
    throw SpecError(f, where.str(), "?",
                    std::string("malformed TOML: ") + std::string(e.description()));
  }

  // The base first: this file's keys override the resolved base spec.
  OrderingSpec spec = default_spec();
  OrderingSpec base_spec;
  std::string base;
  if (const toml::node* b = root.get("base")) {
    const SpecKey& k = *find_key("", "base");
    apply(k, *b, f, spec);
    base = spec.base;
    if (!plain_name(base)) {
      throw SpecError(f, "base", node_text(*b),
                      "must name a spec of the same directory or a shipped spec (letters, "
                      "digits, '-', '_'; no path, no .toml)");
    }
    if (std::find(chain.begin(), chain.end(), base) != chain.end()) {
      std::string cycle;
      for (const auto& c : chain) cycle += c + " -> ";
      throw SpecError(f, "base", node_text(*b), "inheritance cycle " + cycle + base);
    }
    // The spec's own directory first, then the shipped specs.
    std::filesystem::path base_path =
        std::filesystem::path(file_label).parent_path() / (base + ".toml");
    bool ok = false;
    std::string base_text = read_text(base_path.string(), &ok);
    if (!ok) {
      const std::filesystem::path own = base_path;
      base_path = std::filesystem::path(shipped_spec_dir()) / (base + ".toml");
      base_text = read_text(base_path.string(), &ok);
      if (!ok) {
        throw SpecError(f, "base", node_text(*b),
                        "no spec file " + own.string() + " nor " + base_path.string());
      }
    }
    base_spec = parse_layer(base_text, base_path.string(), chain);
    spec = base_spec;
  }
  spec.name = name;
  spec.file = f;
  spec.base = base;

  for (const auto& [k, v] : root) {
    const std::string key(k.str());
    if (key == "base") continue;
    if (const SpecKey* sk = find_key("", key)) {
      apply(*sk, v, f, spec);
      continue;
    }
    // Features of the tool, not physics: every model has them.
    if (key == "emit") {
      throw SpecError(f, key, node_text(v),
                      "no longer a spec key: every model has the nonlinear loads");
    }
    const auto t = tables();
    if (key.empty() || std::find(t.begin(), t.end(), key) == t.end()) {
      throw SpecError(f, key, node_text(v), unknown(""));
    }
    apply_table(key, v, f, spec);
  }
  spec.family = !base.empty() && same_physics(spec, base_spec) ? base_spec.family : spec.name;
  return spec;
}

}  // namespace

const std::vector<SpecKey>& spec_keys() {
  using T = SpecKey::Type;
  static const char* const kCoordinates = "generalized coordinates must be at least O(eps)";
  // Orders of the small quantities: paper Appendix C.1.
  static const std::vector<SpecKey> keys = {
      {"", "base", T::Text, 0, 0, nullptr, false, &base_of, nullptr, nullptr},
      {"", "description", T::Text, 0, 0, nullptr, false, &description_of, nullptr, nullptr},
      {"modes", "flap", T::Integer, 1, 1, nullptr, false, nullptr, &modes_of, nullptr},
      {"modes", "lag", T::Integer, 1, 1, nullptr, false, nullptr, &modes_of, nullptr},
      {"orders", "g", T::Integer, 1, 1, kCoordinates, true, nullptr, &order_of, nullptr},
      {"orders", "h", T::Integer, 1, 1, kCoordinates, true, nullptr, &order_of, nullptr},
      {"orders", "g_dot", T::Integer, 1, 1, kCoordinates, true, nullptr, &order_of, nullptr},
      {"orders", "h_dot", T::Integer, 1, 1, kCoordinates, true, nullptr, &order_of, nullptr},
      {"orders", "theta", T::Integer, 1, 0, nullptr, true, nullptr, &order_of, nullptr},
      {"orders", "inflow", T::Integer, 1, 0, nullptr, true, nullptr, &order_of, nullptr},
      {"orders", "precone", T::Integer, 1, 0, nullptr, true, nullptr, &order_of, nullptr},
      {"orders", "droop", T::Integer, 1, 0, nullptr, true, nullptr, &order_of, nullptr},
      {"orders", "cdo_a", T::Integer, 2, 0, nullptr, true, nullptr, &order_of, nullptr},
      // The advance ratio is O(1) in the paper; mu = 1 truncates its terms like the others.
      {"orders", "mu", T::Integer, 0, 0, nullptr, true, nullptr, &order_of, nullptr, true},
      {"kept", "flap", T::Integer, 2, 0, nullptr, true, nullptr, &kept_of, nullptr},
      {"kept", "lag", T::Integer, 3, 0, nullptr, true, nullptr, &kept_of, nullptr},
      {"terms", "radial_flow", T::Boolean, 1, 0, nullptr, true, nullptr, nullptr, &radial_flow_of},
      // Per equation (the flap load also gives the rotor thrust): the term classes above,
      // switched off for one equation only, and the rule for its O(eps^kept) terms.
      {"terms.flap", "radial_flow", T::Boolean, 1, 0, nullptr, true, nullptr, nullptr,
       &flap_radial_flow_of, true},
      {"terms.flap", "top_order", T::Text, 0, 0, nullptr, true, &flap_top_order_of, nullptr,
       nullptr, true, nullptr, &top_order_choices},
      {"terms.lag", "radial_flow", T::Boolean, 1, 0, nullptr, true, nullptr, nullptr,
       &lag_radial_flow_of, true},
      {"terms.lag", "top_order", T::Text, 0, 0, nullptr, true, &lag_top_order_of, nullptr, nullptr,
       true, nullptr, &top_order_choices},
      // Appendix B names of aerodynamic terms dropped from whichever equation has them.
      {"exclude", "terms", T::TextList, 0, 0, nullptr, true, nullptr, nullptr, nullptr, true,
       &excluded_of, &paper_aero_names},
  };
  return keys;
}

OrderingSpec default_spec() {
  OrderingSpec s;
  for (const auto& k : spec_keys()) {
    if (k.type == SpecKey::Type::Integer) *k.integer(s, k.name) = k.default_value;
    if (k.type == SpecKey::Type::Boolean) *k.boolean(s, k.name) = k.default_value != 0;
    if (k.type == SpecKey::Type::Text && k.choices != nullptr) {
      *k.text(s, k.name) = k.choices().front();
    }
    if (k.type == SpecKey::Type::TextList) k.list(s, k.name)->clear();
  }
  return s;
}

OrderingSpec parse_spec(const std::string& text, const std::string& file_label) {
  return parse_layer(text, file_label, {});
}

OrderingSpec load_spec(const std::string& path) {
  bool ok = false;
  const std::string text = read_text(path, &ok);
  if (!ok) throw SpecError(path, "file", "?", "cannot be read");
  return parse_spec(text, path);
}

namespace {

bool at_default(const SpecKey& k, OrderingSpec& s) {
  switch (k.type) {
    case SpecKey::Type::Text:
      return k.choices != nullptr && *k.text(s, k.name) == k.choices().front();
    case SpecKey::Type::Integer:
      return *k.integer(s, k.name) == k.default_value;
    case SpecKey::Type::Boolean:
      return *k.boolean(s, k.name) == (k.default_value != 0);
    case SpecKey::Type::TextList:
      return k.list(s, k.name)->empty();
  }
  return false;
}

}  // namespace

std::string shipped_spec_dir() { return FLAPLAG_SHIPPED_SPEC_DIR; }

std::string OrderingSpec::canonical_text() const {
  OrderingSpec self = *this;  // the accessors take a mutable spec
  std::ostringstream os;
  if (!base.empty()) {
    os << "# base = \"" << base << "\" (inherited values resolved below; model family \"" << family
       << "\")\n";
  }
  std::string table;
  for (const auto& k : spec_keys()) {
    if (std::string(k.name) == "base" && !*k.table) continue;
    if (k.omit_at_default && at_default(k, self)) continue;
    if (k.table != table) {
      table = k.table;
      os << "[" << table << "]\n";
    }
    os << k.name << " = ";
    switch (k.type) {
      case SpecKey::Type::Text:
        os << '"' << *k.text(self, k.name) << '"';
        break;
      case SpecKey::Type::Integer:
        os << *k.integer(self, k.name);
        break;
      case SpecKey::Type::Boolean:
        os << (*k.boolean(self, k.name) ? "true" : "false");
        break;
      case SpecKey::Type::TextList:
        os << "[" << quoted_list(*k.list(self, k.name)) << "]";
        break;
    }
    os << "\n";
  }
  return os.str();
}

std::string OrderingSpec::summary() const {
  std::ostringstream os;
  const bool any_radial = radial_flow_in(true) || radial_flow_in(false);
  os << name << ": " << flap_modes << " flap x " << lag_modes << " lag modes; flap loads to O(eps^"
     << kept_flap << "), lag loads to O(eps^" << kept_lag << "); radial flow "
     << (any_radial ? "on" : "off");
  // Only what differs from the paper's defaults, so that older summaries stay as they were.
  if (radial_flow_in(true) != radial_flow_in(false)) {
    os << " (" << (radial_flow_in(true) ? "flap" : "lag") << " equation only)";
  }
  if (order("mu") != 0) os << "; mu of O(eps^" << order("mu") << ")";
  for (const bool flap : {true, false}) {
    if (damping_only_at_top_order(flap)) {
      os << "; " << (flap ? "flap" : "lag") << " O(eps^" << (flap ? kept_flap : kept_lag)
         << ") terms: damping only";
    }
  }
  if (!excluded.empty()) {
    os << "; excluded";
    for (const auto& e : excluded) os << " " << e;
  }
  if (cyclic_pitch) os << "; cyclic pitch";
  if (nonlinear) os << "; nonlinear loads";
  return os.str();
}

}  // namespace flaplag::derive
