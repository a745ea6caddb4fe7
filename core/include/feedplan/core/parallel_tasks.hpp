#pragma once
// Independent tasks spread over the machine's cores. run_tasks(n, task) calls task(k) once for every k in
// [0, n), on up to worker_count() threads (the calling thread is one of them), taking the tasks in order
// as threads come free; it returns when all are done and then rethrows the exception of the lowest task
// that threw. Tasks must not share what they write. The work is the same on any number of threads, so a
// result that depends only on each task's own output is the same too.
//
// FEEDPLAN_THREADS=N in the environment caps the threads at N (1: every task on the calling thread).

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <exception>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "feedplan/core/input_error.hpp"

namespace feedplan {

//! Most threads run_tasks uses: FEEDPLAN_THREADS when set, else the hardware's threads (at least 1).
//! Throws InputError when FEEDPLAN_THREADS is not a whole number in [1, 1024].
inline int worker_count() {
  const char* text = std::getenv("FEEDPLAN_THREADS");
  if (text == nullptr || *text == '\0') return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  char* end = nullptr;
  const long value = std::strtol(text, &end, 10);
  if (*end != '\0' || value < 1 || value > 1024) {
    throw InputError("FEEDPLAN_THREADS", "= '" + std::string(text) +
                                             "': must be a whole number from 1 to 1024, the most threads feedplan may "
                                             "use (unset it to use every core)");
  }
  return static_cast<int>(value);
}

inline void run_tasks(std::size_t n, const std::function<void(std::size_t)>& task) {
  const std::size_t threads = std::min<std::size_t>(n, static_cast<std::size_t>(worker_count()));
  if (threads <= 1) {
    for (std::size_t k = 0; k < n; ++k) task(k);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::vector<std::exception_ptr> failures(n);
  const auto work = [&] {
    for (std::size_t k = next++; k < n; k = next++) {
      try {
        task(k);
      } catch (...) {
        failures[k] = std::current_exception();
      }
    }
  };
  std::vector<std::jthread> helpers;
  for (std::size_t t = 1; t < threads; ++t) helpers.emplace_back(work);
  work();
  helpers.clear();  // joins
  for (const auto& failure : failures) {
    if (failure) std::rethrow_exception(failure);
  }
}

}  // namespace feedplan
