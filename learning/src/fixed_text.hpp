#pragma once
// Numbers in the learning module's messages at a fixed count of decimals: "12.5 mm", "99.6 %".
// Internal to learning.

#include <string>

#include "feedplan/core/number_text.hpp"

namespace feedplan::learning::detail {

//! `value` with `decimals` digits after the point.
inline std::string fixed(double value, int decimals) { return fixed_number_text(value, decimals); }

//! `fraction` in percent: whole percent, one decimal just short of 1 (so 99.6 % does not read as 100 %).
inline std::string percent(double fraction) {
  return fixed(100.0 * fraction, fraction > 0.995 && fraction < 1.0 ? 1 : 0) + " %";
}

}  // namespace feedplan::learning::detail
