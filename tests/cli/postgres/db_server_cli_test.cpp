// The CLI on a model database on a PostgreSQL server (the throwaway cluster of the model_db tests): --db
// and $FEEDPLAN_DB take a postgresql:// URL wherever they take a file, two `learn` runs at once never lose
// an update, `db sync` copies a local file to the server and back, and a server that cannot be reached is
// bad input (exit 2) named with --db, the URL and where it was tried.

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdlib>
#include <string>

#include "../../model_db/postgres/pg_test_server.hpp"
#include "../run_feedplan.hpp"

namespace {

using namespace feedplan::cli_test;
namespace pg_test = feedplan::model_db::pg_test;

const std::string kSamples = FEEDPLAN_SAMPLES_DIR;
const std::string kModel = std::string(FEEDPLAN_TEST_DATA_DIR) + "/cli/s50c_d10_model.json";

// A URL on the cluster's host at a port nothing listens on (the cluster's + 1).
std::string closed_port_url(int* port_out) {
  const std::string cluster = pg_test::cluster_url();
  const std::size_t colon = cluster.rfind(':');
  const int port = std::stoi(cluster.substr(colon + 1, cluster.rfind('/') - colon - 1)) + 1;
  *port_out = port;
  return "postgresql://feedplan@127.0.0.1:" + std::to_string(port) + "/models";
}

class DbServerCliTest : public CliTest {};

TEST_F(DbServerCliTest, SyncAFileToTheServerPlanFromItAndSyncBack) {
  const std::string url = pg_test::fresh_database();
  const std::string local = (dir_ / "local.db").string();
  ASSERT_EQ(run_feedplan("db init --db " + local).exit_code, 0);
  ASSERT_EQ(run_feedplan("db import " + kModel + " --db " + local).exit_code, 0);

  const RunResult up = run_feedplan("db sync --from " + local + " --to " + url);
  ASSERT_EQ(up.exit_code, 0) << up.output;
  EXPECT_NE(up.output.find("synced " + local + " into " + url), std::string::npos) << up.output;
  EXPECT_EQ(pg_test::raw_sql(url, "SELECT count(*) FROM models"), "1");
  const RunResult again = run_feedplan("db sync --from " + local + " --to " + url);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("0 tools, 0 materials, 0 model versions, 0 cutting tests, 0 learning entries added"),
            std::string::npos)
      << again.output;

  const RunResult listed = run_feedplan("db list --db " + url);
  ASSERT_EQ(listed.exit_code, 0) << listed.output;
  EXPECT_NE(listed.output.find("SC EM D10 Z4"), std::string::npos) << listed.output;

  const fs::path report = dir_ / "plan.json";
  const RunResult planned = run_feedplan("plan " + kSamples + "/corner.yaml --db " + url + " -o " +
                                         (dir_ / "corner.nc").string() + " --report " + report.string());
  ASSERT_EQ(planned.exit_code, 0) << planned.output;
  EXPECT_NE(read_text(report).find("\"database\": \"" + url + "\""), std::string::npos);  // a URL, not a path

  // A change on the server comes back to a new local copy, which plans without the server.
  ASSERT_EQ(run_feedplan("db add-material S45C --db " + url + " --iso-group P --hardness \"190 HB\"").exit_code, 0);
  const std::string copy = (dir_ / "copy.db").string();
  const RunResult down = run_feedplan("db sync --from " + url + " --to " + copy);
  ASSERT_EQ(down.exit_code, 0) << down.output;
  EXPECT_NE(run_feedplan("db list --db " + copy).output.find("S45C"), std::string::npos);
  const RunResult offline = run_feedplan("plan " + kSamples + "/corner.yaml --db " + copy + " -o " +
                                         (dir_ / "offline.nc").string());
  EXPECT_EQ(offline.exit_code, 0) << offline.output;
}

// The parent version of `version` of the sample pair on the server ("" for none).
std::string parent_of(const std::string& url, int version) {
  return pg_test::raw_sql(url, "SELECT p.version FROM models m JOIN models p ON p.id = m.parent_id WHERE m.version = " +
                                   std::to_string(version));
}

TEST_F(DbServerCliTest, TwoLearnRunsAtOnceNeverLoseAnUpdateAndEachLandsOnItsTrueParent) {
  const std::string url = pg_test::fresh_database();
  ASSERT_EQ(run_feedplan("db init --db " + url).exit_code, 0);
  ASSERT_EQ(run_feedplan("db import " + kModel + " --db " + url).exit_code, 0);
  const std::string spec = kSamples + "/corner.yaml";
  // Plans with v1 and a cut part's log, as each machine would have them.
  const auto plan_and_cut = [&](const std::string& name) {
    const RunResult planned = run_feedplan("plan " + spec + " --db " + url + " -o " + name + ".nc --report " + name + ".json",
                                           dir_);
    ASSERT_EQ(planned.exit_code, 0) << planned.output;
    const RunResult cut = run_feedplan("simulate " + name + ".nc --spec " + spec + " --log " + name + ".csv", dir_);
    ASSERT_EQ(cut.exit_code, 0) << cut.output;
  };
  plan_and_cut("a");
  plan_and_cut("b");
  // Both learn runs at once, each from a plan made with v1.
  const std::string learn = std::string(FEEDPLAN_BINARY) + " learn ";
  const std::string both = "cd '" + dir_.string() + "' || exit 1; (" + learn + "a.json a.csv -o a-next.nc > a.out 2>&1; echo $? > a.rc) & (" +
                           learn + "b.json b.csv -o b-next.nc > b.out 2>&1; echo $? > b.rc) & wait";
  ASSERT_EQ(std::system(both.c_str()), 0);
  const std::string rc_a = read_text(dir_ / "a.rc");
  const std::string rc_b = read_text(dir_ / "b.rc");
  ASSERT_TRUE((rc_a == "0\n" && rc_b == "1\n") || (rc_a == "1\n" && rc_b == "0\n"))
      << "exit codes " << rc_a << rc_b << read_text(dir_ / "a.out") << read_text(dir_ / "b.out");
  const std::string refused = rc_a == "1\n" ? "a" : "b";
  const std::string refusal = read_text(dir_ / (refused + ".out"));
  EXPECT_NE(refusal.find("v2 (id"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("Nothing was stored"), std::string::npos) << refusal;
  EXPECT_FALSE(fs::exists(dir_ / (refused + "-next.nc")));
  EXPECT_EQ(pg_test::raw_sql(url, "SELECT count(*) FROM models"), "2");
  EXPECT_EQ(parent_of(url, 2), "1");
  EXPECT_EQ(pg_test::raw_sql(url, "SELECT count(*) FROM learning_history"), "1");

  // The refused machine plans again (with v2, the active one now), cuts and learns: v3, child of v2.
  plan_and_cut(refused);
  const RunResult again = run_feedplan("learn " + refused + ".json " + refused + ".csv -o " + refused + "-next.nc", dir_);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(pg_test::raw_sql(url, "SELECT string_agg(version::text, ',' ORDER BY version) FROM models"), "1,2,3");
  EXPECT_EQ(parent_of(url, 3), "2");
  EXPECT_EQ(pg_test::raw_sql(url, "SELECT version FROM models WHERE active = 1"), "3");
  EXPECT_EQ(pg_test::raw_sql(url, "SELECT count(*) FROM learning_history"), "2");
}

TEST_F(DbServerCliTest, AnUnreachableServerIsBadInputNamingDbTheUrlAndWhere) {
  int port = 0;
  const std::string url = closed_port_url(&port);
  const RunResult listed = run_feedplan("db list --db " + url);
  EXPECT_EQ(listed.exit_code, 2) << listed.output;
  EXPECT_NE(listed.output.find("--db"), std::string::npos) << listed.output;
  EXPECT_NE(listed.output.find(url), std::string::npos) << listed.output;
  EXPECT_NE(listed.output.find("not reachable at 127.0.0.1:" + std::to_string(port)), std::string::npos) << listed.output;

  const RunResult planned = run_feedplan("plan " + kSamples + "/corner.yaml --db " + url + " -o " + (dir_ / "c.nc").string());
  EXPECT_EQ(planned.exit_code, 2) << planned.output;
  EXPECT_NE(planned.output.find(url), std::string::npos) << planned.output;
  EXPECT_FALSE(fs::exists(dir_ / "c.nc"));

  ::setenv("FEEDPLAN_DB", url.c_str(), 1);
  const RunResult from_env = run_feedplan("db list");
  ::unsetenv("FEEDPLAN_DB");
  EXPECT_EQ(from_env.exit_code, 2) << from_env.output;
  EXPECT_NE(from_env.output.find("not reachable at 127.0.0.1:" + std::to_string(port)), std::string::npos)
      << from_env.output;

  const RunResult bad = run_feedplan("db list --db postgresql://host:notaport/models");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("postgresql://host:notaport/models"), std::string::npos) << bad.output;

  const RunResult sync = run_feedplan("db sync --from " + url + " --to " + (dir_ / "x.db").string());
  EXPECT_EQ(sync.exit_code, 2) << sync.output;
  EXPECT_FALSE(fs::exists(dir_ / "x.db"));
}

}  // namespace
