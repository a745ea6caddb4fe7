#pragma once
// Internal: reading and writing model versions and the activation audit trail. Writers assume an
// open write transaction and a validated record.

#include <optional>
#include <string>
#include <vector>

#include "feedplan/model_db/store_records.hpp"
#include "sql_statement.hpp"

namespace feedplan::model_db::detail {

std::vector<ModelRecord> select_models_for(const Connection& db, RowId tool_id, RowId material_id);
//! The active version of the pair of `kind` (each kind has its own).
std::optional<ModelRecord> select_active_model(const Connection& db, RowId tool_id, RowId material_id, ModelKind kind);
//! Every active version of `kind`, ordered by tool and material name.
std::vector<ModelRecord> select_active_models(const Connection& db, ModelKind kind);
std::vector<ModelRecord> select_all_models(const Connection& db);
std::optional<ModelRecord> select_model_by_id(const Connection& db, RowId id);

//! The highest version stored for the pair, 0 when it has none.
int max_model_version(const Connection& db, RowId tool_id, RowId material_id);

//! Inserts `model` as stored, inactive, taking version, parent_id, source, created_at and note from
//! it (tool and material from the ids). Returns the row id.
RowId insert_model_row(Connection& db, RowId tool_id, RowId material_id, const ModelRecord& model);

//! Makes model `model_id` the active version of its pair and of its kind and records the change with `reason`.
//! Returns false (and records nothing) when it already was the active one.
bool activate_model(Connection& db, RowId tool_id, RowId material_id, RowId model_id, ActivationReason reason,
                    const std::string& created_at);

std::vector<ActivationEvent> select_activation_events(const Connection& db, RowId tool_id, RowId material_id);

}  // namespace feedplan::model_db::detail
