// flaplag — command-line front end of the flap-lag stability analysis (NASA CR-132431).
//
// Exit codes: 0 success (numerical outcomes such as an unstable hover or no mu_c below the scan
// limit are results, not errors); 2 bad input, reported as ONE line on stderr
// "flaplag: error: <option> = <value>: <reason>", with no output file created or changed;
// 1 an internal failure (a bug), also one line on stderr; 3 (flaplag plot) gnuplot is missing
// or failed; 130 a study or map interrupted by Ctrl-C (SIGINT): the rows finished are written
// as a valid output with status "cancelled", and one line on stderr says so.
#include <signal.h>

#include <atomic>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "case_file.h"
#include "command_line.h"
#include "commands.h"
#include "flaplag/core/errors.h"
#include "flaplag/version.h"
#include "output.h"
#include "plot.h"
#include "progress.h"

namespace {

constexpr int kBadInput = 2;
constexpr int kInternalError = 1;
constexpr int kRendererMissing = 3;
constexpr int kInterrupted = 130;  // 128 + SIGINT, as a shell reports a job killed by Ctrl-C

// Set by SIGINT; the study and map poll it between rows.  A lock-free atomic is what a signal
// handler may touch.
std::atomic<bool> interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void on_interrupt(int) { interrupted.store(true); }

// Ctrl-C during a study or map stops it after the rows being computed; a second Ctrl-C (the
// handler is reset by the first) ends flaplag at once.
void catch_interrupt() {
  struct sigaction sa {};
  sa.sa_handler = on_interrupt;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND | SA_RESTART;  // no EINTR for the writes of the output
  ::sigaction(SIGINT, &sa, nullptr);
}

const char* const kVersion = "flaplag " FLAPLAG_VERSION;

// One line, whatever the message contains.
std::string one_line(std::string s) {
  for (char& c : s) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

int report(const std::string& message, int code) {
  std::cerr << (code == kBadInput ? "flaplag: error: " : "flaplag: internal error: ")
            << one_line(message) << std::endl;
  return code;
}

// `flaplag run CASE [options]`: the case file's arguments, then the options typed after it
// (the last of a repeated option wins, so the command line overrides the file).
struct Expanded {
  std::vector<std::string> args;
  flaplag::cli::CaseArguments from_file;
  std::vector<std::string> typed;  // the options given after the file
  bool run_help = false;           // flaplag run --help
};

Expanded expand(const std::vector<std::string>& args) {
  Expanded e;
  if (args.empty() || args[0] != "run") {
    e.args = args;
    return e;
  }
  if (args.size() >= 2 && (args[1] == "--help" || args[1] == "-h")) {
    e.run_help = true;
    return e;
  }
  if (args.size() < 2 || args[1].empty() || args[1][0] == '-')
    throw flaplag::InvalidInput("argument", args.size() < 2 ? "(missing)" : args[1],
                                "flaplag run needs a case file: flaplag run CASE.toml (or a "
                                "--json output of flaplag)");
  e.from_file = flaplag::cli::read_case_file(args[1]);
  e.args = e.from_file.args;
  e.typed.assign(args.begin() + 2, args.end());
  e.args.insert(e.args.end(), e.typed.begin(), e.typed.end());
  return e;
}

// An error about an option that came from the case file names the file, line and key.
std::string with_origin(const Expanded& e, const std::string& line) {
  for (const auto& [option, where] : e.from_file.origin) {
    if (line.rfind(option + " = ", 0) != 0 && line.rfind(option + "=", 0) != 0) continue;
    bool typed = false;
    for (const std::string& t : e.typed)
      typed = typed || t == option || t.rfind(option + "=", 0) == 0;
    if (!typed) return where + line.substr(option.size());
  }
  return line;
}

int run(const std::vector<std::string>& raw) {
  Expanded e;
  try {
    e = expand(raw);
  } catch (const flaplag::InvalidInput& error) {
    return report(error.what(), kBadInput);
  }
  if (e.run_help) {
    std::cout << flaplag::cli::CommandLine::run_help_text() << std::flush;
    return std::cout ? 0 : kInternalError;
  }
  const flaplag::cli::CommandLine cl(e.args);
  if (cl.wants_help() || cl.wants_version()) {
    std::cout << (cl.wants_help() ? cl.help_text() : std::string(kVersion) + "\n") << std::flush;
    return std::cout ? 0 : kInternalError;
  }
  try {
    flaplag::cli::Request request = cl.interpret();
    request.arguments = e.args;
    // Check the output path before a possibly long analysis; nothing is left behind.
    const flaplag::cli::OutputTarget target(request.output);
    std::string warning;
    using flaplag::cli::Command;
    const bool long_run = request.command == Command::Study || request.command == Command::Map;
    if (long_run) catch_interrupt();
    flaplag::cli::ProgressBar bar(
        long_run && !request.quiet && flaplag::cli::stderr_is_terminal(),
        std::string("flaplag ") + flaplag::cli::command_name(request.command),
        request.command == Command::Study ? "values"
        : request.y_name == "mu"          ? "columns"
                                          : "rows");
    flaplag::cli::RunControl control;
    control.cancel = &interrupted;
    control.progress = bar.function();
    const std::string text = flaplag::cli::run_command(request, &warning, &control);
    bar.finish();
    if (request.output.empty()) {
      std::cout << text << std::flush;
      if (!std::cout) return report("cannot write to standard output", kInternalError);
    } else {
      target.write(text);
    }
    for (const std::string& w : e.from_file.warnings)
      std::cerr << "flaplag: warning: " << one_line(w) << std::endl;
    if (!warning.empty()) std::cerr << "flaplag: warning: " << one_line(warning) << std::endl;
    if (control.cancelled) {
      std::cerr << "flaplag: " << one_line(control.message) << std::endl;
      return kInterrupted;
    }
    return 0;
  } catch (const flaplag::cli::RendererUnavailable& error) {
    std::cerr << "flaplag: error: " << one_line(error.what()) << std::endl;
    return kRendererMissing;
  } catch (const flaplag::InvalidInput& error) {
    // The runtime names fields ("omega_lag"); users know options ("--omega-lag").
    if (const std::optional<std::string> line = cl.error_line(error))
      return report(with_origin(e, *line), kBadInput);
    // A name no option answers for is a quantity the analysis derived from valid input (say a
    // non-finite coefficient): the inputs were checked, so this is a bug to report.
    return report(std::string("invalid derived quantity ") + error.what(), kInternalError);
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(std::vector<std::string>(argv + (argc > 0 ? 1 : 0), argv + argc));
  } catch (const std::exception& e) {
    return report(e.what(), kInternalError);
  } catch (...) {
    return report("unknown exception", kInternalError);
  }
}
