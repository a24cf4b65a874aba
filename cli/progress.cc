// flaplag CLI — the progress bar.
#include "progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace flaplag::cli {

namespace {

// Shown once a run has taken this long (a quick run shows nothing).
constexpr double kDelaySeconds = 1.0;
// Redrawn at most this often.
constexpr double kRedrawSeconds = 0.1;
constexpr int kWidth = 30;  // characters of the bar itself

void put(const std::string& s) {
  const char* p = s.data();
  std::size_t left = s.size();
  while (left > 0) {
    const ssize_t n = ::write(STDERR_FILENO, p, left);
    if (n <= 0) return;  // a terminal that went away: no bar, no error
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

std::string seconds_text(double s) {
  char buf[32];
  if (s < 60)
    std::snprintf(buf, sizeof buf, "%.0f s", s);
  else
    std::snprintf(buf, sizeof buf, "%.0f min %02.0f s", std::floor(s / 60), std::fmod(s, 60));
  return buf;
}

}  // namespace

bool stderr_is_terminal() { return ::isatty(STDERR_FILENO) == 1; }

ProgressBar::ProgressBar(bool enabled, std::string what, std::string unit)
    : enabled_(enabled), what_(std::move(what)), unit_(std::move(unit)) {
  start_ = last_ = Clock::now();
}

ProgressBar::~ProgressBar() { finish(); }

std::string ProgressBar::line(const std::string& what, const std::string& unit, std::size_t done,
                              std::size_t total, double seconds) {
  const double f = total > 0 ? static_cast<double>(done) / static_cast<double>(total) : 1.0;
  const int filled = static_cast<int>(f * kWidth);
  std::string bar = what + " [" + std::string(static_cast<std::size_t>(filled), '#') +
                    std::string(static_cast<std::size_t>(kWidth - filled), '.') + "]";
  char buf[96];
  std::snprintf(buf, sizeof buf, " %3d%%  %zu/%zu ", static_cast<int>(f * 100), done, total);
  bar += buf + unit + "  " + seconds_text(seconds);
  if (done > 0 && done < total)
    bar += ", about " +
           seconds_text(seconds * static_cast<double>(total - done) / static_cast<double>(done)) +
           " left";
  return bar;
}

void ProgressBar::update(std::size_t done, std::size_t total) {
  if (!enabled_) return;
  const Clock::time_point now = Clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (elapsed < kDelaySeconds) return;
  if (shown_ && done < total && std::chrono::duration<double>(now - last_).count() < kRedrawSeconds)
    return;
  last_ = now;
  shown_ = true;
  // \r and "erase to the end of the line": the bar overwrites itself.
  put("\r" + line(what_, unit_, done, total, elapsed) + "\033[K");
}

ProgressFunction ProgressBar::function() {
  return [this](std::size_t done, std::size_t total) { update(done, total); };
}

void ProgressBar::finish() {
  if (!shown_) return;
  shown_ = false;
  put("\r\033[K");
}

}  // namespace flaplag::cli
