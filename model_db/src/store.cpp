#include "feedplan/model_db/store.hpp"

#include <functional>

#include <sqlite3.h>

#include <algorithm>
#include <cmath>
#include <system_error>

#include "feedplan/model_db/database_url.hpp"
#include "feedplan/model_db/stale_model_error.hpp"

#include "catalog_rows.hpp"
#include "cutting_test_rows.hpp"
#include "learning_rows.hpp"
#include "model_rows.hpp"
#include "pg_connection.hpp"
#include "pg_schema.hpp"
#include "schema.hpp"
#include "sqlite_handle.hpp"
#include "store_impl.hpp"
#include "utc_time.hpp"
#include "write_transaction.hpp"

namespace feedplan::model_db {

using detail::WriteTransaction;

namespace {

void throw_if_any(std::vector<InputProblem> problems) {
  if (!problems.empty()) throw InputError(std::move(problems));
}

void append(std::vector<InputProblem>& to, std::vector<InputProblem> from) {
  to.insert(to.end(), std::make_move_iterator(from.begin()), std::make_move_iterator(from.end()));
}

}  // namespace

namespace {

// A store on a PostgreSQL server: the URL's server must answer, the database must exist (kCreate makes
// the schema in an empty one, not the database itself).
std::unique_ptr<Store::Impl> open_server(const std::string& url, OpenMode mode, const StoreOptions& options) {
  auto connection = std::make_unique<detail::PgConnection>(url, options.busy_timeout_ms, mode == OpenMode::kReadOnly);
  const int version = detail::prepare_pg_schema(*connection, mode);
  auto impl = std::make_unique<Store::Impl>(shown_location(url), std::move(connection));
  impl->schema_version = version;
  return impl;
}

std::unique_ptr<Store::Impl> open_file(const std::filesystem::path& path, OpenMode mode, const StoreOptions& options) {
  std::error_code ec;
  const bool exists = std::filesystem::exists(path, ec);
  if (!exists && mode != OpenMode::kCreate) {
    // The caller meant an existing database (kCreate is the mode for a new one): say where it was looked
    // for, not how to make an empty one.
    std::string where;
    if (path.is_relative()) where = " (looked for " + (std::filesystem::current_path(ec) / path).lexically_normal().string() + ")";
    throw InputError(path.string(), "cannot be opened: no such file" + where +
                                        ": check the path of the model database (--db, $FEEDPLAN_DB)");
  }
  if (exists && std::filesystem::is_directory(path, ec)) {
    throw InputError(path.string(), "cannot be opened: it is a directory, not a model database");
  }
  int flags = SQLITE_OPEN_NOMUTEX;
  switch (mode) {
    case OpenMode::kCreate: flags |= SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE; break;
    case OpenMode::kExisting: flags |= SQLITE_OPEN_READWRITE; break;
    case OpenMode::kReadOnly: flags |= SQLITE_OPEN_READONLY; break;
  }
  auto connection = std::make_unique<detail::SqliteConnection>(path.string(), flags);
  sqlite3_busy_timeout(connection->get(), options.busy_timeout_ms);
  const int version = detail::prepare_schema(*connection, mode, options.quick_check_on_open);
  connection->exec("PRAGMA foreign_keys = ON");
  connection->exec("PRAGMA cache_size = " + std::to_string(-std::max(options.cache_size_kib, 1)));
  auto impl = std::make_unique<Store::Impl>(path, std::move(connection));
  impl->schema_version = version;
  return impl;
}

}  // namespace

Store Store::open(const std::filesystem::path& path, OpenMode mode, const StoreOptions& options) {
  const std::string location = path.string();
  return Store(is_server_url(location) ? open_server(location, mode, options) : open_file(path, mode, options));
}

Store::Store(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Store::Store(Store&&) noexcept = default;
Store& Store::operator=(Store&&) noexcept = default;
Store::~Store() = default;

const std::filesystem::path& Store::path() const { return impl_->path; }

int Store::schema_version() const { return impl_->schema_version; }

IntegrityReport Store::integrity_check() const {
  IntegrityReport report;
  if (impl_->db.engine() == detail::Engine::kPostgres) {
    report.messages = detail::pg_consistency_check(static_cast<const detail::PgConnection&>(impl_->db));
  } else {
    detail::Statement statement(impl_->db, "PRAGMA integrity_check");
    while (statement.step()) report.messages.push_back(statement.column_text(0));
  }
  report.ok = report.messages.size() == 1 && report.messages.front() == "ok";
  return report;
}

void Store::set_write_hook(WriteHook hook) { impl_->hook = std::move(hook); }

// ---- tools and materials ----

ToolRecord Store::add_tool(const ToolRecord& tool) {
  auto& db = impl_->db;
  WriteTransaction transaction(db);
  auto problems = validate(tool);
  if (detail::select_tool(db, tool.name)) problems.push_back({"tools.name", "= '" + tool.name + "' already exists"});
  throw_if_any(std::move(problems));
  ToolRecord stored = tool;
  stored.id = detail::insert_tool(db, tool);
  impl_->after_step("tools.insert");
  transaction.commit();
  return stored;
}

std::optional<ToolRecord> Store::find_tool(std::string_view name) const { return detail::select_tool(impl_->db, name); }

std::vector<ToolRecord> Store::tools() const { return detail::select_tools(impl_->db); }

MaterialRecord Store::add_material(const MaterialRecord& material) {
  auto& db = impl_->db;
  WriteTransaction transaction(db);
  auto problems = validate(material);
  if (detail::select_material(db, material.name)) {
    problems.push_back({"materials.name", "= '" + material.name + "' already exists"});
  }
  throw_if_any(std::move(problems));
  MaterialRecord stored = material;
  stored.id = detail::insert_material(db, material);
  impl_->after_step("materials.insert");
  transaction.commit();
  return stored;
}

std::optional<MaterialRecord> Store::find_material(std::string_view name) const {
  return detail::select_material(impl_->db, name);
}

std::vector<MaterialRecord> Store::materials() const { return detail::select_materials(impl_->db); }

// ---- models ----

namespace {

// The steps of add_model inside a transaction the caller holds.
RowId insert_and_activate_model(detail::Connection& db, const ModelRecord& model, const std::function<void(const char*)>& after_step) {
  std::vector<InputProblem> problems;
  const auto ids = detail::pair_ids(db, model.tool_name, model.material_name, "models.", problems);
  append(problems, validate(model));
  throw_if_any(std::move(problems));

  ModelRecord stored = model;
  const auto previous = detail::select_active_model(db, ids.tool_id, ids.material_id, model.kind);
  stored.version = detail::max_model_version(db, ids.tool_id, ids.material_id) + 1;
  stored.parent_id = previous ? std::optional<RowId>(previous->id) : std::nullopt;
  stored.created_at = detail::utc_now_iso8601();
  const RowId id = detail::insert_model_row(db, ids.tool_id, ids.material_id, stored);
  after_step("models.insert");
  detail::activate_model(db, ids.tool_id, ids.material_id, id, ActivationReason::kAdded, stored.created_at);
  after_step("models.activate");
  return id;
}

// A learned version is filed as the child of the version it was fitted from, which must therefore still
// be the active one of its pair when the transaction (BEGIN IMMEDIATE: no other writer between this read
// and the commit) stores it: otherwise another learning step or a rollback came in between.
void require_fitted_from_active(const detail::Connection& db, const ModelRecord& model, RowId fitted_from_id) {
  const auto fitted_from = detail::select_model_by_id(db, fitted_from_id);
  if (!fitted_from) return;  // insert_learning names the missing id
  std::vector<InputProblem> problems;
  const auto ids = detail::pair_ids(db, model.tool_name, model.material_name, "models.", problems);
  if (!problems.empty()) return;  // insert_and_activate_model names them
  const auto active = detail::select_active_model(db, ids.tool_id, ids.material_id, fitted_from->kind);
  if (active && active->id != fitted_from_id) throw StaleModelError(*fitted_from, *active);
}

// The checks and insert of add_learning_entry inside a transaction the caller holds.
LearningEntry insert_learning(detail::Connection& db, const LearningEntry& entry, const std::function<void(const char*)>& after_step) {
  auto problems = validate(entry);
  if (entry.model_id_before > 0 && !detail::select_model_by_id(db, entry.model_id_before)) {
    problems.push_back({"learning_history.model_id_before",
                        "= " + std::to_string(entry.model_id_before) + ": no such model version"});
  }
  if (entry.model_id_after > 0 && !detail::select_model_by_id(db, entry.model_id_after)) {
    problems.push_back({"learning_history.model_id_after",
                        "= " + std::to_string(entry.model_id_after) + ": no such model version"});
  }
  throw_if_any(std::move(problems));
  LearningEntry stored = entry;
  stored.created_at = detail::utc_now_iso8601();
  stored.id = detail::insert_learning_entry(db, entry, stored.created_at);
  after_step("learning_history.insert");
  return stored;
}

}  // namespace

ModelRecord Store::add_model(const ModelRecord& model) {
  auto& db = impl_->db;
  WriteTransaction transaction(db);
  const RowId id = insert_and_activate_model(db, model, [this](const char* step) { impl_->after_step(step); });
  transaction.commit();
  return *detail::select_model_by_id(db, id);
}

std::vector<ModelRecord> Store::add_models(const std::vector<ModelRecord>& models) {
  auto& db = impl_->db;
  WriteTransaction transaction(db);
  std::vector<RowId> ids;
  for (const ModelRecord& model : models) {
    ids.push_back(insert_and_activate_model(db, model, [this](const char* step) { impl_->after_step(step); }));
  }
  transaction.commit();
  std::vector<ModelRecord> stored;
  for (const RowId id : ids) stored.push_back(*detail::select_model_by_id(db, id));
  return stored;
}

std::pair<ModelRecord, LearningEntry> Store::add_learned_model(const ModelRecord& model, const LearningEntry& entry,
                                                               const std::vector<LearnedSample>& samples) {
  std::vector<InputProblem> problems;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const LearnedSample& sample = samples[i];
    const std::string field = "learning_samples[" + std::to_string(i) + "].";
    for (const auto& [name, value] : {std::pair{"chip_mm", sample.chip_mm}, std::pair{"contact_length_mm", sample.contact_length_mm},
                                      std::pair{"force_n", sample.force_n}, std::pair{"s_mm", sample.s_mm}}) {
      if (!std::isfinite(value)) problems.push_back({field + name, "= " + std::to_string(value) + ": must be finite"});
    }
    if (!(std::isfinite(sample.weight) && sample.weight > 0.0)) {
      problems.push_back({field + "weight", "= " + std::to_string(sample.weight) + ": must be finite and > 0"});
    }
  }
  throw_if_any(std::move(problems));
  auto& db = impl_->db;
  WriteTransaction transaction(db);
  const auto after_step = [this](const char* step) { impl_->after_step(step); };
  require_fitted_from_active(db, model, entry.model_id_before);
  const RowId id = insert_and_activate_model(db, model, after_step);
  LearningEntry linked = entry;
  linked.model_id_after = id;
  LearningEntry stored = insert_learning(db, linked, after_step);
  detail::insert_learned_samples(db, stored.id, samples);
  after_step("learning_samples.insert");
  transaction.commit();
  return {*detail::select_model_by_id(db, id), stored};
}

std::vector<ModelRecord> Store::models_for(std::string_view tool_name, std::string_view material_name) const {
  const auto ids = detail::pair_ids_or_throw(impl_->db, tool_name, material_name, "");
  return detail::select_models_for(impl_->db, ids.tool_id, ids.material_id);
}

std::optional<ModelRecord> Store::active_model(std::string_view tool_name, std::string_view material_name,
                                               ModelKind kind) const {
  const auto ids = detail::pair_ids_or_throw(impl_->db, tool_name, material_name, "");
  return detail::select_active_model(impl_->db, ids.tool_id, ids.material_id, kind);
}

std::vector<ModelRecord> Store::active_models(ModelKind kind) const {
  return detail::select_active_models(impl_->db, kind);
}

std::vector<ModelRecord> Store::all_models() const { return detail::select_all_models(impl_->db); }

std::optional<ModelRecord> Store::model_by_id(RowId id) const { return detail::select_model_by_id(impl_->db, id); }

ModelRecord Store::rollback(std::string_view tool_name, std::string_view material_name, int version) {
  auto& db = impl_->db;
  WriteTransaction transaction(db);
  const auto ids = detail::pair_ids_or_throw(db, tool_name, material_name, "rollback.");
  const auto versions = detail::select_models_for(db, ids.tool_id, ids.material_id);
  const ModelRecord* target = nullptr;
  for (const auto& candidate : versions) {
    if (candidate.version == version) target = &candidate;
  }
  if (target == nullptr) {
    const std::string pair = std::string(tool_name) + " in " + std::string(material_name);
    throw InputError("rollback.version",
                     "= " + std::to_string(version) + ": no such version of " + pair +
                         (versions.empty() ? "; it has no model yet"
                                           : "; versions 1–" + std::to_string(versions.back().version)));
  }
  const RowId id = target->id;
  detail::activate_model(db, ids.tool_id, ids.material_id, id, ActivationReason::kRollback,
                         detail::utc_now_iso8601());
  impl_->after_step("models.activate");
  transaction.commit();
  return *detail::select_model_by_id(db, id);
}

std::vector<ActivationEvent> Store::activation_history(std::string_view tool_name,
                                                       std::string_view material_name) const {
  const auto ids = detail::pair_ids_or_throw(impl_->db, tool_name, material_name, "");
  return detail::select_activation_events(impl_->db, ids.tool_id, ids.material_id);
}

// ---- cutting tests ----

StoredCuttingTest Store::add_cutting_test(const CuttingTestRecord& test) {
  auto& db = impl_->db;
  WriteTransaction transaction(db);
  std::vector<InputProblem> problems = validate(test);
  const auto ids =
      detail::pair_ids(db, test.conditions.tool_name, test.conditions.material_name, "cutting_tests.", problems);
  throw_if_any(std::move(problems));
  StoredCuttingTest stored{0, detail::utc_now_iso8601(), test};
  stored.id = detail::insert_cutting_test(db, ids.tool_id, ids.material_id, test, stored.created_at);
  impl_->after_step("cutting_tests.insert");
  transaction.commit();
  return stored;
}

std::vector<StoredCuttingTest> Store::cutting_tests(std::string_view tool_name, std::string_view material_name) const {
  const auto ids = detail::pair_ids_or_throw(impl_->db, tool_name, material_name, "");
  return detail::select_cutting_tests(impl_->db, ids.tool_id, ids.material_id);
}

std::vector<StoredCuttingTest> Store::all_cutting_tests() const { return detail::select_cutting_tests(impl_->db, 0, 0); }

// ---- learning history ----

LearningEntry Store::add_learning_entry(const LearningEntry& entry) {
  auto& db = impl_->db;
  WriteTransaction transaction(db);
  LearningEntry stored = insert_learning(db, entry, [this](const char* step) { impl_->after_step(step); });
  transaction.commit();
  return stored;
}

std::vector<LearnedSample> Store::learned_samples(std::string_view tool_name, std::string_view material_name) const {
  const auto ids = detail::pair_ids_or_throw(impl_->db, tool_name, material_name, "");
  return detail::select_learned_samples(impl_->db, ids.tool_id, ids.material_id);
}

std::vector<LearningEntry> Store::learning_history(std::string_view tool_name, std::string_view material_name) const {
  const auto ids = detail::pair_ids_or_throw(impl_->db, tool_name, material_name, "");
  return detail::select_learning_entries(impl_->db, ids.tool_id, ids.material_id);
}

std::vector<LearningEntry> Store::all_learning_entries() const {
  return detail::select_learning_entries(impl_->db, 0, 0);
}

}  // namespace feedplan::model_db
