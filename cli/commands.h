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
// JSON outputs carry the flaplag version and commit and the "case" (the options given) that
// reproduces them.  *warning (when given) receives a one-line warning for stderr, e.g. a plot
// that could not be drawn because gnuplot is missing (the data is still returned).
std::string run_command(const Request& request, std::string* warning = nullptr);
std::string run_command_text(const Request& request, std::string* warning);

// `flaplag modes` (modes_command.cc).
std::string run_modes(const Request& request);

}  // namespace flaplag::cli
