#include "feedplan/gcode/dialect.hpp"

#include <cctype>

namespace feedplan::gcode {

std::string to_string(Dialect dialect) {
  switch (dialect) {
    case Dialect::kLinuxCnc: return "linuxcnc";
    case Dialect::kFanuc: return "fanuc";
    case Dialect::kHaas: return "haas";
  }
  return "dialect " + std::to_string(static_cast<int>(dialect));
}

std::optional<Dialect> dialect_from_string(std::string_view name) {
  std::string lower;
  for (char c : name) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (Dialect dialect : {Dialect::kLinuxCnc, Dialect::kFanuc, Dialect::kHaas}) {
    if (lower == to_string(dialect)) return dialect;
  }
  return std::nullopt;
}

}  // namespace feedplan::gcode
