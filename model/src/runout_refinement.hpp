#pragma once
// Runout and phases of cutting tests, refined jointly with the coefficients (mechanistic
// identification, private to the model module). With runout the force is no longer linear in the
// unknowns, so Ceres minimises the bin residuals over the coefficients, the runout and each test's phase
// at once, with central numeric derivatives of the kernel.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "feedplan/model/mechanistic_identification.hpp"

namespace feedplan::model::detail {

//! How far an identified helix may lie from the catalogue value, deg.
inline constexpr double kMaxHelixChangeDeg = 20.0;

//! The size effect during the refinement: held at `exponent`, or refined from it within [0, kMaxSizeExponent].
struct RunoutSizeEffect {
  bool refine = false;
  double exponent = 0.0;
  double reference_chip_mm = 0.1;  //!< h_ref, mm, always held
};

//! The refined unknowns.
struct RunoutRefinement {
  double size_exponent = 0.0;  //!< the size effect's exponent, refined or held
  std::optional<double> helix_deg;  //!< with identify_helix: the helix the tests show, deg
  std::vector<double> runout_mm;  //!< per tooth, mm, tooth 0 at 0 (only differences are seen)
  std::vector<double> phase_rad;  //!< per test, rad
  bool converged = false;         //!< Ceres reports a usable solution
  std::string message;            //!< Ceres' summary line
};

//! Starting from the phases found without runout (known modulo a tooth period) and the coefficients
//! fitted with them: fits tooth 0's test alone (which fixes the tooth numbering), gives every other test
//! the tooth period shift of its phase that fits best the runout found, then fits all tests together.
//! Needs tests with one cutter (same flute count ≥ 2). With `identify_helix` the helix angle (one for all
//! tests, starting at the first test's cutter's) is refined in the last fit too, within kMaxHelixChangeDeg; so is
//! the size effect's exponent with `size.refine` (else held at `size.exponent` throughout).
RunoutRefinement refine_runout(const std::vector<MechanisticCuttingTest>& tests, const std::vector<double>& phases_rad,
                               const std::array<double, 4>& coefficients, bool identify_helix = false,
                               const RunoutSizeEffect& size = {});

}  // namespace feedplan::model::detail
