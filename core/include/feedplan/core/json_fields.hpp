#pragma once
// The one JSON field reader: the members of a parsed JSON document (nlohmann) read into plain values,
// every problem collected with the member's path and the value found ("models[3].model.beta[2] = null:
// must be a finite number", "blocks[1].feed_mm_per_min is missing") instead of stopping at the first.
// A member that is missing or of the wrong type reads as a neutral value (0, "", empty) and adds a
// problem, so that one pass reports everything. Shared by the formats read as JSON (the model
// database's exchange file, the plan report).
//
// A JsonNode is a place in the document (an object or an array) carrying its path; its accessors read
// its members. The two formats phrase a few problems differently, and tests pin both texts, so each
// format chooses its JsonFieldRules once (see there): how a string value is shown, what a missing or
// mistyped object reports, where a wrong array length is reported, and what a bad list element reads as.
//
// Templates over the document type: nlohmann::json (keys sorted) or nlohmann::ordered_json (keys in
// document order). An object value shown in a problem is dumped in that type's key order.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"

namespace feedplan {

//! How a problem shows a string value found.
enum class JsonTextShown {
  kSingleQuoted,  //!< as written between single quotes, never shortened: = '482' (model exchange)
  kAsJson,        //!< as JSON text, shortened like any value: = "482" (plan report)
};

//! What reading from an object that is missing, or is not an object, reports.
enum class JsonObjectRule {
  //! Nothing for the object itself; each member read from it is missing: "tools[0].name is missing
  //! (tools[0] is not an object)", and "model.beta is missing" after "model is missing" (model exchange).
  kEachMemberMissing,
  //! The object once, "machine is missing" or "blocks[0] = 5: must be an object"; its members are
  //! then read silently as neutral values (plan report).
  kReportedOnce,
};

//! How an array of exactly N numbers with another length is reported.
enum class JsonLengthRule {
  //! Every element checked, then "beta has 3 numbers: must have 6", also after "must be an array"
  //! (model exchange).
  kCountNumbersLast,
  //! "beta has 3 elements: must have 6" first, for an array only; then the first N elements checked
  //! (plan report).
  kCountElementsFirst,
};

//! What an element of a list of numbers that is not a finite number reads as (after its problem).
enum class JsonBadElement {
  kReadAsZero,  //!< 0, so that later elements keep their index for later checks (model exchange)
  kLeftOut,     //!< nothing: the list is shorter (plan report)
};

//! Whether a member must be there.
enum class JsonPresence {
  kRequired,  //!< missing: a problem "<path> is missing"
  kOptional,  //!< missing: the neutral value, no problem
};

//! The phrasing rules of one JSON format (see the enums). The defaults are the plan report's.
struct JsonFieldRules {
  JsonTextShown text_values = JsonTextShown::kAsJson;          //!< how a string value found is shown
  JsonObjectRule objects = JsonObjectRule::kReportedOnce;       //!< missing or mistyped objects
  JsonLengthRule lengths = JsonLengthRule::kCountElementsFirst;  //!< arrays of N numbers
  JsonBadElement bad_list_elements = JsonBadElement::kLeftOut;  //!< bad elements of number lists
};

//! A short text of a JSON value for messages: numbers, literals, arrays and objects as JSON text cut
//! after 40 bytes ("…"); strings as `shown` says.
template <typename Json>
std::string json_value_text(const Json& value, JsonTextShown shown) {
  if (shown == JsonTextShown::kSingleQuoted && value.is_string()) {
    // Built with append: GCC 12 warns falsely (-Wrestrict) on "'" + std::string when inlined.
    std::string quoted = "'";
    quoted.append(value.template get<std::string>()).append("'");
    return quoted;
  }
  constexpr std::size_t kLongest = 40;
  std::string text = value.dump();
  if (text.size() > kLongest) text = text.substr(0, kLongest) + "…";
  return text;
}

template <typename Json>
class JsonNode;

//! Reads one document: holds the format's rules and the problems found. `Json` is nlohmann::json or
//! nlohmann::ordered_json.
template <typename Json>
class JsonFieldReader {
 public:
  std::vector<InputProblem> problems;  //!< problems in the order found

  explicit JsonFieldReader(JsonFieldRules rules = {}) : rules_(rules) {}

  //! The node of `value` (the document or a part of it) named `path` in problems ("" at the top: its
  //! members are named by their keys alone). `value` must outlive the node.
  JsonNode<Json> node(const Json& value, std::string path) { return JsonNode<Json>(&value, std::move(path), this); }

  //! Adds a problem.
  void add(std::string field, std::string message) { problems.push_back({std::move(field), std::move(message)}); }

  //! Throws InputError with every problem found so far, if there is any.
  void throw_if_any() {
    if (!problems.empty()) throw InputError(std::move(problems));
  }

  //! The format's rules.
  const JsonFieldRules& rules() const { return rules_; }

 private:
  JsonFieldRules rules_;
};

//! A place in the document: an object or an array, or absent (missing, or not what it must be). Every
//! accessor reads a member of this object, adds a problem naming the member's path and the value found
//! when it is missing or of the wrong type, and then returns a neutral value.
template <typename Json>
class JsonNode {
 public:
  JsonNode(const Json* value, std::string path, JsonFieldReader<Json>* reader)
      : value_(value), path_(std::move(path)), reader_(reader) {}

  //! The path of this node ("" for the top of a document named so).
  const std::string& path() const { return path_; }

  //! The path of member `key`: "path.key", or `key` at the top.
  std::string child_path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

  //! Adds a problem, e.g. one the caller found in values read from this node.
  void report(std::string field, std::string message) const { reader_->add(std::move(field), std::move(message)); }

  //! The value shown in a problem, as the format's rules say.
  std::string shown(const Json& value) const { return json_value_text(value, reader_->rules().text_values); }

  //! True when member `key` is there (its absence is not a problem).
  bool has(const std::string& key) const {
    return value_ != nullptr && value_->is_object() && value_->find(key) != value_->end();
  }

  //! The member `key`, or nullptr: when it is required, a problem "<path.key> is missing" (see
  //! JsonObjectRule for the members of an absent node or of a value that is not an object).
  const Json* member(const std::string& key, JsonPresence presence = JsonPresence::kRequired) const {
    if (value_ != nullptr && value_->is_object()) {
      const auto found = value_->find(key);
      if (found != value_->end()) return &*found;
    } else if (value_ == nullptr && rules().objects == JsonObjectRule::kReportedOnce) {
      return nullptr;  // this node was reported already
    }
    if (presence == JsonPresence::kRequired) {
      const bool not_an_object = value_ != nullptr && !value_->is_object();
      report(child_path(key), not_an_object ? "is missing (" + path_ + " is not an object)" : "is missing");
    }
    return nullptr;
  }

  //! The member `key` as an object node (JsonObjectRule says what a missing or mistyped one reports).
  JsonNode object(const std::string& key) const {
    const Json* value = member(key);
    if (value != nullptr && !value->is_object() && rules().objects == JsonObjectRule::kReportedOnce) {
      report(child_path(key), "= " + shown(*value) + ": must be an object");
      value = nullptr;
    }
    return JsonNode(value, child_path(key), reader_);
  }

  //! The member `key` as an array node; missing (when required) or not an array: a problem and an
  //! absent node of no elements.
  JsonNode array(const std::string& key, JsonPresence presence = JsonPresence::kRequired) const {
    const Json* value = member(key, presence);
    if (value != nullptr && !value->is_array()) {
      report(child_path(key), "= " + shown(*value) + ": must be an array");
      value = nullptr;
    }
    return JsonNode(value, child_path(key), reader_);
  }

  //! Elements of this array node (0 when it is absent).
  std::size_t size() const { return value_ != nullptr ? value_->size() : 0; }

  //! Element `index` of this array node as an object node, named "<path>[index]".
  JsonNode item(std::size_t index) const { return item(index, index_path(index)); }

  //! Element `index` of this array node as an object node named `path` (JsonObjectRule says what an
  //! element that is not an object reports).
  JsonNode item(std::size_t index, std::string path) const {
    const Json& value = (*value_)[index];
    if (!value.is_object() && rules().objects == JsonObjectRule::kReportedOnce) {
      report(path, "= " + shown(value) + ": must be an object");
      return JsonNode(nullptr, std::move(path), reader_);
    }
    return JsonNode(&value, std::move(path), reader_);
  }

  //! A finite number (0 when it is not).
  double number(const std::string& key) const {
    const Json* value = member(key);
    if (value == nullptr) return 0.0;
    if (is_finite_number(*value)) return value->template get<double>();
    report(child_path(key), "= " + shown(*value) + ": must be a finite number");
    return 0.0;
  }

  //! A finite number ≥ `min`.
  double number_at_least(const std::string& key, double min) const {
    const double value = number(key);
    if (value < min) {
      report(child_path(key), "= " + shortest_number_text(value) + ": must be ≥ " + shortest_number_text(min));
    }
    return value;
  }

  //! A number, or null for a number the writer could not express (NaN; also when it is missing).
  double number_or_null(const std::string& key) const {
    const Json* value = member(key);
    if (value == nullptr || value->is_null()) return std::numeric_limits<double>::quiet_NaN();
    if (value->is_number()) return value->template get<double>();
    report(child_path(key), "= " + shown(*value) + ": must be a number or null");
    return std::numeric_limits<double>::quiet_NaN();
  }

  //! An integer (0 when it is not), as an int; one beyond an int's range is a problem too.
  int integer(const std::string& key) const {
    const Json* value = member(key);
    if (value == nullptr) return 0;
    if (!value->is_number_integer()) {
      report(child_path(key), "= " + shown(*value) + ": must be an integer");
      return 0;
    }
    constexpr auto kMax = static_cast<std::uint64_t>(std::numeric_limits<int>::max());
    const bool fits = value->is_number_unsigned() ? value->template get<std::uint64_t>() <= kMax
                                                  : value->template get<std::int64_t>() >= std::numeric_limits<int>::min() &&
                                                        value->template get<std::int64_t>() <= std::numeric_limits<int>::max();
    if (fits) return static_cast<int>(value->template get<std::int64_t>());
    report(child_path(key), "= " + shown(*value) + ": must be an integer in [" +
                                std::to_string(std::numeric_limits<int>::min()) + ", " +
                                std::to_string(std::numeric_limits<int>::max()) + "]");
    return 0;
  }

  //! An integer in [min, max] (`min` when it is not).
  std::int64_t integer_in(const std::string& key, std::int64_t min, std::int64_t max) const {
    const Json* value = member(key);
    if (value == nullptr) return min;
    if (value->is_number_unsigned()) {
      const auto n = value->template get<std::uint64_t>();
      if (n <= static_cast<std::uint64_t>(max) && static_cast<std::int64_t>(n) >= min) return static_cast<std::int64_t>(n);
    } else if (value->is_number_integer()) {
      const auto n = value->template get<std::int64_t>();
      if (n >= min && n <= max) return n;
    }
    report(child_path(key), "= " + shown(*value) + ": must be an integer in [" + std::to_string(min) + ", " +
                                std::to_string(max) + "]");
    return min;
  }

  //! An int ≥ `min`.
  int count(const std::string& key, int min = 0) const {
    return static_cast<int>(integer_in(key, min, std::numeric_limits<int>::max()));
  }

  //! An integer, or nothing when it is null or missing.
  std::optional<int> optional_integer(const std::string& key) const {
    const Json* value = member(key, JsonPresence::kOptional);
    if (value == nullptr || value->is_null()) return std::nullopt;
    return integer(key);
  }

  //! true or false (false when it is neither).
  bool boolean(const std::string& key) const {
    const Json* value = member(key);
    if (value == nullptr) return false;
    if (value->is_boolean()) return value->template get<bool>();
    report(child_path(key), "= " + shown(*value) + ": must be true or false");
    return false;
  }

  //! A string; nothing when it is missing or not a string.
  std::optional<std::string> text_if_valid(const std::string& key,
                                           JsonPresence presence = JsonPresence::kRequired) const {
    const Json* value = member(key, presence);
    if (value == nullptr) return std::nullopt;
    if (value->is_string()) return value->template get<std::string>();
    report(child_path(key), "= " + shown(*value) + ": must be a string");
    return std::nullopt;
  }

  //! A string ("" when it is missing or not a string).
  std::string text(const std::string& key, JsonPresence presence = JsonPresence::kRequired) const {
    return text_if_valid(key, presence).value_or("");
  }

  //! An array of strings (an element that is not a string is left out).
  std::vector<std::string> texts(const std::string& key, JsonPresence presence = JsonPresence::kRequired) const {
    const JsonNode list = array(key, presence);
    std::vector<std::string> values;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Json& value = (*list.value_)[i];
      if (value.is_string()) {
        values.push_back(value.template get<std::string>());
      } else {
        report(list.index_path(i), "= " + shown(value) + ": must be a string");
      }
    }
    return values;
  }

  //! An array of finite numbers (JsonBadElement says what a bad element reads as).
  std::vector<double> numbers(const std::string& key, JsonPresence presence = JsonPresence::kRequired) const {
    const JsonNode list = array(key, presence);
    std::vector<double> values;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::optional<double> value = list.finite_element(i);
      if (value) {
        values.push_back(*value);
      } else if (rules().bad_list_elements == JsonBadElement::kReadAsZero) {
        values.push_back(0.0);
      }
    }
    return values;
  }

  //! An array of exactly N finite numbers (JsonLengthRule says how another length is reported); a
  //! bad or missing element reads as 0.
  template <std::size_t N>
  std::array<double, N> fixed_numbers(const std::string& key) const {
    std::array<double, N> values{};
    const JsonNode list = array(key);
    const bool count_first = rules().lengths == JsonLengthRule::kCountElementsFirst;
    if (count_first && list.value_ != nullptr && list.size() != N) {
      report(list.path_, "has " + std::to_string(list.size()) + " elements: must have " + std::to_string(N));
    }
    const std::size_t checked = count_first ? std::min(N, list.size()) : list.size();
    for (std::size_t i = 0; i < checked; ++i) {
      const std::optional<double> value = list.finite_element(i);
      if (value && i < N) values[i] = *value;
    }
    if (!count_first && list.size() != N && member(key, JsonPresence::kOptional) != nullptr) {
      report(list.path_, "has " + std::to_string(list.size()) + " numbers: must have " + std::to_string(N));
    }
    return values;
  }

  //! An array of arrays of exactly N finite numbers each (a bad row reads as zeros).
  template <std::size_t N>
  std::vector<std::array<double, N>> number_rows(const std::string& key) const {
    const JsonNode list = array(key);
    std::vector<std::array<double, N>> rows;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Json& row = (*list.value_)[i];
      const JsonNode row_node(&row, list.index_path(i), reader_);
      std::array<double, N> values{};
      if (!row.is_array() || row.size() != N) {
        report(row_node.path_, "= " + shown(row) + ": must be an array of " + std::to_string(N) + " numbers");
      } else {
        for (std::size_t j = 0; j < N; ++j) values[j] = row_node.finite_element(j).value_or(0.0);
      }
      rows.push_back(values);
    }
    return rows;
  }

 private:
  const JsonFieldRules& rules() const { return reader_->rules(); }

  std::string index_path(std::size_t index) const { return path_ + "[" + std::to_string(index) + "]"; }

  static bool is_finite_number(const Json& value) {
    return value.is_number() && std::isfinite(value.template get<double>());
  }

  // Element `index` of this array node when it is a finite number; otherwise a problem and nothing.
  std::optional<double> finite_element(std::size_t index) const {
    const Json& value = (*value_)[index];
    if (is_finite_number(value)) return value.template get<double>();
    report(index_path(index), "= " + shown(value) + ": must be a finite number");
    return std::nullopt;
  }

  const Json* value_;
  std::string path_;
  JsonFieldReader<Json>* reader_;
};

}  // namespace feedplan
