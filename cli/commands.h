// flaplag CLI — the subcommands: each turns a checked Request into the complete output text
// (human-readable or JSON).  Nothing is written here; the caller decides where the text goes.
#pragma once

#include <string>

#include "command_line.h"

namespace flaplag::cli {

// Runs the request and returns what is to be written.  Throws InvalidInput for inputs only the
// runtime can judge (e.g. an exact-mode frequency the Galerkin basis cannot reach), named by the
// runtime's field or argument name (CommandLine::error_line() turns it into an option).  Every
// number written is finite, or the zeta "-inf" of a zero multiplier, or the result carries a
// non-ok status saying what was not shown.
std::string run_command(const Request& request);

// `flaplag modes` (modes_command.cc).
std::string run_modes(const Request& request);

}  // namespace flaplag::cli
