// run_tasks: every task once, on any number of threads; the lowest failing task's exception; and a
// FEEDPLAN_THREADS that is not a thread count is named.

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "feedplan/core/parallel_tasks.hpp"
#include "threads_setting.hpp"

namespace feedplan {
namespace {

using test_support::ThreadsSetting;

TEST(RunTasks, EveryTaskRunsOnceOnAnyNumberOfThreads) {
  for (const char* threads : {"1", "2", "5", "64"}) {
    const ThreadsSetting setting(threads);
    constexpr std::size_t kTasks = 1000;
    std::vector<std::atomic<int>> runs(kTasks);
    run_tasks(kTasks, [&](std::size_t k) { ++runs[k]; });
    for (std::size_t k = 0; k < kTasks; ++k) ASSERT_EQ(runs[k].load(), 1) << "task " << k << " on " << threads;
  }
  run_tasks(0, [](std::size_t) { FAIL() << "no task to run"; });
}

TEST(RunTasks, TheLowestFailingTasksExceptionReachesTheCaller) {
  for (const char* threads : {"1", "4"}) {
    const ThreadsSetting setting(threads);
    std::atomic<int> ran{0};
    try {
      run_tasks(50, [&](std::size_t k) {
        ++ran;
        if (k == 17 || k == 40) throw std::runtime_error("task " + std::to_string(k));
      });
      FAIL() << "no exception on " << threads << " threads";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), "task 17");
    }
    if (std::string(threads) != "1") {
      EXPECT_EQ(ran.load(), 50) << "the other tasks still ran";
    }
  }
}

TEST(RunTasks, AThreadCountThatIsNotOneIsNamed) {
  for (const char* bad : {"0", "-2", "two", "3x", "100000"}) {
    const ThreadsSetting setting(bad);
    try {
      run_tasks(3, [](std::size_t) {});
      FAIL() << "accepted FEEDPLAN_THREADS=" << bad;
    } catch (const InputError& e) {
      const std::string text = e.what();
      EXPECT_NE(text.find("FEEDPLAN_THREADS"), std::string::npos) << text;
      EXPECT_NE(text.find(bad), std::string::npos) << text;
      EXPECT_NE(text.find("from 1 to 1024"), std::string::npos) << text;
    }
  }
}

}  // namespace
}  // namespace feedplan
