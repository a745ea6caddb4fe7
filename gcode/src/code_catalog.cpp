#include "code_catalog.hpp"

#include <cmath>
#include <map>

namespace feedplan::gcode::detail {

namespace {

constexpr CodeUse kS = CodeUse::kSupported;
constexpr CodeUse kI = CodeUse::kIgnored;
constexpr CodeUse kR = CodeUse::kRefused;

constexpr const char* kPlaneReason = "arcs are read in the XY, XZ and YZ planes (G17, G18, G19) only";
constexpr const char* kOffsetReason = "it changes coordinate offsets, which the reader does not keep";
constexpr const char* kHomeReason = "it stores a machine position, which the reader does not keep";
constexpr const char* kCompReason =
    "cutter radius compensation by a diameter in the D word: use G41/G42 D<tool> with the tool's diameter given "
    "to the reader";
constexpr const char* kLengthReason =
    "dynamic or added tool length offsets: Z would no longer be the programmed tool tip; use G43 H<tool>";
constexpr const char* kPathControlReason =
    "path control only changes how the controller blends corners; the programmed path is the same";

// G codes by tenths. Groups as in LinuxCNC's interpreter (interp_array.cc).
const std::map<int, CodeInfo>& g_codes() {
  static const std::map<int, CodeInfo> codes = {
      {0, {1, "motion", kS, ""}},
      {10, {1, "motion", kS, ""}},
      {20, {1, "motion", kS, ""}},
      {30, {1, "motion", kS, ""}},
      {40, {0, "non-modal", kS, ""}},
      {50, {1, "motion", kR, "spline moves"}},
      {51, {1, "motion", kR, "spline moves"}},
      {52, {1, "motion", kR, "spline moves"}},
      {53, {1, "motion", kR, "spline moves"}},
      {70, {15, "lathe diameter mode", kR, "lathe diameter mode"}},
      {80, {15, "lathe diameter mode", kR, "lathe radius mode"}},
      {100, {0, "non-modal", kR, kOffsetReason}},
      {170, {2, "plane", kS, ""}},
      {171, {2, "plane", kR, kPlaneReason}},
      {180, {2, "plane", kS, ""}},
      {181, {2, "plane", kR, kPlaneReason}},
      {190, {2, "plane", kS, ""}},
      {191, {2, "plane", kR, kPlaneReason}},
      {200, {6, "units", kS, ""}},
      {210, {6, "units", kS, ""}},
      {280, {0, "non-modal", kS, ""}},
      {281, {0, "non-modal", kR, kHomeReason}},
      {300, {0, "non-modal", kS, ""}},
      {301, {0, "non-modal", kR, kHomeReason}},
      {330, {1, "motion", kR, "spindle-synchronised motion (threading)"}},
      {331, {1, "motion", kR, "spindle-synchronised motion (rigid tapping)"}},
      {382, {1, "motion", kR, "probing moves"}},
      {383, {1, "motion", kR, "probing moves"}},
      {384, {1, "motion", kR, "probing moves"}},
      {385, {1, "motion", kR, "probing moves"}},
      {400, {7, "cutter compensation", kS, ""}},
      {410, {7, "cutter compensation", kS, ""}},
      {411, {7, "cutter compensation", kR, kCompReason}},
      {420, {7, "cutter compensation", kS, ""}},
      {421, {7, "cutter compensation", kR, kCompReason}},
      {430, {8, "tool length offset", kS, ""}},
      {431, {8, "tool length offset", kR, kLengthReason}},
      {432, {8, "tool length offset", kR, kLengthReason}},
      {490, {8, "tool length offset", kI, "tool length offset off is the state of a program without G43"}},
      {520, {0, "non-modal", kR, kOffsetReason}},
      {530, {0, "non-modal", kS, ""}},
      {540, {12, "work offset", kS, ""}},
      {550, {12, "work offset", kS, ""}},
      {560, {12, "work offset", kS, ""}},
      {570, {12, "work offset", kS, ""}},
      {580, {12, "work offset", kS, ""}},
      {590, {12, "work offset", kS, ""}},
      {591, {12, "work offset", kS, ""}},
      {592, {12, "work offset", kS, ""}},
      {593, {12, "work offset", kS, ""}},
      {610, {13, "path control", kI, kPathControlReason}},
      {611, {13, "path control", kI, kPathControlReason}},
      {640, {13, "path control", kI, kPathControlReason}},
      {730, {1, "motion", kS, ""}},
      {740, {1, "motion", kR, "left-hand tapping: the feed follows the spindle"}},
      {760, {1, "motion", kR, "threading cycle"}},
      // LinuxCNC lists G80 in group 1 but accepts it beside G0–G3 (the motion wins), as in the common
      // safe-start line "G0 G40 G49 G80 G90": it gets a group of its own here.
      {800, {11, "motion cancel", kS, ""}},
      {810, {1, "motion", kS, ""}},
      {820, {1, "motion", kS, ""}},
      {830, {1, "motion", kS, ""}},
      {840, {1, "motion", kR, "tapping: the feed follows the spindle"}},
      {850, {1, "motion", kS, ""}},
      {860, {1, "motion", kS, ""}},
      {870, {1, "motion", kR, "back boring: the spindle is stopped and oriented in the hole"}},
      {880, {1, "motion", kR, "boring with a manual retract"}},
      {890, {1, "motion", kS, ""}},
      {900, {3, "distance mode", kS, ""}},
      {901, {4, "arc distance mode", kS, ""}},
      {910, {3, "distance mode", kS, ""}},
      {911, {4, "arc distance mode", kS, ""}},
      {920, {0, "non-modal", kR, kOffsetReason}},
      {921, {0, "non-modal", kR, kOffsetReason}},
      {922, {0, "non-modal", kR, kOffsetReason}},
      {923, {0, "non-modal", kR, kOffsetReason}},
      {930, {5, "feed mode", kR, "inverse-time feed: F would be 1/minutes per move, not a path speed"}},
      {940, {5, "feed mode", kS, ""}},
      {950, {5, "feed mode", kR, "feed per revolution: program F in length per minute (G94)"}},
      {960, {14, "spindle speed mode", kR, "constant surface speed: the rpm would change along the path"}},
      {970, {14, "spindle speed mode", kI, "constant rpm is the default"}},
      {980, {10, "canned-cycle return", kS, ""}},
      {990, {10, "canned-cycle return", kS, ""}},
  };
  return codes;
}

const std::map<int, CodeInfo>& m_codes() {
  static const std::map<int, CodeInfo> codes = {
      {0, {4, "stopping", kI, "a program pause does not change the path"}},
      {1, {4, "stopping", kI, "an optional pause does not change the path"}},
      {2, {4, "stopping", kS, ""}},
      {3, {7, "spindle", kS, ""}},
      {4, {7, "spindle", kS, ""}},
      {5, {7, "spindle", kS, ""}},
      {6, {6, "tool change", kS, ""}},
      {7, {8, "coolant", kI, "coolant"}},
      {8, {8, "coolant", kI, "coolant"}},
      {9, {8, "coolant", kI, "coolant"}},
      {19, {7, "spindle", kR, "spindle orientation"}},
      {30, {4, "stopping", kS, ""}},
      // Haas: chip conveyor forward, reverse, stop; through-spindle coolant on, off. No effect on the path.
      {31, {10, "chip conveyor", kI, "Haas chip conveyor: no effect on the path, feeds or spindle"}},
      {32, {10, "chip conveyor", kI, "Haas chip conveyor: no effect on the path, feeds or spindle"}},
      {33, {10, "chip conveyor", kI, "Haas chip conveyor: no effect on the path, feeds or spindle"}},
      {88, {8, "coolant", kI, "Haas through-spindle coolant"}},
      {89, {8, "coolant", kI, "Haas through-spindle coolant"}},
      {48, {9, "override switches", kR, "override switches change the feed the machine runs"}},
      {49, {9, "override switches", kR, "override switches change the feed the machine runs"}},
      {50, {9, "override switches", kR, "override switches change the feed the machine runs"}},
      {51, {9, "override switches", kR, "override switches change the feed the machine runs"}},
      {52, {9, "override switches", kR, "override switches change the feed the machine runs"}},
      {53, {9, "override switches", kR, "override switches change the feed the machine runs"}},
      {60, {4, "stopping", kR, "pallet change"}},
      {61, {6, "tool change", kR, "it sets the tool in the spindle"}},
  };
  return codes;
}

}  // namespace

std::optional<int> g_code_tenths(double value) {
  const double tenths = value * 10.0;
  const double rounded = std::round(tenths);
  if (value < 0.0 || std::abs(tenths - rounded) > 1e-6 || rounded > 1e6) return std::nullopt;
  return static_cast<int>(rounded);
}

std::optional<CodeInfo> find_g_code(int tenths) {
  const auto it = g_codes().find(tenths);
  if (it == g_codes().end()) return std::nullopt;
  return it->second;
}

std::optional<CodeInfo> find_m_code(double number) {
  if (number < 0.0 || number > 1e6 || number != std::floor(number)) return std::nullopt;
  const auto it = m_codes().find(static_cast<int>(number));
  if (it == m_codes().end()) return std::nullopt;
  return it->second;
}

std::string letter_refusal(char letter) {
  switch (letter) {
    case 'A': case 'B': case 'C': return "rotary axes; the reader reads X, Y and Z only";
    case 'U': case 'V': case 'W': return "extra linear axes; the reader reads X, Y and Z only";
    default: return "not a word the reader knows";
  }
}

std::string g_code_name(int tenths) {
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string here.
  std::string name(1, 'G');
  name += std::to_string(tenths / 10);
  if (tenths % 10 != 0) {
    name += '.';
    name += std::to_string(tenths % 10);
  }
  return name;
}

}  // namespace feedplan::gcode::detail
