#pragma once
// The feedplan force-log CSV text in parts, for the whole-log writer (format_force_log) and the
// streaming one (ForceLogFileWriter) to write the same text. Internal to the force_log module.

#include <string>

#include "feedplan/force_log/force_log.hpp"

namespace feedplan::force_log::detail {

//! Appends the metadata lines and the header row of `log` (its rows are not read).
void append_force_log_header(std::string& out, const ForceLog& log);

//! Appends one row as format_force_log writes it, with the columns and omissions of `log`'s flags.
void append_force_log_row(std::string& out, const ForceLog& log, const ForceLogRow& row);

}  // namespace feedplan::force_log::detail
