#include "model_rows.hpp"

#include <nlohmann/json.hpp>

namespace feedplan::model_db::detail {
namespace {

// One column list for every model query; read_model() takes the columns in this order.
constexpr const char* kModelSelect =
    "SELECT m.id, t.name, mt.name, m.version, m.parent_id, p.version, "
    "m.beta0, m.beta1, m.beta2, m.beta11, m.beta22, m.beta12, "
    "m.chip_center_mm, m.chip_scale_mm, m.contact_length_center_mm, m.contact_length_scale_mm, "
    "m.chip_min_mm, m.chip_max_mm, m.contact_length_min_mm, m.contact_length_max_mm, "
    "m.axial_depth_mm, m.spindle_rpm, m.quantity, "
    "m.fit_n, m.rmse_n, m.r_squared, m.covariance_json, m.standard_errors_json, m.loo_rmse_n, m.engagement_cv_rmse_n, "
    "m.source, m.created_at, m.note, m.active, m.kind, "
    "k.ktc_n_per_mm2, k.krc_n_per_mm2, k.kac_n_per_mm2, k.kte_n_per_mm, k.kre_n_per_mm, k.kae_n_per_mm, "
    "k.size_exponent, k.size_reference_chip_mm, k.size_min_chip_mm, k.runout_json, k.helix_deg, k.covariance_json, "
    "k.signal_rms_residual_n, k.condition_number, k.identified, k.unidentifiable_json "
    "FROM models m JOIN tools t ON t.id = m.tool_id JOIN materials mt ON mt.id = m.material_id "
    "LEFT JOIN models p ON p.id = m.parent_id LEFT JOIN mechanistic_models k ON k.model_id = m.id ";

template <std::size_t N>
std::array<double, N> numbers_from_json(const std::string& text) {
  std::array<double, N> values{};
  const auto parsed = nlohmann::json::parse(text, nullptr, false);
  if (!parsed.is_array()) return values;
  for (std::size_t i = 0; i < N && i < parsed.size(); ++i) {
    if (parsed[i].is_number()) values[i] = parsed[i].get<double>();
  }
  return values;
}

template <std::size_t N>
std::string numbers_to_json(const std::array<double, N>& values) {
  return nlohmann::json(values).dump();
}

std::vector<double> number_list_from_json(const std::string& text) {
  std::vector<double> values;
  const auto parsed = nlohmann::json::parse(text, nullptr, false);
  if (!parsed.is_array()) return values;
  for (const auto& value : parsed) values.push_back(value.is_number() ? value.get<double>() : 0.0);
  return values;
}

std::vector<std::string> text_list_from_json(const std::string& text) {
  std::vector<std::string> values;
  const auto parsed = nlohmann::json::parse(text, nullptr, false);
  if (!parsed.is_array()) return values;
  for (const auto& value : parsed) {
    if (value.is_string()) values.push_back(value.get<std::string>());
  }
  return values;
}

// The columns of mechanistic_models from column `c` on (present when the row is a mechanistic version).
MechanisticFit read_mechanistic(const Statement& row, int c) {
  MechanisticFit fit;
  model::MechanisticModel& m = fit.model;
  m.ktc_n_per_mm2 = row.column_double(c++);
  m.krc_n_per_mm2 = row.column_double(c++);
  m.kac_n_per_mm2 = row.column_double(c++);
  m.kte_n_per_mm = row.column_double(c++);
  m.kre_n_per_mm = row.column_double(c++);
  m.kae_n_per_mm = row.column_double(c++);
  m.size_exponent = row.column_double(c++);
  m.size_reference_chip_mm = row.column_double(c++);
  m.size_min_chip_mm = row.column_double(c++);
  m.runout_mm = number_list_from_json(row.column_text(c++));
  if (!row.column_is_null(c)) m.helix_deg = row.column_double(c);
  ++c;
  const std::array<double, 16> covariance = numbers_from_json<16>(row.column_text(c++));
  for (std::size_t i = 0; i < 16; ++i) fit.covariance[i / 4][i % 4] = covariance[i];
  fit.signal_rms_residual_n = row.column_double(c++);
  fit.condition_number = row.column_double(c++);
  fit.identified = row.column_int(c++) != 0;
  fit.unidentifiable = text_list_from_json(row.column_text(c++));
  return fit;
}

void insert_mechanistic_row(Connection& db, RowId model_id, const MechanisticFit& fit) {
  Statement statement(db,
                      "INSERT INTO mechanistic_models (model_id, ktc_n_per_mm2, krc_n_per_mm2, kac_n_per_mm2, "
                      "kte_n_per_mm, kre_n_per_mm, kae_n_per_mm, size_exponent, size_reference_chip_mm, "
                      "size_min_chip_mm, runout_json, helix_deg, covariance_json, signal_rms_residual_n, condition_number, "
                      "identified, unidentifiable_json) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  const model::MechanisticModel& m = fit.model;
  std::array<double, 16> covariance{};
  for (std::size_t i = 0; i < 16; ++i) covariance[i] = fit.covariance[i / 4][i % 4];
  statement.bind_all(model_id, m.ktc_n_per_mm2, m.krc_n_per_mm2, m.kac_n_per_mm2, m.kte_n_per_mm, m.kre_n_per_mm,
                     m.kae_n_per_mm, m.size_exponent, m.size_reference_chip_mm, m.size_min_chip_mm,
                     nlohmann::json(m.runout_mm).dump());
  if (m.helix_deg) {
    statement.bind(*m.helix_deg);
  } else {
    statement.bind_null();
  }
  statement.bind_all(numbers_to_json(covariance), fit.signal_rms_residual_n,
                     fit.condition_number, fit.identified ? 1 : 0, nlohmann::json(fit.unidentifiable).dump());
  statement.run();
}

ModelRecord read_model(const Statement& row) {
  ModelRecord record;
  int c = 0;
  record.id = row.column_int64(c++);
  record.tool_name = row.column_text(c++);
  record.material_name = row.column_text(c++);
  record.version = row.column_int(c++);
  record.parent_id = row.column_optional_int64(c++);
  if (!row.column_is_null(c)) record.parent_version = row.column_int(c);
  ++c;
  model::ResponseSurfaceModel& model = record.model;
  for (double& beta : model.beta) beta = row.column_double(c++);
  model.chip_center_mm = row.column_double(c++);
  model.chip_scale_mm = row.column_double(c++);
  model.contact_length_center_mm = row.column_double(c++);
  model.contact_length_scale_mm = row.column_double(c++);
  model.range.chip_min_mm = row.column_double(c++);
  model.range.chip_max_mm = row.column_double(c++);
  model.range.contact_length_min_mm = row.column_double(c++);
  model.range.contact_length_max_mm = row.column_double(c++);
  model.axial_depth_mm = row.column_double(c++);
  model.spindle_rpm = row.column_double(c++);
  model.quantity = row.column_text(c++);
  record.fit.n = row.column_int(c++);
  record.fit.rmse_n = row.column_double(c++);
  record.fit.r_squared = row.column_double(c++);
  record.fit.covariance = model::Covariance::from_entries(numbers_from_json<36>(row.column_text(c++)));
  record.fit.standard_errors = numbers_from_json<6>(row.column_text(c++));
  record.fit.loo_rmse_n = row.column_double(c++);
  record.fit.engagement_cv_rmse_n = row.column_double(c++);
  // The CHECK constraint admits only the three source names.
  record.source = parse_model_source(row.column_text(c++)).value_or(ModelSource::kImported);
  record.created_at = row.column_text(c++);
  record.note = row.column_text(c++);
  record.active = row.column_int(c++) != 0;
  // The CHECK constraint admits only the two kind names.
  record.kind = parse_model_kind(row.column_text(c++)).value_or(ModelKind::kResponseSurface);
  if (record.kind == ModelKind::kMechanistic && !row.column_is_null(c)) record.mechanistic = read_mechanistic(row, c);
  return record;
}

std::vector<ModelRecord> read_models(Statement& statement) {
  std::vector<ModelRecord> models;
  while (statement.step()) models.push_back(read_model(statement));
  return models;
}

std::string to_text(ActivationReason reason) {
  switch (reason) {
    case ActivationReason::kAdded: return "added";
    case ActivationReason::kRollback: return "rollback";
    case ActivationReason::kImported: return "imported";
  }
  return "added";
}

ActivationReason parse_reason(const std::string& text) {
  if (text == "rollback") return ActivationReason::kRollback;
  if (text == "imported") return ActivationReason::kImported;
  return ActivationReason::kAdded;
}

}  // namespace

std::vector<ModelRecord> select_models_for(const Connection& db, RowId tool_id, RowId material_id) {
  Statement statement(db, std::string(kModelSelect) + "WHERE m.tool_id = ? AND m.material_id = ? ORDER BY m.version");
  statement.bind_all(tool_id, material_id);
  return read_models(statement);
}

std::optional<ModelRecord> select_active_model(const Connection& db, RowId tool_id, RowId material_id, ModelKind kind) {
  Statement statement(db, std::string(kModelSelect) +
                              "WHERE m.tool_id = ? AND m.material_id = ? AND m.kind = ? AND m.active = 1");
  statement.bind_all(tool_id, material_id, to_string(kind));
  if (!statement.step()) return std::nullopt;
  return read_model(statement);
}

std::vector<ModelRecord> select_active_models(const Connection& db, ModelKind kind) {
  Statement statement(db, std::string(kModelSelect) + "WHERE m.active = 1 AND m.kind = ? ORDER BY t.name, mt.name");
  statement.bind(to_string(kind));
  return read_models(statement);
}

std::vector<ModelRecord> select_all_models(const Connection& db) {
  Statement statement(db, std::string(kModelSelect) + "ORDER BY t.name, mt.name, m.version");
  return read_models(statement);
}

std::optional<ModelRecord> select_model_by_id(const Connection& db, RowId id) {
  Statement statement(db, std::string(kModelSelect) + "WHERE m.id = ?");
  statement.bind(id);
  if (!statement.step()) return std::nullopt;
  return read_model(statement);
}

int max_model_version(const Connection& db, RowId tool_id, RowId material_id) {
  Statement statement(db, "SELECT coalesce(max(version), 0) FROM models WHERE tool_id = ? AND material_id = ?");
  statement.bind_all(tool_id, material_id);
  return statement.step() ? statement.column_int(0) : 0;
}

RowId insert_model_row(Connection& db, RowId tool_id, RowId material_id, const ModelRecord& record) {
  Statement statement(db,
                      "INSERT INTO models (tool_id, material_id, version, parent_id, "
                      "beta0, beta1, beta2, beta11, beta22, beta12, "
                      "chip_center_mm, chip_scale_mm, contact_length_center_mm, contact_length_scale_mm, "
                      "chip_min_mm, chip_max_mm, contact_length_min_mm, contact_length_max_mm, "
                      "axial_depth_mm, spindle_rpm, quantity, "
                      "fit_n, rmse_n, r_squared, covariance_json, standard_errors_json, loo_rmse_n, "
                      "engagement_cv_rmse_n, source, created_at, note, active, kind) "
                      "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, "
                      "?, ?, ?, 0, ?)");
  const model::ResponseSurfaceModel& model = record.model;
  statement.bind_all(tool_id, material_id, record.version, record.parent_id);
  for (double beta : model.beta) statement.bind(beta);
  statement.bind_all(model.chip_center_mm, model.chip_scale_mm, model.contact_length_center_mm,
                     model.contact_length_scale_mm, model.range.chip_min_mm, model.range.chip_max_mm,
                     model.range.contact_length_min_mm, model.range.contact_length_max_mm, model.axial_depth_mm,
                     model.spindle_rpm, model.quantity);
  statement.bind_all(record.fit.n, record.fit.rmse_n, record.fit.r_squared, numbers_to_json(record.fit.covariance.entries()),
                     numbers_to_json(record.fit.standard_errors), record.fit.loo_rmse_n, record.fit.engagement_cv_rmse_n);
  statement.bind_all(to_string(record.source), record.created_at, record.note, to_string(record.kind));
  statement.run();
  const RowId id = db.last_insert_rowid();
  if (record.mechanistic) insert_mechanistic_row(db, id, *record.mechanistic);
  return id;
}

bool activate_model(Connection& db, RowId tool_id, RowId material_id, RowId model_id, ActivationReason reason,
                    const std::string& created_at) {
  std::optional<RowId> previous;
  {
    Statement statement(db,
                        "SELECT id FROM models WHERE tool_id = ? AND material_id = ? AND active = 1 "
                        "AND kind = (SELECT kind FROM models WHERE id = ?)");
    statement.bind_all(tool_id, material_id, model_id);
    if (statement.step()) previous = statement.column_int64(0);
  }
  if (previous == model_id) return false;
  if (previous) {
    Statement statement(db, "UPDATE models SET active = 0 WHERE id = ?");
    statement.bind(*previous);
    statement.run();
  }
  {
    Statement statement(db, "UPDATE models SET active = 1 WHERE id = ?");
    statement.bind(model_id);
    statement.run();
  }
  Statement statement(db,
                      "INSERT INTO model_activations (tool_id, material_id, model_id, previous_model_id, reason, "
                      "created_at) VALUES (?, ?, ?, ?, ?, ?)");
  statement.bind_all(tool_id, material_id, model_id, previous, to_text(reason), created_at);
  statement.run();
  return true;
}

std::vector<ActivationEvent> select_activation_events(const Connection& db, RowId tool_id, RowId material_id) {
  Statement statement(db,
                      "SELECT a.id, t.name, mt.name, m.version, p.version, a.reason, a.created_at "
                      "FROM model_activations a JOIN tools t ON t.id = a.tool_id "
                      "JOIN materials mt ON mt.id = a.material_id JOIN models m ON m.id = a.model_id "
                      "LEFT JOIN models p ON p.id = a.previous_model_id "
                      "WHERE a.tool_id = ? AND a.material_id = ? ORDER BY a.id");
  statement.bind_all(tool_id, material_id);
  std::vector<ActivationEvent> events;
  while (statement.step()) {
    ActivationEvent event;
    event.id = statement.column_int64(0);
    event.tool_name = statement.column_text(1);
    event.material_name = statement.column_text(2);
    event.version = statement.column_int(3);
    if (!statement.column_is_null(4)) event.previous_version = statement.column_int(4);
    event.reason = parse_reason(statement.column_text(5));
    event.created_at = statement.column_text(6);
    events.push_back(event);
  }
  return events;
}

}  // namespace feedplan::model_db::detail
