#pragma once
// How YAML input appears in problem messages: a value as the user wrote it, and the line it is on.
// Shared by the modules that read YAML (cycles specs, sim materials).
//
// Templates over the node type so that core needs no yaml-cpp: they take a YAML::Node and are
// instantiated only in the modules that link yaml-cpp themselves (PRIVATE, see their CMakeLists).

#include <cstddef>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"

namespace feedplan {

//! The longest value text a problem shows, in bytes before "…": a list of thousands of numbers in the
//! wrong place is named, not echoed, and an alias bomb is not expanded into the message.
inline constexpr std::size_t kLongestYamlValueText = 80;

namespace detail {

// Appends the text of `node` to `out`, stopping once `out` is longer than `longest`.
template <typename YamlNode>
void append_yaml_value_text(const YamlNode& node, std::string& out, std::size_t longest) {
  if (out.size() > longest) return;
  if (node.IsScalar()) {
    out += node.Tag() == "!" ? "\"" + node.Scalar() + "\"" : node.Scalar();
    return;
  }
  if (!node.IsSequence() && !node.IsMap()) {
    out += "null";
    return;
  }
  out += node.IsSequence() ? "[" : "{";
  const std::size_t open = out.size();
  for (const auto& item : node) {
    if (out.size() > longest) return;
    if (out.size() > open) out += ", ";  // an empty first item (a !!str "") adds none
    if (node.IsSequence()) {
      append_yaml_value_text<YamlNode>(item, out, longest);
    } else {
      append_yaml_value_text(item.first, out, longest);
      out += ": ";
      append_yaml_value_text(item.second, out, longest);
    }
  }
  out += node.IsSequence() ? "]" : "}";
}

}  // namespace detail

//! A YAML value as the user wrote it: scalars as they stand, quoted scalars ("1045") in double
//! quotes, lists and mappings in flow style ("[1, 2]", "{x: 1, y: 2}"), an empty value "null"; cut
//! after kLongestYamlValueText bytes ("[1, 2, 3, …"). `YamlNode` is YAML::Node.
template <typename YamlNode>
std::string yaml_value_text(const YamlNode& node) {
  std::string text;
  detail::append_yaml_value_text(node, text, kLongestYamlValueText);
  if (text.size() > kLongestYamlValueText) {
    std::size_t cut = kLongestYamlValueText;
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;  // not inside a UTF-8 character
    text.resize(cut);
    text += "…";
  }
  return text;
}

//! True when `node` counts more than `max_nodes` nodes with every alias (*name) expanded where it is
//! used — what any walk over the document visits. Stops counting there, so an alias bomb (ten
//! aliases of ten aliases of … : 10⁹ nodes from 800 bytes) costs max_nodes steps. `YamlNode` is
//! YAML::Node.
template <typename YamlNode>
bool yaml_expands_beyond(const YamlNode& node, std::size_t max_nodes) {
  std::vector<YamlNode> pending{node};
  std::size_t count = 0;
  while (!pending.empty()) {
    const YamlNode next = pending.back();
    pending.pop_back();
    if (++count > max_nodes) return true;
    if (next.IsSequence()) {
      for (const auto& item : next) pending.push_back(item);
    } else if (next.IsMap()) {
      for (const auto& item : next) {
        pending.push_back(item.first);
        pending.push_back(item.second);
      }
    }
  }
  return false;
}

//! The document `load(yaml_text)` parses (a lambda calling YAML::Load), as an InputError naming
//! `source_name` when the text is not YAML (`Exception` is YAML::Exception: line and column) or expands
//! to more than `max_nodes` nodes through its aliases (`typical`: how many nodes a document of this kind
//! has, for the message).
template <typename Exception, typename Load>
auto load_bounded_yaml(Load load, const std::string& yaml_text, const std::string& source_name, std::size_t max_nodes,
                       const std::string& typical) {
  decltype(load(yaml_text)) root;
  try {
    root = load(yaml_text);
  } catch (const Exception& e) {
    std::string where;
    if (!e.mark.is_null()) {
      where = " at line " + std::to_string(e.mark.line + 1) + ", column " + std::to_string(e.mark.column + 1);
    }
    throw InputError(source_name, "is not valid YAML" + where + ": " + e.msg);
  }
  if (yaml_expands_beyond(root, max_nodes)) {
    throw InputError(source_name, "expands to more than " + std::to_string(max_nodes) +
                                      " YAML nodes through its aliases (*name), counting each use: " + typical +
                                      "; write it without the aliases");
  }
  return root;
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
