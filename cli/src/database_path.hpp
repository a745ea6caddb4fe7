#pragma once
// Which model database a command uses: --db, else $FEEDPLAN_DB, else the bundled sample database.

#include <cstdlib>
#include <string>

namespace feedplan::cli {

//! `flag` when given, else $FEEDPLAN_DB when set and not empty, else the sample database the build made.
inline std::string database_path(const std::string& flag) {
  if (!flag.empty()) return flag;
  if (const char* env = std::getenv("FEEDPLAN_DB"); env && *env) return env;
  return FEEDPLAN_SAMPLE_DB;
}

}  // namespace feedplan::cli
