// Export and import (model_db/model_exchange.hpp): the round trip export → import into an empty store →
// export gives the same bytes; importing twice changes nothing; name and version clashes under each
// policy; bad documents of every kind, each an InputError naming its place, with the store unchanged.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <string>

#include "feedplan/core/input_error.hpp"
#include "feedplan/model_db/model_exchange.hpp"
#include "feedplan/model_db/store.hpp"
#include "store_fixtures.hpp"

namespace feedplan::model_db {
namespace {

using fixtures::input_error_of;
using fixtures::ScratchDir;


class ExchangeTest : public ::testing::Test {
 protected:
  void SetUp() override { fixtures::populate(source_); }
  ScratchDir dir_;
  Store source_ = Store::open(dir_ / "source.db", OpenMode::kCreate);
  Store target_ = Store::open(dir_ / "target.db", OpenMode::kCreate);
};

TEST_F(ExchangeTest, ExportImportExportIsByteIdentical) {
  const std::string first = export_json(source_);
  const ImportSummary summary = import_json(target_, first);
  EXPECT_EQ(summary.tools_added, 3);
  EXPECT_EQ(summary.materials_added, 3);
  EXPECT_EQ(summary.models_added, 4);
  EXPECT_EQ(summary.models_renumbered, 0);
  EXPECT_EQ(summary.cutting_tests_added, 5);
  EXPECT_EQ(summary.learning_entries_added, 2);
  EXPECT_TRUE(summary.messages.empty());
  EXPECT_EQ(export_json(target_), first);

  // And the imported store behaves like the original: same active version, same parents.
  const auto versions = target_.models_for("SC EM D10 Z4", "S50C");
  ASSERT_EQ(versions.size(), 3u);
  EXPECT_TRUE(versions[2].active);
  EXPECT_EQ(versions[2].parent_version, 1);  // v3 was added after the rollback to v1
  EXPECT_EQ(versions[1].source, ModelSource::kLearned);
  EXPECT_EQ(versions[0].created_at, source_.models_for("SC EM D10 Z4", "S50C")[0].created_at);
  const auto history = target_.learning_history("SC EM D10 Z4", "S50C");
  ASSERT_EQ(history.size(), 2u);
  EXPECT_EQ(history[0].model_id_before, versions[0].id);
  EXPECT_EQ(history[0].model_id_after, versions[1].id);
  EXPECT_TRUE(target_.integrity_check().ok);
}

TEST_F(ExchangeTest, TheDocumentHasTheDocumentedShape) {
  const auto document = nlohmann::json::parse(export_json(source_));
  EXPECT_EQ(document["format"], "feedplan-model-db");
  EXPECT_EQ(document["format_version"], 2);
  EXPECT_EQ(document["contents"], "all_versions");
  ASSERT_EQ(document["tools"].size(), 3u);
  EXPECT_EQ(document["tools"][0]["name"], "SC EM D10 Z4");  // sorted by name
  EXPECT_EQ(document["tools"][0]["diameter_mm"], 10.0);
  EXPECT_EQ(document["materials"][2]["iso_group"], "S");
  const auto& model = document["models"][1];
  EXPECT_EQ(model["tool"], "SC EM D10 Z4");
  EXPECT_EQ(model["version"], 2);
  EXPECT_EQ(model["parent_version"], 1);
  EXPECT_EQ(model["active"], false);
  EXPECT_EQ(model["source"], "learned");
  EXPECT_EQ(model["model"]["beta"][0], 480.0 * 1.02);
  EXPECT_EQ(model["fit"]["covariance"].size(), 36u);
  EXPECT_EQ(document["models"][0]["parent_version"], nullptr);
  EXPECT_EQ(document["cutting_tests"].size(), 5u);
  EXPECT_EQ(document["cutting_tests"][0]["steady_peaks_n"].size(), 12u);
  EXPECT_EQ(document["learning_history"][0]["model_after"]["version"], 2);
  EXPECT_EQ(document["learning_history"][1]["model_after"], nullptr);
  EXPECT_FALSE(document.dump().find("\"id\"") != std::string::npos);  // no row ids
}

TEST_F(ExchangeTest, ActiveOnlyExportRoundTripsToo) {
  ExportOptions active_only;
  active_only.active_models_only = true;
  const std::string first = export_json(source_, active_only);
  const auto document = nlohmann::json::parse(first);
  ASSERT_EQ(document["models"].size(), 2u);
  EXPECT_EQ(document["models"][0]["version"], 3);
  EXPECT_EQ(document["models"][0]["parent_version"], nullptr);  // v1 is not in the document
  EXPECT_EQ(document["learning_history"].size(), 0u);            // its models are not either
  import_json(target_, first);
  EXPECT_EQ(export_json(target_, active_only), first);
  EXPECT_EQ(target_.active_model("SC EM D10 Z4", "S50C")->version, 3);
}

TEST_F(ExchangeTest, ImportingTwiceChangesNothing) {
  const std::string document = export_json(source_);
  import_json(target_, document);
  const ImportSummary again = import_json(target_, document);
  EXPECT_EQ(again.tools_added + again.materials_added + again.models_added + again.cutting_tests_added +
                again.learning_entries_added,
            0);
  EXPECT_EQ(again.tools_skipped, 3);
  EXPECT_EQ(again.models_skipped, 4);
  EXPECT_EQ(again.cutting_tests_skipped, 5);
  EXPECT_EQ(again.learning_entries_skipped, 2);
  EXPECT_EQ(export_json(target_), document);
  // Into the store it came from, too.
  import_json(source_, document);
  EXPECT_EQ(export_json(source_), document);
}

TEST_F(ExchangeTest, ToolNameClashFailsByDefaultAndLeavesTheStoreUnchanged) {
  target_.add_tool(fixtures::tool("SC EM D6 Z3", 6, 2, 35));
  target_.add_material(fixtures::material("S50C", IsoGroup::kP, 220));
  const std::string before = export_json(target_);
  EXPECT_EQ(input_error_of([&] { import_json(target_, export_json(source_)); }),
            "tools[2].name = 'SC EM D6 Z3' already exists with different content (flutes: stored 2, incoming 3); "
            "import with rename or replace\n"
            "materials[1].name = 'S50C' already exists with different content (hardness: stored 220 HB, incoming "
            "200 HB); import with rename or replace");
  EXPECT_EQ(export_json(target_), before);
}

TEST_F(ExchangeTest, RenameImportsUnderANewNameWithItsModelsAndTests) {
  target_.add_tool(fixtures::tool("SC EM D6 Z3", 6, 2, 35));
  ImportOptions rename;
  rename.on_name_clash = NameClash::kRename;
  const ImportSummary summary = import_json(target_, export_json(source_), rename);
  EXPECT_EQ(summary.tools_renamed, 1);
  EXPECT_EQ(summary.messages,
            std::vector<std::string>{"tool 'SC EM D6 Z3' imported as 'SC EM D6 Z3 (imported)' (flutes: stored 2, incoming 3)"});
  EXPECT_EQ(target_.find_tool("SC EM D6 Z3")->flutes, 2);
  EXPECT_EQ(target_.find_tool("SC EM D6 Z3 (imported)")->flutes, 3);
  EXPECT_EQ(target_.active_model("SC EM D6 Z3 (imported)", "Al7075-T6")->version, 1);
  EXPECT_EQ(target_.cutting_tests("SC EM D6 Z3 (imported)", "Al7075-T6").size(), 2u);
  EXPECT_TRUE(target_.models_for("SC EM D6 Z3", "Al7075-T6").empty());
  // A second import with rename finds the renamed copy identical and adds nothing.
  const std::string after_first = export_json(target_);
  import_json(target_, export_json(source_), rename);
  EXPECT_EQ(export_json(target_), after_first);
}

TEST_F(ExchangeTest, ReplaceOverwritesTheStoredToolsFields) {
  target_.add_tool(fixtures::tool("SC EM D6 Z3", 6, 2, 35));
  ImportOptions replace;
  replace.on_name_clash = NameClash::kReplace;
  const ImportSummary summary = import_json(target_, export_json(source_), replace);
  EXPECT_EQ(summary.tools_replaced, 1);
  EXPECT_EQ(target_.find_tool("SC EM D6 Z3")->flutes, 3);
  EXPECT_EQ(target_.tools().size(), 3u);
}

TEST_F(ExchangeTest, ADifferentModelUnderTheSameVersionIsAClashAppendedUnderRenameOrReplace) {
  for (const auto& tool : source_.tools()) target_.add_tool(tool);
  for (const auto& material : source_.materials()) target_.add_material(material);
  target_.add_model(fixtures::model("SC EM D10 Z4", "S50C", 2.0));  // its own v1
  const std::string before = export_json(target_);
  const std::string message = input_error_of([&] { import_json(target_, export_json(source_)); });
  EXPECT_EQ(message.rfind("models[0].version = 1: SC EM D10 Z4 in S50C already has a different version 1 (created ", 0),
            0u)
      << message;
  EXPECT_EQ(export_json(target_), before);

  ImportOptions rename;
  rename.on_name_clash = NameClash::kRename;
  const ImportSummary summary = import_json(target_, export_json(source_), rename);
  EXPECT_EQ(summary.models_renumbered, 3);
  EXPECT_EQ(summary.messages, (std::vector<std::string>{"SC EM D10 Z4 in S50C v1 imported as v2",
                                                        "SC EM D10 Z4 in S50C v2 imported as v3",
                                                        "SC EM D10 Z4 in S50C v3 imported as v4"}));
  const auto versions = target_.models_for("SC EM D10 Z4", "S50C");
  ASSERT_EQ(versions.size(), 4u);
  EXPECT_TRUE(versions[0].active);  // rename keeps the stored active version
  EXPECT_FALSE(versions[1].parent_version.has_value());
  EXPECT_EQ(versions[2].parent_version, 2);  // parents follow the renumbering
  EXPECT_EQ(versions[3].parent_version, 2);
  EXPECT_EQ(versions[3].model.beta[0], 480.0 * 0.98);
  // The learning history points at the renumbered versions.
  const auto history = target_.learning_history("SC EM D10 Z4", "S50C");
  ASSERT_EQ(history.size(), 2u);
  EXPECT_EQ(history[0].model_id_before, versions[1].id);
  EXPECT_EQ(history[0].model_id_after, versions[2].id);
}

TEST_F(ExchangeTest, ReplaceMakesTheImportedActiveVersionActive) {
  for (const auto& tool : source_.tools()) target_.add_tool(tool);
  for (const auto& material : source_.materials()) target_.add_material(material);
  target_.add_model(fixtures::model("SC EM D10 Z4", "S50C", 2.0));
  ImportOptions replace;
  replace.on_name_clash = NameClash::kReplace;
  import_json(target_, export_json(source_), replace);
  const auto active = target_.active_model("SC EM D10 Z4", "S50C");
  EXPECT_EQ(active->version, 4);  // the source's active v3, appended as v4
  EXPECT_EQ(active->model.beta[0], 480.0 * 0.98);
  const auto events = target_.activation_history("SC EM D10 Z4", "S50C");
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[1].reason, ActivationReason::kImported);
  EXPECT_EQ(events[1].previous_version, 1);
}

TEST_F(ExchangeTest, ALaterExportOfTheSameHistoryContinuesIt) {
  import_json(target_, export_json(source_));
  source_.add_model(fixtures::model("SC EM D10 Z4", "S50C", 0.97));  // v4 in the source only
  import_json(target_, export_json(source_));
  EXPECT_EQ(target_.active_model("SC EM D10 Z4", "S50C")->version, 4);
  EXPECT_EQ(export_json(target_), export_json(source_));
  // An older export does not roll the active version back.
  ExportOptions active_only;
  active_only.active_models_only = true;
  source_.rollback("SC EM D10 Z4", "S50C", 2);
  import_json(target_, export_json(source_, active_only));
  EXPECT_EQ(target_.active_model("SC EM D10 Z4", "S50C")->version, 4);
}

// ---------------------------------------------------------------------------------------------------
// Bad documents

class BadDocumentTest : public ExchangeTest {
 protected:
  //! The error of importing the source's export after `edit`; checks that the target is unchanged.
  template <typename Edit>
  std::string error_after(Edit&& edit) {
    auto document = nlohmann::json::parse(export_json(source_));
    edit(document);
    const std::string before = export_json(target_);
    const std::string message = input_error_of([&] { import_json(target_, document.dump(), {}, "other.json"); });
    EXPECT_EQ(export_json(target_), before);
    return message;
  }
  void SetUp() override {
    ExchangeTest::SetUp();
    target_.add_tool(fixtures::tool("already here", 4, 2, 30));
  }
};

TEST_F(BadDocumentTest, NotJson) {
  const std::string message = input_error_of([&] { import_json(target_, "{\"format\": ", {}, "other.json"); });
  EXPECT_EQ(message.rfind("other.json is not valid JSON: ", 0), 0u) << message;
  EXPECT_EQ(target_.tools().size(), 1u);
}

TEST_F(BadDocumentTest, NotThisFormat) {
  EXPECT_EQ(error_after([](auto& d) { d["format"] = "something else"; }),
            "other.json is not a feedplan model database export (expected \"format\": \"feedplan-model-db\")");
}

TEST_F(BadDocumentTest, AFormatThatIsNotTextIsNotThisFormat) {
  EXPECT_EQ(error_after([](auto& d) { d["format"] = 5; }),
            "other.json is not a feedplan model database export (expected \"format\": \"feedplan-model-db\")");
}

TEST_F(BadDocumentTest, AnIntegerBeyondAnIntIsNamedNotWrapped) {
  const std::string message = error_after([](auto& d) { d["tools"][0]["flutes"] = 3000000000LL; });
  EXPECT_NE(message.find("tools[0].flutes = 3000000000: must be an integer in [-2147483648, 2147483647]"),
            std::string::npos)
      << message;
}

TEST_F(BadDocumentTest, NewerFormatVersionAsksToUpgrade) {
  EXPECT_EQ(error_after([](auto& d) { d["format_version"] = 3; }),
            "other.json has format_version 3, newer than this feedplan reads (2): upgrade feedplan");
}

TEST_F(BadDocumentTest, IsoGroupX) {
  EXPECT_EQ(error_after([](auto& d) { d["materials"][1]["iso_group"] = "X"; }),
            "materials[1].iso_group = 'X': must be one of P, M, K, N, S, H");
}

TEST_F(BadDocumentTest, NegativeDiameter) {
  EXPECT_EQ(error_after([](auto& d) { d["tools"][0]["diameter_mm"] = -10; }),
            "tools[0].diameter_mm = -10: must be in (0, 1000] mm");
}

TEST_F(BadDocumentTest, NullCoefficientAndMissingField) {
  EXPECT_EQ(error_after([](auto& d) {
              d["models"][2]["model"]["beta"][2] = nullptr;
              d["models"][3]["fit"].erase("rmse_n");
            }),
            "models[2].model.beta[2] = null: must be a finite number\n"
            "models[3].fit.rmse_n is missing");
}

TEST_F(BadDocumentTest, UnknownToolReferenced) {
  EXPECT_EQ(error_after([](auto& d) { d["models"][3]["tool"] = "SC EM D6 Z4"; }),
            "models[3].tool = 'SC EM D6 Z4': unknown tool; known: SC EM D10 Z4, SC EM D12 Z4, SC EM D6 Z3, "
            "already here (did you mean SC EM D6 Z3?)");
}

TEST_F(BadDocumentTest, TwoActiveVersionsAndABadParent) {
  EXPECT_EQ(error_after([](auto& d) {
              d["models"][0]["active"] = true;
              d["models"][1]["parent_version"] = 5;
            }),
            "models[1].parent_version = 5: must be an earlier response_surface version of SC EM D10 Z4 in S50C in the "
            "document (or "
            "null)\n"
            "models SC EM D10 Z4 in S50C has 2 active response_surface versions: must have exactly one");
}

TEST_F(BadDocumentTest, BadCuttingTestAndTimeStamp) {
  EXPECT_EQ(error_after([](auto& d) {
              d["cutting_tests"][4]["mode"] = "climb";
              d["cutting_tests"][4]["created_at"] = "yesterday";
              d["cutting_tests"][0]["steady_peaks_n"][3] = "482";
            }),
            "cutting_tests[0].steady_peaks_n[3] = '482': must be a finite number\n"
            "cutting_tests[4].created_at = 'yesterday': must be UTC ISO 8601, e.g. 2024-05-01T12:00:00.000Z\n"
            "cutting_tests[4].mode = 'climb': must be down, up or slot");
}

TEST_F(BadDocumentTest, AnErrorLateInTheDocumentWritesNothingOfTheEarlierRows) {
  // Tools, materials and models are fine and would be written first; the last learning entry points at
  // a version that exists nowhere, found only while writing. The transaction rolls everything back.
  EXPECT_EQ(error_after([](auto& d) { d["learning_history"][1]["model_before"]["version"] = 9; }),
            "learning_history[1].model_before.version = 9: no such version of SC EM D10 Z4 in S50C in the "
            "document or the store");
  EXPECT_EQ(target_.tools().size(), 1u);
  EXPECT_TRUE(target_.all_models().empty());
}

TEST_F(ExchangeTest, FilesAreWrittenAtomicallyAndReadBack) {
  const auto path = dir_ / "export.json";
  export_to_file(source_, path);
  EXPECT_EQ(fixtures::file_bytes(path), export_json(source_));
  import_from_file(target_, path);
  EXPECT_EQ(export_json(target_), export_json(source_));
  EXPECT_EQ(input_error_of([&] { import_from_file(target_, dir_ / "missing.json"); }),
            (dir_ / "missing.json").string() +
                " cannot be read: no such file (expected a model database export, JSON)");
  const std::string message = input_error_of([&] { export_to_file(source_, dir_ / "no" / "such" / "dir.json"); });
  EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
}

}  // namespace
}  // namespace feedplan::model_db
