// flaplag tests — the built flaplag (FLAPLAG_EXE, tests/cli.cmake) run as a user runs it, for the
// command-line tests that need nothing more than its arguments.
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "process.h"

#ifndef FLAPLAG_EXE
#error "FLAPLAG_EXE must name the flaplag executable"
#endif

namespace flaplag::testing {

// flaplag with `args`; killed after five minutes (Outcome::exit_code -1).
inline Outcome run(const std::vector<std::string>& args) {
  return run_process(FLAPLAG_EXE, args, std::chrono::seconds(300));
}

// The JSON document of flaplag `args` --json; a run that does not exit 0 fails the test (and the
// parse then throws, which fails it again with the text).
inline nlohmann::json run_json(std::vector<std::string> args) {
  args.push_back("--json");
  const Outcome o = run(args);
  EXPECT_EQ(o.exit_code, 0) << o.err;
  return nlohmann::json::parse(o.out);
}

}  // namespace flaplag::testing
