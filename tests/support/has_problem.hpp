#pragma once
// Test helper: checks that a reader reported a given problem, listing every problem it did report
// when it did not. Shared by the tests of user-input readers.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"

namespace feedplan::test_support {

//! Success when some problem has exactly `field` and a message containing `message_part`.
inline ::testing::AssertionResult has_problem(const std::vector<InputProblem>& problems, const std::string& field,
                                              const std::string& message_part) {
  std::string all;
  for (const auto& p : problems) {
    if (p.field == field && p.message.find(message_part) != std::string::npos) return ::testing::AssertionSuccess();
    all += "\n  " + to_string(p);
  }
  return ::testing::AssertionFailure() << "no problem '" << field << "' with '" << message_part << "' among:" << all;
}

}  // namespace feedplan::test_support
