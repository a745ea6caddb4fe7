#pragma once
// Internal: a model database on a PostgreSQL server — one libpq connection in autocommit mode (reads see
// the latest commit), write transactions serialised by one transaction-scoped advisory lock (as SQLite's
// BEGIN IMMEDIATE serialises writers of a file: a learning step's check that its parent is still active
// holds until its commit), and the mapping of server errors to the project's errors. A URL that cannot be
// parsed or a server that cannot be reached is the user's problem (InputError naming the URL, with the
// host and port tried); an error during a statement is a std::runtime_error.

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "sql_connection.hpp"

struct pg_conn;
struct pg_result;

namespace feedplan::model_db::detail {

//! The key of the advisory lock every write transaction takes ("FPDB").
inline constexpr std::int64_t kWriterLockKey = 0x46504442;

//! Frees a libpq result.
struct PgResultDeleter {
  void operator()(pg_result* result) const;
};
using PgResult = std::unique_ptr<pg_result, PgResultDeleter>;

//! One open connection to a PostgreSQL database; closes it when destroyed.
class PgConnection final : public Connection {
 public:
  //! Connects to `url`. A write waits up to `lock_timeout_ms` for another writer's lock; `read_only`
  //! makes the session refuse writes. Throws InputError (field: the URL without its password) when the
  //! URL is not valid or the server refuses or cannot be reached, saying where it tried and what may help.
  PgConnection(const std::string& url, int lock_timeout_ms, bool read_only);
  ~PgConnection() override;

  Engine engine() const override { return Engine::kPostgres; }
  void exec(const std::string& sql) override;
  std::unique_ptr<StatementBackend> prepare(std::string_view sql) const override;
  //! lastval(): the id the last INSERT drew from an identity column in this session.
  std::int64_t last_insert_rowid() const override;
  //! BEGIN, then the writer lock (waits up to the lock timeout, then throws "busy").
  void begin_write() override;
  void commit() override;
  void rollback() noexcept override;

  //! Runs `sql` with text `values` ($1, $2, …; nullptr for NULL) and returns the result. Throws
  //! std::runtime_error naming the database, the server's message and `sql` when it failed.
  PgResult run(const std::string& sql, int count, const char* const* values, const int* lengths) const;

  //! "host:port" of the server, for messages.
  const std::string& server() const { return server_; }

 private:
  pg_conn* connection_ = nullptr;
  std::string server_;
};

}  // namespace feedplan::model_db::detail
