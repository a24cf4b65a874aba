// flaplag CLI — the subcommands: each turns a checked Request into the complete output text
// (human-readable or JSON).  Nothing is written here; the caller decides where the text goes.
#pragma once

#include <atomic>
#include <nlohmann/json.hpp>
#include <string>

#include "command_line.h"
#include "flaplag/study.h"

namespace flaplag::cli {

// How the caller steers a long run (study, map) and learns how it ended.
struct RunControl {
  const std::atomic<bool>* cancel = nullptr;  // polled between rows (set by a SIGINT handler)
  ProgressFunction progress;                  // after each finished row (the progress bar)
  // Out: the run was stopped by *cancel; the output holds the rows finished, with status
  // "cancelled" and this message.
  bool cancelled = false;
  std::string message;
};

// Runs the request and returns what is to be written.  Throws InvalidInput for inputs only the
// runtime can judge (e.g. an exact-mode frequency the Galerkin basis cannot reach), named by the
// runtime's field or argument name (CommandLine::error_line() turns it into an option).  Every
// number written is finite, or the zeta "-inf" of a zero multiplier, or the result carries a
// non-ok status saying what was not shown.
// JSON outputs carry the flaplag version and commit and the "case" (the options given) that
// reproduces them.  *warning (when given) receives a one-line warning for stderr, e.g. a plot
// that could not be drawn because gnuplot is missing (the data is still returned).
// `control` (optional) carries the cancel flag and progress function of a study or map.
// With request.report set, *document (when given) receives the completed JSON document of the
// result (as --json would write it) for the report, whatever the output's form.
std::string run_command(const Request& request, std::string* warning = nullptr,
                        RunControl* control = nullptr, nlohmann::ordered_json* document = nullptr);

// `flaplag modes` (modes_command.cc); *warning as in run_command (the --plot picture).
std::string run_modes(const Request& request, std::string* warning);

}  // namespace flaplag::cli
