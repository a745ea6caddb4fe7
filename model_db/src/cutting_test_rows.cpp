#include "cutting_test_rows.hpp"

#include <nlohmann/json.hpp>

namespace feedplan::model_db::detail {

std::string to_text(CutMode mode) {
  switch (mode) {
    case CutMode::kDown: return "down";
    case CutMode::kUp: return "up";
    case CutMode::kSlot: return "slot";
  }
  return "down";
}

std::optional<CutMode> parse_cut_mode(const std::string& text) {
  if (text == "down") return CutMode::kDown;
  if (text == "up") return CutMode::kUp;
  if (text == "slot") return CutMode::kSlot;
  return std::nullopt;
}

RowId insert_cutting_test(Connection& db, RowId tool_id, RowId material_id, const CuttingTestRecord& test,
                          const std::string& created_at) {
  const CuttingTestConditions& conditions = test.conditions;
  Statement statement(db,
                      "INSERT INTO cutting_tests (tool_id, material_id, spindle_rpm, feed_mm_per_min, "
                      "radial_depth_mm, axial_depth_mm, mode, feed_per_tooth_mm, chip_mm, contact_length_mm, "
                      "peak_mean_n, peak_std_n, peak_min_n, peak_max_n, revolutions_total, revolutions_used, "
                      "source_file, notes_json, created_at) "
                      "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  statement.bind_all(tool_id, material_id, conditions.spindle_rpm, conditions.feed_mm_per_min,
                     conditions.radial_depth_mm, conditions.axial_depth_mm, to_text(conditions.mode));
  statement.bind_all(test.feed_per_tooth_mm, test.chip_mm, test.contact_length_mm, test.peak_mean_n, test.peak_std_n,
                     test.peak_min_n, test.peak_max_n, test.revolutions_total, test.revolutions_used);
  statement.bind_all(test.source, nlohmann::json(test.notes).dump(), created_at);
  statement.run();
  const RowId id = db.last_insert_rowid();
  Statement peak(db, "INSERT INTO cutting_test_peaks (cutting_test_id, revolution_index, peak_n) VALUES (?, ?, ?)");
  for (std::size_t i = 0; i < test.steady_peaks_n.size(); ++i) {
    peak.reset();
    peak.bind_all(id, static_cast<std::int64_t>(i), test.steady_peaks_n[i]);
    peak.run();
  }
  if (!test.synchronous_fx_n.empty()) {
    Statement signal(db, "INSERT INTO cutting_test_signals (cutting_test_id, fx_json, fy_json) VALUES (?, ?, ?)");
    signal.bind_all(id, nlohmann::json(test.synchronous_fx_n).dump(), nlohmann::json(test.synchronous_fy_n).dump());
    signal.run();
  }
  return id;
}

namespace {

// The numbers of a stored JSON array (written by insert_cutting_test); empty when it is not one.
std::vector<double> numbers_of(const std::string& text) {
  const auto array = nlohmann::json::parse(text, nullptr, false);
  std::vector<double> numbers;
  if (!array.is_array()) return numbers;
  for (const auto& v : array) {
    if (!v.is_number()) return {};
    numbers.push_back(v.get<double>());
  }
  return numbers;
}

}  // namespace

std::vector<StoredCuttingTest> select_cutting_tests(const Connection& db, RowId tool_id, RowId material_id) {
  const bool all = tool_id == 0 && material_id == 0;
  Statement statement(db, std::string("SELECT c.id, c.created_at, t.name, mt.name, c.spindle_rpm, c.feed_mm_per_min, "
                                      "c.radial_depth_mm, c.axial_depth_mm, c.mode, c.feed_per_tooth_mm, c.chip_mm, "
                                      "c.contact_length_mm, c.peak_mean_n, c.peak_std_n, c.peak_min_n, c.peak_max_n, "
                                      "c.revolutions_total, c.revolutions_used, c.source_file, c.notes_json "
                                      "FROM cutting_tests c JOIN tools t ON t.id = c.tool_id "
                                      "JOIN materials mt ON mt.id = c.material_id ") +
                              (all ? "" : "WHERE c.tool_id = ? AND c.material_id = ? ") +
                              "ORDER BY t.name, mt.name, c.created_at, c.id");
  if (!all) statement.bind_all(tool_id, material_id);
  Statement peaks(db, "SELECT peak_n FROM cutting_test_peaks WHERE cutting_test_id = ? ORDER BY revolution_index");
  Statement signal(db, "SELECT fx_json, fy_json FROM cutting_test_signals WHERE cutting_test_id = ?");
  std::vector<StoredCuttingTest> tests;
  while (statement.step()) {
    StoredCuttingTest stored;
    int c = 0;
    stored.id = statement.column_int64(c++);
    stored.created_at = statement.column_text(c++);
    CuttingTestRecord& test = stored.test;
    test.conditions.tool_name = statement.column_text(c++);
    test.conditions.material_name = statement.column_text(c++);
    test.conditions.spindle_rpm = statement.column_double(c++);
    test.conditions.feed_mm_per_min = statement.column_double(c++);
    test.conditions.radial_depth_mm = statement.column_double(c++);
    test.conditions.axial_depth_mm = statement.column_double(c++);
    // The CHECK constraint admits only the three mode names.
    test.conditions.mode = parse_cut_mode(statement.column_text(c++)).value_or(CutMode::kDown);
    test.feed_per_tooth_mm = statement.column_double(c++);
    test.chip_mm = statement.column_double(c++);
    test.contact_length_mm = statement.column_double(c++);
    test.peak_mean_n = statement.column_double(c++);
    test.peak_std_n = statement.column_double(c++);
    test.peak_min_n = statement.column_double(c++);
    test.peak_max_n = statement.column_double(c++);
    test.revolutions_total = statement.column_int(c++);
    test.revolutions_used = statement.column_int(c++);
    test.source = statement.column_text(c++);
    const auto notes = nlohmann::json::parse(statement.column_text(c++), nullptr, false);
    if (notes.is_array()) {
      for (const auto& note : notes) {
        if (note.is_string()) test.notes.push_back(note.get<std::string>());
      }
    }
    peaks.reset();
    peaks.bind(stored.id);
    while (peaks.step()) test.steady_peaks_n.push_back(peaks.column_double(0));
    signal.reset();
    signal.bind(stored.id);
    if (signal.step()) {
      test.synchronous_fx_n = numbers_of(signal.column_text(0));
      test.synchronous_fy_n = numbers_of(signal.column_text(1));
      if (test.synchronous_fx_n.size() != test.synchronous_fy_n.size()) {
        test.synchronous_fx_n.clear();
        test.synchronous_fy_n.clear();
      }
    }
    tests.push_back(std::move(stored));
  }
  return tests;
}

}  // namespace feedplan::model_db::detail
