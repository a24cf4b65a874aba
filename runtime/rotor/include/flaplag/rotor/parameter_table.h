// flaplag — the table of rotor parameters: RotorParameters field <-> paper symbol <-> units <->
// admissible range <-> one-line description.
//
// This is the single source of truth for what each field is.  validate() reports errors under
// the field name ("gamma", "omega_lag"); front ends (the command line, later Python) map field
// names to their own vocabulary and build their help and docstrings from these rows.  Nothing
// here knows how a front end spells an option.  Adding a field to RotorParameters means adding
// one row here.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "flaplag/core/validation.h"
#include "flaplag/rotor/parameters.h"

namespace flaplag {

enum class ParameterType {
  Real,     // double field with an admissible interval
  Integer,  // int field with an admissible closed interval [lo, hi] (range, both ends integers)
  Text,     // std::string field (the model name)
  Flag,     // bool field
  Choice,   // ModeKind field, one of `choices`
};

// Admissible values of a Real parameter: an Interval (core/validation.h) whose bounds are all
// finite: each admissible value is a blade the analysis can answer for (possibly with a non-ok
// status), and NaN and inf are never admissible.

struct ParameterSpec {
  const char* field;        // RotorParameters member: the name in InvalidInput and messages
  const char* symbol;       // the paper's symbol, ASCII ("omega_L1"); "" when there is none
  const char* units;        // "rad", "per rev", "1/rad" or "-" (dimensionless)
  const char* description;  // one line: what the field is (flags: what `true` turns on)
  ParameterType type;
  const char* requirement;  // admissible values in words, e.g. "in (0, 1e4]"; "" if any
  // Real only
  double RotorParameters::*real;
  Interval range;  // Real and Integer rows
  // Flag only
  bool RotorParameters::*flag;
  // Choice only: values separated by '|', e.g. "assumed|exact"
  const char* choices;
  // Integer only
  int RotorParameters::*integer;
  // Integer only: named values outside the range, "name=value|name=value" (the basis:
  // "converged=0|paper=5"); nullptr when there are none.  A value outside the range is shown by
  // its name.
  const char* names = nullptr;
};

// All rows, in the order of RotorParameters.
const std::vector<ParameterSpec>& parameter_table();

// Row by field name ("omega_lag"); nullptr when there is none.
const ParameterSpec* find_parameter(std::string_view field);

// True when v is finite and inside the row's interval (Real and Integer rows).
bool in_range(const ParameterSpec& spec, double v);

// Current value of a row as text: reals in shortest round-trip form, integers in decimal,
// flags "true"/"false",
// choices by name, the model as is.
std::string parameter_text(const RotorParameters& p, const ParameterSpec& spec);

// The value of an Integer row called `name` (one of its `names`); false when there is none.
bool integer_from_name(const ParameterSpec& spec, std::string_view name, int* value);
// The name of an Integer row's value outside its range ("converged"); "" when it has none.
std::string integer_name(const ParameterSpec& spec, int value);
// Integer rows: the admissible value (in range, or named).
bool integer_admissible(const ParameterSpec& spec, int value);

const char* mode_kind_name(ModeKind k);  // "assumed", "exact"
// The ModeKind called `name` ("assumed", "exact"); false when there is none.
bool mode_kind_from_name(std::string_view name, ModeKind* kind);

}  // namespace flaplag
