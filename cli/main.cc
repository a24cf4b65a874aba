// flaplag — command-line front end of the flap-lag stability analysis (NASA CR-132431).
//
// Exit codes: 0 success (numerical outcomes such as an unstable hover or no mu_c below the scan
// limit are results, not errors); 2 bad input, reported as ONE line on stderr
// "flaplag: error: <option> = <value>: <reason>", with no output file created or changed;
// 1 an internal failure (a bug), also one line on stderr.
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "command_line.h"
#include "commands.h"
#include "flaplag/core/errors.h"
#include "output.h"

namespace {

constexpr int kBadInput = 2;
constexpr int kInternalError = 1;

const char* const kVersion = "flaplag 0.1.0";

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

int run(const std::vector<std::string>& args) {
  const flaplag::cli::CommandLine cl(args);
  if (cl.wants_help() || cl.wants_version()) {
    std::cout << (cl.wants_help() ? cl.help_text() : std::string(kVersion) + "\n") << std::flush;
    return std::cout ? 0 : kInternalError;
  }
  try {
    const flaplag::cli::Request request = cl.interpret();
    // Check the output path before a possibly long analysis; nothing is left behind.
    const flaplag::cli::OutputTarget target(request.output);
    const std::string text = flaplag::cli::run_command(request);
    if (request.output.empty()) {
      std::cout << text << std::flush;
      if (!std::cout) return report("cannot write to standard output", kInternalError);
    } else {
      target.write(text);
    }
    return 0;
  } catch (const flaplag::InvalidInput& e) {
    // The runtime names fields ("omega_lag"); users know options ("--omega-lag").
    if (const std::optional<std::string> line = cl.error_line(e)) return report(*line, kBadInput);
    // A name no option answers for is a quantity the analysis derived from valid input (say a
    // non-finite coefficient): the inputs were checked, so this is a bug to report.
    return report(std::string("invalid derived quantity ") + e.what(), kInternalError);
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
