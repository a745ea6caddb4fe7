#pragma once
// Internal: reading and writing stored cutting tests with their steady per-revolution peaks (a child
// table, one row per peak). Writers assume an open write transaction and a validated record.

#include <optional>
#include <string>
#include <vector>

#include "feedplan/model_db/store_records.hpp"
#include "sql_statement.hpp"

namespace feedplan::model_db::detail {

//! "down", "up" or "slot".
std::string to_text(CutMode mode);

//! The mode named by its text, or nothing.
std::optional<CutMode> parse_cut_mode(const std::string& text);

//! Inserts the test and its peaks with `created_at`; returns its row id.
RowId insert_cutting_test(Connection& db, RowId tool_id, RowId material_id, const CuttingTestRecord& test,
                          const std::string& created_at);

//! The pair's cutting tests (every test when both ids are 0), ordered by tool name, material name,
//! created_at and id.
std::vector<StoredCuttingTest> select_cutting_tests(const Connection& db, RowId tool_id, RowId material_id);

}  // namespace feedplan::model_db::detail
