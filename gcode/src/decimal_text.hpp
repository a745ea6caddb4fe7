#pragma once
// Fixed-point numbers as G-code words print them: a value on a grid of 10^-decimals, held as a whole
// number of grid steps so that what is printed and what the writer keeps as the position are the
// same number. Internal to the gcode module.

#include <string>

namespace feedplan::gcode::detail {

//! 10^decimals as a double (decimals in 0..9).
double grid_steps_per_unit(int decimals);

//! `value` rounded to the nearest multiple of 10^-decimals, in grid steps. Needs |value| · 10^decimals
//! well inside the range of long long (the writer keeps coordinates within ±99999 mm, decimals ≤ 6).
long long to_grid(double value, int decimals);

//! The value of `steps` grid steps.
double grid_value(long long steps, int decimals);

//! `steps` grid steps (decimals ≥ 1) as G-code text: always a decimal point, trailing zeros trimmed, no sign on
//! zero: 10000 at 3 decimals is "10.", −5 is "-0.005", 0 is "0.", 12340 is "12.34".
std::string grid_text(long long steps, int decimals);

}  // namespace feedplan::gcode::detail
