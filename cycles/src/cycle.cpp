#include "feedplan/cycles/cycle.hpp"

#include <cmath>
#include <type_traits>

#include "feedplan/core/number_text.hpp"
#include "feedplan/cycles/corner.hpp"
#include "feedplan/cycles/helical_boring.hpp"
#include "feedplan/cycles/pocket.hpp"
#include "feedplan/cycles/spiral.hpp"
#include "feedplan/cycles/trochoid.hpp"
#include "common_checks.hpp"
#include "problems.hpp"

namespace feedplan::cycles {

const char* to_string(Direction direction) { return direction == Direction::kCcw ? "ccw" : "cw"; }

const char* cycle_name(const CycleGeometry& geometry) {
  return std::visit(
      [](const auto& g) -> const char* {
        using T = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<T, CornerSpec>) return "corner";
        if constexpr (std::is_same_v<T, TrochoidSpec>) return "trochoid";
        if constexpr (std::is_same_v<T, SpiralSpec>) return "spiral";
        if constexpr (std::is_same_v<T, HelicalBoringSpec>) return "helical_boring";
        if constexpr (std::is_same_v<T, PocketSpec>) return "pocket";
      },
      geometry);
}

std::vector<InputProblem> validate_tool(const geometry::Tool& tool, const std::string& field) {
  using namespace detail;
  std::vector<InputProblem> problems;
  check(problems, field + ".diameter_mm", tool.diameter_mm, above(0), "the cutting diameter of the end mill");
  if (tool.flutes < 1 || tool.flutes > 32) {
    problems.push_back({field + ".flutes", "= " + std::to_string(tool.flutes) + ": must be in [1, 32] — the number of teeth"});
  }
  check(problems, field + ".helix_deg", tool.helix_deg, {0, true, 60, false}, "the helix angle of the flutes");
  // 0 is the default (geometry::Tool); a spec that gives the field gives a value in range.
  if (tool.max_plunge_feed_per_tooth_mm != 0.0) {
    check(problems, field + ".max_plunge_feed_per_tooth_mm", tool.max_plunge_feed_per_tooth_mm,
          plunge_feed_per_tooth_range(tool), kPlungeFeedPerToothMeaning);
  }
  return problems;
}

namespace detail {

Range plunge_feed_per_tooth_range(const geometry::Tool& tool) {
  const bool diameter_known = std::isfinite(tool.diameter_mm) && tool.diameter_mm > 0.0;
  return diameter_known ? Range{0.0, false, tool.diameter_mm, true} : above(0.0);
}

std::vector<InputProblem> validate_common(const CycleSpec& spec) {
  std::vector<InputProblem> problems;
  check(problems, "spindle_rpm", spec.spindle_rpm, at_least(0), "spindle speed in rev/min (0: not given)");
  check(problems, "target_force_n", spec.target_force_n, at_least(0), "the cutting force to hold in N (0: not given)");
  check(problems, "clearance_z_mm", spec.clearance_z_mm, at_least(kFeedPlaneAboveTopMm),
        "rapids stop " + six_digit_number_text(kFeedPlaneAboveTopMm) + " mm above the stock before feeding down");
  for (auto& problem : geometry::validate(spec.machine)) problems.push_back(std::move(problem));
  if (spec.feed_mm_per_min) {
    check(problems, "feed_mm_per_min", *spec.feed_mm_per_min,
          {spec.machine.min_feed_mm_per_min, true, spec.machine.max_feed_mm_per_min, true},
          "the constant feed you would program, in the machine's feed range, mm/min");
  }
  if (spec.stock) {
    for (auto& problem : geometry::validate(*spec.stock, "stock")) problems.push_back(std::move(problem));
  }
  return problems;
}

}  // namespace detail

std::vector<InputProblem> validate(const CycleSpec& spec) {
  using namespace detail;
  std::vector<InputProblem> problems = std::visit(
      [&](const auto& g) -> std::vector<InputProblem> {
        using T = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<T, HelicalBoringSpec> || std::is_same_v<T, PocketSpec>) {
          return validate(g, spec.tool);
        } else {
          return validate(g, spec.tool, spec.axial_depth_mm);
        }
      },
      spec.geometry);
  const std::string name = cycle_name(spec.geometry);
  if (spec.cycle != name) {
    problems.insert(problems.begin(), {"cycle", "= \"" + spec.cycle + "\": does not match the " + name +
                                                    " parameters the spec holds"});
  }
  if ((name == "helical_boring" || name == "pocket") && spec.axial_depth_mm != 0.0) {
    problems.push_back({"axial_depth_mm", "= " + six_digit_number_text(spec.axial_depth_mm) + ": not used by a " + name +
                                              " cycle — remove it and give " + name + ".depth_mm"});
  }
  for (auto& problem : validate_common(spec)) problems.push_back(std::move(problem));
  return problems;
}

Cycle generate(const CycleSpec& spec) {
  if (auto problems = validate(spec); !problems.empty()) throw InputError(std::move(problems));
  const ZLevels z{spec.stock ? spec.stock->z_top_mm : 0.0, spec.clearance_z_mm};
  Cycle cycle = std::visit(
      [&](const auto& g) -> Cycle {
        using T = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<T, CornerSpec>) return generate_corner(g, spec.tool, spec.axial_depth_mm, z);
        if constexpr (std::is_same_v<T, TrochoidSpec>) return generate_trochoid(g, spec.tool, spec.axial_depth_mm, z);
        if constexpr (std::is_same_v<T, SpiralSpec>) return generate_spiral(g, spec.tool, spec.axial_depth_mm, z);
        if constexpr (std::is_same_v<T, HelicalBoringSpec>) return generate_helical_boring(g, spec.tool, z);
        if constexpr (std::is_same_v<T, PocketSpec>) return generate_pocket(g, spec.tool, z);
      },
      spec.geometry);
  if (spec.stock) cycle.stock = *spec.stock;
  return cycle;
}

}  // namespace feedplan::cycles
