// The thread pool of core/parallel.h: every task once, in claimed order, the count of finished
// tasks, cancellation between tasks, and the thread-count checks.
#include "flaplag/core/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

namespace flaplag {
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
}  // namespace flaplag
