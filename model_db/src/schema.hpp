#pragma once
// Internal: the model database schema as a list of migrations (step k takes a file from schema version
// k to k + 1) and the check-and-migrate run when a store is opened.

#include <string>
#include <vector>

#include "feedplan/model_db/store.hpp"
#include "sqlite_handle.hpp"

namespace feedplan::model_db::detail {

//! PRAGMA application_id of a feedplan model database: "FPDB" in ASCII.
inline constexpr int kApplicationId = 0x46504442;

//! The SQL of each migration step; element k takes version k to k + 1. Its size is kStoreSchemaVersion.
const std::vector<std::string>& schema_migrations();

//! Reads the file's application id and schema version, refuses a file that is not a feedplan model
//! database, is damaged (when `quick_check`), or has a newer schema, then (not read-only) switches to
//! WAL and applies the missing migrations in one transaction. Returns the schema version of the file.
int prepare_schema(Connection& connection, OpenMode mode, bool quick_check);

}  // namespace feedplan::model_db::detail
