#pragma once
// Internal: a statement of the row code run on a PostgreSQL server. The `?` / `?N` parameters become
// `$n`; the values are sent as text (numbers in their shortest exact form) and the server's column types
// convert them; the rows come back as text and are parsed here.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pg_connection.hpp"

namespace feedplan::model_db::detail {

//! `sql` with `?N` written as `$N` and each bare `?` as the next `$n`; text in quotes is left alone.
std::string dollar_parameters(std::string_view sql);

//! A statement on a PostgreSQL connection: runs on the first step() with the values bound so far.
class PgStatement final : public StatementBackend {
 public:
  PgStatement(const PgConnection& connection, std::string_view sql);

  void bind_double(int parameter, double value) override;
  void bind_int64(int parameter, std::int64_t value) override;
  void bind_text(int parameter, std::string_view value) override;
  void bind_null(int parameter) override;
  bool step() override;
  void reset() override;

  double column_double(int index) const override;
  std::int64_t column_int64(int index) const override;
  int column_int(int index) const override;
  std::string column_text(int index) const override;
  bool column_is_null(int index) const override;

 private:
  void set(int parameter, std::optional<std::string> value);
  [[noreturn]] void refuse_value(int index, const std::string& expected) const;

  const PgConnection& connection_;
  std::string sql_;
  std::vector<std::optional<std::string>> values_;
  PgResult result_;
  int row_ = -1;
};

}  // namespace feedplan::model_db::detail
