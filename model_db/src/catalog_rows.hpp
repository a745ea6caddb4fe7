#pragma once
// Internal: reading and writing the rows of the tools and materials tables, and turning a name into
// a row id with an InputError that lists the known names when there is no such row. Writers assume
// an open write transaction and validated records.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/model_db/store_records.hpp"
#include "sql_statement.hpp"

namespace feedplan::model_db::detail {

std::optional<ToolRecord> select_tool(const Connection& db, std::string_view name);
std::optional<ToolRecord> select_tool_by_id(const Connection& db, RowId id);
std::vector<ToolRecord> select_tools(const Connection& db);
RowId insert_tool(Connection& db, const ToolRecord& tool);
void update_tool(Connection& db, RowId id, const ToolRecord& tool);

std::optional<MaterialRecord> select_material(const Connection& db, std::string_view name);
std::optional<MaterialRecord> select_material_by_id(const Connection& db, RowId id);
std::vector<MaterialRecord> select_materials(const Connection& db);
RowId insert_material(Connection& db, const MaterialRecord& material);
void update_material(Connection& db, RowId id, const MaterialRecord& material);

//! The problem for a tool name not in the store: "<field> = 'X': unknown tool; known: A, B (did you
//! mean A?)".
InputProblem unknown_tool_problem(const Connection& db, std::string_view name, const std::string& field);

//! The same for a material name.
InputProblem unknown_material_problem(const Connection& db, std::string_view name, const std::string& field);

//! The row ids of a tool and a material given by name; every unknown name is added to `problems`
//! (and its id returned as 0).
struct PairIds {
  RowId tool_id = 0;
  RowId material_id = 0;
};
PairIds pair_ids(const Connection& db, std::string_view tool_name, std::string_view material_name,
                 const std::string& field_prefix, std::vector<InputProblem>& problems);

//! pair_ids() that throws InputError when a name is unknown.
PairIds pair_ids_or_throw(const Connection& db, std::string_view tool_name, std::string_view material_name,
                          const std::string& field_prefix);

}  // namespace feedplan::model_db::detail
