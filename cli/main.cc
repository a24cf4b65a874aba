// flaplag — command-line front end of the flap-lag stability analysis (NASA CR-132431).
//
// Exit codes: 0 success (numerical outcomes such as an unstable hover or no mu_c below the scan
// limit are results, not errors); 2 bad input, reported as ONE line on stderr
// "flaplag: error: <option> = <value>: <reason>", with no output file created or changed;
// 1 an internal failure (a bug), also one line on stderr.
#include <cstdio>
#include <exception>
#include <iostream>
#include <string>

#include "command_line.h"
#include "commands.h"
#include "flaplag/core/errors.h"
#include "flaplag/rotor/parameter_table.h"
#include "output.h"

namespace {

constexpr int kBadInput = 2;
constexpr int kInternalError = 1;

// One line, whatever the message contains.
std::string one_line(std::string s) {
  for (char& c : s) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

int report(const std::string& message, int code) {
  std::cerr << "flaplag: error: " << one_line(message) << std::endl;
  return code;
}

// CLI11 says "The following argument(s) was/were not expected: x y"; say what the user needs.
std::string parse_error_text(const CLI::ParseError& e) {
  const std::string what = e.what();
  if (dynamic_cast<const CLI::ExtrasError*>(&e) != nullptr) {
    const auto colon = what.find(": ");
    const std::string args = colon == std::string::npos ? what : what.substr(colon + 2);
    return args + ": unknown option, subcommand or argument (see flaplag --help)";
  }
  return what;
}

int run(int argc, char** argv) {
  flaplag::cli::CommandLine cl;
  try {
    cl.app().parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return cl.app().exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return cl.app().exit(e);
  } catch (const CLI::CallForVersion& e) {
    return cl.app().exit(e);
  } catch (const CLI::ParseError& e) {
    return report(parse_error_text(e), kBadInput);
  }
  try {
    const flaplag::cli::Request request = cl.interpret();
    // Check the output path before a possibly long analysis; nothing is left behind.
    if (!request.output.empty()) flaplag::cli::probe_output_path(request.output);
    const std::string text = flaplag::cli::run_command(request);
    if (request.output.empty()) {
      std::cout << text << std::flush;
      if (!std::cout) return report("cannot write to standard output", kInternalError);
    } else {
      flaplag::cli::write_file_atomically(request.output, text);
    }
    return 0;
  } catch (const flaplag::InvalidInput& e) {
    // The runtime names fields ("omega_lag"); users know options ("--omega-lag").
    const std::string option = flaplag::option_for(e.name());
    if (option.empty() || option[0] != '-') {
      // Not an option but a quantity derived from several (e.g. a non-finite coefficient of
      // A(psi) for an extreme mu or gamma): say that it comes from the inputs as a whole.
      return report(std::string(e.what()) + " (for the parameters given)", kBadInput);
    }
    const std::string* typed = cl.typed(option);
    const std::string value = typed != nullptr && !typed->empty() ? *typed : e.value();
    return report(option + " = " + value + ": " + flaplag::cli::reason_of(e), kBadInput);
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    return report(std::string("internal error: ") + e.what(), kInternalError);
  } catch (...) {
    return report("internal error: unknown exception", kInternalError);
  }
}
