#pragma once
// Where a model database is: a file path (SQLite, the embedded default) or the URL of a PostgreSQL
// server ("postgresql://user@host:port/dbname", or "postgres://…"), as --db and $FEEDPLAN_DB take it.

#include <string>
#include <string_view>

namespace feedplan::model_db {

//! Whether `location` names a PostgreSQL database (starts with "postgresql://" or "postgres://") rather
//! than a file.
bool is_server_url(std::string_view location);

//! `location` as messages and reports show it: a URL without its password ("postgresql://ann:***@host/db",
//! also a "password=" query parameter), a path unchanged.
std::string shown_location(std::string_view location);

}  // namespace feedplan::model_db
