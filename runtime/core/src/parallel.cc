// flaplag — the one pool of threads behind studies, maps and sweeps.
//
// The worker threads are kept between calls.  Starting a thread per call costs about 40 us on
// the project's machine (creation and join, then a cold allocator cache on the new thread), a
// few per cent of a 151-point sweep; a kept thread waits on a condition variable, after a short
// spin so that back-to-back calls (a study's sweeps, a benchmark) find it awake.  A call made
// while the pool runs another (from a task, or from a second user thread at the same time)
// starts threads of its own instead, as every call used to.  After fork() the child starts a
// new pool: the parent's threads do not exist there.
#include "flaplag/core/parallel.h"

#include <pthread.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <exception>
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

namespace {

// How long an idle worker polls for the next job before it sleeps.
constexpr std::chrono::microseconds kSpin{200};

class Pool {
 public:
  // Runs `work` on up to `extra` pool threads and on the calling thread, and returns once every
  // one of them has returned from it.  False (nothing run) when the pool is running another call.
  bool try_run(std::size_t extra, const std::function<void()>& work) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (busy_) return false;
    busy_ = true;
    while (threads_ < extra) {
      try {
        // It waits for the generation after this one: the job below is its first.
        std::thread(&Pool::worker, this, threads_, generation_.load()).detach();
      } catch (const std::system_error&) {
        break;  // no more threads to be had: the call runs on those there are
      }
      ++threads_;
    }
    job_ = &work;
    participants_ = std::min(extra, threads_);
    running_ = participants_;
    generation_.fetch_add(1, std::memory_order_release);
    wake_.notify_all();  // under the lock, as helgrind wants it
    lock.unlock();
    std::exception_ptr thrown;  // a task must not throw; if one does, the pool still ends clean
    try {
      work();
    } catch (...) {
      thrown = std::current_exception();
    }
    lock.lock();
    done_.wait(lock, [&] { return running_ == 0; });
    job_ = nullptr;
    busy_ = false;
    if (thrown) std::rethrow_exception(thrown);
    return true;
  }

 private:
  void worker(std::size_t index, unsigned long seen) {
    for (;;) {
      // Poll, then sleep, until the next call.
      const auto until = std::chrono::steady_clock::now() + kSpin;
      while (generation_.load(std::memory_order_acquire) == seen &&
             std::chrono::steady_clock::now() < until)
        std::this_thread::yield();
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return generation_.load(std::memory_order_acquire) != seen; });
      seen = generation_.load(std::memory_order_acquire);
      if (index >= participants_) continue;  // this call asked for fewer threads
      const std::function<void()>* job = job_;
      lock.unlock();
      (*job)();
      lock.lock();
      if (--running_ == 0) done_.notify_one();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_, done_;
  std::atomic<unsigned long> generation_{0};
  bool busy_ = false;
  std::size_t threads_ = 0;       // started, all alive
  std::size_t participants_ = 0;  // of the current call: the workers with index < this
  std::size_t running_ = 0;       // participants that have not returned from the job yet
  const std::function<void()>* job_ = nullptr;
};

// The process's pool, made on first use and never destroyed (its detached threads may still
// be waiting when the process exits).  The fork handler drops the parent's pool in the child.
std::atomic<Pool*> the_pool{nullptr};

void forget_pool_in_child() { the_pool.store(nullptr); }

Pool& pool() {
  Pool* p = the_pool.load(std::memory_order_acquire);
  if (p != nullptr) return *p;
  static const int registered = pthread_atfork(nullptr, nullptr, forget_pool_in_child);
  (void)registered;
  Pool* made = new Pool;
  if (the_pool.compare_exchange_strong(p, made)) return *made;
  delete made;  // another thread made one first
  return *p;
}

}  // namespace

std::size_t parallel_for(std::size_t n, int threads, const std::atomic<bool>* cancel,
                         const ProgressFunction& progress,
                         const std::function<void(std::size_t)>& task) {
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> finished{0};
  std::mutex progress_mutex;
  const std::function<void()> worker = [&] {
    for (;;) {
      if (cancel != nullptr && cancel->load()) return;
      const std::size_t i = next.fetch_add(1);
      if (i >= n) return;
      task(i);
      if (progress) {
        // Counted under the lock, so that the counts reported rise strictly (counted before it,
        // a thread could report 65 after another had reported 74).
        std::lock_guard<std::mutex> lock(progress_mutex);
        progress(finished.fetch_add(1) + 1, n);
      } else {
        finished.fetch_add(1);
      }
    }
  };
  const std::size_t count = std::min(thread_count(threads), n);
  if (count <= 1) {
    worker();
  } else if (!pool().try_run(count - 1, worker)) {
    // The pool is running another call: threads of this call's own.
    std::vector<std::thread> own;
    own.reserve(count - 1);
    for (std::size_t t = 1; t < count; ++t) {
      try {
        own.emplace_back(worker);
      } catch (const std::system_error&) {
        break;  // no more threads to be had: the tasks run on those there are, the same results
      }
    }
    worker();
    for (std::thread& t : own) t.join();
  }
  return std::min(next.load(), n) == finished.load() ? finished.load() : std::min(next.load(), n);
}

}  // namespace flaplag
