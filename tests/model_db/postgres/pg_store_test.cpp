// The model database on a PostgreSQL server, against a real server (the throwaway cluster of
// pg_cluster.sh): the same records, versions, activations, rollbacks, history and lineage as the SQLite
// file, writes that are whole or absent, and the schema's versions and migrations.

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "../store_fixtures.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/model_db/database_url.hpp"
#include "feedplan/model_db/stale_model_error.hpp"
#include "feedplan/model_db/store.hpp"
#include "pg_test_server.hpp"

namespace feedplan::model_db {
namespace {

const std::string kTool = "SC EM D10 Z4";
const std::string kMaterial = "S50C";

std::string message_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no exception)";
}

TEST(PgStore, RecordsReadBackExactlyAsWritten) {
  const std::string url = pg_test::fresh_database();
  {
    Store store = Store::open(url, OpenMode::kCreate);
    EXPECT_EQ(store.schema_version(), kStoreSchemaVersion);
    store.add_tool(fixtures::tool(kTool, 10, 4, 30));
    store.add_tool(fixtures::tool("a lower-case tool", 6, 3, 35));
    store.add_material(fixtures::material(kMaterial, IsoGroup::kP, 200));
    ModelRecord model = fixtures::model(kTool, kMaterial, 1.0);
    model.model.beta[0] = 0.1 + 0.2;  // not a short decimal: only an exact round trip gives it back
    model.model.beta[3] = -1.0 / 3.0;
    model.note = "note with 'quotes' and ? marks";
    store.add_model(model);
  }
  const Store store = Store::open(url, OpenMode::kReadOnly);
  const ModelRecord active = *store.active_model(kTool, kMaterial);
  EXPECT_EQ(active.model.beta[0], 0.1 + 0.2);
  EXPECT_EQ(active.model.beta[3], -1.0 / 3.0);
  EXPECT_EQ(active.model.beta[1], fixtures::model(kTool, kMaterial, 1.0).model.beta[1]);
  EXPECT_EQ(active.note, "note with 'quotes' and ? marks");
  EXPECT_EQ(active.version, 1);
  EXPECT_FALSE(active.parent_id.has_value());
  // Names sort bytewise, as in the SQLite file: upper case before lower case.
  const auto tools = store.tools();
  ASSERT_EQ(tools.size(), 2u);
  EXPECT_EQ(tools[0].name, kTool);
  EXPECT_EQ(tools[1].name, "a lower-case tool");
  EXPECT_EQ(tools[0].diameter_mm, 10.0);
  EXPECT_EQ(store.path().string(), url);
  EXPECT_TRUE(store.integrity_check().ok);
}

TEST(PgStore, VersionsRollbackHistoryAndLineage) {
  const std::string url = pg_test::fresh_database();
  Store store = Store::open(url, OpenMode::kCreate);
  store.add_tool(fixtures::tool(kTool, 10, 4, 30));
  store.add_material(fixtures::material(kMaterial, IsoGroup::kP, 200));
  const ModelRecord v1 = store.add_model(fixtures::model(kTool, kMaterial, 1.0));
  const ModelRecord v2 = fixtures::learn_step(store, kTool, kMaterial, 5);
  const ModelRecord v3 = fixtures::learn_step(store, kTool, kMaterial, 5);
  EXPECT_EQ(v2.version, 2);
  EXPECT_EQ(v2.parent_id, v1.id);
  EXPECT_EQ(v2.parent_version, 1);
  EXPECT_EQ(v3.parent_id, v2.id);
  EXPECT_TRUE(v3.active);

  const ModelRecord back = store.rollback(kTool, kMaterial, 1);
  EXPECT_EQ(back.id, v1.id);
  EXPECT_EQ(store.active_model(kTool, kMaterial)->version, 1);
  EXPECT_EQ(store.models_for(kTool, kMaterial).size(), 3u);  // nothing deleted
  const std::string unknown = message_of([&] { store.rollback(kTool, kMaterial, 7); });
  EXPECT_NE(unknown.find("rollback.version = 7: no such version of SC EM D10 Z4 in S50C; versions 1–3"),
            std::string::npos)
      << unknown;

  const auto events = store.activation_history(kTool, kMaterial);
  ASSERT_EQ(events.size(), 4u);
  EXPECT_EQ(events[0].reason, ActivationReason::kAdded);
  EXPECT_EQ(events[2].version, 3);
  EXPECT_EQ(events[2].previous_version, 2);
  EXPECT_EQ(events[3].reason, ActivationReason::kRollback);
  EXPECT_EQ(events[3].version, 1);
  EXPECT_EQ(events[3].previous_version, 3);

  const auto history = store.learning_history(kTool, kMaterial);
  ASSERT_EQ(history.size(), 2u);
  EXPECT_EQ(history[0].model_id_before, v1.id);
  EXPECT_EQ(history[0].model_id_after, v2.id);
  EXPECT_EQ(history[1].model_id_after, v3.id);
  EXPECT_EQ(store.learned_samples(kTool, kMaterial).size(), 10u);
  EXPECT_EQ(pg_test::raw_sql(url, "SELECT count(*) FROM learning_samples"), "10");

  // A step fitted from v3 while v1 is active again is refused and stores nothing.
  ModelRecord learned = fixtures::model(kTool, kMaterial, 1.3);
  learned.source = ModelSource::kLearned;
  LearningEntry entry;
  entry.model_id_before = v3.id;
  entry.part_name = "late part";
  EXPECT_THROW(store.add_learned_model(learned, entry, {{0.02, 4.0, 350.0, 1.0, 0.0}}), StaleModelError);
  EXPECT_EQ(pg_test::raw_sql(url, "SELECT count(*) FROM models"), "3");
  EXPECT_EQ(pg_test::raw_sql(url, "SELECT count(*) FROM learning_history"), "2");
}

TEST(PgStore, AWriteThatFailsHalfwayStoresNothing) {
  const std::string url = pg_test::fresh_database();
  Store store = Store::open(url, OpenMode::kCreate);
  store.add_tool(fixtures::tool(kTool, 10, 4, 30));
  store.add_material(fixtures::material(kMaterial, IsoGroup::kP, 200));
  const ModelRecord v1 = store.add_model(fixtures::model(kTool, kMaterial, 1.0));
  for (const char* failing_step : {"models.insert", "models.activate", "learning_history.insert", "learning_samples.insert"}) {
    SCOPED_TRACE(failing_step);
    store.set_write_hook([failing_step](std::string_view step) {
      if (step == failing_step) throw std::runtime_error("interrupted");
    });
    EXPECT_THROW(fixtures::learn_step(store, kTool, kMaterial, 5), std::runtime_error);
    store.set_write_hook({});
    EXPECT_EQ(pg_test::raw_sql(url, "SELECT count(*) FROM models"), "1");
    EXPECT_EQ(pg_test::raw_sql(url, "SELECT count(*) FROM learning_history"), "0");
    EXPECT_EQ(pg_test::raw_sql(url, "SELECT count(*) FROM learning_samples"), "0");
    EXPECT_EQ(store.active_model(kTool, kMaterial)->id, v1.id);
  }
  // The connection is usable after the rolled-back transactions.
  EXPECT_EQ(fixtures::learn_step(store, kTool, kMaterial, 5).version, 2);
}

TEST(PgStore, TheStoreRulesHoldOnTheServer) {
  const std::string url = pg_test::fresh_database();
  Store store = Store::open(url, OpenMode::kCreate);
  store.add_tool(fixtures::tool(kTool, 10, 4, 30));
  const std::string duplicate = message_of([&] { store.add_tool(fixtures::tool(kTool, 12, 4, 30)); });
  EXPECT_NE(duplicate.find("tools.name = 'SC EM D10 Z4' already exists"), std::string::npos) << duplicate;
  const std::string unknown = message_of([&] { store.add_model(fixtures::model(kTool, "S55C", 1.0)); });
  EXPECT_NE(unknown.find("models.material_name = 'S55C': unknown material"), std::string::npos) << unknown;
  store.add_material(fixtures::material(kMaterial, IsoGroup::kP, 200));
  store.add_model(fixtures::model(kTool, kMaterial, 1.0));
  // Behind the store's back, the server itself refuses to delete a version or rewrite the audit trail.
  EXPECT_NE(pg_test::raw_sql(url, "DELETE FROM models").find("models are never deleted"), std::string::npos);
  EXPECT_NE(pg_test::raw_sql(url, "UPDATE model_activations SET reason = 'rollback'").find("append-only"),
            std::string::npos);
  // A read-only store refuses writes.
  Store reader = Store::open(url, OpenMode::kReadOnly);
  EXPECT_THROW(reader.add_material(fixtures::material("S45C", IsoGroup::kP, 190)), std::runtime_error);
  EXPECT_FALSE(store.find_material("S45C").has_value());
}

TEST(PgStore, AVersionOneDatabaseIsMigrated) {
  const std::string url = pg_test::fresh_database();
  {
    Store store = Store::open(url, OpenMode::kCreate);
    store.add_tool(fixtures::tool(kTool, 10, 4, 30));
    store.add_material(fixtures::material(kMaterial, IsoGroup::kP, 200));
    store.add_model(fixtures::model(kTool, kMaterial, 1.0));
  }
  // What a version-1 database is: no learning_samples, cutting_test_signals or mechanistic_models table, no
  // model kind (one active version per pair), no leave-one-engagement-out error, version 1.
  for (const char* sql : {"DROP TABLE learning_samples", "DROP TABLE cutting_test_signals", "DROP TABLE mechanistic_models",
                          "DROP INDEX models_one_active", "ALTER TABLE models DROP COLUMN kind",
                          "ALTER TABLE models DROP COLUMN engagement_cv_rmse_n",
                          "CREATE UNIQUE INDEX models_one_active ON models (tool_id, material_id) WHERE active = 1",
                          "UPDATE feedplan_schema SET version = 1"}) {
    ASSERT_EQ(pg_test::raw_sql(url, sql), "") << sql;
  }
  const std::string read_only = message_of([&] { Store::open(url, OpenMode::kReadOnly); });
  EXPECT_NE(read_only.find("schema version 1 and needs migrating to 5"), std::string::npos) << read_only;
  EXPECT_EQ(Store::open(url, OpenMode::kExisting).schema_version(), kStoreSchemaVersion);
  EXPECT_EQ(pg_test::raw_sql(url, "SELECT version FROM feedplan_schema"), "5");
  EXPECT_EQ(pg_test::raw_sql(url, "SELECT count(*) FROM pg_tables WHERE tablename IN "
                                  "('learning_samples', 'cutting_test_signals', 'mechanistic_models')"),
            "3");
  const Store store = Store::open(url, OpenMode::kReadOnly);
  const ModelRecord kept = *store.active_model(kTool, kMaterial);
  EXPECT_EQ(kept.version, 1);
  EXPECT_EQ(kept.kind, ModelKind::kResponseSurface);
  EXPECT_EQ(kept.fit.engagement_cv_rmse_n, 0.0);
}

TEST(PgStore, OpenRefusesWhatIsNotAModelDatabase) {
  const std::string url = pg_test::fresh_database();
  const std::string empty = message_of([&] { Store::open(url, OpenMode::kExisting); });
  EXPECT_NE(empty.find("is an empty PostgreSQL database"), std::string::npos) << empty;
  EXPECT_NE(empty.find("feedplan db init"), std::string::npos) << empty;
  ASSERT_EQ(pg_test::raw_sql(url, "CREATE TABLE invoices (id INTEGER)"), "");
  const std::string other = message_of([&] { Store::open(url, OpenMode::kCreate); });
  EXPECT_NE(other.find("not a feedplan model database"), std::string::npos) << other;

  const std::string newer_url = pg_test::fresh_database();
  Store::open(newer_url, OpenMode::kCreate);
  ASSERT_EQ(pg_test::raw_sql(newer_url, "UPDATE feedplan_schema SET version = 9"), "");
  const std::string newer = message_of([&] { Store::open(newer_url, OpenMode::kExisting); });
  EXPECT_NE(newer.find("schema version 9, newer than this feedplan knows (5): upgrade feedplan"), std::string::npos)
      << newer;
}

TEST(PgStore, AnUnreachableServerOrABadUrlIsNamedWithWhatMayHelp) {
  // A port nothing listens on: the cluster's port + 1 is taken by nothing the tests start.
  const std::string cluster = pg_test::cluster_url();
  const std::size_t colon = cluster.rfind(':');
  const int port = std::stoi(cluster.substr(colon + 1, cluster.rfind('/') - colon - 1)) + 1;
  const std::string closed = "postgresql://feedplan:secret@127.0.0.1:" + std::to_string(port) + "/models";
  try {
    Store::open(closed, OpenMode::kReadOnly);
    ADD_FAILURE() << "opened " << closed;
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("postgresql://feedplan:***@127.0.0.1:" + std::to_string(port) + "/models"), std::string::npos)
        << message;
    EXPECT_EQ(message.find("secret"), std::string::npos) << message;
    EXPECT_NE(message.find("not reachable at 127.0.0.1:" + std::to_string(port)), std::string::npos) << message;
    EXPECT_NE(message.find("--db"), std::string::npos) << message;
  }
  const std::string bad = message_of([] { Store::open(std::string("postgresql://host:notaport/db"), OpenMode::kReadOnly); });
  EXPECT_NE(bad.find("postgresql://host:notaport/db"), std::string::npos) << bad;
  EXPECT_NE(bad.find("--db"), std::string::npos) << bad;
  const std::string missing = message_of([&] {
    Store::open(cluster.substr(0, cluster.rfind('/') + 1) + "no_such_database", OpenMode::kReadOnly);
  });
  EXPECT_NE(missing.find("does not exist"), std::string::npos) << missing;
  EXPECT_NE(missing.find("createdb"), std::string::npos) << missing;
}

TEST(PgStore, UrlsAreToldFromPathsAndShownWithoutPasswords) {
  EXPECT_TRUE(is_server_url("postgresql://ann@db.example/models"));
  EXPECT_TRUE(is_server_url("postgres://ann@db.example/models"));
  EXPECT_FALSE(is_server_url("models.db"));
  EXPECT_FALSE(is_server_url("./postgresql:/x"));
  EXPECT_EQ(shown_location("postgresql://ann:pw@db.example:5433/models"), "postgresql://ann:***@db.example:5433/models");
  EXPECT_EQ(shown_location("postgresql://db.example/models?user=ann&password=pw&sslmode=require"),
            "postgresql://db.example/models?user=ann&password=***&sslmode=require");
  EXPECT_EQ(shown_location("postgresql://ann@db.example/models"), "postgresql://ann@db.example/models");
  EXPECT_EQ(shown_location("/var/lib/a:b@c/models.db"), "/var/lib/a:b@c/models.db");
}

}  // namespace
}  // namespace feedplan::model_db
