// flaplag documents — how the documents layer names what it refuses, and how a front end spells
// what the layer names by field.
//
// The documents layer (result files read, written, drawn, reported and merged) names options and
// arguments by their field only ("memory_limit", "label", "plot"); the front end that calls it
// says how its users write them (the command line's option, Python's keyword argument), so that
// a refusal names what the user typed and only the front ends know option names.
#pragma once

#include <functional>
#include <string>
#include <string_view>

#include "flaplag/rotor/parameter_table.h"

namespace flaplag::documents {

// A front end's spelling of an option or argument named by its field (the command line's
// option for "memory_limit", Python's keyword memory_limit).
using Spelling = std::function<std::string(std::string_view field)>;

// The value of an option as shown in an error line: the text as typed, "\"\"" when empty, quoted
// with control characters escaped when it has blanks at its ends or control characters.
std::string shown(const std::string& text);

// Refuses a file named by the user (or in a file they name): throws
// InvalidInput("argument", shown(file), reason), the one form every file reader uses.
[[noreturn]] void refuse_file(const std::string& file, const std::string& reason);

// The JSON key of a field: '_' -> '-' ("omega_lag" -> "omega-lag").
std::string json_word(std::string_view field);
// The JSON key of a rotor parameter: json_word of its field.
std::string json_key(const ParameterSpec& spec);

}  // namespace flaplag::documents
