#pragma once
// Internal: the append-only learning history. The writer assumes an open write transaction and a
// validated entry whose model ids exist.

#include <string>
#include <vector>

#include "feedplan/model_db/store_records.hpp"
#include "sql_statement.hpp"

namespace feedplan::model_db::detail {

//! Appends `entry` with `created_at`; returns its row id.
RowId insert_learning_entry(Connection& db, const LearningEntry& entry, const std::string& created_at);

//! The entries whose model before or after belongs to the pair (every entry when both ids are 0),
//! ordered by created_at and id.
std::vector<LearningEntry> select_learning_entries(const Connection& db, RowId tool_id, RowId material_id);

void insert_learned_samples(Connection& db, RowId learning_entry_id, const std::vector<LearnedSample>& samples);

std::vector<LearnedSample> select_learned_samples(const Connection& db, RowId tool_id, RowId material_id);

//! The samples of one learning entry, in their order.
std::vector<LearnedSample> select_samples_of_entry(const Connection& db, RowId learning_entry_id);

}  // namespace feedplan::model_db::detail
