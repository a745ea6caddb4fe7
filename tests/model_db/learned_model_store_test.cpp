// Store::add_learned_model (model_db/store.hpp): a learned version and the learning entry that explains it
// in one transaction. The new version is the next number, active, with the version active until then as its
// parent (not the highest one: a rollback may have made an older one active), and the entry points at it.
// Any problem with the entry or the model, found after the model row was written, leaves neither stored;
// the counts are read from the file directly (SQLite), not through the store.

#include <gtest/gtest.h>

#include <cmath>

#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "feedplan/core/input_error.hpp"
#include "feedplan/model_db/store.hpp"
#include "store_fixtures.hpp"

namespace feedplan::model_db {
namespace {

using fixtures::input_error_of;
using fixtures::ScratchDir;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const std::string kTool = "SC EM D10 Z4";
const std::string kMaterial = "S50C";

// A store with the tool and material, versions 1 and 2 of their model, and version 1 made active again.
class LearnedModelStore : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = dir_ / "models.db";
    store_.emplace(Store::open(path_, OpenMode::kCreate));
    store_->add_tool(fixtures::tool(kTool, 10, 4, 30));
    store_->add_material(fixtures::material(kMaterial, IsoGroup::kP, 200));
    v1_ = store_->add_model(fixtures::model(kTool, kMaterial, 1.0));
    v2_ = store_->add_model(fixtures::model(kTool, kMaterial, 1.1));
    store_->rollback(kTool, kMaterial, 1);
  }

  ModelRecord learned_record() const {
    ModelRecord learned = fixtures::model(kTool, kMaterial, 1.25);
    learned.source = ModelSource::kLearned;
    learned.note = "learned from 2 logs of corner";
    return learned;
  }

  LearningEntry entry() const {
    LearningEntry e;
    e.model_id_before = v1_.id;
    e.model_id_after = 0;
    e.part_name = "corner.json";
    e.n_samples = 412;
    e.error_before_n = 38.5;
    e.error_after_n = 4.75;
    e.note = "learned from 2 logs of corner";
    return e;
  }

  std::string count(const std::string& table) const {
    return fixtures::raw_sql(path_, "SELECT count(*) FROM " + table);
  }

  // Expects the database as SetUp left it: 2 versions, version 1 active, no learning entry.
  void expect_unchanged() const {
    EXPECT_EQ(count("models"), "2");
    EXPECT_EQ(count("learning_history"), "0");
    EXPECT_EQ(count("model_activations"), "3");  // added 1, added 2, rollback to 1
    EXPECT_EQ(fixtures::raw_sql(path_, "SELECT group_concat(version) FROM models WHERE active = 1"), "1");
    const auto active = store_->active_model(kTool, kMaterial);
    ASSERT_TRUE(active.has_value());
    EXPECT_EQ(active->version, 1);
    EXPECT_EQ(store_->models_for(kTool, kMaterial).size(), 2u);
    EXPECT_TRUE(store_->all_learning_entries().empty());
  }

  ScratchDir dir_;
  std::filesystem::path path_;
  std::optional<Store> store_;
  ModelRecord v1_;
  ModelRecord v2_;
};

TEST_F(LearnedModelStore, StoresTheNextVersionActiveWithTheActiveOneAsParentAndTheEntryPointingAtIt) {
  ASSERT_EQ(count("models"), "2");
  LearningEntry given = entry();
  given.model_id_after = v2_.id;  // whatever the caller puts here, the entry must point at the new version
  const auto [stored, stored_entry] = store_->add_learned_model(learned_record(), given);

  EXPECT_EQ(stored.version, 3);
  EXPECT_TRUE(stored.active);
  EXPECT_EQ(stored.source, ModelSource::kLearned);
  ASSERT_TRUE(stored.parent_version.has_value());
  EXPECT_EQ(*stored.parent_version, 1);  // the active one, not the highest (2)
  ASSERT_TRUE(stored.parent_id.has_value());
  EXPECT_EQ(*stored.parent_id, v1_.id);
  EXPECT_NE(stored.id, v1_.id);
  EXPECT_NE(stored.id, v2_.id);
  EXPECT_DOUBLE_EQ(stored.model.beta[0], 480.0 * 1.25);
  EXPECT_EQ(stored.note, "learned from 2 logs of corner");

  EXPECT_GT(stored_entry.id, 0);
  EXPECT_EQ(stored_entry.model_id_before, v1_.id);
  EXPECT_EQ(stored_entry.model_id_after, stored.id);
  EXPECT_EQ(stored_entry.n_samples, 412);

  // Read back through the store and straight from the file.
  const auto active = store_->active_model(kTool, kMaterial);
  ASSERT_TRUE(active.has_value());
  EXPECT_EQ(active->id, stored.id);
  EXPECT_EQ(active->version, 3);
  const auto versions = store_->models_for(kTool, kMaterial);
  ASSERT_EQ(versions.size(), 3u);
  EXPECT_FALSE(versions[0].active);
  EXPECT_FALSE(versions[1].active);
  EXPECT_TRUE(versions[2].active);
  const auto history = store_->learning_history(kTool, kMaterial);
  ASSERT_EQ(history.size(), 1u);
  EXPECT_EQ(history[0].model_id_before, v1_.id);
  EXPECT_EQ(history[0].model_id_after, stored.id);
  EXPECT_EQ(history[0].part_name, "corner.json");
  EXPECT_EQ(history[0].n_samples, 412);
  EXPECT_DOUBLE_EQ(history[0].error_before_n, 38.5);
  EXPECT_DOUBLE_EQ(history[0].error_after_n, 4.75);
  const auto events = store_->activation_history(kTool, kMaterial);
  ASSERT_EQ(events.size(), 4u);
  EXPECT_EQ(events.back().version, 3);
  ASSERT_TRUE(events.back().previous_version.has_value());
  EXPECT_EQ(*events.back().previous_version, 1);

  EXPECT_EQ(count("models"), "3");
  EXPECT_EQ(count("learning_history"), "1");
  EXPECT_EQ(fixtures::raw_sql(path_, "SELECT group_concat(version) FROM models WHERE active = 1"), "3");
  EXPECT_EQ(fixtures::raw_sql(path_, "SELECT model_id_after FROM learning_history"), std::to_string(stored.id));

  // A second step learns from the third version: version 4, parent 3.
  LearningEntry next = entry();
  next.model_id_before = stored.id;
  const auto [fourth, fourth_entry] = store_->add_learned_model(learned_record(), next);
  EXPECT_EQ(fourth.version, 4);
  ASSERT_TRUE(fourth.parent_version.has_value());
  EXPECT_EQ(*fourth.parent_version, 3);
  EXPECT_EQ(fourth_entry.model_id_after, fourth.id);
  EXPECT_EQ(count("learning_history"), "2");
}

TEST_F(LearnedModelStore, AnInvalidEntryStoresNeitherTheModelNorTheEntry) {
  struct Case {
    const char* what;
    void (*spoil)(LearningEntry&);
    const char* field;
  };
  const Case cases[] = {
      {"negative sample count", [](LearningEntry& e) { e.n_samples = -1; }, "learning_history.n_samples"},
      {"NaN error before", [](LearningEntry& e) { e.error_before_n = kNaN; }, "learning_history.error_before_n"},
      {"negative error after", [](LearningEntry& e) { e.error_after_n = -2.0; }, "learning_history.error_after_n"},
      {"no model before", [](LearningEntry& e) { e.model_id_before = 0; }, "learning_history.model_id_before"},
      {"model before not stored", [](LearningEntry& e) { e.model_id_before = 9999; },
       "learning_history.model_id_before"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    LearningEntry bad = entry();
    c.spoil(bad);
    const std::string message = input_error_of([&] { store_->add_learned_model(learned_record(), bad); });
    EXPECT_NE(message.find(c.field), std::string::npos) << message;
    expect_unchanged();
  }
  // The store is still usable after the rolled-back attempts: the next version is 3, not 8.
  const auto [stored, stored_entry] = store_->add_learned_model(learned_record(), entry());
  EXPECT_EQ(stored.version, 3);
  EXPECT_EQ(stored_entry.model_id_after, stored.id);
}

TEST_F(LearnedModelStore, AnInvalidModelStoresNeitherTheModelNorTheEntry) {
  ModelRecord bad = learned_record();
  bad.model.beta[2] = kNaN;
  const std::string message = input_error_of([&] { store_->add_learned_model(bad, entry()); });
  EXPECT_NE(message.find("beta[2]"), std::string::npos) << message;
  expect_unchanged();

  ModelRecord unknown = learned_record();
  unknown.material_name = "Inconel 718";
  const std::string unknown_message = input_error_of([&] { store_->add_learned_model(unknown, entry()); });
  EXPECT_NE(unknown_message.find("Inconel 718"), std::string::npos) << unknown_message;
  expect_unchanged();
}

TEST_F(LearnedModelStore, AFailureAfterBothRowsWereWrittenRollsBothBack) {
  int steps = 0;
  store_->set_write_hook([&steps](std::string_view step) {
    ++steps;
    if (step == "learning_history.insert") throw std::runtime_error("disk gone");
  });
  EXPECT_THROW(store_->add_learned_model(learned_record(), entry()), std::runtime_error);
  EXPECT_GE(steps, 2);  // the model's steps ran before the entry's
  store_->set_write_hook({});
  expect_unchanged();
}

}  // namespace
}  // namespace feedplan::model_db

namespace feedplan::model_db {
namespace {

TEST(LearnedSamples, StoredWithTheirStepAndReadBackForThePair) {
  fixtures::ScratchDir dir;
  const auto path = dir / "samples.db";
  {
    Store store = Store::open(path, OpenMode::kCreate);
    store.add_tool(fixtures::tool("SC EM D10 Z4", 10, 4, 30));
    store.add_material(fixtures::material("S50C", IsoGroup::kP, 200));
    const ModelRecord base = store.add_model(fixtures::model("SC EM D10 Z4", "S50C", 1.0));
    LearningEntry entry;
    entry.model_id_before = base.id;
    entry.part_name = "corner";
    entry.n_samples = 2;
    ModelRecord learned = base;
    learned.source = ModelSource::kLearned;
    store.add_learned_model(learned, entry, {{0.02, 4.0, 350.0, 1.0, 25.0}, {0.03, 4.2, 380.0, 2.0, 26.0}});
    entry.model_id_before = store.active_model("SC EM D10 Z4", "S50C")->id;
    store.add_learned_model(learned, entry, {{0.04, 4.4, 400.0, 1.0, 27.0}});
    // A bad sample stores nothing.
    EXPECT_THROW(store.add_learned_model(learned, entry, {{0.04, std::nan(""), 400.0, 1.0, 27.0}}), InputError);
    EXPECT_EQ(store.models_for("SC EM D10 Z4", "S50C").size(), 3u);
  }
  const Store store = Store::open(path, OpenMode::kReadOnly);
  const std::vector<LearnedSample> samples = store.learned_samples("SC EM D10 Z4", "S50C");
  ASSERT_EQ(samples.size(), 3u);
  EXPECT_DOUBLE_EQ(samples[0].force_n, 350.0);
  EXPECT_DOUBLE_EQ(samples[1].weight, 2.0);
  EXPECT_DOUBLE_EQ(samples[2].contact_length_mm, 4.4);
}

TEST(LearnedSamples, AVersionOneDatabaseIsMigrated) {
  fixtures::ScratchDir dir;
  const auto path = dir / "v1.db";
  Store::open(path, OpenMode::kCreate);
  // What a version-1 file is: no learning_samples, cutting_test_signals or mechanistic_models table, no
  // model kind (one active version per pair), no leave-one-engagement-out error, user_version 1.
  fixtures::raw_sql(path, "DROP TABLE learning_samples");
  fixtures::raw_sql(path, "DROP TABLE cutting_test_signals");
  fixtures::raw_sql(path, "DROP TABLE mechanistic_models");
  fixtures::raw_sql(path, "DROP INDEX models_one_active");
  fixtures::raw_sql(path, "ALTER TABLE models DROP COLUMN kind");
  fixtures::raw_sql(path, "ALTER TABLE models DROP COLUMN engagement_cv_rmse_n");
  fixtures::raw_sql(path, "CREATE UNIQUE INDEX models_one_active ON models (tool_id, material_id) WHERE active = 1");
  fixtures::raw_sql(path, "PRAGMA user_version = 1");
  EXPECT_THROW(Store::open(path, OpenMode::kReadOnly), InputError);  // reading never migrates
  EXPECT_EQ(Store::open(path, OpenMode::kExisting).schema_version(), kStoreSchemaVersion);
  EXPECT_EQ(fixtures::raw_sql(path, "SELECT count(*) FROM sqlite_schema WHERE name = 'learning_samples'"), "1");
  EXPECT_EQ(fixtures::raw_sql(path, "SELECT count(*) FROM sqlite_schema WHERE name = 'cutting_test_signals'"), "1");
  EXPECT_EQ(fixtures::raw_sql(path, "SELECT count(*) FROM sqlite_schema WHERE name = 'mechanistic_models'"), "1");
  EXPECT_EQ(fixtures::raw_sql(path, "SELECT count(*) FROM pragma_table_info('models') WHERE name = 'kind'"), "1");
  EXPECT_EQ(fixtures::raw_sql(path, "SELECT count(*) FROM pragma_table_info('models') WHERE name = 'engagement_cv_rmse_n'"),
            "1");
}

}  // namespace
}  // namespace feedplan::model_db
