#pragma once
// Items of a list in one text, for messages: "corner, trochoid, spiral".

#include <string>
#include <vector>

namespace feedplan {

//! The items in order with `separator` between them; "" for none.
inline std::string joined_text(const std::vector<std::string>& items, const std::string& separator) {
  std::string text;
  for (const auto& item : items) {
    if (!text.empty()) text += separator;
    text += item;
  }
  return text;
}

}  // namespace feedplan
