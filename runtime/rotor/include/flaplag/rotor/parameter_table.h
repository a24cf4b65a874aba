// flaplag — the table of rotor parameters: RotorParameters field <-> command-line option <->
// paper symbol <-> units <-> help text <-> admissible range.
//
// This is the single source of truth for parameter names.  validate() reports errors under the
// option name users type ("--gamma", "--omega-lag"), the CLI builds its options and help from the
// same rows, and JSON output uses the field names.  Adding a field to RotorParameters means adding
// one row here; nothing else needs to learn its name.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "flaplag/core/format.h"
#include "flaplag/rotor/parameters.h"

namespace flaplag {

enum class ParameterType {
  Real,    // double field with an admissible interval
  Text,    // std::string field (the model name)
  Flag,    // bool field; giving the option sets it to flag_value
  Choice,  // ModeKind field, one of `choices`
};

// Admissible values of a Real parameter.  Unbounded ends are +-infinity; every value must be
// finite in any case (NaN and inf are never admissible).
struct Interval {
  double lo;
  double hi;
  bool lo_open;  // true: value > lo; false: value >= lo
  bool hi_open;  // true: value < hi; false: value <= hi
};

struct ParameterSpec {
  const char* field;   // RotorParameters member, also the JSON key
  const char* option;  // command-line long option, also the name in InvalidInput
  const char* symbol;  // the paper's symbol, ASCII
  const char* units;   // "rad", "per rev", "1/rad" or "-" (dimensionless)
  const char* help;    // one line for --help
  ParameterType type;
  const char* requirement;  // human form of the admissible values, e.g. "> 0"; "" if none
  // Real only
  double RotorParameters::*real;
  Interval range;
  // Flag only
  bool RotorParameters::*flag;
  bool flag_value;
  // Choice only: values separated by '|', e.g. "assumed|exact"
  const char* choices;
};

// All rows, in the order of RotorParameters.
const std::vector<ParameterSpec>& parameter_table();

// Row by field name ("lock") or option ("--gamma"); nullptr when there is none.
const ParameterSpec* find_parameter(std::string_view field_or_option);

// The option users know for a field name ("lock" -> "--gamma").  Names that are not fields
// (or are already options) come back unchanged, so callers can pass any InvalidInput name.
std::string option_for(std::string_view name);

// Current value of a row as text: reals in shortest round-trip form, flags "true"/"false",
// choices by name, the model as is.
std::string parameter_text(const RotorParameters& p, const ParameterSpec& spec);

// Sets a row from command-line text.  Reals must be a complete decimal number; Flag rows ignore
// the text and set flag_value; Choice rows must name a choice.  Throws InvalidInput under the
// option name for text that does not parse.  Range checks are left to validate(), so that a
// parameter set built in code and one built from the command line are checked by the same code.
void set_parameter(RotorParameters& p, const ParameterSpec& spec, const std::string& text);

// Strict number parsing for command-line values (also used for non-parameter options such as
// --mu): the whole text must be one decimal or hexadecimal floating-point literal, surrounding
// blanks excluded; "nan", "inf" and out-of-range magnitudes are rejected.  Throws
// InvalidInput(option, text, reason).
double parse_real(const std::string& option, const std::string& text);
// Whole decimal integer in [lo, hi].  Throws InvalidInput(option, text, reason).
int parse_int(const std::string& option, const std::string& text, int lo, int hi);

const char* mode_kind_name(ModeKind k);  // "assumed", "exact"

}  // namespace flaplag
