#pragma once
// How much material the pocket's roughing (the stadium of the centre bore, spiral and slots) and the
// corner clean-up leave on the finished walls: the thickest stock, measured along the walls' normals.
// The pocket uses it to choose its semi-finishing contours. Internal to the cycles module.
//
// Canonical coordinates: the pocket's centre at the origin, its long axis along +x; one quarter
// (x ≥ 0, y ≥ 0) stands for all four, as the roughing and the clean-up are symmetric.

namespace feedplan::cycles::detail {

//! The quarter pocket and what was cut in it, canonical coordinates, mm.
struct QuarterPocket {
  double half_long_mm = 0.0;        //!< L / 2
  double half_short_mm = 0.0;       //!< S / 2
  double corner_radius_mm = 0.0;    //!< R_c
  double slot_end_mm = 0.0;         //!< x of the slot end centre O = ((L − S) / 2, 0)
  double rough_radius_mm = 0.0;     //!< R_s: the roughing cut everything within R_s of the slot axis
  double clean_up_start_x_mm = 0.0; //!< first corner loop centre (on O–Q)
  double clean_up_start_y_mm = 0.0;
  double clean_up_reach_mm = 0.0;   //!< R_q: the clean-up cut everything within R_q of its loop centres;
                                    //!< 0 when the corner has no clean-up
};

//! Largest distance, along the inward normal of the finished outline (walls and corner arc), from the
//! finished outline to the material already cut, sampled every `step_mm` along the outline, mm.
double thickest_wall_stock_mm(const QuarterPocket& pocket, double step_mm = 0.02);

}  // namespace feedplan::cycles::detail
