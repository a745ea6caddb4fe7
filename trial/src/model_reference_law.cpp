#include "feedplan/trial/model_reference_law.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <memory>
#include <utility>

#include "feedplan/control/beta_switching.hpp"
#include "feedplan/control/froh_model_reference_controller.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"

namespace feedplan::trial {

namespace {

// Seed 002's feed drive on the virtual machine: 14 e^(−0.08 s)/(s + 14) (sim::FeedOverrideOptions).
constexpr double kFeedDriveTimeConstantS = 1.0 / 14.0;
// The controller's feed unit: 100 of its mm/s is the program's feed (see the file comment).
constexpr double kPercentAsMmPerMin = 60.0 * kProgrammedFeedPercent;

}  // namespace

std::vector<InputProblem> validate(const ModelReferenceLawSettings& settings, const std::string& field_prefix) {
  ProblemList problems(field_prefix);
  problems.positive("target_force_n", settings.target_force_n);
  problems.positive("spindle_rpm", settings.spindle_rpm);
  if (settings.flutes < 1) problems.add_value("flutes", std::to_string(settings.flutes), "must be ≥ 1 (the tool's flutes)");
  problems.positive("max_ratio", settings.max_ratio);
  const bool max_ok = std::isfinite(settings.max_ratio) && settings.max_ratio > 0.0;
  if (!(std::isfinite(settings.min_ratio) && settings.min_ratio >= 0.0 && (!max_ok || settings.min_ratio <= settings.max_ratio))) {
    problems.add_value("min_ratio", shortest_number_text(settings.min_ratio), "must be finite and in [0, max_ratio]");
  }
  problems.positive("min_period_s", settings.min_period_s);
  problems.positive("rise_time_periods", settings.rise_time_periods);
  return problems.take();
}

namespace {

// The controller's parameters of the file comment (its period is set by its first step's time step; the
// rise time is rise_time_periods of it).
control::FrohModelReferenceParameters model_reference_parameters(const ModelReferenceLawSettings& settings) {
  assert(validate(settings).empty());
  control::FrohModelReferenceParameters p;
  const double process_gain_n_per_percent = settings.target_force_n / kProgrammedFeedPercent;
  p.plant.teeth = settings.flutes;
  p.plant.spindle_speed_rpm = settings.spindle_rpm;
  p.plant.immersion_function = 1.0;
  const double revolutions_per_s = settings.spindle_rpm / 60.0;
  p.plant.cutting_pressure_n_per_mm2 =
      process_gain_n_per_percent * settings.flutes * revolutions_per_s / (p.plant.immersion_function * kModelReferenceNominalDepthMm);
  p.plant.feed_drive_time_constant_s = kFeedDriveTimeConstantS;
  p.plant.cutting_time_constant_s = 60.0 / (settings.spindle_rpm * settings.flutes);
  p.initial_depth_mm = kModelReferenceNominalDepthMm;
  p.reference_model.rise_time_periods = settings.rise_time_periods;
  p.reference_force_n = settings.target_force_n;
  switch (settings.variant) {
    case ModelReferenceVariant::kZeroOrderHold:
      p.scheme = control::SwitchingScheme::kFixedSet;
      p.betas = {0.0};
      break;
    case ModelReferenceVariant::kFixedBank:
      p.scheme = control::SwitchingScheme::kFixedSet;
      p.betas = control::seed_004_beta_bank();
      break;
    case ModelReferenceVariant::kNeighbourSearch:
      p.scheme = control::SwitchingScheme::kNeighbourSearch;
      break;
  }
  p.programmed_feed_mm_per_min = kPercentAsMmPerMin;
  p.override_range = {settings.max_ratio, 0.0, settings.min_ratio};
  return p;
}

// The controller, started at its first step from the cut under way (the override 100 % before it).
struct ModelReferenceState {
  explicit ModelReferenceState(const control::FrohModelReferenceParameters& p) : controller(p) {}
  double step(double force_n, double dt_s) {
    if (!started) controller.start_in_steady_state(force_n, 1.0);
    started = true;
    return controller.step(force_n, dt_s);
  }
  control::FrohModelReferenceController controller;
  bool started = false;
};

}  // namespace

ControlLaw model_reference_law(const ModelReferenceLawSettings& settings) {
  if (auto problems = validate(settings); !problems.empty()) throw InputError(std::move(problems));
  auto state = std::make_shared<ModelReferenceState>(model_reference_parameters(settings));
  ControlLaw law;
  law.step = [state](double force_n, double dt_s) { return state->step(force_n, dt_s); };
  law.hold = [state](double fraction_of_period) {
    return state->controller.held_feed_mm_per_s(std::clamp(fraction_of_period, 0.0, 1.0)) * 60.0 / kPercentAsMmPerMin;
  };
  law.period_s = settings.min_period_s;
  law.per_revolution = true;
  return law;
}

}  // namespace feedplan::trial
