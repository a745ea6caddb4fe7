// libFuzzer harness: cycles::read_cycle_spec on arbitrary text (a cycle spec file, YAML).
#include <cstddef>
#include <cstdint>

#include "../fuzz_input.hpp"
#include "feedplan/cycles/spec_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  feedplan::fuzz::read_or_refuse(data, size, [](const std::string& text) {
    (void)feedplan::cycles::read_cycle_spec(text, "fuzz.yaml");
  });
  return 0;
}
