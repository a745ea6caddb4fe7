// Seed 004's controller refuses bad settings, each problem naming the field, the value and the allowed range
// (STYLE.md, "Errors").

#include <gtest/gtest.h>

#include <limits>

#include "feedplan/control/beta_switching.hpp"
#include "feedplan/control/froh_model_reference_controller.hpp"
#include "feedplan/control/milling_plant.hpp"
#include "feedplan/control/reference_model.hpp"
#include "has_problem.hpp"

namespace feedplan::control {
namespace {

using test_support::has_problem;

TEST(FrohParameterValidation, NamesEveryBadField) {
  FrohModelReferenceParameters p;
  p.betas = {1.0, 1.5, -1.2};
  p.plant.feed_drive_time_constant_s = 0.0;
  p.plant.cutting_time_constant_s = -0.02;
  p.plant.teeth = 0;
  p.reference_model.damping_ratio = -0.1;
  p.forgetting_factor = 0.0;
  p.index_window_periods = 0;
  p.zero_cancellation_radius = 1.5;
  p.initial_depth_mm = 0.0;
  const auto problems = validate(p);
  EXPECT_TRUE(has_problem(problems, "froh_mrc.betas[1]", "= 1.5: must be finite and in [−1, 1]"));
  EXPECT_TRUE(has_problem(problems, "froh_mrc.betas[2]", "= -1.2: must be finite and in [−1, 1]"));
  EXPECT_FALSE(has_problem(problems, "froh_mrc.betas[0]", ""));
  EXPECT_TRUE(has_problem(problems, "froh_mrc.plant.feed_drive_time_constant_s", "= 0: must be finite and > 0"));
  EXPECT_TRUE(has_problem(problems, "froh_mrc.plant.cutting_time_constant_s", "= -0.02: must be finite and > 0"));
  EXPECT_TRUE(has_problem(problems, "froh_mrc.plant.teeth", "= 0: must be ≥ 1"));
  EXPECT_TRUE(has_problem(problems, "froh_mrc.reference_model.damping_ratio", "= -0.1: must be finite and > 0"));
  EXPECT_TRUE(has_problem(problems, "froh_mrc.forgetting_factor", "= 0: must be finite and in (0, 1]"));
  EXPECT_TRUE(has_problem(problems, "froh_mrc.index_window_periods", "= 0: must be ≥ 1"));
  EXPECT_TRUE(has_problem(problems, "froh_mrc.zero_cancellation_radius", "= 1.5: must be finite and in (0, 1]"));
  EXPECT_TRUE(has_problem(problems, "froh_mrc.initial_depth_mm", "= 0: must be finite and > 0"));
  EXPECT_THROW(FrohModelReferenceController{p}, InputError);
}

TEST(FrohParameterValidation, EmptyModelBankIsRefused) {
  FrohModelReferenceParameters p;
  p.betas.clear();
  try {
    FrohModelReferenceController controller(p);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_TRUE(has_problem(e.problems(), "froh_mrc.betas", "= []: must hold at least one β"));
  }
  p.scheme = SwitchingScheme::kNeighbourSearch;  // scheme 2 needs no bank
  EXPECT_TRUE(validate(p).empty());
}

TEST(FrohParameterValidation, NeighbourSearchSettingsAreChecked) {
  FrohModelReferenceParameters p;
  p.scheme = SwitchingScheme::kNeighbourSearch;
  p.neighbour_search = {1.1, 0.0, 1.0};
  const auto problems = validate(p);
  EXPECT_TRUE(has_problem(problems, "froh_mrc.neighbour_search.initial_beta", "= 1.1: must be finite and in [−1, 1]"));
  EXPECT_TRUE(has_problem(problems, "froh_mrc.neighbour_search.initial_step", "= 0: must be finite and in (0, 2]"));
  EXPECT_TRUE(has_problem(problems, "froh_mrc.neighbour_search.step_divisor", "= 1: must be finite and > 1"));
}

// A non-positive sampling period is refused where it is given (the controller's step() asserts it; the
// validators of the hold and the reference model take no period). The reference model's poles: a ξ ≤ 0 puts
// them on or outside the unit circle, refused by validate(); a discrete reference model with a pole outside
// is refused by the design (model_reference_design_test.cpp).
TEST(FrohParameterValidation, DefaultsAreValidAndBetaIsCheckedAlone) {
  EXPECT_TRUE(validate(FrohModelReferenceParameters{}).empty());
  EXPECT_TRUE(validate(MillingPlantParameters{}).empty());
  EXPECT_TRUE(validate(ReferenceModelParameters{}).empty());
  EXPECT_TRUE(has_problem(validate_beta(std::numeric_limits<double>::quiet_NaN(), "froh.beta"), "froh.beta", "= nan"));
  EXPECT_TRUE(validate_beta(-1.0, "froh.beta").empty());
}

}  // namespace
}  // namespace feedplan::control
