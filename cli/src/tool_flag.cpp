#include "tool_flag.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "feedplan/core/number_text.hpp"

namespace feedplan::cli {

geometry::Tool parse_tool(const std::string& text, std::vector<InputProblem>& problems) {
  geometry::Tool tool;
  tool.name.clear();
  bool have_diameter = false;
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    const auto eq = item.find('=');
    const std::string key = item.substr(0, eq);
    const std::string value = eq == std::string::npos ? "" : item.substr(eq + 1);
    if (eq == std::string::npos) {
      problems.push_back({"--tool", "item '" + item + "' is not key=value; expected diameter_mm=10,flutes=4,helix_deg=30"});
      continue;
    }
    if (key == "name") {
      tool.name = value;
      continue;
    }
    char* end = nullptr;
    const double number = std::strtod(value.c_str(), &end);
    const bool numeric = !value.empty() && end && *end == '\0' && std::isfinite(number);
    if (key == "diameter_mm" || key == "flutes" || key == "helix_deg" || key == "max_plunge_feed_per_tooth_mm") {
      have_diameter = have_diameter || key == "diameter_mm";
      if (!numeric) {
        problems.push_back({"--tool " + key, "= " + value + ": must be a finite number"});
        continue;
      }
      if (key == "diameter_mm") {
        tool.diameter_mm = number;
      } else if (key == "flutes") {
        if (number != std::floor(number)) {
          problems.push_back({"--tool flutes", "= " + value + ": must be a whole number of teeth"});
          continue;
        }
        tool.flutes = static_cast<int>(number);
      } else if (key == "helix_deg") {
        tool.helix_deg = number;
      } else {
        tool.max_plunge_feed_per_tooth_mm = number;
      }
    } else {
      problems.push_back({"--tool", "key '" + key +
                                       "' is not known; expected diameter_mm, flutes, helix_deg, max_plunge_feed_per_tooth_mm, name"});
    }
  }
  // The plunge feed per tooth, when given: a positive chip no thicker than the cutter (as a spec's tool section).
  if (tool.max_plunge_feed_per_tooth_mm != 0.0 &&
      !(tool.max_plunge_feed_per_tooth_mm > 0.0 && tool.max_plunge_feed_per_tooth_mm <= tool.diameter_mm)) {
    problems.push_back({"--tool max_plunge_feed_per_tooth_mm",
                        "= " + shortest_number_text(tool.max_plunge_feed_per_tooth_mm) +
                            ": must be > 0 mm and at most the diameter (the largest feed per tooth along -Z while "
                            "the tool descends into material; 0.0025 x diameter when not given)"});
  }
  if (!have_diameter) problems.push_back({"--tool", "= '" + text + "': diameter_mm is required, e.g. diameter_mm=10,flutes=4"});
  if (tool.name.empty()) {
    std::string name(1, 'D');
    name += six_digit_number_text(tool.diameter_mm);
    name += " Z";
    name += std::to_string(tool.flutes);
    tool.name = std::move(name);
  }
  return tool;
}

}  // namespace feedplan::cli
