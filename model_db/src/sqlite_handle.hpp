#pragma once
// Internal: a thin RAII layer over the SQLite C API — one connection, prepared statements with
// sequential binding, and the mapping of SQLite result codes to the project's errors. A file that
// is not a database or is damaged is the user's problem (InputError naming the path); anything else
// SQLite reports (I/O, disk full, busy past the timeout) is a std::runtime_error.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

struct sqlite3;
struct sqlite3_stmt;

namespace feedplan::model_db::detail {

//! One open SQLite connection; closes it when destroyed.
class Connection {
 public:
  //! Opens `path` with the sqlite3_open_v2 `flags`. Throws like check().
  Connection(const std::string& path, int flags);
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;
  ~Connection();

  //! Runs one or more statements that return no rows needed. Throws like check().
  void exec(const std::string& sql);

  //! Throws for a result code other than SQLITE_OK / SQLITE_ROW / SQLITE_DONE: InputError naming the
  //! path for SQLITE_NOTADB and SQLITE_CORRUPT, std::runtime_error otherwise; `what` says what was
  //! being done.
  void check(int result_code, std::string_view what) const;

  //! The rowid of the last INSERT.
  std::int64_t last_insert_rowid() const;

  //! The file name, for messages.
  const std::string& path() const { return path_; }

  sqlite3* get() const { return db_; }

 private:
  sqlite3* db_ = nullptr;
  std::string path_;
};

//! A prepared statement. bind() takes values in parameter order (1, 2, …); step() runs it.
class Statement {
 public:
  Statement(const Connection& connection, std::string_view sql);
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  ~Statement();

  //! Binds the next parameter.
  Statement& bind(double value);
  Statement& bind(std::int64_t value);
  Statement& bind(int value);
  Statement& bind(bool value);
  Statement& bind(std::string_view value);
  Statement& bind(const std::string& value) { return bind(std::string_view(value)); }
  Statement& bind(const char* value) { return bind(std::string_view(value)); }
  Statement& bind(std::optional<std::int64_t> value);
  Statement& bind_null();

  //! Binds each argument in turn.
  template <typename... Args>
  Statement& bind_all(const Args&... args) {
    (bind(args), ...);
    return *this;
  }

  //! Steps once: true when a row is available, false when the statement is done.
  bool step();

  //! Steps to completion, expecting no rows.
  void run();

  //! Resets the statement and its bindings for another run.
  void reset();

  //! The value of result column `index`. A stored value of another kind — text or a blob where a
  //! number belongs, a fraction or a number beyond int where a whole number belongs, text that is not
  //! UTF-8 — is an InputError naming the file, table, column and row ("models.db table tools, column
  //! diameter_mm, row id 3 = 'ten': must be a number; …"): only a change behind the store's back puts
  //! it there (SQLite's column types do not refuse it), and reading it as 0 would plan with nonsense.
  //! NULL reads as 0 or "" (aggregates over no rows; the schema keeps NULL out of stored columns).
  double column_double(int index) const;
  std::int64_t column_int64(int index) const;
  int column_int(int index) const;
  std::string column_text(int index) const;
  bool column_is_null(int index) const;
  std::optional<std::int64_t> column_optional_int64(int index) const;

 private:
  // Throws the InputError of a stored value that is not what column `index` holds (see column_double).
  [[noreturn]] void refuse_value(int index, const std::string& shown, const std::string& expected) const;
  // "table T, column C, row id N" for result column `index`, as far as the statement knows it.
  std::string value_place(int index) const;

  const Connection& connection_;
  sqlite3_stmt* statement_ = nullptr;
  int next_parameter_ = 1;
  std::string sql_;
};

//! BEGIN IMMEDIATE on construction (takes the write lock at once, so the checks made inside see what
//! the writes will change); ROLLBACK on destruction unless commit() was called.
class WriteTransaction {
 public:
  explicit WriteTransaction(Connection& connection);
  WriteTransaction(const WriteTransaction&) = delete;
  WriteTransaction& operator=(const WriteTransaction&) = delete;
  ~WriteTransaction();

  //! Commits. On failure throws and the destructor rolls back.
  void commit();

 private:
  Connection& connection_;
  bool open_ = false;
};

}  // namespace feedplan::model_db::detail
