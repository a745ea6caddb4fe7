#include "json_fields.hpp"

#include <cmath>

namespace feedplan::model_db::detail {

std::string value_text(const nlohmann::json& value) {
  if (value.is_string()) {
    // Built with append: GCC 12 warns falsely (-Wrestrict) on "'" + std::string when inlined.
    std::string quoted = "'";
    quoted.append(value.get<std::string>()).append("'");
    return quoted;
  }
  std::string text = value.dump();
  constexpr std::size_t kLongest = 40;
  if (text.size() > kLongest) text = text.substr(0, kLongest) + "…";
  return text;
}

const nlohmann::json* JsonFields::member(const nlohmann::json& object, const std::string& path, const char* key,
                                         bool required) {
  if (object.is_object()) {
    const auto found = object.find(key);
    if (found != object.end()) return &*found;
  }
  if (required) add(path + "." + key, object.is_object() ? "is missing" : "is missing (" + path + " is not an object)");
  return nullptr;
}

double JsonFields::number(const nlohmann::json& object, const std::string& path, const char* key) {
  const nlohmann::json* value = member(object, path, key);
  if (value == nullptr) return 0.0;
  if (!value->is_number() || !std::isfinite(value->get<double>())) {
    add(path + "." + key, "= " + value_text(*value) + ": must be a finite number");
    return 0.0;
  }
  return value->get<double>();
}

int JsonFields::integer(const nlohmann::json& object, const std::string& path, const char* key) {
  const nlohmann::json* value = member(object, path, key);
  if (value == nullptr) return 0;
  if (!value->is_number_integer()) {
    add(path + "." + key, "= " + value_text(*value) + ": must be an integer");
    return 0;
  }
  return value->get<int>();
}

std::optional<int> JsonFields::optional_integer(const nlohmann::json& object, const std::string& path,
                                                const char* key) {
  const nlohmann::json* value = member(object, path, key, false);
  if (value == nullptr || value->is_null()) return std::nullopt;
  return integer(object, path, key);
}

bool JsonFields::boolean(const nlohmann::json& object, const std::string& path, const char* key) {
  const nlohmann::json* value = member(object, path, key);
  if (value == nullptr) return false;
  if (!value->is_boolean()) {
    add(path + "." + key, "= " + value_text(*value) + ": must be true or false");
    return false;
  }
  return value->get<bool>();
}

std::string JsonFields::text(const nlohmann::json& object, const std::string& path, const char* key, bool required) {
  const nlohmann::json* value = member(object, path, key, required);
  if (value == nullptr) return {};
  if (!value->is_string()) {
    add(path + "." + key, "= " + value_text(*value) + ": must be a string");
    return {};
  }
  return value->get<std::string>();
}

std::vector<double> JsonFields::numbers(const nlohmann::json& object, const std::string& path, const char* key) {
  std::vector<double> values;
  const nlohmann::json& list = array(object, path, key);
  for (std::size_t i = 0; i < list.size(); ++i) {
    const nlohmann::json& value = list[i];
    if (!value.is_number() || !std::isfinite(value.get<double>())) {
      add(path + "." + key + "[" + std::to_string(i) + "]", "= " + value_text(value) + ": must be a finite number");
      values.push_back(0.0);
    } else {
      values.push_back(value.get<double>());
    }
  }
  return values;
}

std::vector<std::string> JsonFields::texts(const nlohmann::json& object, const std::string& path, const char* key) {
  std::vector<std::string> values;
  const nlohmann::json& list = array(object, path, key, false);
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (!list[i].is_string()) {
      add(path + "." + key + "[" + std::to_string(i) + "]", "= " + value_text(list[i]) + ": must be a string");
    } else {
      values.push_back(list[i].get<std::string>());
    }
  }
  return values;
}

const nlohmann::json& JsonFields::array(const nlohmann::json& object, const std::string& path, const char* key,
                                        bool required) {
  static const nlohmann::json kEmpty = nlohmann::json::array();
  const nlohmann::json* value = member(object, path, key, required);
  if (value == nullptr) return kEmpty;
  if (!value->is_array()) {
    add(path + "." + key, "= " + value_text(*value) + ": must be an array");
    return kEmpty;
  }
  return *value;
}

}  // namespace feedplan::model_db::detail
