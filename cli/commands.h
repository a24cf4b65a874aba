// flaplag CLI — the subcommands: each turns a checked Request into the complete output text
// (human-readable or JSON).  Nothing is written here; the caller decides where the text goes.
#pragma once

#include <string>

#include "command_line.h"

namespace flaplag::cli {

// Runs the request and returns what is to be written.  Throws InvalidInput for inputs only the
// runtime can judge (e.g. an exact-mode frequency the Galerkin basis cannot reach).
std::string run_command(const Request& request);

// `flaplag modes` (modes_command.cc).
std::string run_modes(const Request& request);

}  // namespace flaplag::cli
