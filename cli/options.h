// flaplag CLI — the option vocabulary: which options each command takes, how a value is parsed,
// and how the library's field and argument names ("omega_lag", "steps", "mu") map to what the
// user types ("--omega-lag", "--steps", "--mu").
//
// The runtime names fields only (rotor/parameter_table.h); this file is the only place that
// spells options.  The rule: an option is "--" + the field name with '_' -> '-'
// ("omega_lag" -> "--omega-lag"), except the bool fields, whose option turns them off
// (--no-reversed-flow, --no-elastic-coupling) or on (--paper-1974-shapes).  JSON parameter keys
// are the same words without "--" ("omega-lag", "reversed-flow").
//
// The options of the library's options structs (CriticalOptions, CampbellOptions, TrimOptions,
// TransitionOptions, SimulationOptions) are made from their field tables (core/fields.h) by
// the same rule: name, metavar by type, help from the row's doc, units and range, default from
// a default-constructed struct; each sets its member of the Request's struct.  An option whose
// name users' scripts know under another word keeps it (an alias in the table of build()).
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "flaplag/documents/names.h"
#include "flaplag/rotor/parameter_table.h"

namespace flaplag::cli {

struct Request;  // command_line.h

enum class Command {
  Typical,
  Point,
  Sweep,
  Critical,
  System,
  Models,
  Modes,
  Study,
  Map,
  Response,
  Simulate,
  Merge,    // flaplag merge PART...: the --shard parts of a map or study as one file
  Plot,     // flaplag plot DATA.json --plot FILE: the picture of an existing result
  Trim,     // flaplag trim --mu X: the trimmed controls and inflow
  Campbell  // flaplag campbell: mode frequencies against the rotor speed
};

const char* command_name(Command c);  // "" for Typical, else "point", ...
// The commands that have a name (not Typical), in help order.
const std::vector<Command>& subcommands();
// false when `name` is not a subcommand.
bool command_from_name(std::string_view name, Command* c);

// modes --export-shapes: the stations of the mode file, enough for its shapes to give the
// exact modes' critical advance ratio to ~1e-11 when imported (tests/imported_modes_test.cpp).
inline constexpr int kExportedModeStations = 1001;

struct OptionSpec {
  std::string name;          // "--omega-lag", "-o"
  std::string alias;         // another spelling ("--output" for -o), or ""
  bool takes_value = false;  // false: a flag
  std::string metavar;       // "REAL", "N", "A:B:STEP", "FILE"
  std::string help;          // one line (units, range and default added by the help printer)
  std::string default_text;  // "" when there is no default to show
  // The library names this option answers for (InvalidInput::name(), backticked names in
  // messages): a RotorParameters field, a TransitionOptions / CriticalOptions field or an
  // argument of analysis.h.
  std::vector<std::string> library_names;
  const ParameterSpec* rotor = nullptr;  // rotor parameter rows
  bool flag_value = false;               // rotor Flag rows: the value the option sets
  // Options of an options struct's table: sets the member from the text typed (as `spelling`),
  // parsed by its type: a real strictly (its range is the struct's Check()'s), a whole number
  // within the row's range, an enum by name, a flag on.  Throws InvalidInput(spelling, ...).
  std::function<void(Request&, const std::string& spelling, const std::string& text)> set;
};

// The options of a command, in help order (never --help / --version, which every command has).
const std::vector<OptionSpec>& options_of(Command c);
// The option of command c called `name` (either spelling); nullptr when c has none.
const OptionSpec* find_option(Command c, std::string_view name);
// The option `name` of any command (value-taking or not is the same in all of them); nullptr when
// no command has it.
const OptionSpec* find_any_option(std::string_view name);
// The option of command c that answers for the library name (field or argument); nullptr when
// there is none.
const OptionSpec* option_for_library_name(Command c, std::string_view library_name);

// The kinds --inflow takes (InflowKind's names but `given`), joined by sep ("|", ", ").
std::string inflow_kind_names(const char* sep);

// "--" + kebab: "omega_lag" -> "--omega-lag".
std::string kebab_option(std::string_view field);
// The option of a key of a result's case, which holds the command line's options by their
// words: "--" + key ("omega-lag" -> "--omega-lag").
std::string case_option(std::string_view key);

// A library message in the command line's vocabulary: every `name` in backticks that names an
// option of command c becomes that option ("increase `steps`" -> "increase --steps");
// "`name` = value" becomes "--option=value".  Other text is unchanged.
std::string in_cli_vocabulary(Command c, const std::string& message);

// The documents layer's forms of a value in an error line, a refused file and a JSON key.
using documents::json_key;
using documents::refuse_file;
using documents::shown;

// Strict number parsing: the whole text must be one decimal or hexadecimal floating-point
// literal (no surrounding blanks); "nan", "inf" and magnitudes beyond double are rejected.
// Throws InvalidInput(option, shown(text), reason).
double parse_real(const std::string& option, const std::string& text);
// Whole decimal integer in [lo, hi] ('+' allowed).  Throws InvalidInput(option, shown(text), ...).
int parse_int(const std::string& option, const std::string& text, int lo, int hi);

// Sets the rotor parameter of `option` (option.rotor != nullptr) from the text typed: reals
// parsed strictly (ranges are validate()'s job, so that a parameter set built in code and one
// built from the command line are checked by the same code), flags set flag_value, choices must
// name one.  Throws InvalidInput(option.name, ...).
void set_parameter(RotorParameters& p, const OptionSpec& option, const std::string& text);

}  // namespace flaplag::cli
