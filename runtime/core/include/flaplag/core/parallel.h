// flaplag — the one pool of threads behind studies, maps and sweeps.
//
// Work is split into tasks whose results do not depend on which thread runs them or in which
// order, so that every answer is the same for any number of threads.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <optional>

#include "flaplag/core/errors.h"

namespace flaplag {

// Largest thread count accepted anywhere (0 means "as many as the hardware has").
inline constexpr int kMaxThreads = 256;

// InvalidInput("threads", ...) unless 0 <= threads <= kMaxThreads.
std::optional<InvalidInput> threads_problem(int threads);

// Threads that `threads` asks for: itself when > 0, the hardware's count (at least 1) for 0.
std::size_t thread_count(int threads);

// Called after each finished task with (tasks finished, tasks in all); from worker threads, one
// call at a time.
using ProgressFunction = std::function<void(std::size_t, std::size_t)>;

// Runs task(i) for i = 0 .. n-1 on min(thread_count(threads), n) threads (the calling thread
// is one of them; fewer when the system refuses to start more), claiming indices in increasing
// order; stops claiming when *cancel is set.  The other threads are the process's pool, kept
// between calls (a call made while the pool runs another, e.g. from inside a task, starts
// threads of its own; a forked child starts a new pool).  Safe to call from several threads.
// Every claimed task finishes, so the finished tasks are 0 .. k-1; returns k.  A task must not
// throw (catch inside and store what is needed: an exception escaping a worker ends the
// process).
std::size_t parallel_for(std::size_t n, int threads, const std::atomic<bool>* cancel,
                         const ProgressFunction& progress,
                         const std::function<void(std::size_t)>& task);

}  // namespace flaplag
