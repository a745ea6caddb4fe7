// The SQLite model store (model_db/store.hpp): schema and version, WAL, records written and read back
// field by field, model versions with parent, active flag and rollback, cutting tests and learning
// history, and bad input of every kind — each an InputError naming the field (or file) and the value,
// with the database unchanged.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "feedplan/core/input_error.hpp"
#include "feedplan/model_db/model_exchange.hpp"
#include "feedplan/model_db/store.hpp"
#include "store_fixtures.hpp"

namespace feedplan::model_db {
namespace {

using fixtures::input_error_of;
using fixtures::ScratchDir;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();


// ---------------------------------------------------------------------------------------------------
// Schema, version, journal

TEST(Store, CreatesTheSchemaWithItsVersionInWalMode) {
  ScratchDir dir;
  const auto path = dir / "models.db";
  {
    Store store = Store::open(path, OpenMode::kCreate);
    EXPECT_EQ(store.schema_version(), kStoreSchemaVersion);
    EXPECT_EQ(store.path(), path);
    const auto report = store.integrity_check();
    EXPECT_TRUE(report.ok);
    EXPECT_EQ(report.messages, std::vector<std::string>{"ok"});
  }
  EXPECT_EQ(fixtures::raw_sql(path, "PRAGMA user_version"), std::to_string(kStoreSchemaVersion));
  EXPECT_EQ(fixtures::raw_sql(path, "PRAGMA application_id"), std::to_string(0x46504442));
  EXPECT_EQ(fixtures::raw_sql(path, "PRAGMA journal_mode"), "wal");
  EXPECT_EQ(fixtures::raw_sql(path, "SELECT group_concat(name, ',') FROM (SELECT name FROM sqlite_schema WHERE "
                                    "type = 'table' ORDER BY name)"),
            "cutting_test_peaks,cutting_test_signals,cutting_tests,learning_history,learning_samples,materials,"
            "mechanistic_models,model_activations,"
            "models,tools");
}

TEST(Store, ReopensAnExistingFileAndKeepsItsContent) {
  ScratchDir dir;
  const auto path = dir / "models.db";
  {
    Store store = Store::open(path, OpenMode::kCreate);
    fixtures::populate(store);
  }
  Store again = Store::open(path, OpenMode::kExisting);
  EXPECT_EQ(again.tools().size(), 3u);
  EXPECT_EQ(again.all_models().size(), 4u);
  Store create_again = Store::open(path, OpenMode::kCreate);  // kCreate opens an existing file as it is
  EXPECT_EQ(create_again.materials().size(), 3u);
}

// ---------------------------------------------------------------------------------------------------
// Tools and materials

TEST(Store, ToolsAndMaterialsReadBackFieldByField) {
  ScratchDir dir;
  Store store = Store::open(dir / "models.db", OpenMode::kCreate);
  ToolRecord tool = fixtures::tool("SC EM D6 Z3", 6, 3, 35);
  tool.notes = "regrind 2×";
  const ToolRecord added = store.add_tool(tool);
  EXPECT_GT(added.id, 0);
  store.add_tool(fixtures::tool("A first by name", 8, 2, 0));

  const auto found = store.find_tool("SC EM D6 Z3");
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(found->id, added.id);
  EXPECT_EQ(found->diameter_mm, 6.0);
  EXPECT_EQ(found->flutes, 3);
  EXPECT_EQ(found->helix_deg, 35.0);
  EXPECT_EQ(found->tool_material, "solid carbide");
  EXPECT_EQ(found->coating, "TiAlN");
  EXPECT_EQ(found->notes, "regrind 2×");
  EXPECT_FALSE(store.find_tool("sc em d6 z3").has_value());  // names are exact
  const auto tools = store.tools();
  ASSERT_EQ(tools.size(), 2u);
  EXPECT_EQ(tools[0].name, "A first by name");

  store.add_material(fixtures::material("Ti6Al4V", IsoGroup::kS, 36, "HRC"));
  const auto material = store.find_material("Ti6Al4V");
  ASSERT_TRUE(material.has_value());
  EXPECT_EQ(material->iso_group, IsoGroup::kS);
  EXPECT_EQ(material->hardness_value, 36.0);
  EXPECT_EQ(material->hardness_scale, "HRC");
  EXPECT_FALSE(store.find_material("S50C").has_value());
}

TEST(Store, DuplicateToolNameIsAnInputErrorAndChangesNothing) {
  ScratchDir dir;
  Store store = Store::open(dir / "models.db", OpenMode::kCreate);
  store.add_tool(fixtures::tool("X", 10, 4, 30));
  EXPECT_EQ(input_error_of([&] { store.add_tool(fixtures::tool("X", 12, 2, 45)); }), "tools.name = 'X' already exists");
  ASSERT_EQ(store.tools().size(), 1u);
  EXPECT_EQ(store.tools()[0].diameter_mm, 10.0);
}

TEST(Store, DuplicateMaterialNameIsAnInputErrorAndChangesNothing) {
  ScratchDir dir;
  Store store = Store::open(dir / "models.db", OpenMode::kCreate);
  store.add_material(fixtures::material("S50C", IsoGroup::kP, 200));
  EXPECT_EQ(input_error_of([&] { store.add_material(fixtures::material("S50C", IsoGroup::kM, 180)); }),
            "materials.name = 'S50C' already exists");
  ASSERT_EQ(store.materials().size(), 1u);
  EXPECT_EQ(store.materials()[0].iso_group, IsoGroup::kP);
}

TEST(Store, NegativeDiameterAndOtherBadToolFieldsAreAllReported) {
  ScratchDir dir;
  Store store = Store::open(dir / "models.db", OpenMode::kCreate);
  ToolRecord bad = fixtures::tool("", -10, 0, 90);
  EXPECT_EQ(input_error_of([&] { store.add_tool(bad); }),
            "tools.name = '': must be a non-empty name without leading or trailing blanks\n"
            "tools.diameter_mm = -10: must be in (0, 1000] mm\n"
            "tools.flutes = 0: must be in [1, 100]\n"
            "tools.helix_deg = 90: must be in [0, 90)");
  EXPECT_TRUE(store.tools().empty());
}

TEST(Store, IsoGroupIsOneOfTheSixLetters) {
  for (const char* letter : {"P", "M", "K", "N", "S", "H"}) {
    const auto group = parse_iso_group(letter);
    ASSERT_TRUE(group.has_value()) << letter;
    EXPECT_EQ(to_string(*group), letter);
  }
  EXPECT_EQ(parse_iso_group("n"), IsoGroup::kN);
  EXPECT_FALSE(parse_iso_group("X").has_value());
  EXPECT_FALSE(parse_iso_group("PM").has_value());
  EXPECT_FALSE(parse_iso_group("").has_value());
}

TEST(Store, IsoGroupXWrittenBehindTheStoresBackIsRefusedByTheSchema) {
  ScratchDir dir;
  const auto path = dir / "models.db";
  { Store store = Store::open(path, OpenMode::kCreate); }
  const std::string result = fixtures::raw_sql(
      path, "INSERT INTO materials (name, iso_group, hardness_value, hardness_scale) VALUES ('Y', 'X', 200, 'HB')");
  EXPECT_NE(result.find("CHECK constraint failed"), std::string::npos) << result;
  EXPECT_EQ(fixtures::raw_sql(path, "SELECT count(*) FROM materials"), "0");
}

TEST(Store, BadMaterialFieldsAreReported) {
  ScratchDir dir;
  Store store = Store::open(dir / "models.db", OpenMode::kCreate);
  EXPECT_EQ(input_error_of([&] { store.add_material(fixtures::material("S50C", IsoGroup::kP, kNaN, "Brinell")); }),
            "materials.hardness_value = nan: must be finite and > 0\n"
            "materials.hardness_scale = 'Brinell': must be one of HB, HV, HRC, HRB");
  EXPECT_TRUE(store.materials().empty());
}

// ---------------------------------------------------------------------------------------------------
// Models: versions, parents, the active one, rollback

class StoreWithCatalog : public ::testing::Test {
 protected:
  void SetUp() override {
    store_.add_tool(fixtures::tool("SC EM D10 Z4", 10, 4, 30));
    store_.add_tool(fixtures::tool("SC EM D6 Z3", 6, 3, 35));
    store_.add_material(fixtures::material("S50C", IsoGroup::kP, 200));
    store_.add_material(fixtures::material("Al7075-T6", IsoGroup::kN, 150));
  }
  ScratchDir dir_;
  Store store_ = Store::open(dir_ / "models.db", OpenMode::kCreate);
};

TEST_F(StoreWithCatalog, AModelReadsBackFieldByField) {
  const ModelRecord in = fixtures::model("SC EM D10 Z4", "S50C", 1.0);
  const ModelRecord out = store_.add_model(in);
  EXPECT_GT(out.id, 0);
  EXPECT_EQ(out.version, 1);
  EXPECT_FALSE(out.parent_id.has_value());
  EXPECT_FALSE(out.parent_version.has_value());
  EXPECT_TRUE(out.active);
  EXPECT_EQ(out.tool_name, "SC EM D10 Z4");
  EXPECT_EQ(out.material_name, "S50C");
  EXPECT_EQ(out.model.beta, (std::array<double, 6>{480.0, 120.5, 60.25, -5.0, 3.0, 8.125}));
  EXPECT_EQ(out.model.chip_center_mm, 0.04);
  EXPECT_EQ(out.model.chip_scale_mm, 0.02);
  EXPECT_EQ(out.model.contact_length_center_mm, 4.0);
  EXPECT_EQ(out.model.contact_length_scale_mm, 1.5);
  EXPECT_EQ(out.model.range.chip_min_mm, 0.01);
  EXPECT_EQ(out.model.range.chip_max_mm, 0.08);
  EXPECT_EQ(out.model.range.contact_length_min_mm, 2.2);
  EXPECT_EQ(out.model.range.contact_length_max_mm, 5.8);
  EXPECT_EQ(out.model.axial_depth_mm, 10.0);
  EXPECT_EQ(out.model.spindle_rpm, 2546.0);
  EXPECT_EQ(out.model.quantity, "peak_xy_force_per_revolution_n");
  EXPECT_EQ(out.fit.n, 25);
  EXPECT_EQ(out.fit.rmse_n, 4.2);
  EXPECT_EQ(out.fit.r_squared, 0.9987);
  EXPECT_EQ(out.fit.covariance(0, 0), 2.0);
  EXPECT_EQ(out.fit.covariance(5, 5), 2.0 / 11.0);  // exact: stored as text that reads back to the same double
  EXPECT_EQ(out.fit.covariance(0, 1), 0.1 / 2.0);
  EXPECT_EQ(out.fit.standard_errors[5], 0.1 / 3.0);
  EXPECT_EQ(out.fit.loo_rmse_n, 5.1);
  EXPECT_EQ(out.source, ModelSource::kCuttingTests);
  EXPECT_EQ(out.note, "fixture k = 1.000000");
  EXPECT_EQ(out.created_at.size(), std::string("2024-05-01T12:00:00.000Z").size());
  EXPECT_EQ(out.created_at.back(), 'Z');
  EXPECT_EQ(out.created_at[10], 'T');
}

TEST_F(StoreWithCatalog, EachNewVersionBecomesActiveWithThePreviousActiveAsParent) {
  const auto v1 = store_.add_model(fixtures::model("SC EM D10 Z4", "S50C", 1.0));
  const auto v2 = store_.add_model(fixtures::model("SC EM D10 Z4", "S50C", 1.1));
  const auto v3 = store_.add_model(fixtures::model("SC EM D10 Z4", "S50C", 1.2));
  store_.add_model(fixtures::model("SC EM D6 Z3", "S50C", 0.5));  // another pair: its own numbering
  EXPECT_EQ(v2.version, 2);
  EXPECT_EQ(v2.parent_id, v1.id);
  EXPECT_EQ(v3.parent_version, 2);

  const auto history = store_.models_for("SC EM D10 Z4", "S50C");
  ASSERT_EQ(history.size(), 3u);
  EXPECT_EQ(history[0].version, 1);
  EXPECT_FALSE(history[0].active);
  EXPECT_FALSE(history[1].active);
  EXPECT_TRUE(history[2].active);
  EXPECT_EQ(history[2].model.beta[0], 480.0 * 1.2);
  EXPECT_EQ(store_.active_model("SC EM D10 Z4", "S50C")->id, v3.id);
  EXPECT_EQ(store_.active_model("SC EM D6 Z3", "S50C")->version, 1);
  EXPECT_FALSE(store_.active_model("SC EM D6 Z3", "Al7075-T6").has_value());
  EXPECT_EQ(store_.active_models().size(), 2u);
  EXPECT_EQ(store_.all_models().size(), 4u);
}

TEST_F(StoreWithCatalog, RollbackMakesAnOlderVersionActiveDeletesNothingAndIsRecorded) {
  store_.add_model(fixtures::model("SC EM D10 Z4", "S50C", 1.0));
  store_.add_model(fixtures::model("SC EM D10 Z4", "S50C", 1.1));
  const auto v3 = store_.add_model(fixtures::model("SC EM D10 Z4", "S50C", 1.2));

  const auto active = store_.rollback("SC EM D10 Z4", "S50C", 1);
  EXPECT_EQ(active.version, 1);
  EXPECT_TRUE(active.active);
  const auto history = store_.models_for("SC EM D10 Z4", "S50C");
  ASSERT_EQ(history.size(), 3u);
  EXPECT_TRUE(history[0].active);
  EXPECT_FALSE(history[2].active);
  EXPECT_EQ(history[2].model.beta[0], 480.0 * 1.2);

  // The next version descends from the version in use, not from the newest.
  const auto v4 = store_.add_model(fixtures::model("SC EM D10 Z4", "S50C", 1.3));
  EXPECT_EQ(v4.version, 4);
  EXPECT_EQ(v4.parent_version, 1);
  store_.rollback("SC EM D10 Z4", "S50C", 3);
  EXPECT_EQ(store_.active_model("SC EM D10 Z4", "S50C")->id, v3.id);
  store_.rollback("SC EM D10 Z4", "S50C", 3);  // already active: nothing recorded

  const auto events = store_.activation_history("SC EM D10 Z4", "S50C");
  ASSERT_EQ(events.size(), 6u);
  const std::vector<std::pair<int, ActivationReason>> expected{
      {1, ActivationReason::kAdded}, {2, ActivationReason::kAdded},    {3, ActivationReason::kAdded},
      {1, ActivationReason::kRollback}, {4, ActivationReason::kAdded}, {3, ActivationReason::kRollback}};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(events[i].version, expected[i].first) << i;
    EXPECT_EQ(events[i].reason, expected[i].second) << i;
  }
  EXPECT_FALSE(events[0].previous_version.has_value());
  EXPECT_EQ(events[3].previous_version, 3);
  EXPECT_EQ(events[5].previous_version, 4);
}

TEST_F(StoreWithCatalog, RollbackToAVersionThatDoesNotExistIsAnInputError) {
  store_.add_model(fixtures::model("SC EM D10 Z4", "S50C", 1.0));
  store_.add_model(fixtures::model("SC EM D10 Z4", "S50C", 1.1));
  EXPECT_EQ(input_error_of([&] { store_.rollback("SC EM D10 Z4", "S50C", 7); }),
            "rollback.version = 7: no such version of SC EM D10 Z4 in S50C; versions 1–2");
  EXPECT_EQ(input_error_of([&] { store_.rollback("SC EM D6 Z3", "S50C", 1); }),
            "rollback.version = 1: no such version of SC EM D6 Z3 in S50C; it has no model yet");
  EXPECT_EQ(store_.active_model("SC EM D10 Z4", "S50C")->version, 2);
  EXPECT_EQ(store_.activation_history("SC EM D10 Z4", "S50C").size(), 2u);
}

TEST_F(StoreWithCatalog, NanCoefficientIsAnInputErrorAndNothingIsWritten) {
  store_.add_model(fixtures::model("SC EM D10 Z4", "S50C", 1.0));
  ModelRecord bad = fixtures::model("SC EM D10 Z4", "S50C", 1.1);
  bad.model.beta[2] = kNaN;
  EXPECT_EQ(input_error_of([&] { store_.add_model(bad); }), "models.beta[2] = nan: must be finite");
  bad.model.beta[2] = 1.0;
  bad.model.chip_scale_mm = 0.0;
  bad.fit.covariance(1, 1) = std::numeric_limits<double>::infinity();
  bad.model.range.chip_min_mm = 0.09;
  EXPECT_EQ(input_error_of([&] { store_.add_model(bad); }),
            "models.chip_scale_mm = 0: must be finite and > 0\n"
            "models.range.chip_min_mm = 0.09: must be ≤ range.chip_max_mm = 0.08\n"
            "models.fit.covariance[7] = inf: must be finite");
  const auto history = store_.models_for("SC EM D10 Z4", "S50C");
  ASSERT_EQ(history.size(), 1u);
  EXPECT_TRUE(history[0].active);
}

TEST_F(StoreWithCatalog, UnknownToolOrMaterialIsAnInputErrorWithTheKnownNames) {
  EXPECT_EQ(input_error_of([&] { store_.add_model(fixtures::model("SC EM D10 Z5", "S50C")); }),
            "models.tool_name = 'SC EM D10 Z5': unknown tool; known: SC EM D10 Z4, SC EM D6 Z3 "
            "(did you mean SC EM D10 Z4?)");
  EXPECT_EQ(input_error_of([&] { store_.add_model(fixtures::model("SC EM D10 Z4", "Inconel 718")); }),
            "models.material_name = 'Inconel 718': unknown material; known: Al7075-T6, S50C");
  EXPECT_EQ(input_error_of([&] { store_.active_model("nope", "S50C"); }),
            "tool_name = 'nope': unknown tool; known: SC EM D10 Z4, SC EM D6 Z3");
  EXPECT_TRUE(store_.all_models().empty());
}

// ---------------------------------------------------------------------------------------------------
// Cutting tests and learning history

TEST_F(StoreWithCatalog, CuttingTestsReadBackWithTheirSteadyPeaks) {
  auto in = fixtures::cutting_test("SC EM D10 Z4", "S50C", 3, 40);
  in.synchronous_fx_n = {1.5, -2.25, 1e-7, 480.125};
  in.synchronous_fy_n = {-0.5, 3.0, 12.75, -99.0};
  const auto stored = store_.add_cutting_test(in);
  EXPECT_GT(stored.id, 0);
  store_.add_cutting_test(fixtures::cutting_test("SC EM D6 Z3", "S50C", 1));
  auto slot = fixtures::cutting_test("SC EM D10 Z4", "S50C", 4);
  slot.conditions.mode = CutMode::kSlot;
  slot.conditions.radial_depth_mm = 10.0;
  store_.add_cutting_test(slot);

  const auto tests = store_.cutting_tests("SC EM D10 Z4", "S50C");
  ASSERT_EQ(tests.size(), 2u);
  const CuttingTestRecord& out = tests[0].test;
  EXPECT_EQ(tests[0].id, stored.id);
  EXPECT_EQ(tests[0].created_at, stored.created_at);
  EXPECT_EQ(out.conditions.tool_name, "SC EM D10 Z4");
  EXPECT_EQ(out.conditions.material_name, "S50C");
  EXPECT_EQ(out.conditions.spindle_rpm, 2546.0);
  EXPECT_EQ(out.conditions.feed_mm_per_min, 1021.4);
  EXPECT_EQ(out.conditions.radial_depth_mm, 1.5);
  EXPECT_EQ(out.conditions.axial_depth_mm, 10.0);
  EXPECT_EQ(out.conditions.mode, CutMode::kDown);
  EXPECT_EQ(out.feed_per_tooth_mm, 0.1 + 0.003);
  EXPECT_EQ(out.chip_mm, 0.0634 + 0.0003);
  EXPECT_EQ(out.contact_length_mm, 3.9646);
  EXPECT_EQ(out.peak_mean_n, 485.0);
  EXPECT_EQ(out.peak_std_n, 1.3);
  EXPECT_EQ(out.peak_min_n, 483.0);
  EXPECT_EQ(out.peak_max_n, 487.07);
  EXPECT_EQ(out.revolutions_total, 44);
  EXPECT_EQ(out.revolutions_used, 40);
  ASSERT_EQ(out.steady_peaks_n.size(), 40u);
  EXPECT_EQ(out.steady_peaks_n[0], 483.0);
  EXPECT_EQ(out.steady_peaks_n[39], 480.0 + 0.37 * 39 + 3);
  EXPECT_EQ(out.synchronous_fx_n, in.synchronous_fx_n);  // JSON numbers read back as the same doubles
  EXPECT_EQ(out.synchronous_fy_n, in.synchronous_fy_n);
  EXPECT_TRUE(tests[1].test.synchronous_fx_n.empty());
  EXPECT_EQ(out.source, "test_3.csv");
  EXPECT_EQ(out.notes, (std::vector<std::string>{"first 2 revolutions dropped (entry)",
                                                 "note with \"quotes\" and ünïcode"}));
  EXPECT_EQ(tests[1].test.conditions.mode, CutMode::kSlot);
  EXPECT_EQ(store_.all_cutting_tests().size(), 3u);
}

TEST_F(StoreWithCatalog, BadCuttingTestIsAnInputErrorNamingEachField) {
  auto bad = fixtures::cutting_test("SC EM D10 Z4", "Steel", 0);
  bad.conditions.spindle_rpm = -2800;
  bad.revolutions_used = 99;
  bad.steady_peaks_n[2] = kNaN;
  bad.synchronous_fx_n = {1.0, kNaN};
  bad.synchronous_fy_n = {1.0};
  EXPECT_EQ(input_error_of([&] { store_.add_cutting_test(bad); }),
            "cutting_tests.spindle_rpm = -2800: must be in (0, 200000] rev/min\n"
            "cutting_tests.revolutions_used = 99: must be in [0, revolutions_total = 16]\n"
            "cutting_tests.steady_peaks_n[2] = nan: must be finite and ≥ 0\n"
            "cutting_tests.synchronous_fy_n = 1 values: must have as many as synchronous_fx_n (2)\n"
            "cutting_tests.synchronous_fx_n[1] = nan: must be finite\n"
            "cutting_tests.material_name = 'Steel': unknown material; known: Al7075-T6, S50C");
  EXPECT_TRUE(store_.all_cutting_tests().empty());
}

TEST_F(StoreWithCatalog, LearningHistoryIsAppendedAndFoundByPair) {
  const auto v1 = store_.add_model(fixtures::model("SC EM D10 Z4", "S50C", 1.0));
  const auto v2 = store_.add_model(fixtures::model("SC EM D10 Z4", "S50C", 1.1));
  const auto other = store_.add_model(fixtures::model("SC EM D6 Z3", "Al7075-T6", 0.4));
  LearningEntry entry;
  entry.model_id_before = v1.id;
  entry.model_id_after = v2.id;
  entry.part_name = "pocket A";
  entry.n_samples = 1800;
  entry.error_before_n = 31.5;
  entry.error_after_n = 6.25;
  const auto stored = store_.add_learning_entry(entry);
  EXPECT_GT(stored.id, 0);
  entry.model_id_before = other.id;
  entry.model_id_after = 0;
  entry.part_name = "trochoid slot";
  store_.add_learning_entry(entry);

  const auto history = store_.learning_history("SC EM D10 Z4", "S50C");
  ASSERT_EQ(history.size(), 1u);
  EXPECT_EQ(history[0].model_id_before, v1.id);
  EXPECT_EQ(history[0].model_id_after, v2.id);
  EXPECT_EQ(history[0].part_name, "pocket A");
  EXPECT_EQ(history[0].n_samples, 1800);
  EXPECT_EQ(history[0].error_before_n, 31.5);
  EXPECT_EQ(history[0].error_after_n, 6.25);
  EXPECT_EQ(history[0].created_at, stored.created_at);
  const auto other_history = store_.learning_history("SC EM D6 Z3", "Al7075-T6");
  ASSERT_EQ(other_history.size(), 1u);
  EXPECT_EQ(other_history[0].model_id_after, 0);
  EXPECT_EQ(store_.all_learning_entries().size(), 2u);

  entry.model_id_before = 999;
  entry.n_samples = -1;
  EXPECT_EQ(input_error_of([&] { store_.add_learning_entry(entry); }),
            "learning_history.n_samples = -1: must be ≥ 0\n"
            "learning_history.model_id_before = 999: no such model version");
  EXPECT_EQ(store_.all_learning_entries().size(), 2u);
}

TEST_F(StoreWithCatalog, LearningHistoryCannotBeRewrittenBehindTheStoresBack) {
  const auto v1 = store_.add_model(fixtures::model("SC EM D10 Z4", "S50C", 1.0));
  LearningEntry entry;
  entry.model_id_before = v1.id;
  entry.part_name = "pocket A";
  store_.add_learning_entry(entry);
  const auto path = store_.path();
  EXPECT_NE(fixtures::raw_sql(path, "DELETE FROM learning_history").find("append-only"), std::string::npos);
  EXPECT_NE(fixtures::raw_sql(path, "UPDATE learning_history SET n_samples = 5").find("append-only"),
            std::string::npos);
  EXPECT_NE(fixtures::raw_sql(path, "DELETE FROM models").find("never deleted"), std::string::npos);
  EXPECT_EQ(store_.all_learning_entries().size(), 1u);
}

// ---------------------------------------------------------------------------------------------------
// Readers while a writer writes (WAL)

TEST_F(StoreWithCatalog, AReaderSeesTheCommittedStateWhileAWriteIsInProgress) {
  store_.add_model(fixtures::model("SC EM D10 Z4", "S50C", 1.0));
  Store reader = Store::open(store_.path(), OpenMode::kReadOnly);
  int seen_version = 0;
  std::size_t seen_versions = 0;
  store_.set_write_hook([&](std::string_view step) {
    if (step != "models.activate") return;
    // Inside the writer's open transaction: the reader is not blocked and sees the last commit.
    seen_version = reader.active_model("SC EM D10 Z4", "S50C")->version;
    seen_versions = reader.models_for("SC EM D10 Z4", "S50C").size();
  });
  store_.add_model(fixtures::model("SC EM D10 Z4", "S50C", 1.1));
  EXPECT_EQ(seen_version, 1);
  EXPECT_EQ(seen_versions, 1u);
  EXPECT_EQ(reader.active_model("SC EM D10 Z4", "S50C")->version, 2);
}

TEST_F(StoreWithCatalog, ASecondWriterWaitsForTheBusyTimeoutThenFailsWithoutWriting) {
  StoreOptions quick;
  quick.busy_timeout_ms = 50;
  Store second = Store::open(store_.path(), OpenMode::kExisting, quick);
  std::string message;
  store_.set_write_hook([&](std::string_view) {
    try {
      second.add_tool(fixtures::tool("from the second writer", 8, 3, 30));
    } catch (const std::runtime_error& error) {
      message = error.what();
    }
  });
  store_.add_tool(fixtures::tool("from the first writer", 8, 3, 30));
  EXPECT_NE(message.find("is busy"), std::string::npos) << message;
  EXPECT_TRUE(second.find_tool("from the first writer").has_value());
  EXPECT_FALSE(second.find_tool("from the second writer").has_value());
}

TEST_F(StoreWithCatalog, AReadOnlyStoreReadsButDoesNotWrite) {
  store_.add_model(fixtures::model("SC EM D10 Z4", "S50C", 1.0));
  Store reader = Store::open(store_.path(), OpenMode::kReadOnly);
  EXPECT_EQ(reader.tools().size(), 2u);
  EXPECT_THROW(reader.add_tool(fixtures::tool("new", 8, 3, 30)), std::runtime_error);
  EXPECT_EQ(store_.tools().size(), 2u);
}

// ---------------------------------------------------------------------------------------------------
// Files that are not (usable) model databases

TEST(StoreOpen, MissingFileIsAnInputErrorForExistingAndReadOnly) {
  ScratchDir dir;
  const auto path = dir / "none.db";
  // The caller meant an existing database: no advice to create an empty one.
  const std::string expected =
      path.string() + " cannot be opened: no such file: check the path of the model database (--db, $FEEDPLAN_DB)";
  EXPECT_EQ(input_error_of([&] { Store::open(path, OpenMode::kExisting); }), expected);
  EXPECT_EQ(input_error_of([&] { Store::open(path, OpenMode::kReadOnly); }), expected);
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(StoreOpen, RandomBytesAreAnInputErrorNamingThePathAndTheFileIsUntouched) {
  ScratchDir dir;
  const auto path = dir / "random.db";
  std::string bytes;
  unsigned state = 12345;  // fixed LCG: the same bytes every run
  for (int i = 0; i < 8192; ++i) {
    state = state * 1103515245u + 12345u;
    bytes.push_back(static_cast<char>(state >> 16));
  }
  std::ofstream(path, std::ios::binary) << bytes;
  for (const auto mode : {OpenMode::kExisting, OpenMode::kCreate, OpenMode::kReadOnly}) {
    const std::string message = input_error_of([&] { Store::open(path, mode); });
    EXPECT_EQ(message.rfind(path.string() + " is not a usable model database: file is not a database", 0), 0u)
        << message;
  }
  EXPECT_EQ(fixtures::file_bytes(path), bytes);
}

TEST(StoreOpen, TruncatedDatabaseIsAnInputErrorNamingThePath) {
  ScratchDir dir;
  const auto path = dir / "truncated.db";
  {
    Store store = Store::open(path, OpenMode::kCreate);
    fixtures::populate(store);
    for (int i = 0; i < 40; ++i) store.add_cutting_test(fixtures::cutting_test("SC EM D12 Z4", "S50C", i, 200));
  }  // closing the last connection checkpoints the WAL into the file
  const auto size = std::filesystem::file_size(path);
  ASSERT_GT(size, 40u * 4096u);
  std::filesystem::resize_file(path, size / 2);
  const std::string truncated = fixtures::file_bytes(path);
  const std::string message = input_error_of([&] { Store::open(path, OpenMode::kExisting); });
  EXPECT_EQ(message.rfind(path.string() + " is ", 0), 0u) << message;
  EXPECT_TRUE(message.find("damaged") != std::string::npos || message.find("malformed") != std::string::npos)
      << message;
  EXPECT_EQ(fixtures::file_bytes(path), truncated);
}

TEST(StoreOpen, EmptyFileIsNotADatabaseUnlessCreating) {
  ScratchDir dir;
  const auto path = dir / "empty.db";
  std::ofstream(path).close();
  EXPECT_EQ(input_error_of([&] { Store::open(path, OpenMode::kExisting); }),
            path.string() + " is empty (no tables), not a model database: check the path of the model database (--db, "
                            "$FEEDPLAN_DB); `feedplan db init` would make this file a new database with no models");
  EXPECT_EQ(Store::open(path, OpenMode::kCreate).schema_version(), kStoreSchemaVersion);
}

TEST(StoreOpen, OtherSqliteDatabaseIsAnInputError) {
  ScratchDir dir;
  const auto path = dir / "other.db";
  fixtures::raw_sql(path, "CREATE TABLE customers (id INTEGER PRIMARY KEY, name TEXT)");
  EXPECT_EQ(input_error_of([&] { Store::open(path, OpenMode::kCreate); }),
            path.string() + " is a SQLite database but not a feedplan model database (application_id 0x00000000, "
                            "expected 0x46504442)");
  EXPECT_EQ(fixtures::raw_sql(path, "SELECT count(*) FROM sqlite_schema"), "1");
}

TEST(StoreOpen, NewerSchemaVersionAsksToUpgradeFeedplanAndChangesNothing) {
  ScratchDir dir;
  const auto path = dir / "future.db";
  {
    Store store = Store::open(path, OpenMode::kCreate);
    fixtures::populate(store);
  }
  fixtures::raw_sql(path, "PRAGMA user_version = 7");
  const std::string before = fixtures::file_bytes(path);
  const std::string expected =
      path.string() + " has model database schema version 7, newer than this feedplan knows (5): upgrade feedplan";
  EXPECT_EQ(input_error_of([&] { Store::open(path, OpenMode::kExisting); }), expected);
  EXPECT_EQ(input_error_of([&] { Store::open(path, OpenMode::kReadOnly); }), expected);
  EXPECT_EQ(fixtures::file_bytes(path), before);
  EXPECT_EQ(fixtures::raw_sql(path, "PRAGMA user_version"), "7");
}

TEST(StoreOpen, DirectoryIsAnInputError) {
  ScratchDir dir;
  const auto path = dir / "a_directory";
  std::filesystem::create_directory(path);
  EXPECT_EQ(input_error_of([&] { Store::open(path, OpenMode::kCreate); }),
            path.string() + " cannot be opened: it is a directory, not a model database");
}

}  // namespace
}  // namespace feedplan::model_db
