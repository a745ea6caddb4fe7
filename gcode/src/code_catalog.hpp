#pragma once
// The G and M codes and word letters the reader knows: each code's modal group (LinuxCNC's
// numbering) and whether the reader executes it, accepts it without effect, or refuses it — with
// the reason, which goes into the problem text. Internal to the gcode module.

#include <optional>
#include <string>

namespace feedplan::gcode::detail {

//! What the reader does with a code.
enum class CodeUse {
  kSupported,  //!< executed (see reader.hpp)
  kIgnored,    //!< accepted without effect on path, feeds or spindle; `reason` says why that is safe
  kRefused,    //!< a problem; `reason` says what the code would do that the reader cannot follow
};

//! One G or M code.
struct CodeInfo {
  int group = 0;                //!< modal group, LinuxCNC numbering (G: 0 non-modal, 1 motion, …; M: 4, 6, 7, …)
  const char* group_name = "";  //!< the group in words, for "same modal group" problems
  CodeUse use = CodeUse::kRefused;  //!< executed, ignored or refused
  const char* reason = "";      //!< why ignored or refused
};

//! A G number as an integer in tenths (G0 → 0, G90.1 → 901, G59.3 → 593); nullopt when the number
//! is negative or has more than one decimal.
std::optional<int> g_code_tenths(double value);

//! The G code with number `tenths`; nullopt for codes the reader does not know at all.
std::optional<CodeInfo> find_g_code(int tenths);

//! The M code `number` (whole numbers only; nullopt otherwise or when unknown).
std::optional<CodeInfo> find_m_code(double number);

//! Why a word letter other than F G H I J M N O P Q R S T X Y Z is not read.
std::string letter_refusal(char letter);

//! "G90.1", "G0" from tenths.
std::string g_code_name(int tenths);

}  // namespace feedplan::gcode::detail
