#pragma once
// The dynamometer's modes refined jointly with the coefficients and each test's phase — and the runout and
// helix when they are identified — by Ceres (mechanistic identification with identify_sensor, private to
// the model module), from the search's start (sensor_search.hpp). The bins' residuals are those of the
// kernel's force read through the sensor (sensed_bin_rows.hpp), with central numeric derivatives.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "feedplan/model/mechanistic_identification.hpp"
#include "feedplan/model/sensor_response.hpp"
#include "sensed_bin_rows.hpp"

namespace feedplan::model::detail {

//! Smallest and largest damping ratio the refinement may reach.
inline constexpr double kMinRefinedDamping = 0.002;
inline constexpr double kMaxRefinedDamping = 0.9;

//! Where the refinement starts, and what it refines besides the sensor, the coefficients and the phases.
struct SensorRefinementStart {
  SensorResponse sensor;
  std::array<double, 4> coefficients{};  //!< K_tc, K_rc, K_te, K_re
  std::vector<double> phase_rad;         //!< per test
  std::vector<double> runout_mm;         //!< per tooth; refined (teeth 1 … N−1) when not empty
  std::optional<double> helix_deg;       //!< refined when set, within kMaxHelixChangeDeg of the cutter's
  double size_exponent = 0.0;            //!< the size effect, held
  double size_reference_chip_mm = 0.1;   //!< its reference chip, mm
};

//! The refined unknowns.
struct SensorRefinement {
  SensorResponse sensor;  //!< with θ in (−45°, 45°] (θ − 90° with the modes swapped is the same sensor)
  std::array<double, 4> coefficients{};
  std::vector<double> phase_rad;
  std::vector<double> runout_mm;
  std::optional<double> helix_deg;
  bool converged = false;  //!< Ceres reports a usable solution
  std::string message;     //!< Ceres' summary line
};

//! Refines from `start`, natural frequencies within [min_hz, max_hz]. `binnings[i]` belongs to `tests[i]`.
SensorRefinement refine_sensor(const std::vector<MechanisticCuttingTest>& tests,
                               const std::vector<SensedBinning>& binnings, const SensorRefinementStart& start,
                               double min_hz, double max_hz);

}  // namespace feedplan::model::detail
