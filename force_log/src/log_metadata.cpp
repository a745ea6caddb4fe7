#include "log_metadata.hpp"

#include <array>
#include <cmath>
#include <optional>
#include <string_view>

#include "feedplan/core/utf8_text.hpp"
#include "log_cells.hpp"

namespace feedplan::force_log::detail {
namespace {

// What a numeric key of the writer may hold.
enum class Rule { kPositive, kNonNegative, kFlutes, kHelix };

struct NumericKey {
  std::string_view key;
  Rule rule;
};

// The keys feedplan_csv_writer's callers (the virtual machine) write as numbers. A spindle that never
// turned in the simulated program writes spindle_rpm 0.
constexpr std::array<NumericKey, 8> kNumericKeys{{{"sample_rate_hz", Rule::kPositive},
                                                   {"tool_diameter_mm", Rule::kPositive},
                                                   {"flutes", Rule::kFlutes},
                                                   {"helix_deg", Rule::kHelix},
                                                   {"spindle_rpm", Rule::kNonNegative},
                                                   {"radial_depth_mm", Rule::kPositive},
                                                   {"axial_depth_mm", Rule::kPositive},
                                                   {"feed_per_tooth_mm", Rule::kNonNegative}}};

constexpr int kMaxFlutes = 100;  // as the model store's tools

// Empty when `value` satisfies `rule`; else what it must be.
std::string rule_problem(Rule rule, const std::string& value) {
  const std::optional<double> number = parse_number(value);
  switch (rule) {
    case Rule::kPositive:
      if (number && std::isfinite(*number) && *number > 0.0) return {};
      return "must be a finite number > 0";
    case Rule::kNonNegative:
      if (number && std::isfinite(*number) && *number >= 0.0) return {};
      return "must be a finite number ≥ 0";
    case Rule::kFlutes:
      if (number && *number >= 1.0 && *number <= kMaxFlutes && *number == std::floor(*number)) return {};
      return "must be a whole number in [1, " + std::to_string(kMaxFlutes) + "]";
    case Rule::kHelix:
      if (number && *number >= 0.0 && *number < 90.0) return {};
      return "must be a number in [0, 90)";
  }
  return {};
}

}  // namespace

bool check_metadata_entry(Problems& problems, std::size_t line, const std::string& shown_key, const std::string& key,
                          const std::string& value) {
  // Built with append: GCC 12 warns falsely (-Wrestrict) on "(" + std::string when inlined.
  std::string where = "(";
  where.append(utf8_shown(shown_key)).append(")");
  std::string shown_value = "= \"";
  shown_value.append(utf8_shown(value)).append("\": ");
  if (std::string problem = utf8_problem(key); !problem.empty()) {
    problems.add(line, where, "the key " + problem);
    return false;
  }
  if (std::string problem = utf8_problem(value); !problem.empty()) {
    problems.add(line, where, shown_value + problem);
    return false;
  }
  for (const NumericKey& numeric : kNumericKeys) {
    if (numeric.key != key) continue;
    const std::string problem = rule_problem(numeric.rule, value);
    if (problem.empty()) return true;
    problems.add(line, where, shown_value + problem);
    return false;
  }
  return true;
}

}  // namespace feedplan::force_log::detail
