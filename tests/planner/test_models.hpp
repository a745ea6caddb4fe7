#pragma once
// Force models and cycles shared by the planner tests (test-only).

#include "feedplan/cycles/spec.hpp"
#include "feedplan/model/response_surface_model.hpp"

namespace feedplan::planner::testing {

//! F̂ = β0 + β1 X1 (+ β2 X2 …): a model of the magnitude seed 003 reports for S50C with a D10 4-flute
//! end mill at a_p 10 mm (≈ 300 N at t_m 0.05 mm, L 4 mm), rising in t_m over its whole range.
inline model::ResponseSurfaceModel s50c_like_model(bool linear = false) {
  model::ResponseSurfaceModel model;
  model.beta = {300.0, 180.0, 40.0, linear ? 0.0 : -8.0, linear ? 0.0 : -4.0, linear ? 0.0 : 12.0};
  if (linear) model.beta[2] = 0.0;
  model.chip_center_mm = 0.05;
  model.chip_scale_mm = 0.04;
  model.contact_length_center_mm = 4.0;
  model.contact_length_scale_mm = 2.0;
  model.range = {0.005, 0.15, 0.0, 8.0};
  model.axial_depth_mm = 10.0;
  model.spindle_rpm = 2800.0;
  return model;
}

//! The corner-rounding sample of seed 003 Fig. 5 (samples/corner.yaml).
inline cycles::CycleSpec corner_spec() {
  cycles::CycleSpec spec;
  spec.cycle = "corner";
  spec.tool = {"SC EM D10 Z4", 10.0, 4, 30.0};
  spec.material = "S50C";
  spec.spindle_rpm = 2800.0;
  spec.axial_depth_mm = 10.0;
  spec.target_force_n = 350.0;
  cycles::CornerSpec corner;
  corner.corner_radius_mm = 10.0;
  corner.radial_depth_mm = 1.5;
  corner.wall_length_mm = 30.0;
  spec.geometry = corner;
  return spec;
}

}  // namespace feedplan::planner::testing
