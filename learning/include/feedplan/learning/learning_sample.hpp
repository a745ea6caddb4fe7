#pragma once
// One measured point for learning: a spindle revolution's peak XY force paired with the force model's
// inputs at the place and feed where it was measured (docs/method.md §5.4).

#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/model/response_surface_model.hpp"

namespace feedplan::learning {

//! A per-revolution measurement with the model inputs it belongs to.
struct LearningSample {
  double chip_mm = 0.0;            //!< t_m at the feed actually run there, mm
  double contact_length_mm = 0.0;  //!< L at that place (as the model is evaluated: ≥ its fitted L_min), mm
  double force_n = 0.0;            //!< measured peak XY force of the revolution, N, scaled to the model's axial depth
  double weight = 1.0;             //!< relative precision (> 0)
  double s_mm = 0.0;               //!< where on the planned path (middle of the revolution), mm
  //! The factor force_n was divided by to stand for the straight-cut model's own force there
  //! (planner::force_transfer_factor; 1 when not transferred): force_n × transfer_factor is the measured peak
  double transfer_factor = 1.0;
  double feed_mm_per_min = 0.0;  //!< the feed actually run where the peak was measured, mm/min (0: not known)
  double s_peak_mm = 0.0;        //!< where on the planned path the peak was measured, mm
};

//! Appends the problems with one sample's numbers to `problems`, fields named `prefix` + member
//! ("samples[3].force_n = nan: must be finite"): t_m and L finite and ≥ 0, the force finite, the weight
//! finite and > 0.
void validate(const LearningSample& sample, const std::string& prefix, std::vector<InputProblem>& problems);

//! Appends the problems with a model to learn from (model::validate) and with every sample
//! ("samples[i]." + member) to `problems`.
void validate(const model::ResponseSurfaceModel& model, const std::vector<LearningSample>& samples,
              std::vector<InputProblem>& problems);

//! √(Σ w (F − F̂)² / Σ w), the weighted RMS error of `model` over `samples`, N; 0 for none.
double weighted_rms_error(const model::ResponseSurfaceModel& model, const std::vector<LearningSample>& samples);

}  // namespace feedplan::learning
