#pragma once
// The checks of a log's metadata ("# key: value" lines, a DynoWare header block) as they are read.
// Internal to the force_log module.
//
// Metadata is free text, except that the keys feedplan's own writer uses for numbers (the virtual
// machine writes flutes, spindle_rpm, ...) must hold numbers a tool or a recording can have: later
// steps take `# spindle_rpm:` as the spindle speed, and a log claiming `# flutes: inf` is not one
// feedplan wrote. Every key and value must be UTF-8, since metadata is echoed into JSON.

#include <cstddef>
#include <string>

#include "log_problems.hpp"

namespace feedplan::force_log::detail {

//! Adds a problem, named "<line> (<shown_key>)", when `key`'s `value` is not UTF-8, or when `key` is one
//! of the writer's numeric keys and `value` is not a number in its range. True when there was none.
bool check_metadata_entry(Problems& problems, std::size_t line, const std::string& shown_key, const std::string& key,
                          const std::string& value);

}  // namespace feedplan::force_log::detail
