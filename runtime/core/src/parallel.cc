// flaplag — the one pool of threads behind studies, maps and sweeps.
#include "flaplag/core/parallel.h"

#include <algorithm>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

namespace flaplag {

std::optional<InvalidInput> threads_problem(int threads) {
  if (threads < 0 || threads > kMaxThreads)
    return InvalidInput("threads", std::to_string(threads),
                        "must be 0 (all cores) or 1.." + std::to_string(kMaxThreads));
  return std::nullopt;
}

std::size_t thread_count(int threads) {
  return threads > 0 ? static_cast<std::size_t>(threads)
                     : std::max(1u, std::thread::hardware_concurrency());
}

std::size_t parallel_for(std::size_t n, int threads, const std::atomic<bool>* cancel,
                         const ProgressFunction& progress,
                         const std::function<void(std::size_t)>& task) {
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> finished{0};
  std::mutex progress_mutex;
  auto worker = [&] {
    for (;;) {
      if (cancel != nullptr && cancel->load()) return;
      const std::size_t i = next.fetch_add(1);
      if (i >= n) return;
      task(i);
      const std::size_t done = finished.fetch_add(1) + 1;
      if (progress) {
        std::lock_guard<std::mutex> lock(progress_mutex);
        progress(done, n);
      }
    }
  };
  const std::size_t count = std::min(thread_count(threads), n);
  std::vector<std::thread> pool;
  if (count > 1) pool.reserve(count - 1);
  for (std::size_t t = 1; t < count; ++t) {
    try {
      pool.emplace_back(worker);
    } catch (const std::system_error&) {
      break;  // no more threads to be had: the tasks run on those there are, the same results
    }
  }
  worker();
  for (std::thread& t : pool) t.join();
  return std::min(next.load(), n) == finished.load() ? finished.load() : std::min(next.load(), n);
}

}  // namespace flaplag
