#pragma once
// Shared by the store, closest-model, exchange and crash-safety tests: a scratch directory, records with
// plausible numbers, a store filled with every kind of row, and direct SQLite access for looking at a
// file behind the store's back.

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/model_db/store.hpp"

namespace feedplan::model_db::fixtures {

//! A fresh directory under the system temporary directory, removed with everything in it.
class ScratchDir {
 public:
  ScratchDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "feedplan-store-XXXXXX").string();
    path_ = ::mkdtemp(pattern.data());
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

inline ToolRecord tool(const std::string& name, double diameter_mm, int flutes, double helix_deg) {
  ToolRecord t;
  t.name = name;
  t.diameter_mm = diameter_mm;
  t.flutes = flutes;
  t.helix_deg = helix_deg;
  t.tool_material = "solid carbide";
  t.coating = "TiAlN";
  return t;
}

inline MaterialRecord material(const std::string& name, IsoGroup group, double hardness_value,
                               const std::string& scale = "HB") {
  MaterialRecord m;
  m.name = name;
  m.iso_group = group;
  m.hardness_value = hardness_value;
  m.hardness_scale = scale;
  return m;
}

//! A model version with numbers of the size seed 003 reports (peaks of a few hundred N); `k` varies them.
inline ModelRecord model(const std::string& tool_name, const std::string& material_name, double k = 1.0) {
  ModelRecord r;
  r.tool_name = tool_name;
  r.material_name = material_name;
  r.model.beta = {480.0 * k, 120.5 * k, 60.25, -5.0, 3.0 / k, 8.125};
  r.model.chip_center_mm = 0.04;
  r.model.chip_scale_mm = 0.02;
  r.model.contact_length_center_mm = 4.0;
  r.model.contact_length_scale_mm = 1.5;
  r.model.range = {0.01, 0.08, 2.2, 5.8};
  r.model.axial_depth_mm = 10.0;
  r.model.spindle_rpm = 2546.0;
  r.fit.n = 25;
  r.fit.rmse_n = 4.2 * k;
  r.fit.r_squared = 0.9987;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) r.fit.covariance(i, j) = (i == j ? 2.0 : 0.1) / (1 + i + j);
  }
  r.fit.standard_errors = {1.41, 0.5, 0.3, 0.2, 0.1, 0.1 / 3.0};
  r.fit.loo_rmse_n = 5.1 * k;
  r.source = ModelSource::kCuttingTests;
  r.note = "fixture k = " + std::to_string(k);
  return r;
}

//! A cutting test with `peaks` steady per-revolution peaks.
inline CuttingTestRecord cutting_test(const std::string& tool_name, const std::string& material_name, int i,
                                      int peaks = 12) {
  CuttingTestRecord t;
  t.conditions = {tool_name, material_name, 2546.0, 1018.4 + i, 1.5, 10.0, CutMode::kDown};
  t.feed_per_tooth_mm = 0.1 + 0.001 * i;
  t.chip_mm = 0.0634 + 0.0001 * i;
  t.contact_length_mm = 3.9646;
  for (int p = 0; p < peaks; ++p) t.steady_peaks_n.push_back(480.0 + 0.37 * p + i);
  t.peak_mean_n = 482.0 + i;
  t.peak_std_n = 1.3;
  t.peak_min_n = 480.0 + i;
  t.peak_max_n = 484.07 + i;
  t.revolutions_total = peaks + 4;
  t.revolutions_used = peaks;
  t.source = "test_" + std::to_string(i) + ".csv";
  t.notes = {"first 2 revolutions dropped (entry)", "note with \"quotes\" and ünïcode"};
  return t;
}

//! Fills a store: 3 tools, 3 materials, 4 model versions of one pair (with a rollback), one of another,
//! 5 cutting tests and 2 learning entries.
inline void populate(Store& store) {
  store.add_tool(tool("SC EM D10 Z4", 10, 4, 30));
  store.add_tool(tool("SC EM D6 Z3", 6, 3, 35));
  store.add_tool(tool("SC EM D12 Z4", 12, 4, 30));
  store.add_material(material("S50C", IsoGroup::kP, 200));
  store.add_material(material("Al7075-T6", IsoGroup::kN, 150));
  store.add_material(material("Ti6Al4V", IsoGroup::kS, 36, "HRC"));
  const auto v1 = store.add_model(model("SC EM D10 Z4", "S50C", 1.0));
  auto learned = model("SC EM D10 Z4", "S50C", 1.02);
  learned.source = ModelSource::kLearned;
  const auto v2 = store.add_model(learned);
  store.rollback("SC EM D10 Z4", "S50C", 1);
  store.add_model(model("SC EM D10 Z4", "S50C", 0.98));
  store.add_model(model("SC EM D6 Z3", "Al7075-T6", 0.4));
  for (int i = 0; i < 3; ++i) store.add_cutting_test(cutting_test("SC EM D10 Z4", "S50C", i));
  for (int i = 0; i < 2; ++i) store.add_cutting_test(cutting_test("SC EM D6 Z3", "Al7075-T6", i));
  LearningEntry entry;
  entry.model_id_before = v1.id;
  entry.model_id_after = v2.id;
  entry.part_name = "pocket A";
  entry.n_samples = 1800;
  entry.error_before_n = 31.5;
  entry.error_after_n = 6.25;
  entry.note = "3 logs";
  store.add_learning_entry(entry);
  entry.model_id_after = 0;
  entry.note = "no improvement, nothing stored";
  store.add_learning_entry(entry);
}

//! The bytes of a file.
inline std::string file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

//! Runs `sql` on the file directly (not through the store); returns the first column of the first row.
inline std::string raw_sql(const std::filesystem::path& path, const std::string& sql) {
  sqlite3* db = nullptr;
  sqlite3_open(path.string().c_str(), &db);
  sqlite3_stmt* statement = nullptr;
  std::string result;
  if (sqlite3_prepare_v2(db, sql.c_str(), -1, &statement, nullptr) == SQLITE_OK) {
    const int rc = sqlite3_step(statement);
    if (rc == SQLITE_ROW && sqlite3_column_text(statement, 0) != nullptr) {
      result = reinterpret_cast<const char*>(sqlite3_column_text(statement, 0));
    } else if (rc != SQLITE_ROW && rc != SQLITE_DONE) {
      result = std::string("error: ") + sqlite3_errmsg(db);
    }
  } else {
    result = std::string("error: ") + sqlite3_errmsg(db);
  }
  sqlite3_finalize(statement);
  sqlite3_close(db);
  return result;
}

//! One learning-style write, as `feedplan learn` makes it: the pair's active version is read, `between`
//! runs (the fitting would, in learn), and a learned version "fitted from" it is stored with its learning
//! entry and `samples` learning samples, in one transaction. Throws StaleModelError when another writer
//! changed the active version in between. Returns the stored version.
inline ModelRecord learn_step(Store& store, const std::string& tool_name, const std::string& material_name,
                              int samples, const std::function<void()>& between = {}) {
  const ModelRecord before = *store.active_model(tool_name, material_name);
  if (between) between();
  ModelRecord learned = model(tool_name, material_name, 1.0 + 0.001 * before.version);
  learned.source = ModelSource::kLearned;
  LearningEntry entry;
  entry.model_id_before = before.id;
  entry.part_name = "part after v" + std::to_string(before.version);
  entry.n_samples = samples;
  std::vector<LearnedSample> learned_samples;
  for (int i = 0; i < samples; ++i) learned_samples.push_back({0.02 + 1e-5 * i, 4.0, 350.0 + i, 1.0, 0.1 * i});
  return store.add_learned_model(learned, entry, learned_samples).first;
}

//! Expects the pair's history to be a true lineage of learning steps (learn_step with `samples` samples
//! each) on one first version: every later version learned, with one learning entry whose model before is
//! the version's parent, that parent the version just before it (so no two versions share a parent: no
//! update was lost or filed under a version it was not fitted from), the last version active, and every
//! step's samples all stored (each transaction whole). Reads the rows from the file directly too.
inline void expect_true_lineage(const std::filesystem::path& path, const std::string& tool_name,
                                const std::string& material_name, int samples) {
  const Store store = Store::open(path, OpenMode::kReadOnly);
  const std::vector<ModelRecord> versions = store.models_for(tool_name, material_name);
  ASSERT_FALSE(versions.empty());
  std::map<RowId, RowId> fitted_from;  // learning entry: model after → model before
  for (const LearningEntry& entry : store.learning_history(tool_name, material_name)) {
    EXPECT_TRUE(fitted_from.emplace(entry.model_id_after, entry.model_id_before).second)
        << "two learning entries for model id " << entry.model_id_after;
  }
  EXPECT_EQ(fitted_from.size(), versions.size() - 1);
  for (std::size_t i = 0; i < versions.size(); ++i) {
    const ModelRecord& v = versions[i];
    EXPECT_EQ(v.version, static_cast<int>(i) + 1);
    EXPECT_EQ(v.active, i + 1 == versions.size()) << "version " << v.version;
    if (i == 0) continue;
    EXPECT_EQ(v.source, ModelSource::kLearned) << "version " << v.version;
    ASSERT_TRUE(v.parent_id.has_value()) << "version " << v.version;
    EXPECT_EQ(*v.parent_id, versions[i - 1].id) << "version " << v.version << ": parent is not the version before it";
    ASSERT_EQ(fitted_from.count(v.id), 1u) << "version " << v.version << " has no learning entry";
    EXPECT_EQ(fitted_from[v.id], *v.parent_id) << "version " << v.version << " is filed under a version it was not fitted from";
  }
  EXPECT_EQ(raw_sql(path, "SELECT count(*) FROM learning_samples"),
            std::to_string(static_cast<int>(versions.size() - 1) * samples));
  EXPECT_EQ(raw_sql(path, "SELECT count(*) FROM (SELECT learning_entry_id FROM learning_samples GROUP BY "
                          "learning_entry_id HAVING count(*) != " + std::to_string(samples) + ")"),
            "0");
}

//! The InputError message thrown by `action`, or "(no InputError)".
template <typename Action>
std::string input_error_of(Action&& action) {
  try {
    action();
  } catch (const InputError& error) {
    return error.what();
  }
  return "(no InputError)";
}

}  // namespace feedplan::model_db::fixtures
