#pragma once
// The controller families the G-code writer speaks (writer.hpp says what differs between them).

#include <optional>
#include <string>
#include <string_view>

namespace feedplan::gcode {

//! A controller's G-code dialect.
enum class Dialect {
  kLinuxCnc,  //!< LinuxCNC (RS274NGC): `G1`, `G4 P<s>`, explicit `G91.1`, ends with `M2`, no O number
  kFanuc,     //!< Fanuc 0i / 30i: `%`, `O1000`, `G01`, `G04 X<s>`, ends with `M30` and `%`
  kHaas,      //!< Haas (NGC / classic): `%`, `O01000`, `G01`, `G04 P<s.>`, ends with `M30` and `%`
};

//! The dialect's name as the CLI spells it: "linuxcnc", "fanuc" or "haas".
std::string to_string(Dialect dialect);

//! The dialect named `name` ("linuxcnc", "fanuc", "haas"; ASCII letter case ignored), or nullopt for
//! any other text (the CLI then lists the three names).
std::optional<Dialect> dialect_from_string(std::string_view name);

}  // namespace feedplan::gcode
