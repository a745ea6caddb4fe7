// libFuzzer harness: planner::parse_plan_report on arbitrary text (a plan report, JSON).
#include <cstddef>
#include <cstdint>

#include "../fuzz_input.hpp"
#include "feedplan/planner/plan_report.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  feedplan::fuzz::read_or_refuse(data, size, [](const std::string& text) {
    (void)feedplan::planner::parse_plan_report(text, "fuzz.json");
  });
  return 0;
}
