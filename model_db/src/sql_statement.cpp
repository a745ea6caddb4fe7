#include "sql_statement.hpp"

namespace feedplan::model_db::detail {

Statement& Statement::bind(double value) {
  backend_->bind_double(next_parameter_++, value);
  return *this;
}

Statement& Statement::bind(std::int64_t value) {
  backend_->bind_int64(next_parameter_++, value);
  return *this;
}

Statement& Statement::bind(std::string_view value) {
  backend_->bind_text(next_parameter_++, value);
  return *this;
}

Statement& Statement::bind_null() {
  backend_->bind_null(next_parameter_++);
  return *this;
}

void Statement::run() {
  while (step()) {
  }
}

void Statement::reset() {
  backend_->reset();
  next_parameter_ = 1;
}

std::optional<std::int64_t> Statement::column_optional_int64(int index) const {
  if (column_is_null(index)) return std::nullopt;
  return column_int64(index);
}

}  // namespace feedplan::model_db::detail
