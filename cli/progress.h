// flaplag CLI — a progress bar on stderr for the long runs (study, map): drawn only when stderr
// is a terminal and the run has taken more than about a second, redrawn at most ten times a
// second, erased when the run ends.  Never written anywhere but the terminal, so it can never
// reach an output file or a pipe.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

#include "flaplag/study.h"

namespace flaplag::cli {

// isatty(stderr).
bool stderr_is_terminal();

class ProgressBar {
 public:
  // `what` names the run ("flaplag map"), `unit` what is counted ("rows").  A disabled bar
  // draws nothing.
  ProgressBar(bool enabled, std::string what, std::string unit);
  ~ProgressBar();  // finish()
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // (finished, all) after each finished line; safe to call from the study's worker threads
  // (the library calls it one at a time).
  void update(std::size_t done, std::size_t total);
  ProgressFunction function();
  // Erases the bar, if drawn (before the output or a message is written to the terminal).
  void finish();

  // The bar's text: "flaplag map [#####.....]  45%  90/200 rows  12 s, about 15 s left".
  static std::string line(const std::string& what, const std::string& unit, std::size_t done,
                          std::size_t total, double seconds);

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_;
  std::string what_, unit_;
  Clock::time_point start_, last_;
  bool shown_ = false;
};

}  // namespace flaplag::cli
