#pragma once
// Which model database a command uses: --db, else $FEEDPLAN_DB, else the bundled sample database — a file
// or a PostgreSQL server's URL (postgresql://…); and how a plan report names it so that `learn` finds the
// same database from any folder.

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/model_db/database_url.hpp"

namespace feedplan::cli {

//! `flag` when given, else $FEEDPLAN_DB when set and not empty, else the sample database the build made.
inline std::string database_path(const std::string& flag) {
  if (!flag.empty()) return flag;
  if (const char* env = std::getenv("FEEDPLAN_DB"); env && *env) return env;
  return FEEDPLAN_SAMPLE_DB;
}

//! The path a plan report keeps for a file: absolute, with `.`, `..` and symbolic links resolved, so that
//! it names the same file from any folder. `path` itself when that cannot be worked out, and for a server's
//! URL (the same from anywhere).
inline std::string stored_path(const std::string& path) {
  namespace fs = std::filesystem;
  if (path.empty() || model_db::is_server_url(path)) return path;
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  if (ec) return path;
  const fs::path canonical = fs::weakly_canonical(absolute, ec);
  return ec ? absolute.lexically_normal().string() : canonical.string();
}

//! The database a plan report names (`stored`, "model.database"), found from here: as stored — reports
//! store it absolute — or, for a relative path from an older report, relative to the current folder, else
//! to the folder of the report (`report_path`). Throws InputError naming "model.database" and every place
//! looked at when it is in none of them: the database was moved or deleted, and --db can say where it is.
//! A server's URL is returned as stored: opening it says whether the server is reachable.
inline std::string report_database_path(const std::string& stored, const std::string& report_path) {
  namespace fs = std::filesystem;
  if (model_db::is_server_url(stored)) return stored;
  std::vector<fs::path> candidates{fs::path(stored)};
  if (fs::path(stored).is_relative()) candidates.push_back(fs::path(report_path).parent_path() / stored);
  std::string looked_at;
  for (const fs::path& candidate : candidates) {
    std::error_code ec;
    if (fs::exists(candidate, ec)) return candidate.string();
    looked_at += (looked_at.empty() ? "" : ", ") + stored_path(candidate.string());
  }
  throw InputError(report_path + ": model.database",
                   "= '" + stored + "': the model database the plan was made with is not there (looked at " + looked_at +
                       "): was it moved or renamed? give its path with --db");
}

}  // namespace feedplan::cli
