// Syncing a local model database file and a shared one on a PostgreSQL server, both ways: everything the
// one holds reaches the other with its versions, lineage and history, and a second sync changes nothing.

#include <gtest/gtest.h>

#include <string>

#include "../store_fixtures.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/model_db/model_exchange.hpp"
#include "feedplan/model_db/model_sync.hpp"
#include "feedplan/model_db/store.hpp"
#include "pg_test_server.hpp"

namespace feedplan::model_db {
namespace {

const std::string kTool = "SC EM D10 Z4";
const std::string kMaterial = "S50C";

TEST(PgSync, AFileReachesTheServerAndComesBackWithItsLineage) {
  const std::string kSyncTool = "SC EM D8 Z4";  // a pair populate() leaves alone
  const std::string kSyncMaterial = "SUS304";
  fixtures::ScratchDir dir;
  const auto file = dir / "local.db";
  {
    Store local = Store::open(file, OpenMode::kCreate);
    fixtures::populate(local);
    local.add_tool(fixtures::tool(kSyncTool, 8, 4, 30));
    local.add_material(fixtures::material(kSyncMaterial, IsoGroup::kM, 180));
    local.add_model(fixtures::model(kSyncTool, kSyncMaterial, 1.0));
    fixtures::learn_step(local, kSyncTool, kSyncMaterial, 3);
    fixtures::learn_step(local, kSyncTool, kSyncMaterial, 3);
    local.rollback(kSyncTool, kSyncMaterial, 2);
  }
  const std::string url = pg_test::fresh_database();
  Store local = Store::open(file, OpenMode::kExisting);
  Store server = Store::open(url, OpenMode::kCreate);

  const ImportSummary up = sync_models(local, server);
  EXPECT_GT(up.models_added, 3);
  EXPECT_EQ(export_json(server), export_json(local));  // every exported field equal, active flags included
  const auto versions = server.models_for(kSyncTool, kSyncMaterial);
  ASSERT_EQ(versions.size(), 3u);
  EXPECT_EQ(versions[2].parent_version, 2);
  EXPECT_EQ(versions[1].parent_version, 1);
  EXPECT_EQ(server.active_model(kSyncTool, kSyncMaterial)->version, 2);
  EXPECT_EQ(server.learning_history(kSyncTool, kSyncMaterial).size(), 2u);
  EXPECT_EQ(server.learned_samples(kSyncTool, kSyncMaterial).size(), 6u);  // the steps' samples too

  const ImportSummary again = sync_models(local, server);
  EXPECT_EQ(again.models_added + again.tools_added + again.materials_added + again.cutting_tests_added +
                again.learning_entries_added,
            0);
  EXPECT_EQ(again.models_skipped, up.models_added);

  // Another machine learns on the server; the file gets it back on the next sync down.
  fixtures::learn_step(server, kSyncTool, kSyncMaterial, 3);
  const ImportSummary down = sync_models(server, local);
  EXPECT_EQ(down.models_added, 1);
  EXPECT_EQ(down.learning_entries_added, 1);
  const ModelRecord v4 = *local.active_model(kSyncTool, kSyncMaterial);
  EXPECT_EQ(v4.version, 4);
  EXPECT_EQ(v4.parent_version, 2);
  EXPECT_EQ(local.learned_samples(kSyncTool, kSyncMaterial).size(), 9u);
  EXPECT_EQ(export_json(local), export_json(server));
  EXPECT_EQ(sync_models(server, local).models_added, 0);
}

TEST(PgSync, VersionsLearnedApartClashAndChangeNothing) {
  const std::string url = pg_test::fresh_database();
  fixtures::ScratchDir dir;
  Store server = Store::open(url, OpenMode::kCreate);
  server.add_tool(fixtures::tool(kTool, 10, 4, 30));
  server.add_material(fixtures::material(kMaterial, IsoGroup::kP, 200));
  server.add_model(fixtures::model(kTool, kMaterial, 1.0));
  Store local = Store::open(dir / "local.db", OpenMode::kCreate);
  sync_models(server, local);
  fixtures::learn_step(server, kTool, kMaterial, 3);
  ModelRecord other = fixtures::model(kTool, kMaterial, 1.7);  // v2 learned offline, different content
  other.source = ModelSource::kLearned;
  local.add_model(other);
  const std::string before = export_json(server);
  EXPECT_THROW(sync_models(local, server), InputError);
  EXPECT_EQ(export_json(server), before);
}

}  // namespace
}  // namespace feedplan::model_db
