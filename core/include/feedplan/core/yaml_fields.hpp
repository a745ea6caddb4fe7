#pragma once
// The one YAML field reader: the fields of YAML mappings read into plain values, every problem
// collected with the field path, its line and the value as written. Shared by the modules that
// read YAML (cycles specs, sim materials), so both follow one rule for keys:
//
//   Keys are exact, as YAML's are: "Pitch_mm" is not pitch_mm, and is reported as an unknown field.
//   The hint for an unknown key is the closest known field compared ignoring letter case, so a key
//   that differs only in case is always named ("did you mean pitch_mm?"); among equally close
//   fields, one not given yet is preferred ("kte_n_per_mm2" is one edit from both ktc_n_per_mm2 and
//   kte_n_per_mm, but only the missing one is meant).
//
// Templates over the node type so that core needs no yaml-cpp: they take a YAML::Node and are
// instantiated only in the modules that link yaml-cpp themselves (PRIVATE, see their CMakeLists).
// Read through const nodes only: a non-const operator[] may add the key it looks up.

#include <algorithm>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "feedplan/core/did_you_mean.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/core/utf8_text.hpp"
#include "feedplan/core/yaml_text.hpp"

namespace feedplan {

//! The case rule for hints on unknown YAML keys (see the file comment).
inline constexpr LetterCase kYamlKeyHintCase = LetterCase::kIgnored;

//! A mapping key as text: a scalar key as written, any other key as yaml_value_text() shows it.
//! `YamlNode` is YAML::Node.
template <typename YamlNode>
std::string yaml_key_text(const YamlNode& key) {
  return key.IsScalar() ? key.Scalar() : yaml_value_text(key);
}

//! Decodes a plain scalar as `Number` (double, long long, ...) into `value`. False, leaving `value`
//! as it was, for a list, a mapping, an empty value, a quoted scalar ("2000" is text, not a number)
//! or a scalar yaml-cpp does not read as `Number`. ".nan" and ".inf" are numbers here: range checks
//! report them. `YamlNode` is YAML::Node.
template <typename Number, typename YamlNode>
bool decode_yaml_number(const YamlNode& node, Number& value) {
  if (!node.IsScalar() || node.Tag() == "!") return false;
  try {
    value = node.template as<Number>();  // YAML::convert<Number>::decode, throwing when it fails
    return true;
  } catch (const std::runtime_error&) {    // YAML::BadConversion
    return false;
  }
}

//! How "is missing from ..." names the mapping a required field is missing from.
enum class YamlSectionWording {
  kPath,     //!< by its path: "is missing from materials[0] (line 2)"
  kSection,  //!< as a section: "is missing from the trochoid section (line 4)"
};

//! Reads fields of YAML mappings, collecting problems instead of stopping at the first. A module
//! derives its reader from it and adds what its format needs (points, contours, ranges). Every
//! problem's field is a dotted path ("trochoid.pitch_mm", "materials[0].name") followed by
//! " (line N)" when the line is known. `YamlNode` is YAML::Node.
template <typename YamlNode>
class YamlFieldReader {
 public:
  std::vector<InputProblem> problems;  //!< problems in the order found, fields carrying their line
  std::set<std::string> reported;      //!< fields with a problem (their value is a placeholder)
  std::map<std::string, int> lines;    //!< field path → 1-based line of its key, for fields visited

  explicit YamlFieldReader(YamlSectionWording wording) : wording_(wording) {}

  //! "path.key", or `key` at the top level (empty `path`).
  static std::string child(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

  //! Adds a problem for `field` on `line` (0: unknown).
  void add(const std::string& field, int line, const std::string& message) {
    problems.push_back({with_yaml_line(field, line), message});
    reported.insert(field);
  }

  //! Checks that `node` (the value of `path`) is a mapping with keys from `allowed` only, each given
  //! once, and records the line of every key. Not a mapping: a problem "= <value>: <not_a_mapping>"
  //! and false. Each unknown key: a problem naming the allowed keys and the closest one; each repeated
  //! key: "is given twice (also on line N)"; the mapping is still read.
  bool check_mapping(const YamlNode& node, const std::string& path, const std::vector<std::string>& allowed,
                     const std::string& not_a_mapping) {
    if (!node.IsMap()) {
      type_problem(path, node, not_a_mapping);
      return false;
    }
    std::vector<std::string> unused;
    for (const auto& name : allowed) {
      if (!node[name]) unused.push_back(name);
    }
    std::map<std::string, int> key_lines;  // key → line of its first appearance in this mapping
    for (const auto& item : node) {
      const std::string key = yaml_key_text(item.first);
      const std::string field = child(path, key);
      if (const auto first = key_lines.find(key); first != key_lines.end()) {
        // YAML lookups find the first; the second value would be ignored without a word.
        add(field, yaml_line(item.first),
            "is given twice (also on line " + std::to_string(first->second) + "): give it once");
        continue;
      }
      key_lines[key] = yaml_line(item.first);
      lines[field] = yaml_line(item.first);
      if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
      std::string message = "is not a known field; expected one of " + joined(allowed);
      std::string best = closest_name(key, unused, kYamlKeyHintCase);
      if (best.empty()) best = closest_name(key, allowed, kYamlKeyHintCase);
      if (!best.empty()) message += " (did you mean " + best + "?)";
      add(field, yaml_line(item.first), message);
    }
    return true;
  }

  //! The number at map[key]. Nullopt when it is absent (a problem when `required`) or not a number
  //! (a problem "must be a number — <meaning>").
  std::optional<double> number(const YamlNode& map, const std::string& path, const std::string& key, bool required,
                               const std::string& meaning) {
    const YamlNode node = map[key];
    if (!node) {
      if (required) missing(map, path, key, meaning);
      return std::nullopt;
    }
    double value = 0;
    if (!decode_yaml_number(node, value)) {
      type_problem(child(path, key), node, "must be a number — " + meaning);
      return std::nullopt;
    }
    return value;
  }

  //! The integer at map[key]. Nullopt when it is absent (a problem when `required`) or not an int
  //! (a problem "must be an integer — <meaning>").
  std::optional<int> integer(const YamlNode& map, const std::string& path, const std::string& key, bool required,
                             const std::string& meaning) {
    const YamlNode node = map[key];
    if (!node) {
      if (required) missing(map, path, key, meaning);
      return std::nullopt;
    }
    long long value = 0;
    if (!decode_yaml_number(node, value) || value < std::numeric_limits<int>::min() ||
        value > std::numeric_limits<int>::max()) {
      type_problem(child(path, key), node, "must be an integer — " + meaning);
      return std::nullopt;
    }
    return static_cast<int>(value);
  }

  //! The text at map[key]; empty when it is absent (a problem when `required`), not a scalar (a
  //! problem "must be text — <meaning>") or not UTF-8 (a problem naming the byte).
  std::string text(const YamlNode& map, const std::string& path, const std::string& key, bool required,
                   const std::string& meaning) {
    const YamlNode node = map[key];
    if (!node) {
      if (required) missing(map, path, key, meaning);
      return {};
    }
    if (!node.IsScalar()) {
      type_problem(child(path, key), node, "must be text — " + meaning);
      return {};
    }
    if (const std::string problem = utf8_problem(node.Scalar()); !problem.empty()) {
      // Texts reach JSON (reports, the model database), which holds nothing but UTF-8.
      // Built with append: GCC 12 warns falsely (-Wrestrict) on "= \"" + std::string when inlined.
      std::string message = "= \"";
      message.append(utf8_shown(node.Scalar())).append("\": ").append(problem).append("; save the file as UTF-8");
      add(child(path, key), yaml_line(node), message);
      return {};
    }
    return node.Scalar();
  }

  //! Adds "<path.key> is missing from <path> (line N): required — <meaning>" (the mapping worded as
  //! the constructor says; nothing after "missing" at the top level).
  void missing(const YamlNode& map, const std::string& path, const std::string& key, const std::string& meaning) {
    const std::string section = wording_ == YamlSectionWording::kSection ? "the " + path + " section" : path;
    const std::string where =
        path.empty() ? "" : " from " + section + " (line " + std::to_string(yaml_line(map)) + ")";
    problems.push_back({child(path, key), "is missing" + where + ": required — " + meaning});
    reported.insert(child(path, key));
  }

  //! Adds "<field> = <value as written>: <expected>", or "<field> has no value: <expected>".
  void type_problem(const std::string& field, const YamlNode& node, const std::string& expected) {
    const std::string value = node.IsNull() ? "has no value" : "= " + yaml_value_text(node);
    add(field, yaml_line(node), value + ": " + expected);
  }

  //! `items` separated by ", ", for lists of allowed fields.
  static std::string joined(const std::vector<std::string>& items) {
    std::string text;
    for (const auto& item : items) {
      if (!text.empty()) text += ", ";
      text += item;
    }
    return text;
  }

 private:
  YamlSectionWording wording_;
};

}  // namespace feedplan
