#pragma once
// The bin-averaged regressors of a cutting test (mechanistic identification, private to the model
// module): the kernel's XY regressor columns K_tc, K_rc, K_te, K_re averaged over each bin of the
// synchronous average at kPhaseStepsPerBin sub-steps, for a phase offset Ω₀ of bin 0.

#include <array>
#include <vector>

#include <Eigen/Dense>

#include "feedplan/model/mechanistic_identification.hpp"

namespace feedplan::model::detail {

inline constexpr int kIdentifiedCoefficients = 4;  //!< K_tc, K_rc, K_te, K_re

using XyRegressors = std::array<std::array<double, kIdentifiedCoefficients>, 2>;  //!< [Fx, Fy][coefficient]

int bin_count(const MechanisticCuttingTest& test);

//! The regressors without runout at Ω_k = 2π (k + ½) / (bins · kPhaseStepsPerBin), k over a revolution.
std::vector<XyRegressors> regressor_table(const MechanisticCuttingTest& test);

//! Rows 0 … bins − 1: Fx, bins … 2·bins − 1: Fy, at a phase offset of `offset` sub-steps, from the table.
Eigen::MatrixXd table_rows(const std::vector<XyRegressors>& table, int bins, int offset);

//! The same rows at any phase Ω₀, rad, with the size effect and runout of `model`.
Eigen::MatrixXd phase_rows(const MechanisticCuttingTest& test, double phase_rad, const MechanisticModel& model);

//! The regressors at every sub-step of the bins, unaveraged: row j at Ω₀ + 2π (j + ½) / (bins · kPhaseStepsPerBin),
//! columns 0 … 3 Fx, 4 … 7 Fy (K_tc, K_rc, K_te, K_re each), with the size effect and runout of `model` — the
//! samples phase_rows averages, for a sensor to act on first (sensed_bin_rows.hpp).
Eigen::MatrixXd substep_regressors(const MechanisticCuttingTest& test, double phase_rad, const MechanisticModel& model);

//! The measured Fx then Fy bins of the test.
Eigen::VectorXd measured(const MechanisticCuttingTest& test);

}  // namespace feedplan::model::detail
