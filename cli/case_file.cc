// flaplag CLI — case files (TOML, or the "case" object of a JSON output) to arguments.
#include "case_file.h"

#include <toml++/toml.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/rotor/parameter_table.h"
#include "options.h"

namespace flaplag::cli {
namespace {

// The tables a case file may use to group its keys.
const char* const kGroups[] = {"parameters", "blade", "method", "analysis", "critical",
                               "sweep",      "study", "map",    "output",   "plot"};

bool is_group(const std::string& name) {
  for (const char* g : kGroups)
    if (name == g) return true;
  return false;
}

// The rotor Flag row whose JSON key is `key`, or nullptr.
const ParameterSpec* rotor_flag(const std::string& key) {
  for (const ParameterSpec& s : parameter_table())
    if (s.type == ParameterType::Flag && json_key(s) == key) return &s;
  return nullptr;
}

// One key = value, turned into arguments.  `where` is "<file>:<line>: <key>" for messages.
void add(CaseArguments& out, const std::string& key, const std::string& where, bool is_bool,
         bool bool_value, const std::string& text) {
  if (key == "command") {
    if (is_bool) throw InvalidInput(where, bool_value ? "true" : "false", "must be a string");
    Command c;
    if (!command_from_name(text, &c) && !text.empty())
      throw InvalidInput(where, shown(text), "not a subcommand");
    out.args.insert(out.args.begin(), text);
    return;
  }
  if (const ParameterSpec* flag = rotor_flag(key)) {
    if (!is_bool) throw InvalidInput(where, shown(text), "must be true or false");
    // The option that sets the field to flag_value; giving the default is a no-op.
    const OptionSpec* set = nullptr;
    for (Command c : subcommands())
      for (const OptionSpec& o : options_of(c))
        if (o.rotor == flag) set = &o;
    if (set == nullptr) throw InvalidInput(where, "?", "no option sets this field");
    if (bool_value == set->flag_value) {
      out.args.push_back(set->name);
      out.origin[set->name] = where;
    }
    return;
  }
  const std::string option = "--" + key;
  const OptionSpec* spec = find_any_option(option);
  if (spec == nullptr || key.empty() || key[0] == '-')
    throw InvalidInput(where, is_bool ? (bool_value ? "true" : "false") : shown(text),
                       "unknown key (keys are option names without --)");
  out.origin[spec->name] = where;
  if (!spec->takes_value) {
    if (!is_bool) throw InvalidInput(where, shown(text), "must be true or false");
    if (bool_value) out.args.push_back(spec->name);
    return;
  }
  if (is_bool) throw InvalidInput(where, bool_value ? "true" : "false", "needs a value");
  out.args.push_back(spec->name);
  out.args.push_back(text);
}

void from_toml_table(CaseArguments& out, const std::string& file, const toml::table& t, bool top) {
  for (const auto& [k, node] : t) {
    const std::string key(k.str());
    const std::string where = file + ":" + std::to_string(node.source().begin.line) + ": " + key;
    if (const toml::table* sub = node.as_table()) {
      if (!top || !is_group(key))
        throw InvalidInput(where, "[table]",
                           "unknown table (tables only group keys: parameters, blade, method, "
                           "analysis, critical, sweep, study, map, output, plot)");
      from_toml_table(out, file, *sub, false);
      continue;
    }
    if (const auto* s = node.as_string()) {
      add(out, key, where, false, false, s->get());
    } else if (const auto* i = node.as_integer()) {
      add(out, key, where, false, false, std::to_string(i->get()));
    } else if (const auto* f = node.as_floating_point()) {
      add(out, key, where, false, false, round_trip_text(f->get()));
    } else if (const auto* b = node.as_boolean()) {
      add(out, key, where, true, b->get(), "");
    } else {
      const char* what = node.is_array() ? "[array]" : "(date or time)";
      throw InvalidInput(where, what, "must be a string, number or boolean");
    }
  }
}

void from_json_object(CaseArguments& out, const std::string& file, const nlohmann::json& j) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string where = file + ": case." + it.key();
    const nlohmann::json& v = it.value();
    if (v.is_object()) {
      if (!is_group(it.key())) throw InvalidInput(where, "{...}", "unknown group");
      from_json_object(out, file, v);
    } else if (v.is_string()) {
      add(out, it.key(), where, false, false, v.get<std::string>());
    } else if (v.is_number_integer()) {
      add(out, it.key(), where, false, false, std::to_string(v.get<long long>()));
    } else if (v.is_number()) {
      add(out, it.key(), where, false, false, round_trip_text(v.get<double>()));
    } else if (v.is_boolean()) {
      add(out, it.key(), where, true, v.get<bool>(), "");
    } else if (!v.is_null()) {
      throw InvalidInput(where, v.dump(), "must be a string, number or boolean");
    }
  }
}

}  // namespace

CaseArguments parse_case_text(const std::string& name, const std::string& text) {
  CaseArguments out;
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && text[first] == '{') {
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
      throw InvalidInput(name, "(JSON)", std::string("does not parse: ") + e.what());
    }
    if (!j.is_object() || !j.contains("case") || !j["case"].is_object())
      throw InvalidInput(name, "(JSON)", "has no \"case\" object (not a flaplag --json output)");
    from_json_object(out, name, j["case"]);
    return out;
  }
  toml::table t;
  try {
    t = toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    throw InvalidInput(name + ":" + std::to_string(e.source().begin.line), "(TOML)",
                       std::string(e.description()));
  }
  from_toml_table(out, name, t, true);
  return out;
}

CaseArguments read_case_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidInput("argument", shown(path), "case file cannot be read");
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) throw InvalidInput("argument", shown(path), "case file cannot be read");
  return parse_case_text(path, s.str());
}

}  // namespace flaplag::cli
