// flaplag CLI — case files (TOML, or the "case" object of a JSON output) to arguments.
#include "case_file.h"

#include <toml++/toml.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/documents/read_file.h"
#include "flaplag/rotor/parameter_table.h"
#include "options.h"

namespace flaplag::cli {

using documents::JsonParse;
using documents::kMaxCaseBytes;
using documents::kMaxNesting;
using documents::parse_json;
using documents::size_text;
using documents::toml_too_deep;
namespace {

// The tables a case file may use to group its keys.
const char* const kGroups[] = {"parameters", "blade", "method",   "analysis", "critical", "sweep",
                               "study",      "map",   "campbell", "output",   "plot"};

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

// An option that names a file flaplag writes (-o FILE, --plot FILE.svg|FILE.png): the options
// whose value is a FILE.
bool names_output_file(const OptionSpec& o) {
  return o.takes_value && o.metavar.rfind("FILE", 0) == 0;
}

// The case being read: its arguments, and where each key was given (one place per key).
struct Reader {
  CaseArguments& out;
  bool from_json;                            // a result's case: never a path to write
  std::map<std::string, std::string> given;  // option (or "command") -> where
  std::string directory;                     // of a TOML case file ("": the working directory)
};

// A key given twice (in two tables, or as two spellings of one option) is refused, as a key
// twice in one table is by the TOML parser.
void once(Reader& in, const std::string& id, const std::string& where,
          const std::string& shown_value) {
  const auto [it, fresh] = in.given.emplace(id, where);
  if (!fresh) throw InvalidInput(where, shown_value, "given twice (also at " + it->second + ")");
}

// One key = value, turned into arguments.  `where` is "<file>:<line>: <key>" for messages.
void add(Reader& in, const std::string& key, const std::string& where, bool is_bool,
         bool bool_value, const std::string& text) {
  CaseArguments& out = in.out;
  const std::string value = is_bool ? (bool_value ? "true" : "false") : shown(text);
  if (key == "command") {
    if (is_bool) throw InvalidInput(where, value, "must be a string");
    Command c;
    if (!command_from_name(text, &c) && !text.empty())
      throw InvalidInput(where, value, "not a subcommand");
    once(in, "command", where, value);
    // "" is the typical case (what its JSON output records): no subcommand word.
    if (!text.empty()) out.args.insert(out.args.begin(), text);
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
    once(in, set->name, where, value);
    if (bool_value == set->flag_value) {
      out.args.push_back(set->name);
      out.origin[set->name] = where;
    }
    return;
  }
  const std::string option = "--" + key;
  const OptionSpec* spec = find_any_option(option);
  if (spec == nullptr || key.empty() || key[0] == '-')
    throw InvalidInput(where, value, "unknown key (keys are option names without --)");
  once(in, spec->name, where, value);
  // Where output goes comes from the user: the command line, or a TOML case they wrote.  A
  // JSON result may come from anyone; rerunning it writes to stdout.
  if (in.from_json && names_output_file(*spec)) {
    out.warnings.push_back(where + " = " + value +
                           " ignored: a result file does not choose where "
                           "output goes (give " +
                           spec->name + " on the command line)");
    return;
  }
  if (spec->name == "--blade-table" || spec->name == "--mode-shapes") {
    if (in.from_json) {
      throw InvalidInput(where, value,
                         "a result file names no file to read (its case holds the table itself, "
                         "as " +
                             spec->name.substr(2) + "-csv)");
    }
    // A table named in a TOML case is found beside the case file.
    const std::filesystem::path path(text);
    if (path.is_relative() && !in.directory.empty()) {
      out.origin[spec->name] = where;
      out.args.push_back(spec->name + "=" + (std::filesystem::path(in.directory) / path).string());
      return;
    }
  }
  out.origin[spec->name] = where;
  if (!spec->takes_value) {
    if (!is_bool) throw InvalidInput(where, shown(text), "must be true or false");
    if (bool_value) out.args.push_back(spec->name);
    return;
  }
  if (is_bool) throw InvalidInput(where, bool_value ? "true" : "false", "needs a value");
  // "--name=value": the value is the value whatever it looks like (never another option).
  if (spec->name.rfind("--", 0) == 0) {
    out.args.push_back(spec->name + "=" + text);
  } else {
    out.args.push_back(spec->name);
    out.args.push_back(text);
  }
}

// The keys of a TOML table (and of its group tables) in file order: toml++ keeps a table's keys
// sorted, and a key given twice must be reported where it is given the second time.
struct TomlKey {
  std::string key;
  const toml::node* node;
  toml::source_position at;
};

void toml_keys(const std::string& file, const toml::table& t, bool top,
               std::vector<TomlKey>& keys) {
  for (const auto& [k, node] : t) {
    const std::string key(k.str());
    if (const toml::table* sub = node.as_table()) {
      if (!top || !is_group(key)) {
        const std::string where =
            file + ":" + std::to_string(node.source().begin.line) + ": " + key;
        throw InvalidInput(where, "[table]",
                           "unknown table (tables only group keys: parameters, blade, method, "
                           "analysis, critical, sweep, study, map, output, plot)");
      }
      toml_keys(file, *sub, false, keys);
      continue;
    }
    keys.push_back({key, &node, node.source().begin});
  }
}

void from_toml_table(Reader& in, const std::string& file, const toml::table& t) {
  std::vector<TomlKey> keys;
  toml_keys(file, t, true, keys);
  std::stable_sort(keys.begin(), keys.end(), [](const TomlKey& a, const TomlKey& b) {
    return a.at.line != b.at.line ? a.at.line < b.at.line : a.at.column < b.at.column;
  });
  for (const TomlKey& k : keys) {
    const std::string& key = k.key;
    const toml::node& node = *k.node;
    const std::string where = file + ":" + std::to_string(k.at.line) + ": " + key;
    if (const auto* s = node.as_string()) {
      add(in, key, where, false, false, s->get());
    } else if (const auto* i = node.as_integer()) {
      add(in, key, where, false, false, std::to_string(i->get()));
    } else if (const auto* f = node.as_floating_point()) {
      add(in, key, where, false, false, round_trip_text(f->get()));
    } else if (const auto* b = node.as_boolean()) {
      add(in, key, where, true, b->get(), "");
    } else {
      const char* what = node.is_array() ? "[array]" : "(date or time)";
      throw InvalidInput(where, what, "must be a string, number or boolean");
    }
  }
}

void from_json_object(Reader& in, const std::string& file, const nlohmann::ordered_json& j,
                      const std::string& path, bool top) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string where = file + ": " + path + "." + it.key();
    const nlohmann::ordered_json& v = it.value();
    if (v.is_object()) {
      if (!top || !is_group(it.key())) throw InvalidInput(where, "{...}", "unknown group");
      from_json_object(in, file, v, path + "." + it.key(), false);
    } else if (v.is_string()) {
      add(in, it.key(), where, false, false, v.get<std::string>());
    } else if (v.is_number_integer()) {
      add(in, it.key(), where, false, false, v.dump());
    } else if (v.is_number()) {
      add(in, it.key(), where, false, false, round_trip_text(v.get<double>()));
    } else if (v.is_boolean()) {
      add(in, it.key(), where, true, v.get<bool>(), "");
    } else if (!v.is_null()) {
      throw InvalidInput(where, v.is_array() ? "[...]" : v.dump(),
                         "must be a string, number or boolean");
    }
  }
}

}  // namespace

CaseArguments parse_case_text(const std::string& name, const std::string& text) {
  CaseArguments out;
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && text[first] == '{') {
    nlohmann::ordered_json j;
    std::string error;
    const JsonParse parsed = parse_json(text, &j, &error);
    if (parsed != JsonParse::Ok)
      throw InvalidInput(name, "(JSON)",
                         (parsed == JsonParse::NotJson ? "does not parse: " : "") + error);
    if (!j.is_object() || !j.contains("case") || !j["case"].is_object())
      throw InvalidInput(name, "(JSON)", "has no \"case\" object (not a flaplag --json output)");
    return case_object_arguments(name, j["case"]);
  }
  if (text.size() > kMaxCaseBytes)
    throw InvalidInput(
        "argument", shown(name),
        "larger than " + size_text(kMaxCaseBytes) + " (the limit on a TOML case file)");
  if (const std::size_t line = toml_too_deep(text))
    throw InvalidInput(name + ":" + std::to_string(line), "(TOML)",
                       "nested deeper than " + std::to_string(kMaxNesting) +
                           " levels (tables, arrays and dotted keys)");
  toml::table t;
  try {
    t = toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    throw InvalidInput(name + ":" + std::to_string(e.source().begin.line), "(TOML)",
                       std::string(e.description()));
  }
  Reader in{out, false, {}, std::filesystem::path(name).parent_path().string()};
  from_toml_table(in, name, t);
  return out;
}

CaseArguments case_object_arguments(const std::string& name,
                                    const nlohmann::ordered_json& case_object) {
  CaseArguments out;
  Reader in{out, true, {}, ""};
  from_json_object(in, name, case_object, "case", true);
  return out;
}

CaseArguments read_case_file(const std::string& path, std::uint64_t memory_limit) {
  // A JSON result (read within the memory limit) or a TOML case (checked against its own,
  // smaller limit after reading).
  return parse_case_text(path, documents::read_json_file(path, memory_limit, "case file",
                                                         "case file cannot be read", kebab_option));
}

}  // namespace flaplag::cli
