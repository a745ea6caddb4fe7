#include "sqlite_handle.hpp"

#include <sqlite3.h>

#include <stdexcept>

#include "feedplan/core/input_error.hpp"

namespace feedplan::model_db::detail {

Connection::Connection(const std::string& path, int flags) : path_(path) {
  const int rc = sqlite3_open_v2(path.c_str(), &db_, flags, nullptr);
  if (rc != SQLITE_OK) {
    // sqlite3_open_v2 hands back a handle even on failure (for the message); close it after use.
    const std::string message = db_ != nullptr ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
    sqlite3_close(db_);
    db_ = nullptr;
    throw InputError(path, "cannot be opened as a model database: " + message);
  }
  sqlite3_extended_result_codes(db_, 1);
}

Connection::~Connection() { sqlite3_close(db_); }

void Connection::exec(const std::string& sql) {
  check(sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, nullptr), sql);
}

void Connection::check(int result_code, std::string_view what) const {
  const int primary = result_code & 0xff;
  if (primary == SQLITE_OK || primary == SQLITE_ROW || primary == SQLITE_DONE) return;
  const std::string message = sqlite3_errmsg(db_);
  if (primary == SQLITE_NOTADB || primary == SQLITE_CORRUPT) {
    throw InputError(path_, "is not a usable model database: " + message + " (a damaged file or not a database at all)");
  }
  if (primary == SQLITE_BUSY) {
    throw std::runtime_error("model database " + path_ + " is busy: another process kept it locked past the busy timeout (" +
                             std::string(what) + ")");
  }
  throw std::runtime_error("model database " + path_ + ": " + message + " (" + std::string(what) + ")");
}

std::int64_t Connection::last_insert_rowid() const { return sqlite3_last_insert_rowid(db_); }

Statement::Statement(const Connection& connection, std::string_view sql) : connection_(connection), sql_(sql) {
  connection_.check(sqlite3_prepare_v2(connection_.get(), sql_.data(), static_cast<int>(sql_.size()), &statement_, nullptr),
                    sql_);
}

Statement::~Statement() { sqlite3_finalize(statement_); }

Statement& Statement::bind(double value) {
  connection_.check(sqlite3_bind_double(statement_, next_parameter_++, value), sql_);
  return *this;
}

Statement& Statement::bind(std::int64_t value) {
  connection_.check(sqlite3_bind_int64(statement_, next_parameter_++, value), sql_);
  return *this;
}

Statement& Statement::bind(int value) { return bind(static_cast<std::int64_t>(value)); }

Statement& Statement::bind(bool value) { return bind(static_cast<std::int64_t>(value ? 1 : 0)); }

Statement& Statement::bind(std::string_view value) {
  connection_.check(sqlite3_bind_text(statement_, next_parameter_++, value.data(), static_cast<int>(value.size()),
                                      SQLITE_TRANSIENT),
                    sql_);
  return *this;
}

Statement& Statement::bind(std::optional<std::int64_t> value) { return value ? bind(*value) : bind_null(); }

Statement& Statement::bind_null() {
  connection_.check(sqlite3_bind_null(statement_, next_parameter_++), sql_);
  return *this;
}

bool Statement::step() {
  const int rc = sqlite3_step(statement_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  connection_.check(rc, sql_);
  return false;
}

void Statement::run() {
  while (step()) {
  }
}

void Statement::reset() {
  sqlite3_reset(statement_);
  sqlite3_clear_bindings(statement_);
  next_parameter_ = 1;
}

double Statement::column_double(int index) const { return sqlite3_column_double(statement_, index); }

std::int64_t Statement::column_int64(int index) const { return sqlite3_column_int64(statement_, index); }

int Statement::column_int(int index) const { return sqlite3_column_int(statement_, index); }

std::string Statement::column_text(int index) const {
  const auto* text = sqlite3_column_text(statement_, index);
  if (text == nullptr) return {};
  return std::string(reinterpret_cast<const char*>(text), static_cast<std::size_t>(sqlite3_column_bytes(statement_, index)));
}

bool Statement::column_is_null(int index) const { return sqlite3_column_type(statement_, index) == SQLITE_NULL; }

std::optional<std::int64_t> Statement::column_optional_int64(int index) const {
  if (column_is_null(index)) return std::nullopt;
  return column_int64(index);
}

WriteTransaction::WriteTransaction(Connection& connection) : connection_(connection) {
  connection_.exec("BEGIN IMMEDIATE");
  open_ = true;
}

WriteTransaction::~WriteTransaction() {
  // Unwinding from an error or exception: undo everything. A failing ROLLBACK (the connection is
  // gone) leaves SQLite to roll back the hot journal on the next open.
  if (open_) sqlite3_exec(connection_.get(), "ROLLBACK", nullptr, nullptr, nullptr);
}

void WriteTransaction::commit() {
  connection_.exec("COMMIT");
  open_ = false;
}

}  // namespace feedplan::model_db::detail
