// flaplag — memory estimates of the runs and the memory limit (limits.h).
#include "flaplag/limits.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>

#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"

namespace flaplag {
namespace {

// Bytes per item, measured (peak resident memory over a range of sizes, the larger of the
// command line with --json and Python) and rounded up.  Memory includes the output.
constexpr double kMapCellMemory = 640, kMapCellOutput = 96;
constexpr double kStudyRowMemory = 8000, kStudyRowExponentMemory = 800;
constexpr double kStudyRowOutput = 1500, kStudyRowExponentOutput = 200;
constexpr double kSweepPointMemory = 6000, kSweepExponentMemory = 2400;
constexpr double kSweepPointOutput = 400, kSweepExponentOutput = 400;
constexpr double kResponseSampleMemory = 320, kResponseStateMemory = 40;
constexpr double kResponseSampleOutput = 96;
constexpr double kSimulationSampleMemory = 400, kSimulationStateMemory = 24;
constexpr double kSimulationNonlinearMemory = 160;
constexpr double kSimulationSampleOutput = 96, kSimulationNonlinearOutput = 64;
constexpr double kStationMemory = 48, kStationShapeMemory = 16;
// A merge holds the parts and the merged document (nlohmann::json nodes: a few times the
// text of the numbers they hold) and the text.
constexpr double kJsonTextMemory = 4;

std::uint64_t saturated(double bytes) {
  constexpr double top = static_cast<double>(std::numeric_limits<std::uint64_t>::max());
  if (!(bytes < top)) return std::numeric_limits<std::uint64_t>::max();
  return static_cast<std::uint64_t>(std::ceil(bytes));
}

MemoryEstimate estimate(std::string what, double memory, double output) {
  return MemoryEstimate{std::move(what), saturated(memory), saturated(output)};
}

std::string count_text(double n) {
  if (n < 1e15) return std::to_string(static_cast<long long>(n));
  return short_text(n);
}

}  // namespace

MemoryEstimate map_memory(std::size_t x_values, std::size_t y_values) {
  const double cells = static_cast<double>(x_values) * static_cast<double>(y_values);
  return estimate(
      "a map of " + std::to_string(x_values) + " x " + std::to_string(y_values) + " cells",
      cells * kMapCellMemory, cells * kMapCellOutput);
}

MemoryEstimate study_memory(std::size_t values, int state_size) {
  const double n = static_cast<double>(values), s = std::max(state_size, 0);
  return estimate("a study of " + std::to_string(values) + " values",
                  n * (kStudyRowMemory + s * kStudyRowExponentMemory),
                  n * (kStudyRowOutput + s * kStudyRowExponentOutput));
}

MemoryEstimate sweep_memory(std::size_t points, int state_size) {
  const double n = static_cast<double>(points), s = std::max(state_size, 0);
  return estimate("a sweep of " + std::to_string(points) + " points of " +
                      std::to_string(state_size) + " exponents",
                  n * (kSweepPointMemory + s * kSweepExponentMemory),
                  n * (kSweepPointOutput + s * kSweepExponentOutput));
}

MemoryEstimate response_memory(int samples, int state_size) {
  const double n = std::max(samples, 0), s = std::max(state_size, 0);
  return estimate("a response of " + std::to_string(samples) + " samples",
                  n * (kResponseSampleMemory + s * kResponseStateMemory),
                  n * kResponseSampleOutput);
}

MemoryEstimate simulation_memory(double revolutions, int samples_per_rev, int state_size,
                                 bool nonlinear) {
  double n = std::ceil(revolutions * std::max(samples_per_rev, 0) - 1e-9) + 1.0;
  if (!std::isfinite(n) || n < 1.0) n = 1.0;
  const double s = std::max(state_size, 0);
  return estimate("a simulation of " + count_text(n) + " samples (" + short_text(revolutions) +
                      " revolutions x " + std::to_string(samples_per_rev) + " samples)",
                  n * (kSimulationSampleMemory + s * kSimulationStateMemory +
                       (nonlinear ? kSimulationNonlinearMemory : 0.0)),
                  n * (kSimulationSampleOutput + (nonlinear ? kSimulationNonlinearOutput : 0.0)));
}

MemoryEstimate stations_memory(std::size_t stations, int shapes) {
  const double n = static_cast<double>(stations), s = std::max(shapes, 0);
  return estimate(
      std::to_string(stations) + " stations of " + std::to_string(shapes) + " mode shapes",
      n * (kStationMemory + s * kStationShapeMemory), 0.0);
}

MemoryEstimate json_output_memory(std::uint64_t bytes) {
  const double b = static_cast<double>(bytes);
  return estimate("a JSON output of " + memory_text(bytes), b * kJsonTextMemory, b);
}

void check_memory(const MemoryEstimate& e, std::uint64_t limit, const std::string& name,
                  const std::string& value) {
  if (e.memory <= limit) return;
  std::string reason = e.what + " would need about " + memory_text(e.memory) + " of memory";
  if (e.output > 0) reason += " (its output about " + memory_text(e.output) + ")";
  reason += ", more than the memory limit of " + memory_text(limit) +
            " (`memory_limit`): raise `memory_limit` or ask for less";
  throw InvalidInput(name, value, reason);
}

std::uint64_t parse_memory_size(const std::string& name, const std::string& text) {
  const char* const expected =
      "expected a size such as 2G, 512M or 3000000000 (bytes; units K, M, G, T, P: powers of "
      "1024)";
  std::size_t i = 0;
  while (i < text.size() && (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '.'))
    ++i;
  const std::string number = text.substr(0, i);
  std::string unit = text.substr(i);
  if (!unit.empty() && unit.front() == ' ') unit.erase(0, 1);
  for (char& c : unit) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  int dots = 0;
  for (char c : number) dots += c == '.';
  if (number.empty() || number == "." || dots > 1 || number.size() > 30)
    throw InvalidInput(name, text.empty() ? "\"\"" : text, expected);
  double scale = 1.0;
  const std::string units = "kmgtp";
  if (!unit.empty() && unit != "b") {
    const std::size_t power = units.find(unit.front());
    const std::string rest = unit.substr(1);
    if (power == std::string::npos || !(rest.empty() || rest == "b" || rest == "ib"))
      throw InvalidInput(name, text, expected);
    scale = std::ldexp(1.0, 10 * static_cast<int>(power + 1));
  }
  const double bytes = std::strtod(number.c_str(), nullptr) * scale;
  if (!(bytes >= static_cast<double>(kMinMemoryLimit) &&
        bytes <= static_cast<double>(kMaxMemoryLimit)))
    throw InvalidInput(name, text, "must be 1M .. 1P (1 MiB .. 1 PiB)");
  return saturated(bytes);
}

std::uint64_t checked_memory_size(const std::string& name, double bytes) {
  if (!(std::isfinite(bytes) && bytes >= static_cast<double>(kMinMemoryLimit) &&
        bytes <= static_cast<double>(kMaxMemoryLimit)))
    throw InvalidInput(name,
                       std::isfinite(bytes) ? memory_text(saturated(std::max(bytes, 0.0)))
                                            : round_trip_text(bytes),
                       "must be 1 MiB .. 1 PiB (1048576 .. 2**50 bytes)");
  return saturated(bytes);
}

std::string memory_text(std::uint64_t bytes) {
  static const char* const units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  double v = static_cast<double>(bytes);
  int u = 0;
  while (v >= 1024.0 && u < 6) {
    v /= 1024.0;
    ++u;
  }
  char buffer[32];
  if (u == 0) {
    std::snprintf(buffer, sizeof buffer, "%llu bytes", static_cast<unsigned long long>(bytes));
  } else {
    std::snprintf(buffer, sizeof buffer, "%.3g %s", v, units[u]);
  }
  return buffer;
}

}  // namespace flaplag
