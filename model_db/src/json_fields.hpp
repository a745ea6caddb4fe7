#pragma once
// Internal: reading typed fields out of a parsed JSON document while collecting every problem with its
// place in the document ("models[3].model.beta[2] = null: must be a finite number") instead of stopping
// at the first. A missing or ill-typed field yields a default value and a problem.

#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "feedplan/core/input_error.hpp"

namespace feedplan::model_db::detail {

class JsonFields {
 public:
  explicit JsonFields(std::vector<InputProblem>& problems) : problems_(problems) {}

  //! The member `key` of `object`, or nullptr (and, when `required`, a problem "<path>.<key> is missing").
  const nlohmann::json* member(const nlohmann::json& object, const std::string& path, const char* key,
                               bool required = true);

  //! A finite number.
  double number(const nlohmann::json& object, const std::string& path, const char* key);
  //! An integer.
  int integer(const nlohmann::json& object, const std::string& path, const char* key);
  //! An integer or null (nothing).
  std::optional<int> optional_integer(const nlohmann::json& object, const std::string& path, const char* key);
  //! A boolean.
  bool boolean(const nlohmann::json& object, const std::string& path, const char* key);
  //! A string; when not `required` a missing member is "".
  std::string text(const nlohmann::json& object, const std::string& path, const char* key, bool required = true);
  //! An array of finite numbers.
  std::vector<double> numbers(const nlohmann::json& object, const std::string& path, const char* key);
  //! An array of exactly N finite numbers.
  template <std::size_t N>
  std::array<double, N> fixed_numbers(const nlohmann::json& object, const std::string& path, const char* key) {
    std::array<double, N> values{};
    const std::vector<double> list = numbers(object, path, key);
    if (list.size() != N && member(object, path, key, false) != nullptr) {
      add(path + "." + key, "has " + std::to_string(list.size()) + " numbers: must have " + std::to_string(N));
    }
    for (std::size_t i = 0; i < N && i < list.size(); ++i) values[i] = list[i];
    return values;
  }
  //! An array of strings (missing: empty).
  std::vector<std::string> texts(const nlohmann::json& object, const std::string& path, const char* key);
  //! The array member `key` (missing or not an array: a problem and an empty array).
  const nlohmann::json& array(const nlohmann::json& object, const std::string& path, const char* key,
                              bool required = true);

  //! Adds a problem.
  void add(std::string field, std::string message) { problems_.push_back({std::move(field), std::move(message)}); }

 private:
  std::vector<InputProblem>& problems_;
};

//! A short text of a JSON value for messages: numbers and literals as written, strings quoted.
std::string value_text(const nlohmann::json& value);

}  // namespace feedplan::model_db::detail
