#include "learning_rows.hpp"

#include <cstdint>

namespace feedplan::model_db::detail {

RowId insert_learning_entry(Connection& db, const LearningEntry& entry, const std::string& created_at) {
  Statement statement(db,
                      "INSERT INTO learning_history (model_id_before, model_id_after, part_name, n_samples, "
                      "error_before_n, error_after_n, created_at, note) VALUES (?, ?, ?, ?, ?, ?, ?, ?)");
  statement.bind(entry.model_id_before);
  if (entry.model_id_after == 0) {
    statement.bind_null();
  } else {
    statement.bind(entry.model_id_after);
  }
  statement.bind_all(entry.part_name, entry.n_samples, entry.error_before_n, entry.error_after_n, created_at,
                     entry.note);
  statement.run();
  return db.last_insert_rowid();
}

std::vector<LearningEntry> select_learning_entries(const Connection& db, RowId tool_id, RowId material_id) {
  const bool all = tool_id == 0 && material_id == 0;
  Statement statement(db, std::string("SELECT h.id, h.model_id_before, h.model_id_after, h.part_name, h.n_samples, "
                                      "h.error_before_n, h.error_after_n, h.created_at, h.note "
                                      "FROM learning_history h JOIN models b ON b.id = h.model_id_before "
                                      "LEFT JOIN models a ON a.id = h.model_id_after ") +
                              (all ? "" : "WHERE (b.tool_id = ?1 AND b.material_id = ?2) OR "
                                          "(a.tool_id = ?1 AND a.material_id = ?2) ") +
                              "ORDER BY h.created_at, h.id");
  if (!all) statement.bind_all(tool_id, material_id);
  std::vector<LearningEntry> entries;
  while (statement.step()) {
    LearningEntry entry;
    entry.id = statement.column_int64(0);
    entry.model_id_before = statement.column_int64(1);
    entry.model_id_after = statement.column_optional_int64(2).value_or(0);
    entry.part_name = statement.column_text(3);
    entry.n_samples = statement.column_int(4);
    entry.error_before_n = statement.column_double(5);
    entry.error_after_n = statement.column_double(6);
    entry.created_at = statement.column_text(7);
    entry.note = statement.column_text(8);
    entries.push_back(entry);
  }
  return entries;
}

void insert_learned_samples(Connection& db, RowId learning_entry_id, const std::vector<LearnedSample>& samples) {
  Statement statement(db,
                      "INSERT INTO learning_samples (learning_entry_id, sample_index, chip_mm, contact_length_mm, "
                      "force_n, weight, s_mm) VALUES (?, ?, ?, ?, ?, ?, ?)");
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const LearnedSample& sample = samples[i];
    statement.bind_all(learning_entry_id, static_cast<std::int64_t>(i), sample.chip_mm, sample.contact_length_mm,
                       sample.force_n, sample.weight, sample.s_mm);
    statement.run();
    statement.reset();
  }
}

std::vector<LearnedSample> select_learned_samples(const Connection& db, RowId tool_id, RowId material_id) {
  Statement statement(db,
                      "SELECT s.chip_mm, s.contact_length_mm, s.force_n, s.weight, s.s_mm FROM learning_samples s "
                      "JOIN learning_history h ON h.id = s.learning_entry_id JOIN models a ON a.id = h.model_id_after "
                      "WHERE a.tool_id = ?1 AND a.material_id = ?2 ORDER BY h.created_at, h.id, s.sample_index");
  statement.bind_all(tool_id, material_id);
  std::vector<LearnedSample> samples;
  while (statement.step()) {
    samples.push_back({statement.column_double(0), statement.column_double(1), statement.column_double(2),
                       statement.column_double(3), statement.column_double(4)});
  }
  return samples;
}

std::vector<LearnedSample> select_samples_of_entry(const Connection& db, RowId learning_entry_id) {
  Statement statement(db,
                      "SELECT chip_mm, contact_length_mm, force_n, weight, s_mm FROM learning_samples "
                      "WHERE learning_entry_id = ? ORDER BY sample_index");
  statement.bind(learning_entry_id);
  std::vector<LearnedSample> samples;
  while (statement.step()) {
    samples.push_back({statement.column_double(0), statement.column_double(1), statement.column_double(2),
                       statement.column_double(3), statement.column_double(4)});
  }
  return samples;
}

}  // namespace feedplan::model_db::detail
