#include "sqlite_handle.hpp"

#include <sqlite3.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string_view>

#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/core/utf8_text.hpp"

namespace feedplan::model_db::detail {

SqliteConnection::SqliteConnection(const std::string& path, int flags) : Connection(path) {
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

SqliteConnection::~SqliteConnection() { sqlite3_close(db_); }

void SqliteConnection::exec(const std::string& sql) {
  check(sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, nullptr), sql);
}

void SqliteConnection::check(int result_code, std::string_view what) const {
  const int primary = result_code & 0xff;
  if (primary == SQLITE_OK || primary == SQLITE_ROW || primary == SQLITE_DONE) return;
  const std::string message = sqlite3_errmsg(db_);
  const std::string& path_ = path();
  if (primary == SQLITE_NOTADB || primary == SQLITE_CORRUPT) {
    throw InputError(path_, "is not a usable model database: " + message + " (a damaged file or not a database at all)");
  }
  if (primary == SQLITE_BUSY) {
    throw std::runtime_error("model database " + path_ + " is busy: another process kept it locked past the busy timeout (" +
                             std::string(what) + ")");
  }
  throw std::runtime_error("model database " + path_ + ": " + message + " (" + std::string(what) + ")");
}

std::int64_t SqliteConnection::last_insert_rowid() const { return sqlite3_last_insert_rowid(db_); }

std::unique_ptr<StatementBackend> SqliteConnection::prepare(std::string_view sql) const {
  return std::make_unique<SqliteStatement>(*this, sql);
}

void SqliteConnection::begin_write() { exec("BEGIN IMMEDIATE"); }

void SqliteConnection::commit() { exec("COMMIT"); }

void SqliteConnection::rollback() noexcept { sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr); }

SqliteStatement::SqliteStatement(const SqliteConnection& connection, std::string_view sql) : connection_(connection), sql_(sql) {
  connection_.check(sqlite3_prepare_v2(connection_.get(), sql_.data(), static_cast<int>(sql_.size()), &statement_, nullptr),
                    sql_);
}

SqliteStatement::~SqliteStatement() { sqlite3_finalize(statement_); }

void SqliteStatement::bind_double(int parameter, double value) {
  connection_.check(sqlite3_bind_double(statement_, parameter, value), sql_);
}

void SqliteStatement::bind_int64(int parameter, std::int64_t value) {
  connection_.check(sqlite3_bind_int64(statement_, parameter, value), sql_);
}

void SqliteStatement::bind_text(int parameter, std::string_view value) {
  connection_.check(sqlite3_bind_text(statement_, parameter, value.data(), static_cast<int>(value.size()),
                                      SQLITE_TRANSIENT),
                    sql_);
}

void SqliteStatement::bind_null(int parameter) { connection_.check(sqlite3_bind_null(statement_, parameter), sql_); }

bool SqliteStatement::step() {
  const int rc = sqlite3_step(statement_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  connection_.check(rc, sql_);
  return false;
}

void SqliteStatement::reset() {
  sqlite3_reset(statement_);
  sqlite3_clear_bindings(statement_);
}

std::string SqliteStatement::value_place(int index) const {
  const char* table = sqlite3_column_table_name(statement_, index);
  const char* column = sqlite3_column_origin_name(statement_, index);
  if (table == nullptr || column == nullptr) return "result column " + std::to_string(index + 1) + " of " + sql_;
  // The row by the key columns the statement selected from the same table: id, *_id, *_index.
  std::string row;
  for (int k = 0; k < sqlite3_column_count(statement_); ++k) {
    const char* key_table = sqlite3_column_table_name(statement_, k);
    const char* key = sqlite3_column_origin_name(statement_, k);
    if (key_table == nullptr || key == nullptr || std::string_view(key_table) != table) continue;
    const std::string_view name(key);
    const bool is_key = name == "id" || name.ends_with("_id") || name.ends_with("_index");
    if (!is_key || sqlite3_column_type(statement_, k) != SQLITE_INTEGER) continue;
    row += (row.empty() ? ", row " : ", ") + std::string(name) + " " +
           std::to_string(sqlite3_column_int64(statement_, k));
  }
  return "table " + std::string(table) + ", column " + column + row;
}

void SqliteStatement::refuse_value(int index, const std::string& shown, const std::string& expected) const {
  throw InputError(connection_.path() + " " + value_place(index),
                   "= " + shown + ": " + expected +
                       "; the file was changed outside feedplan: correct the row or restore the file from a backup");
}

namespace {

// A stored text or blob as a problem shows it: quoted, bytes that are not UTF-8 as '?', shortened.
std::string shown_text(sqlite3_stmt* statement, int index) {
  const auto* bytes = static_cast<const char*>(sqlite3_column_blob(statement, index));
  const std::string_view text(bytes == nullptr ? "" : bytes, static_cast<std::size_t>(sqlite3_column_bytes(statement, index)));
  constexpr std::size_t kLongest = 40;
  const std::string shown = utf8_shown(text.substr(0, kLongest));
  return "'" + shown + (text.size() > kLongest ? "…'" : "'");
}

}  // namespace

double SqliteStatement::column_double(int index) const {
  const int type = sqlite3_column_type(statement_, index);
  if (type == SQLITE_TEXT || type == SQLITE_BLOB) refuse_value(index, shown_text(statement_, index), "must be a number");
  return sqlite3_column_double(statement_, index);
}

std::int64_t SqliteStatement::column_int64(int index) const {
  const int type = sqlite3_column_type(statement_, index);
  if (type == SQLITE_TEXT || type == SQLITE_BLOB) {
    refuse_value(index, shown_text(statement_, index), "must be a whole number");
  }
  if (type == SQLITE_FLOAT) {
    const double value = sqlite3_column_double(statement_, index);
    // 2^63 is exact as a double; the range check keeps the cast defined.
    if (!(value >= -9223372036854775808.0 && value < 9223372036854775808.0) || value != std::floor(value)) {
      refuse_value(index, shortest_number_text(value), "must be a whole number");
    }
    return static_cast<std::int64_t>(value);
  }
  return sqlite3_column_int64(statement_, index);
}

int SqliteStatement::column_int(int index) const {
  const std::int64_t value = column_int64(index);
  if (value < std::numeric_limits<int>::min() || value > std::numeric_limits<int>::max()) {
    refuse_value(index, std::to_string(value),
                 "must be a whole number in [" + std::to_string(std::numeric_limits<int>::min()) + ", " +
                     std::to_string(std::numeric_limits<int>::max()) + "]");
  }
  return static_cast<int>(value);
}

std::string SqliteStatement::column_text(int index) const {
  const auto* text = sqlite3_column_text(statement_, index);
  if (text == nullptr) return {};
  std::string value(reinterpret_cast<const char*>(text), static_cast<std::size_t>(sqlite3_column_bytes(statement_, index)));
  if (const std::string problem = utf8_problem(value); !problem.empty()) {
    refuse_value(index, shown_text(statement_, index), problem);
  }
  return value;
}

bool SqliteStatement::column_is_null(int index) const { return sqlite3_column_type(statement_, index) == SQLITE_NULL; }

}  // namespace feedplan::model_db::detail
