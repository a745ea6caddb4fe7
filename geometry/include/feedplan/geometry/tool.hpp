#pragma once
// The cutting tool as the geometry and the force model see it: a flat end mill.

#include <string>

namespace feedplan::geometry {

//! Default largest feed per tooth along −Z while the tool descends into material (plunge, ramp, helix),
//! as a fraction of the diameter: 0.0025·D (0.025 mm for D10). Half of a typical side-milling feed per
//! tooth of solid carbide end mills in steel (about 0.005·D in vendor catalogues), following the
//! common rule of plunging and ramping at 50 % of the milling feed (e.g. Harvey Performance, "Ramping
//! to Interpolation Strategies"; Sandvik Coromant, "Ramping" application guide). Set the tool's own
//! value from its vendor's plunge data when it has one.
inline constexpr double kDefaultPlungeFeedPerToothPerDiameter = 0.0025;

//! A flat end mill.
struct Tool {
  std::string name;          //!< free text shown in reports and G-code comments
  double diameter_mm = 10.0; //!< cutting diameter, mm
  int flutes = 4;            //!< number of teeth
  double helix_deg = 30.0;   //!< helix angle, degrees (user-facing spec unit)
  //! Largest feed per tooth along −Z while descending into material, mm; 0: the default,
  //! kDefaultPlungeFeedPerToothPerDiameter × diameter
  double max_plunge_feed_per_tooth_mm = 0.0;

  double radius_mm() const { return 0.5 * diameter_mm; }
  //! The plunge feed per tooth in effect, mm (the tool's own, or the default).
  double plunge_feed_per_tooth_mm() const {
    return max_plunge_feed_per_tooth_mm > 0.0 ? max_plunge_feed_per_tooth_mm
                                              : kDefaultPlungeFeedPerToothPerDiameter * diameter_mm;
  }
};

}  // namespace feedplan::geometry
