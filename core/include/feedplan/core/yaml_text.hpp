#pragma once
// How YAML input appears in problem messages: a value as the user wrote it, and the line it is on.
// Shared by the modules that read YAML (cycles specs, sim materials).
//
// Templates over the node type so that core needs no yaml-cpp: they take a YAML::Node and are
// instantiated only in the modules that link yaml-cpp themselves (PRIVATE, see their CMakeLists).

#include <string>

namespace feedplan {

//! A YAML value as the user wrote it: scalars as they stand, quoted scalars ("1045") in double
//! quotes, lists and mappings in flow style ("[1, 2]", "{x: 1, y: 2}"), an empty value "null".
//! `YamlNode` is YAML::Node.
template <typename YamlNode>
std::string yaml_value_text(const YamlNode& node) {
  if (node.IsScalar()) return node.Tag() == "!" ? "\"" + node.Scalar() + "\"" : node.Scalar();
  if (!node.IsSequence() && !node.IsMap()) return "null";
  std::string items;  // ", " between items; an empty first item (a !!str "") adds none
  for (const auto& item : node) {
    if (!items.empty()) items += ", ";
    if (node.IsSequence()) {
      items += yaml_value_text<YamlNode>(item);
    } else {
      items += yaml_value_text(item.first) + ": " + yaml_value_text(item.second);
    }
  }
  return node.IsSequence() ? "[" + items + "]" : "{" + items + "}";
}

//! The 1-based line of `node` in its document, or 0 when it has none (a node built in code).
//! `YamlNode` is YAML::Node.
template <typename YamlNode>
int yaml_line(const YamlNode& node) {
  const auto mark = node.Mark();
  return mark.is_null() ? 0 : mark.line + 1;
}

//! `field` followed by " (line <line>)", or `field` alone when `line` is 0 (unknown).
inline std::string with_yaml_line(const std::string& field, int line) {
  return line > 0 ? field + " (line " + std::to_string(line) + ")" : field;
}

}  // namespace feedplan
