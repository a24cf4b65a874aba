// The thread pool of core/parallel.h: every task once, in claimed order, the count of finished
// tasks, cancellation between tasks, the threads kept between calls, nested, concurrent and
// forked calls, and the thread-count checks.
#include "flaplag/core/parallel.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

namespace flaplag::parallel_test {
namespace {

TEST(ParallelFor, RunsEveryTaskOnceOnTheThreadsAskedFor) {
  for (int threads : {1, 2, 3, 0}) {
    std::vector<std::atomic<int>> runs(100);
    std::mutex m;
    std::set<std::thread::id> ids;
    std::size_t progress_calls = 0, last_done = 0;
    const std::size_t done = parallel_for(
        runs.size(), threads, nullptr,
        [&](std::size_t finished, std::size_t all) {
          ++progress_calls;  // one call at a time: no lock needed here
          EXPECT_EQ(100u, all);
          EXPECT_GT(finished, last_done);
          last_done = finished;
        },
        [&](std::size_t i) {
          runs[i]++;
          std::lock_guard<std::mutex> lock(m);
          ids.insert(std::this_thread::get_id());
        });
    EXPECT_EQ(100u, done);
    EXPECT_EQ(100u, progress_calls);
    for (const auto& r : runs) EXPECT_EQ(1, r.load()) << "threads " << threads;
    EXPECT_LE(ids.size(), thread_count(threads));
  }
}

TEST(ParallelFor, OneThreadRunsTheTasksInOrderOnTheCaller) {
  std::vector<std::size_t> order;
  const std::thread::id caller = std::this_thread::get_id();
  parallel_for(5, 1, nullptr, {}, [&](std::size_t i) {
    EXPECT_EQ(caller, std::this_thread::get_id());
    order.push_back(i);
  });
  EXPECT_EQ((std::vector<std::size_t>{0, 1, 2, 3, 4}), order);
  EXPECT_EQ(0u, parallel_for(0, 2, nullptr, {}, [](std::size_t) { FAIL(); }));
}

TEST(ParallelFor, CancelStopsClaimingAndTheFinishedTasksAreAPrefix) {
  std::atomic<bool> cancel{false};
  std::vector<int> ran(50, 0);
  const std::size_t done = parallel_for(50, 1, &cancel, {}, [&](std::size_t i) {
    ran[i] = 1;
    if (i == 9) cancel = true;
  });
  EXPECT_EQ(10u, done);
  for (std::size_t i = 0; i < ran.size(); ++i) EXPECT_EQ(i < 10 ? 1 : 0, ran[i]) << i;
}

// The ids of the threads that ran a call's tasks.
std::set<std::thread::id> threads_of_a_call(std::size_t n, int threads) {
  std::mutex m;
  std::condition_variable arrived;
  std::set<std::thread::id> ids;
  // Each task waits until `threads` distinct threads have run one, so that every thread asked
  // for gets a task however the machine schedules them (a fixed sleep let one thread take every
  // task on a loaded machine).  A pool with fewer threads fails after the deadline, once.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  parallel_for(n, threads, nullptr, {}, [&](std::size_t) {
    std::unique_lock<std::mutex> lock(m);
    ids.insert(std::this_thread::get_id());
    arrived.notify_all();
    arrived.wait_until(lock, deadline,
                       [&] { return ids.size() >= static_cast<std::size_t>(threads); });
  });
  return ids;
}

// The workers are kept between calls (no thread started per call), and a call that asks for
// more threads than the pool has gets them.
TEST(ParallelFor, KeepsItsThreadsBetweenCalls) {
  const std::set<std::thread::id> first = threads_of_a_call(8, 2);
  const std::set<std::thread::id> second = threads_of_a_call(8, 2);
  EXPECT_EQ(2u, first.size());
  EXPECT_EQ(first, second);
  const std::set<std::thread::id> more = threads_of_a_call(12, 3);
  EXPECT_EQ(3u, more.size());
  for (std::thread::id id : first) EXPECT_EQ(1u, more.count(id));
  EXPECT_EQ(1u, threads_of_a_call(4, 1).size());
}

// A task that runs a call of its own (the pool is busy: that call starts threads of its own),
// and two user threads calling at once: every task runs once, nothing waits forever.
TEST(ParallelFor, NestedAndConcurrentCallsComplete) {
  std::vector<std::atomic<int>> inner(4 * 10);
  const std::size_t outer = parallel_for(4, 2, nullptr, {}, [&](std::size_t i) {
    EXPECT_EQ(10u, parallel_for(10, 2, nullptr, {}, [&](std::size_t j) { inner[10 * i + j]++; }));
  });
  EXPECT_EQ(4u, outer);
  for (const auto& r : inner) EXPECT_EQ(1, r.load());
  std::vector<std::atomic<int>> a(200), b(200);
  std::thread other(
      [&] { parallel_for(a.size(), 2, nullptr, {}, [&](std::size_t i) { a[i]++; }); });
  parallel_for(b.size(), 2, nullptr, {}, [&](std::size_t i) { b[i]++; });
  other.join();
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(1, a[i].load()) << i;
    EXPECT_EQ(1, b[i].load()) << i;
  }
}

// After fork() the child has none of the parent's threads: its calls start a pool of its own
// (a child waiting for the parent's workers would hang; the alarm turns that into a failure).
TEST(ParallelFor, WorksInAForkedChild) {
  ASSERT_EQ(2u, threads_of_a_call(8, 2).size());  // the parent's pool is running
  const pid_t pid = fork();
  ASSERT_NE(-1, pid);
  if (pid == 0) {
    alarm(20);
    std::atomic<int> ran{0};
    const std::size_t done = parallel_for(50, 2, nullptr, {}, [&](std::size_t) { ran++; });
    _exit(done == 50 && ran.load() == 50 ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(pid, waitpid(pid, &status, 0));
  ASSERT_TRUE(WIFEXITED(status)) << "the child was killed by signal " << WTERMSIG(status);
  EXPECT_EQ(0, WEXITSTATUS(status));
}

TEST(ThreadCount, ZeroIsTheHardwareAndTheRangeIsChecked) {
  EXPECT_GE(thread_count(0), 1u);
  EXPECT_EQ(3u, thread_count(3));
  EXPECT_FALSE(threads_problem(0).has_value());
  EXPECT_FALSE(threads_problem(kMaxThreads).has_value());
  const auto p = threads_problem(-1);
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ("threads", p->name());
  EXPECT_EQ("-1", p->value());
  EXPECT_TRUE(threads_problem(kMaxThreads + 1).has_value());
}

}  // namespace
}  // namespace flaplag::parallel_test
