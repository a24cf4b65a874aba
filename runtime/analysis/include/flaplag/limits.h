// flaplag — the memory a run may take, decided before it starts.
//
// A map, study, sweep, simulation or forced response keeps its whole result, and a front end
// keeps it once more as output (the command line's JSON document and its text, Python's lists
// and arrays).  How much that is follows from the request alone (cells, rows, points, samples),
// so it is estimated before anything is allocated and compared with a budget, the memory
// limit: a larger request is refused (InvalidInput naming the size that makes it large, the
// estimate and the limit) instead of running until the machine has no memory left.
//
// The estimates are bytes per item (cell, row, point, sample, station) measured on the larger
// of the two front ends (the command line writing JSON, Python's results) and rounded up well
// above the measurement (a map cell: 640 bytes estimated, 340-400 measured; a sample of a
// simulation: 496 estimated, 370 measured; a sweep point of a 1 x 1 model: 15.6 kB estimated,
// 12 kB measured); they are meant to be above the real peak, not equal to it.  The output (the
// JSON text a run writes, its largest form) is estimated with them: it is held in memory next
// to the result, so it is part of the memory estimate (a fifth of it or less).
//
// The default limit, 2 GiB, is a quarter of the memory of an 8 GiB laptop and lets a 24 GiB
// 2-core machine run one large job per core with room to spare.  It admits maps of 3.3 million
// cells (1800 x 1800; output about 300 MiB), every study of a model of up to 4 modes (100000
// values at most), every sweep of the command line with a 1 x 1 model (100001 points at most),
// simulations of 4.3 million samples (100000 revolutions at the default 36 samples each) and
// every forced response.  Larger runs need the limit raised (memory_limit; the command line's
// --memory-limit) or the work split (flaplag map --shard, or fewer samples).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace flaplag {

inline constexpr std::uint64_t kDefaultMemoryLimit = std::uint64_t{2} << 30;  // 2 GiB
// Accepted limits: 1 MiB .. 1 PiB.
inline constexpr std::uint64_t kMinMemoryLimit = std::uint64_t{1} << 20;
inline constexpr std::uint64_t kMaxMemoryLimit = std::uint64_t{1} << 50;

// What a run will hold: bytes at its peak and bytes of its JSON output (saturating at
// UINT64_MAX), and what it is in words ("a map of 1000 x 2000 cells").
struct MemoryEstimate {
  std::string what;
  std::uint64_t memory = 0;
  std::uint64_t output = 0;
};

// state_size: 2 (M + N), Analysis::state_size() (a model of M flap and N lag modes).
MemoryEstimate map_memory(std::size_t x_values, std::size_t y_values);
MemoryEstimate study_memory(std::size_t values, int state_size);
MemoryEstimate sweep_memory(std::size_t points, int state_size);
MemoryEstimate response_memory(int samples, int state_size);
// revolutions * samples_per_rev samples (rounded up) and the start.
MemoryEstimate simulation_memory(double revolutions, int samples_per_rev, int state_size,
                                 bool nonlinear);
// Mode shapes sampled at `stations` stations (Python's Analysis.modes), `shapes` shapes.
MemoryEstimate stations_memory(std::size_t stations, int shapes);
// A JSON text of `bytes` bytes made from documents already in memory (flaplag merge): the
// parts, the merged document and its text.
MemoryEstimate json_output_memory(std::uint64_t bytes);

// Throws InvalidInput(name, value, reason) when e.memory > limit, the reason
// "<what> needs about <memory> of memory (its output about <output>), more than the memory
// limit of <limit> (`memory_limit`): raise `memory_limit` or ask for less".  name and value:
// the input that makes the run large, as the caller's user knows it (a field, an argument).
void check_memory(const MemoryEstimate& e, std::uint64_t limit, const std::string& name,
                  const std::string& value);

// A memory size from text: a whole or decimal number of bytes with an optional unit K, M, G,
// T, P (powers of 1024; "KiB", "KB", "k", "kb" are the same), "2G", "512MiB", "1.5g",
// "3000000000"; kMinMemoryLimit..kMaxMemoryLimit.  Throws InvalidInput(name, text, reason).
std::uint64_t parse_memory_size(const std::string& name, const std::string& text);
// The same for a number of bytes given as a number (Python's memory_limit=2**31).
std::uint64_t checked_memory_size(const std::string& name, double bytes);

// "2 GiB", "1.5 GiB", "640 MiB", "12 KiB", "100 bytes": three significant digits at most.
std::string memory_text(std::uint64_t bytes);

}  // namespace flaplag
