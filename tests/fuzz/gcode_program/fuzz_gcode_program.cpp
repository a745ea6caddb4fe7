// libFuzzer harness: gcode::read_program on arbitrary text (an RS274/NGC program).
#include <cstddef>
#include <cstdint>

#include "../fuzz_input.hpp"
#include "feedplan/gcode/reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  feedplan::fuzz::read_or_refuse(data, size, [](const std::string& text) {
    (void)feedplan::gcode::read_program(text, "fuzz.ngc");
  });
  return 0;
}
