#pragma once
// Internal: a prepared statement of either engine, with sequential binding — the row code's one way to
// run SQL with parameters and read rows.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "sql_connection.hpp"

namespace feedplan::model_db::detail {

//! A prepared statement. bind() takes values in parameter order (1, 2, …); step() runs it.
class Statement {
 public:
  Statement(const Connection& connection, std::string_view sql) : backend_(connection.prepare(sql)) {}
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  //! Binds the next parameter.
  Statement& bind(double value);
  Statement& bind(std::int64_t value);
  Statement& bind(int value) { return bind(static_cast<std::int64_t>(value)); }
  Statement& bind(bool value) { return bind(static_cast<std::int64_t>(value ? 1 : 0)); }
  Statement& bind(std::string_view value);
  Statement& bind(const std::string& value) { return bind(std::string_view(value)); }
  Statement& bind(const char* value) { return bind(std::string_view(value)); }
  Statement& bind(std::optional<std::int64_t> value) { return value ? bind(*value) : bind_null(); }
  Statement& bind_null();

  //! Binds each argument in turn.
  template <typename... Args>
  Statement& bind_all(const Args&... args) {
    (bind(args), ...);
    return *this;
  }

  //! Steps once: true when a row is available, false when the statement is done.
  bool step() { return backend_->step(); }

  //! Steps to completion, expecting no rows.
  void run();

  //! Resets the statement and its bindings for another run.
  void reset();

  //! The value of result column `index`. A stored value of another kind — text where a number belongs,
  //! a fraction or a number beyond int where a whole number belongs, text that is not UTF-8 — is an
  //! InputError naming the database and where the value is: only a change behind the store's back puts it
  //! there, and reading it as 0 would plan with nonsense. NULL reads as 0 or "" (aggregates over no rows;
  //! the schema keeps NULL out of stored columns).
  double column_double(int index) const { return backend_->column_double(index); }
  std::int64_t column_int64(int index) const { return backend_->column_int64(index); }
  int column_int(int index) const { return backend_->column_int(index); }
  std::string column_text(int index) const { return backend_->column_text(index); }
  bool column_is_null(int index) const { return backend_->column_is_null(index); }
  std::optional<std::int64_t> column_optional_int64(int index) const;

 private:
  std::unique_ptr<StatementBackend> backend_;
  int next_parameter_ = 1;
};

}  // namespace feedplan::model_db::detail
