#include "number_flag.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"

namespace feedplan::cli {
namespace {

// "--target-force" from "-t,--target-force": the name people read in messages.
std::string flag_name(const std::string& names) {
  const auto comma = names.rfind(',');
  return comma == std::string::npos ? names : names.substr(comma + 1);
}

[[noreturn]] void not_a_number(const std::string& flag, const std::string& text, const char* expected) {
  throw InputError(flag, "= '" + text + "': expected " + expected);
}

// A finite number written in full (no leading blanks, nothing after it), or nothing.
std::optional<double> finite_number(const std::string& text) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front()))) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(value)) return std::nullopt;
  return value;
}

// A base-10 whole number in [low, high] written in full, or nothing.
std::optional<long long> whole_number(const std::string& text, long long low, long long high) {
  if (text.empty() || !(std::isdigit(static_cast<unsigned char>(text.front())) || text.front() == '-' || text.front() == '+')) {
    return std::nullopt;
  }
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(text.c_str(), &end, 10);
  if (end != text.c_str() + text.size() || errno == ERANGE || value < low || value > high) return std::nullopt;
  return value;
}

template <typename Store>
CLI::Option* add_parsed_flag(CLI::App* command, const std::string& names, const std::string& description,
                             const char* type_name, Store store) {
  const std::string flag = flag_name(names);
  return command->add_option_function<std::string>(names, [flag, store](const std::string& text) { store(flag, text); },
                                                  description)
      ->type_name(type_name);
}

template <typename Integer, typename Target>
CLI::Option* add_whole_flag(CLI::App* command, const std::string& names, Target& value, const std::string& description,
                            long long low) {
  constexpr long long high = static_cast<long long>(std::min<unsigned long long>(
      std::numeric_limits<Integer>::max(), static_cast<unsigned long long>(std::numeric_limits<long long>::max())));
  return add_parsed_flag(command, names, description, "INT", [&value, low](const std::string& flag, const std::string& text) {
    const auto parsed = whole_number(text, low, high);
    if (!parsed) not_a_number(flag, text, ("a whole number in [" + std::to_string(low) + ", " + std::to_string(high) + "]").c_str());
    value = static_cast<Integer>(*parsed);
  });
}

// "(0, 0.5]", "> 0", "≥ 1".
std::string range_text(const FlagRange& r) {
  const bool has_low = std::isfinite(r.low);
  const bool has_high = std::isfinite(r.high);
  if (has_low && has_high) {
    return std::string(r.low_closed ? "[" : "(") + shortest_number_text(r.low) + ", " + shortest_number_text(r.high) +
           (r.high_closed ? "]" : ")");
  }
  if (has_low) return (r.low_closed ? "≥ " : "> ") + shortest_number_text(r.low);
  if (has_high) return (r.high_closed ? "≤ " : "< ") + shortest_number_text(r.high);
  return "finite";
}

bool in_range(double value, const FlagRange& r) {
  if (!std::isfinite(value)) return false;
  const bool above_low = r.low_closed ? value >= r.low : value > r.low;
  const bool below_high = r.high_closed ? value <= r.high : value < r.high;
  return above_low && below_high;
}

}  // namespace

void check_flag(std::vector<InputProblem>& problems, const std::string& flag, double value, const FlagRange& range,
                const std::string& why) {
  if (in_range(value, range)) return;
  const std::string bound = range_text(range);
  const bool interval = bound.front() == '[' || bound.front() == '(';
  problems.push_back({flag, "= " + shortest_number_text(value) + ": must be " + (interval ? "in " : "") + bound +
                                (why.empty() ? "" : " — " + why)});
}

void check_flag(std::vector<InputProblem>& problems, const std::string& flag, const std::optional<double>& value,
                const FlagRange& range, const std::string& why) {
  if (value) check_flag(problems, flag, *value, range, why);
}

void with_flag_names(const std::map<std::string, std::string>& flag_of_field, const std::function<void()>& action) {
  try {
    action();
  } catch (const InputError& e) {
    std::vector<InputProblem> problems = e.problems();
    for (InputProblem& p : problems) {
      if (const auto flag = flag_of_field.find(p.field); flag != flag_of_field.end()) p.field = flag->second;
    }
    throw InputError(std::move(problems));
  }
}

CLI::Option* add_number_flag(CLI::App* command, const std::string& names, std::optional<double>& value,
                             const std::string& description) {
  return add_parsed_flag(command, names, description, "NUMBER", [&value](const std::string& flag, const std::string& text) {
    const auto parsed = finite_number(text);
    if (!parsed) not_a_number(flag, text, "a finite number");
    value = *parsed;
  });
}

CLI::Option* add_number_flag(CLI::App* command, const std::string& names, double& value, const std::string& description) {
  return add_parsed_flag(command, names, description, "NUMBER", [&value](const std::string& flag, const std::string& text) {
    const auto parsed = finite_number(text);
    if (!parsed) not_a_number(flag, text, "a finite number");
    value = *parsed;
  });
}

CLI::Option* add_integer_flag(CLI::App* command, const std::string& names, std::optional<std::int64_t>& value,
                              const std::string& description) {
  return add_whole_flag<std::int64_t>(command, names, value, description, std::numeric_limits<std::int64_t>::min());
}

CLI::Option* add_integer_flag(CLI::App* command, const std::string& names, std::optional<int>& value,
                              const std::string& description) {
  return add_whole_flag<int>(command, names, value, description, std::numeric_limits<int>::min());
}

CLI::Option* add_integer_flag(CLI::App* command, const std::string& names, int& value, const std::string& description) {
  return add_whole_flag<int>(command, names, value, description, std::numeric_limits<int>::min());
}

CLI::Option* add_integer_flag(CLI::App* command, const std::string& names, std::uint64_t& value,
                              const std::string& description) {
  return add_whole_flag<std::uint64_t>(command, names, value, description, 0);
}

}  // namespace feedplan::cli
