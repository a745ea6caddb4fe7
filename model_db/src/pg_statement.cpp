#include "pg_statement.hpp"

#include <libpq-fe.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <system_error>

#include "feedplan/core/input_error.hpp"
#include "feedplan/core/utf8_text.hpp"

namespace feedplan::model_db::detail {

std::string dollar_parameters(std::string_view sql) {
  std::string out;
  out.reserve(sql.size() + 16);
  int next = 0;
  bool quoted = false;
  for (std::size_t i = 0; i < sql.size(); ++i) {
    const char c = sql[i];
    if (c == '\'') quoted = !quoted;
    if (quoted || c != '?') {
      out += c;
      continue;
    }
    out += '$';
    if (i + 1 < sql.size() && sql[i + 1] >= '0' && sql[i + 1] <= '9') continue;  // ?N keeps its number
    out += std::to_string(++next);
  }
  return out;
}

PgStatement::PgStatement(const PgConnection& connection, std::string_view sql)
    : connection_(connection), sql_(dollar_parameters(sql)) {}

void PgStatement::set(int parameter, std::optional<std::string> value) {
  const auto index = static_cast<std::size_t>(parameter - 1);
  if (values_.size() <= index) values_.resize(index + 1);
  values_[index] = std::move(value);
}

void PgStatement::bind_double(int parameter, double value) {
  if (std::isnan(value)) return set(parameter, "NaN");
  if (std::isinf(value)) return set(parameter, value > 0 ? "Infinity" : "-Infinity");
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;  // shortest text that reads back exactly
  set(parameter, std::string(text, end));
}

void PgStatement::bind_int64(int parameter, std::int64_t value) { set(parameter, std::to_string(value)); }

void PgStatement::bind_text(int parameter, std::string_view value) { set(parameter, std::string(value)); }

void PgStatement::bind_null(int parameter) { set(parameter, std::nullopt); }

bool PgStatement::step() {
  if (!result_) {
    std::vector<const char*> values;
    std::vector<int> lengths;
    for (const auto& value : values_) {
      values.push_back(value ? value->c_str() : nullptr);
      lengths.push_back(value ? static_cast<int>(value->size()) : 0);
    }
    result_ = connection_.run(sql_, static_cast<int>(values.size()), values.data(), lengths.data());
    row_ = -1;
  }
  ++row_;
  return row_ < PQntuples(result_.get());
}

void PgStatement::reset() {
  result_.reset();
  values_.clear();
  row_ = -1;
}

void PgStatement::refuse_value(int index, const std::string& expected) const {
  std::string place = connection_.path();
  place += " result column ";
  place += PQfname(result_.get(), index);
  std::string shown = "'";
  shown += utf8_shown(column_text(index));
  shown += "': ";
  shown += expected;
  shown += "; the database was changed outside feedplan: correct the row or restore it from a backup";
  throw InputError(place, "= " + shown);
}

double PgStatement::column_double(int index) const {
  if (column_is_null(index)) return 0.0;
  const char* text = PQgetvalue(result_.get(), row_, index);
  const char* end = text + PQgetlength(result_.get(), row_, index);
  double value = 0.0;
  const auto parsed = std::from_chars(text, end, value);
  if (parsed.ec != std::errc() || parsed.ptr != end) refuse_value(index, "must be a number");
  return value;
}

std::int64_t PgStatement::column_int64(int index) const {
  if (column_is_null(index)) return 0;
  const char* text = PQgetvalue(result_.get(), row_, index);
  const char* end = text + PQgetlength(result_.get(), row_, index);
  std::int64_t value = 0;
  const auto parsed = std::from_chars(text, end, value);
  if (parsed.ec != std::errc() || parsed.ptr != end) refuse_value(index, "must be a whole number");
  return value;
}

int PgStatement::column_int(int index) const {
  const std::int64_t value = column_int64(index);
  if (value < std::numeric_limits<int>::min() || value > std::numeric_limits<int>::max()) {
    refuse_value(index, "must be a whole number in [" + std::to_string(std::numeric_limits<int>::min()) + ", " +
                            std::to_string(std::numeric_limits<int>::max()) + "]");
  }
  return static_cast<int>(value);
}

std::string PgStatement::column_text(int index) const {
  if (column_is_null(index)) return {};
  return std::string(PQgetvalue(result_.get(), row_, index),
                     static_cast<std::size_t>(PQgetlength(result_.get(), row_, index)));
}

bool PgStatement::column_is_null(int index) const { return PQgetisnull(result_.get(), row_, index) != 0; }

}  // namespace feedplan::model_db::detail
