#pragma once
// Internal: the model database schema on a PostgreSQL server — the same versions as the SQLite file's
// (schema.hpp), each step written in PostgreSQL's dialect — and the check-and-migrate run when a store is
// opened. The version lives in the one-row table feedplan_schema (application_id marks the database as a
// feedplan one, as PRAGMA application_id marks a file).

#include <string>
#include <vector>

#include "feedplan/model_db/store.hpp"
#include "pg_connection.hpp"

namespace feedplan::model_db::detail {

//! The SQL of each migration step on PostgreSQL; element k takes version k to k + 1. Its size is
//! kStoreSchemaVersion.
const std::vector<std::string>& pg_schema_migrations();

//! Reads the database's schema version, refuses a database that is empty (unless kCreate), is not a
//! feedplan one or has a newer schema, then (not read-only) applies the missing migrations in one write
//! transaction. Returns the schema version of the database.
int prepare_pg_schema(PgConnection& connection, OpenMode mode);

//! The problems a PostgreSQL model database can have that its constraints do not rule out (a tool and
//! material with versions of a kind of which none is active), one line each; {"ok"} when there are none.
std::vector<std::string> pg_consistency_check(const PgConnection& connection);

}  // namespace feedplan::model_db::detail
