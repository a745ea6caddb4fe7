#pragma once
// The starting point for identifying a dynamometer's modes (mechanistic identification with identify_sensor,
// private to the model module): a search over natural frequency and damping, each try scored by the
// residual of the coefficients' least-squares fit to every test's bins as that sensor would read the kernel
// (variable projection: the coefficients are linear, the modes are not). The residual has a valley for
// every harmonic of the revolution a mode may sit on, so a local method needs a start in the right one.
//
// Steps, each keeping the best try:
//   1. one mode for both axes, over the frequency grid × the damping grid;
//   2. the modes along x and y (θ = 0) in turn, each over the grids with the other held, twice;
//   3. the modes' direction θ over (−45°, 45°] in 5° steps with the modes held, then step 2 once more.

#include <vector>

#include <Eigen/Dense>

#include "feedplan/model/sensor_response.hpp"
#include "sensed_bin_rows.hpp"

namespace feedplan::model::detail {

//! Natural frequencies tried: a geometric grid from the range's lower end, 2 % apart.
inline constexpr double kSensorSearchFrequencyRatio = 1.02;
//! Damping ratios tried: from kSensorSearchMinDamping doubling up to below 0.5.
inline constexpr double kSensorSearchMinDamping = 0.005;

//! What the search scores a sensor with: each test's binning and spectrum (at its phase, with the runout
//! and helix found so far) and the measured bins of all tests stacked in the same order.
struct SensorSearchData {
  std::vector<const SensedBinning*> binnings;
  std::vector<Eigen::MatrixXcd> spectra;
  Eigen::VectorXd measured;
};

//! The sum of squared bin residuals of the coefficients' least-squares fit through `sensor`, N².
double sensor_residual(const SensorSearchData& data, const SensorResponse& sensor);

//! The best sensor of the search (file comment) with natural frequencies in [min_hz, max_hz].
SensorResponse search_sensor(const SensorSearchData& data, double min_hz, double max_hz);

}  // namespace feedplan::model::detail
