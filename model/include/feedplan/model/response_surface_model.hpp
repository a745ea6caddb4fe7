#pragma once
// The response-surface force model of seed 003 Eq. 1 (docs/method.md §5.3): the peak XY resultant force
// per spindle revolution as a quadratic in the maximum undeformed chip thickness t_m and the contact
// length L, normalised by centres and scales stored with the model, valid inside the range it was
// fitted on.

#include <array>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"

namespace feedplan::model {

//! Index of each coefficient in ResponseSurfaceModel::beta.
enum BetaIndex { kBeta0 = 0, kBeta1 = 1, kBeta2 = 2, kBeta11 = 3, kBeta22 = 4, kBeta12 = 5 };

//! The inputs' range seen in fitting; predictions outside it are extrapolations.
struct FittedRange {
  double chip_min_mm = 0.0;             //!< smallest t_m fitted, mm
  double chip_max_mm = 0.0;             //!< largest t_m fitted, mm
  double contact_length_min_mm = 0.0;   //!< smallest L fitted, mm
  double contact_length_max_mm = 0.0;   //!< largest L fitted, mm
};

//! F̂ = β0 + β1 X1 + β2 X2 + β11 X1² + β22 X2² + β12 X1 X2, X1 = (t_m − c1)/s1, X2 = (L − c2)/s2.
struct ResponseSurfaceModel {
  std::array<double, 6> beta{};          //!< β0, β1, β2, β11, β22, β12, N (see BetaIndex)
  double chip_center_mm = 0.05;          //!< c1: centre of t_m, mm
  double chip_scale_mm = 0.05;           //!< s1: scale of t_m, mm (> 0)
  double contact_length_center_mm = 5.0; //!< c2: centre of L, mm
  double contact_length_scale_mm = 5.0;  //!< s2: scale of L, mm (> 0)
  FittedRange range;                     //!< where the model was fitted
  double axial_depth_mm = 0.0;           //!< axial depth of cut of the data the model was fitted on, mm
  double spindle_rpm = 0.0;              //!< spindle speed of that data, rev/min (0: mixed or unknown)
  //! What F̂ is: always the peak XY resultant force per spindle revolution, N.
  std::string quantity = "peak_xy_force_per_revolution_n";
};

//! Which quantities validate() accepts as what F̂ stands for.
enum class QuantityRule {
  kThisProjects,  //!< only the one this project models: "= 'mean_force_n': must be 'peak_xy_force_per_revolution_n'"
  kAnyNamed,      //!< any non-empty name: "= '': must name what the model predicts" (the model database)
};

//! How validate() names the fields it reports and which quantities it accepts. The defaults are the
//! planner's; the model database names them after its table ("models.beta[2]", bounds without it).
struct ModelCheckOptions {
  std::string field_prefix = "model.";                    //!< before each field: "model.beta[3]"
  std::string bound_prefix = "model.";                    //!< before the bound in "must be ≤ model.range.chip_max_mm = 0.08"
  QuantityRule quantity = QuantityRule::kThisProjects;  //!< the quantities accepted
};

//! Every problem with a model's numbers, each naming its field ("model.beta[3] = nan: must be finite"):
//! finite β; finite centres; finite scales > 0; a finite range with non-negative values and min ≤ max for
//! t_m and for L; finite, non-negative axial depth and spindle speed; and the quantity F̂ stands for must
//! be the one this project models ("peak_xy_force_per_revolution_n"), or any name as `options` say.
//! Empty when the model is usable.
std::vector<InputProblem> validate(const ResponseSurfaceModel& model, const ModelCheckOptions& options = {});

}  // namespace feedplan::model
