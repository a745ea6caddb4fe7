// libFuzzer harness: force_log::read_force_log on arbitrary text (feedplan CSV or a Kistler DynoWare
// export), then the logged spindle speed, which reads the log's metadata.
#include <cstddef>
#include <cstdint>

#include "../fuzz_input.hpp"
#include "feedplan/force_log/force_log.hpp"
#include "feedplan/force_log/logged_spindle_speed.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  feedplan::fuzz::read_or_refuse(data, size, [](const std::string& text) {
    const feedplan::force_log::ForceLog log = feedplan::force_log::read_force_log(text, "fuzz.csv");
    (void)feedplan::force_log::logged_spindle_rpm(log);
  });
  return 0;
}
