#pragma once
// The cutting tool as the geometry and the force model see it: a flat end mill.

#include <string>

namespace feedplan::geometry {

//! A flat end mill.
struct Tool {
  std::string name;          //!< free text shown in reports and G-code comments
  double diameter_mm = 10.0; //!< cutting diameter, mm
  int flutes = 4;            //!< number of teeth
  double helix_deg = 30.0;   //!< helix angle, degrees (user-facing spec unit)

  double radius_mm() const { return 0.5 * diameter_mm; }
};

}  // namespace feedplan::geometry
