#pragma once
// The PostgreSQL server of the model database tests: the throwaway cluster pg_cluster.sh started (its
// state file named by $FEEDPLAN_TEST_PG_STATE, set by CTest), a new empty database on it for each test, and
// direct access for looking at a database behind the store's back.

#include <gtest/gtest.h>
#include <libpq-fe.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>

namespace feedplan::model_db::pg_test {

//! The URL of the cluster's "postgres" database, from the state file. Throws when there is no cluster:
//! the tests need one (run them through ctest, which starts it).
inline std::string cluster_url() {
  const char* state = std::getenv("FEEDPLAN_TEST_PG_STATE");
  if (state == nullptr || *state == '\0') {
    throw std::runtime_error("FEEDPLAN_TEST_PG_STATE is not set: run these tests through ctest, whose fixture "
                             "starts the PostgreSQL cluster (tests/model_db/postgres/pg_cluster.sh)");
  }
  std::ifstream in(state);
  std::string line;
  while (std::getline(in, line)) {
    if (line.starts_with("PG_URL=")) return line.substr(7);
  }
  throw std::runtime_error(std::string("no PG_URL in ") + state + ": the cluster did not start");
}

//! Runs `sql` on the database at `url` directly (not through the store); returns the first column of the
//! first row, "" when there is none, "error: …" when the server refused it.
inline std::string raw_sql(const std::string& url, const std::string& sql) {
  PGconn* connection = PQconnectdb(url.c_str());
  std::string value;
  if (PQstatus(connection) != CONNECTION_OK) {
    value = std::string("error: ") + PQerrorMessage(connection);
  } else {
    PQsetNoticeProcessor(connection, [](void*, const char*) {}, nullptr);
    PGresult* result = PQexec(connection, sql.c_str());
    const ExecStatusType status = PQresultStatus(result);
    if (status == PGRES_TUPLES_OK && PQntuples(result) > 0) {
      value = PQgetvalue(result, 0, 0);
    } else if (status != PGRES_TUPLES_OK && status != PGRES_COMMAND_OK) {
      value = std::string("error: ") + PQresultErrorMessage(result);
    }
    PQclear(result);
  }
  PQfinish(connection);
  return value;
}

//! A new empty database on the cluster for one test; its URL.
inline std::string fresh_database() {
  static std::atomic<int> counter{0};
  const std::string name = "t_" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
  const std::string url = cluster_url();
  const std::string created = raw_sql(url, "CREATE DATABASE " + name);
  if (created.starts_with("error")) throw std::runtime_error("CREATE DATABASE " + name + ": " + created);
  return url.substr(0, url.rfind('/') + 1) + name;
}

}  // namespace feedplan::model_db::pg_test
