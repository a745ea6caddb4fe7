#include "catalog_rows.hpp"

#include "feedplan/core/did_you_mean.hpp"

namespace feedplan::model_db::detail {
namespace {

constexpr const char* kToolColumns = "id, name, diameter_mm, flutes, helix_deg, tool_material, coating, notes";
constexpr const char* kMaterialColumns = "id, name, iso_group, hardness_value, hardness_scale, notes";

ToolRecord read_tool(const Statement& row) {
  ToolRecord tool;
  tool.id = row.column_int64(0);
  tool.name = row.column_text(1);
  tool.diameter_mm = row.column_double(2);
  tool.flutes = row.column_int(3);
  tool.helix_deg = row.column_double(4);
  tool.tool_material = row.column_text(5);
  tool.coating = row.column_text(6);
  tool.notes = row.column_text(7);
  return tool;
}

MaterialRecord read_material(const Statement& row) {
  MaterialRecord material;
  material.id = row.column_int64(0);
  material.name = row.column_text(1);
  // The CHECK constraint admits only the six letters.
  material.iso_group = parse_iso_group(row.column_text(2)).value_or(IsoGroup::kP);
  material.hardness_value = row.column_double(3);
  material.hardness_scale = row.column_text(4);
  material.notes = row.column_text(5);
  return material;
}

std::vector<std::string> names_of(const Connection& db, const char* table) {
  Statement statement(db, std::string("SELECT name FROM ") + table + " ORDER BY name");
  std::vector<std::string> names;
  while (statement.step()) names.push_back(statement.column_text(0));
  return names;
}

InputProblem unknown_problem(const std::vector<std::string>& known, std::string_view name, const std::string& field,
                             const char* what) {
  std::string message = "= '" + std::string(name) + "': unknown " + what;
  if (known.empty()) {
    message += "; the store has none yet";
  } else {
    message += "; known: ";
    constexpr std::size_t kListed = 12;
    for (std::size_t i = 0; i < known.size() && i < kListed; ++i) message += (i == 0 ? "" : ", ") + known[i];
    if (known.size() > kListed) message += ", … (" + std::to_string(known.size()) + " in all)";
    const std::string suggestion = closest_name(name, known, LetterCase::kIgnored);
    if (!suggestion.empty()) message += " (did you mean " + suggestion + "?)";
  }
  return {field, message};
}

}  // namespace

std::optional<ToolRecord> select_tool(const Connection& db, std::string_view name) {
  Statement statement(db, std::string("SELECT ") + kToolColumns + " FROM tools WHERE name = ?");
  statement.bind(name);
  if (!statement.step()) return std::nullopt;
  return read_tool(statement);
}

std::optional<ToolRecord> select_tool_by_id(const Connection& db, RowId id) {
  Statement statement(db, std::string("SELECT ") + kToolColumns + " FROM tools WHERE id = ?");
  statement.bind(id);
  if (!statement.step()) return std::nullopt;
  return read_tool(statement);
}

std::vector<ToolRecord> select_tools(const Connection& db) {
  Statement statement(db, std::string("SELECT ") + kToolColumns + " FROM tools ORDER BY name");
  std::vector<ToolRecord> tools;
  while (statement.step()) tools.push_back(read_tool(statement));
  return tools;
}

RowId insert_tool(Connection& db, const ToolRecord& tool) {
  Statement statement(db,
                      "INSERT INTO tools (name, diameter_mm, flutes, helix_deg, tool_material, coating, notes) "
                      "VALUES (?, ?, ?, ?, ?, ?, ?)");
  statement.bind_all(tool.name, tool.diameter_mm, tool.flutes, tool.helix_deg, tool.tool_material, tool.coating,
                     tool.notes);
  statement.run();
  return db.last_insert_rowid();
}

void update_tool(Connection& db, RowId id, const ToolRecord& tool) {
  Statement statement(db,
                      "UPDATE tools SET name = ?, diameter_mm = ?, flutes = ?, helix_deg = ?, tool_material = ?, "
                      "coating = ?, notes = ? WHERE id = ?");
  statement.bind_all(tool.name, tool.diameter_mm, tool.flutes, tool.helix_deg, tool.tool_material, tool.coating,
                     tool.notes, id);
  statement.run();
}

std::optional<MaterialRecord> select_material(const Connection& db, std::string_view name) {
  Statement statement(db, std::string("SELECT ") + kMaterialColumns + " FROM materials WHERE name = ?");
  statement.bind(name);
  if (!statement.step()) return std::nullopt;
  return read_material(statement);
}

std::optional<MaterialRecord> select_material_by_id(const Connection& db, RowId id) {
  Statement statement(db, std::string("SELECT ") + kMaterialColumns + " FROM materials WHERE id = ?");
  statement.bind(id);
  if (!statement.step()) return std::nullopt;
  return read_material(statement);
}

std::vector<MaterialRecord> select_materials(const Connection& db) {
  Statement statement(db, std::string("SELECT ") + kMaterialColumns + " FROM materials ORDER BY name");
  std::vector<MaterialRecord> materials;
  while (statement.step()) materials.push_back(read_material(statement));
  return materials;
}

RowId insert_material(Connection& db, const MaterialRecord& material) {
  Statement statement(db,
                      "INSERT INTO materials (name, iso_group, hardness_value, hardness_scale, notes) "
                      "VALUES (?, ?, ?, ?, ?)");
  statement.bind_all(material.name, to_string(material.iso_group), material.hardness_value, material.hardness_scale,
                     material.notes);
  statement.run();
  return db.last_insert_rowid();
}

void update_material(Connection& db, RowId id, const MaterialRecord& material) {
  Statement statement(db,
                      "UPDATE materials SET name = ?, iso_group = ?, hardness_value = ?, hardness_scale = ?, "
                      "notes = ? WHERE id = ?");
  statement.bind_all(material.name, to_string(material.iso_group), material.hardness_value, material.hardness_scale,
                     material.notes, id);
  statement.run();
}

InputProblem unknown_tool_problem(const Connection& db, std::string_view name, const std::string& field) {
  return unknown_problem(names_of(db, "tools"), name, field, "tool");
}

InputProblem unknown_material_problem(const Connection& db, std::string_view name, const std::string& field) {
  return unknown_problem(names_of(db, "materials"), name, field, "material");
}

PairIds pair_ids(const Connection& db, std::string_view tool_name, std::string_view material_name,
                 const std::string& field_prefix, std::vector<InputProblem>& problems) {
  PairIds ids;
  if (auto tool = select_tool(db, tool_name)) {
    ids.tool_id = tool->id;
  } else {
    problems.push_back(unknown_tool_problem(db, tool_name, field_prefix + "tool_name"));
  }
  if (auto material = select_material(db, material_name)) {
    ids.material_id = material->id;
  } else {
    problems.push_back(unknown_material_problem(db, material_name, field_prefix + "material_name"));
  }
  return ids;
}

PairIds pair_ids_or_throw(const Connection& db, std::string_view tool_name, std::string_view material_name,
                          const std::string& field_prefix) {
  std::vector<InputProblem> problems;
  const PairIds ids = pair_ids(db, tool_name, material_name, field_prefix, problems);
  if (!problems.empty()) throw InputError(std::move(problems));
  return ids;
}

}  // namespace feedplan::model_db::detail
