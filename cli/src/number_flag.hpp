#pragma once
// Numeric flags, read strictly. CLI11 alone reads an empty value (`--target-force ''`) as 0 and takes
// "nan" or "inf" for numbers; here a numeric flag's value must be a finite number written in full, or
// the command stops with exit 2 naming the flag and the value. A flag that is not given leaves its
// variable as it was: std::optional for flags without a default (not given = unset; 0 is a value like
// any other, checked against the flag's range by the command), the default for the others.

#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <string>

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

}  // namespace feedplan::cli
