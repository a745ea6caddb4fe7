#include "decimal_text.hpp"

#include <cassert>
#include <cmath>
#include <cstdlib>

namespace feedplan::gcode::detail {

double grid_steps_per_unit(int decimals) {
  assert(decimals >= 0 && decimals <= 9);
  double scale = 1.0;
  for (int i = 0; i < decimals; ++i) scale *= 10.0;
  return scale;
}

long long to_grid(double value, int decimals) {
  assert(std::isfinite(value));
  return std::llround(value * grid_steps_per_unit(decimals));
}

double grid_value(long long steps, int decimals) {
  return static_cast<double>(steps) / grid_steps_per_unit(decimals);
}

std::string grid_text(long long steps, int decimals) {
  assert(decimals >= 1);
  const long long scale = static_cast<long long>(grid_steps_per_unit(decimals));
  const unsigned long long magnitude = steps < 0 ? 0ULL - static_cast<unsigned long long>(steps)
                                                 : static_cast<unsigned long long>(steps);
  std::string text = steps < 0 ? "-" : "";
  text += std::to_string(magnitude / static_cast<unsigned long long>(scale));
  text += '.';
  std::string fraction = std::to_string(magnitude % static_cast<unsigned long long>(scale));
  fraction.insert(0, static_cast<std::size_t>(decimals) - fraction.size(), '0');
  while (!fraction.empty() && fraction.back() == '0') fraction.pop_back();
  return text + fraction;
}

}  // namespace feedplan::gcode::detail
