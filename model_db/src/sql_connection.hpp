#pragma once
// Internal: what the row code needs of a connection to a model database, whichever engine holds it — an
// embedded SQLite file (sqlite_handle.hpp) or a PostgreSQL server (pg_connection.hpp). The row code writes
// the SQL common to both dialects, with `?` (or `?N`) parameters; each engine prepares it its own way.

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>

namespace feedplan::model_db::detail {

//! The engine behind a connection.
enum class Engine {
  kSqlite,    //!< an embedded SQLite file
  kPostgres,  //!< a PostgreSQL server
};

//! One prepared statement of an engine, driven by Statement (sql_statement.hpp). Parameter and column
//! indices are as Statement documents them (parameters from 1, columns from 0).
class StatementBackend {
 public:
  virtual ~StatementBackend() = default;
  virtual void bind_double(int parameter, double value) = 0;
  virtual void bind_int64(int parameter, std::int64_t value) = 0;
  virtual void bind_text(int parameter, std::string_view value) = 0;
  virtual void bind_null(int parameter) = 0;
  virtual bool step() = 0;
  virtual void reset() = 0;
  virtual double column_double(int column) const = 0;
  virtual std::int64_t column_int64(int column) const = 0;
  virtual int column_int(int column) const = 0;
  virtual std::string column_text(int column) const = 0;
  virtual bool column_is_null(int column) const = 0;
};

//! One open connection to a model database; closes it when destroyed.
class Connection {
 public:
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;
  virtual ~Connection() = default;

  virtual Engine engine() const = 0;

  //! Runs one or more statements whose rows are not needed. Throws as the engine maps its errors.
  virtual void exec(const std::string& sql) = 0;

  //! Prepares one statement written with `?` / `?N` parameters.
  virtual std::unique_ptr<StatementBackend> prepare(std::string_view sql) const = 0;

  //! The row id the last INSERT into a table with an id column gave.
  virtual std::int64_t last_insert_rowid() const = 0;

  //! Starts a write transaction that holds the database's one writer lock until it ends, so that what
  //! is checked inside it stays true until the commit (see WriteTransaction).
  virtual void begin_write() = 0;
  virtual void commit() = 0;
  //! Undoes the open transaction; never throws (a lost connection rolls back on the server's side).
  virtual void rollback() noexcept = 0;

  //! The file name or the URL (without a password), for messages.
  const std::string& path() const { return path_; }

 protected:
  explicit Connection(std::string path) : path_(std::move(path)) {}

 private:
  std::string path_;
};

}  // namespace feedplan::model_db::detail
