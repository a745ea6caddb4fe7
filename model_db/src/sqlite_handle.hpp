#pragma once
// Internal: a model database in a SQLite file — the connection and its prepared statements over the
// SQLite C API, and the mapping of SQLite result codes to the project's errors. A file that is not a
// database or is damaged is the user's problem (InputError naming the path); anything else SQLite reports
// (I/O, disk full, busy past the timeout) is a std::runtime_error.

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "sql_statement.hpp"
#include "write_transaction.hpp"

struct sqlite3;
struct sqlite3_stmt;

namespace feedplan::model_db::detail {

//! One open SQLite connection; closes it when destroyed.
class SqliteConnection final : public Connection {
 public:
  //! Opens `path` with the sqlite3_open_v2 `flags`. Throws like check().
  SqliteConnection(const std::string& path, int flags);
  ~SqliteConnection() override;

  Engine engine() const override { return Engine::kSqlite; }
  void exec(const std::string& sql) override;
  std::unique_ptr<StatementBackend> prepare(std::string_view sql) const override;
  std::int64_t last_insert_rowid() const override;
  //! BEGIN IMMEDIATE: takes the write lock at once.
  void begin_write() override;
  void commit() override;
  //! A failing ROLLBACK (the connection is gone) leaves SQLite to roll back the hot journal on the next open.
  void rollback() noexcept override;

  //! Throws for a result code other than SQLITE_OK / SQLITE_ROW / SQLITE_DONE: InputError naming the
  //! path for SQLITE_NOTADB and SQLITE_CORRUPT, std::runtime_error otherwise; `what` says what was
  //! being done.
  void check(int result_code, std::string_view what) const;

  sqlite3* get() const { return db_; }

 private:
  sqlite3* db_ = nullptr;
};

//! A prepared SQLite statement.
class SqliteStatement final : public StatementBackend {
 public:
  SqliteStatement(const SqliteConnection& connection, std::string_view sql);
  ~SqliteStatement() override;

  void bind_double(int parameter, double value) override;
  void bind_int64(int parameter, std::int64_t value) override;
  void bind_text(int parameter, std::string_view value) override;
  void bind_null(int parameter) override;
  bool step() override;
  void reset() override;

  //! A stored value of another kind is an InputError naming the file, table, column and row ("models.db
  //! table tools, column diameter_mm, row id 3 = 'ten': must be a number; …"): SQLite's column types do
  //! not refuse it.
  double column_double(int index) const override;
  std::int64_t column_int64(int index) const override;
  int column_int(int index) const override;
  std::string column_text(int index) const override;
  bool column_is_null(int index) const override;

 private:
  // Throws the InputError of a stored value that is not what column `index` holds (see column_double).
  [[noreturn]] void refuse_value(int index, const std::string& shown, const std::string& expected) const;
  // "table T, column C, row id N" for result column `index`, as far as the statement knows it.
  std::string value_place(int index) const;

  const SqliteConnection& connection_;
  sqlite3_stmt* statement_ = nullptr;
  std::string sql_;
};

}  // namespace feedplan::model_db::detail
