#pragma once
// Test helper: FEEDPLAN_THREADS set for one scope (core/parallel_tasks.hpp reads it), and what was there
// before put back when the scope ends.

#include <cstdlib>
#include <string>

namespace feedplan::test_support {

class ThreadsSetting {
 public:
  explicit ThreadsSetting(const char* value) {
    if (const char* old = std::getenv("FEEDPLAN_THREADS")) old_ = old;
    setenv("FEEDPLAN_THREADS", value, 1);
  }
  ~ThreadsSetting() {
    if (old_.empty()) {
      unsetenv("FEEDPLAN_THREADS");
    } else {
      setenv("FEEDPLAN_THREADS", old_.c_str(), 1);
    }
  }
  ThreadsSetting(const ThreadsSetting&) = delete;
  ThreadsSetting& operator=(const ThreadsSetting&) = delete;

 private:
  std::string old_;
};

}  // namespace feedplan::test_support
