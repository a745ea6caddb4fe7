#pragma once
// One measured point for learning: a spindle revolution's peak XY force paired with the force model's
// inputs at the place and feed where it was measured (DESIGN.md §5.4).

namespace feedplan::learning {

//! A per-revolution measurement with the model inputs it belongs to.
struct LearningSample {
  double chip_mm = 0.0;            //!< t_m at the feed actually run there, mm
  double contact_length_mm = 0.0;  //!< L at that place (as the model is evaluated: ≥ its fitted L_min), mm
  double force_n = 0.0;            //!< measured peak XY force of the revolution, N, scaled to the model's axial depth
  double weight = 1.0;             //!< relative precision (> 0)
  double s_mm = 0.0;               //!< where on the planned path (middle of the revolution), mm
};

}  // namespace feedplan::learning
