// flaplag CLI — case files: a study, a map or any other command written down as TOML (or as the
// "case" object of any JSON output), turned into the command-line arguments it stands for.
//
// One vocabulary: a key is an option name without "--" ("omega-lag", "mu-max", "steps",
// "vary"), the value its text.  Tables ([parameters], [method], ...) only group keys for the
// reader; their names are not part of the key.  A boolean rotor parameter is written as its
// JSON key ("reversed-flow = false" is --no-reversed-flow; "paper-1974-shapes = true" is
// --paper-1974-shapes); any other boolean key is a flag given when true ("json = true").
// "command" names the subcommand ("" or no command: the typical case).  A key may be given once
// in a case, whatever table holds it (two spellings of one option count as one key).
// Command-line options given after `flaplag run FILE` override the file (the last of a repeated
// option wins).
//
// Where output goes comes only from the user: a TOML case file (the user's own) may give -o
// ("output") and --plot, but the case of a JSON result (which anyone may have written) never
// names a file to write: such keys are skipped with a warning, and the rerun writes to stdout
// unless the command line says otherwise.  Files are read with the bounds of read_file.h.
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace flaplag::cli {

struct CaseArguments {
  std::vector<std::string> args;  // subcommand first (when the case names one), then options
  // Where each option came from, for error messages: "--theta" -> "case.toml:3: theta".
  std::map<std::string, std::string> origin;
  // Keys that were read but not used, one message each (joined into the one
  // "flaplag: warning: ..." line).
  std::vector<std::string> warnings;
};

// Reads a TOML case file, or a JSON document with a "case" object (any flaplag --json output).
// Throws InvalidInput naming "<file>:<line>: <key>" (the file alone for a file that does not
// parse, "argument" = the file for one that cannot be read, is a directory or is too large)
// with the value as written: unknown keys, keys given twice, wrong types (arrays, dates, nested
// tables below the grouping level), nesting deeper than kMaxNesting, and so on.  Values are checked
// by the command line like typed ones.
// A JSON file is read up to json_read_limit(memory_limit) bytes (read_file.h), the
// --memory-limit typed after the file (the default otherwise).
CaseArguments read_case_file(const std::string& path, std::uint64_t memory_limit);

// The same from text already read (`name` stands for the file in messages).
CaseArguments parse_case_text(const std::string& name, const std::string& text);

// The same from the "case" object of a JSON output already parsed.
CaseArguments case_object_arguments(const std::string& name,
                                    const nlohmann::ordered_json& case_object);

}  // namespace flaplag::cli
