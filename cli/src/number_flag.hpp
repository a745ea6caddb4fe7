#pragma once
// Numeric flags, read strictly. CLI11 alone reads an empty value (`--target-force ''`) as 0 and takes
// "nan" or "inf" for numbers; here a numeric flag's value must be a finite number written in full, or
// the command stops with exit 2 naming the flag and the value. A flag that is not given leaves its
// variable as it was: std::optional for flags without a default (not given = unset; 0 is a value like
// any other, checked against the flag's range by the command), the default for the others.

#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"

namespace feedplan::cli {

//! Registers `names` (e.g. "--target-force") as a number: a finite decimal number, else InputError.
CLI::Option* add_number_flag(CLI::App* command, const std::string& names, std::optional<double>& value,
                             const std::string& description);
//! The same for a flag with a default: `value` keeps it when the flag is not given.
CLI::Option* add_number_flag(CLI::App* command, const std::string& names, double& value, const std::string& description);
//! A whole number in the range of the type (base 10, no fraction), else InputError.
CLI::Option* add_integer_flag(CLI::App* command, const std::string& names, std::optional<std::int64_t>& value,
                              const std::string& description);
CLI::Option* add_integer_flag(CLI::App* command, const std::string& names, std::optional<int>& value,
                              const std::string& description);  //!< see above
CLI::Option* add_integer_flag(CLI::App* command, const std::string& names, int& value,
                              const std::string& description);  //!< see above
CLI::Option* add_integer_flag(CLI::App* command, const std::string& names, std::uint64_t& value,
                              const std::string& description);  //!< see above (≥ 0)

//! An interval of allowed flag values; an infinite bound is no bound.
struct FlagRange {
  double low = -std::numeric_limits<double>::infinity();  //!< lower bound
  bool low_closed = true;                                 //!< the lower bound itself is allowed
  double high = std::numeric_limits<double>::infinity();  //!< upper bound
  bool high_closed = true;                                //!< the upper bound itself is allowed
};

//! Appends "<flag> = <value>: must be in <range>[ — <why>]" unless `value` is finite and in `range`.
void check_flag(std::vector<InputProblem>& problems, const std::string& flag, double value, const FlagRange& range,
                const std::string& why = "");

//! The same for a flag that may be left out: nothing to check when it was not given.
void check_flag(std::vector<InputProblem>& problems, const std::string& flag, const std::optional<double>& value,
                const FlagRange& range, const std::string& why = "");

//! Runs `action`; an InputError it throws is thrown again with the fields in `flag_of_field` (a
//! library's field path, e.g. "tools.diameter_mm") named by the flag that set them ("--diameter-mm").
void with_flag_names(const std::map<std::string, std::string>& flag_of_field, const std::function<void()>& action);

}  // namespace feedplan::cli
