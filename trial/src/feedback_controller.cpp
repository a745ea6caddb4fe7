#include "feedplan/trial/feedback_controller.hpp"

#include <cassert>
#include <cmath>
#include <memory>
#include <utility>

#include "feedplan/control/adaptive_robust_servo.hpp"
#include "feedplan/control/feed_drive.hpp"
#include "feedplan/control/integral_force_controller.hpp"
#include "feedplan/control/override_range.hpp"
#include "feedplan/control/variable_gain_controller.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/trial/model_reference_law.hpp"

namespace feedplan::trial {

namespace {

// Time constants of the variable-gain controller's estimator (Eq. 4) and adaptation (Eq. 5), s.
constexpr double kModelGainTimeConstantS = 1.0;
constexpr double kControllerGainTimeConstantS = 0.5;
// The controllers' sample period of seeds 000/001, s.
constexpr double kSeedPeriodS = 0.1;

void add_problem(std::vector<InputProblem>& problems, std::string field, double value, const char* rule) {
  std::string message = "= ";
  message += shortest_number_text(value);
  message += ": ";
  message += rule;
  problems.push_back({std::move(field), std::move(message)});
}

// The process gain the controllers start from, N per percent of the programmed feed.
double start_process_gain(const ControllerSettings& settings) {
  return settings.target_force_n / kProgrammedFeedPercent;
}

ControlLaw integral_law(const ControllerSettings& settings) {
  control::IntegralControllerParameters p;
  p.reference_force_n = settings.target_force_n;
  p.controller_gain_mm_per_min_per_n_s = settings.loop_gain_per_s / start_process_gain(settings);
  p.programmed_feed_mm_per_min = kProgrammedFeedPercent;
  p.initial_feed_mm_per_min = kProgrammedFeedPercent;
  p.override_range = {settings.max_ratio, 0.0, settings.min_ratio};
  auto controller = std::make_shared<control::IntegralForceController>(p);
  return {[controller](double force_n, double dt_s) { return controller->step(force_n, dt_s); }, kSeedPeriodS, false, {}};
}

ControlLaw variable_gain_law(const ControllerSettings& settings, bool lathe) {
  control::VariableGainParameters p;
  const double gain = start_process_gain(settings);
  p.reference_force_n = settings.target_force_n;
  p.desired_loop_gain_per_s = settings.loop_gain_per_s;
  p.estimation_rate_c1 = 1.0 / (kModelGainTimeConstantS * kProgrammedFeedPercent);
  p.adaptation_rate_c2 = 1.0 / (kControllerGainTimeConstantS * gain);
  p.initial_model_gain_n_per_mm_per_min = gain;
  p.programmed_feed_mm_per_min = kProgrammedFeedPercent;
  p.initial_feed_mm_per_min = kProgrammedFeedPercent;
  p.override_range = {settings.max_ratio, lathe ? control::kLatheOverrideSteps.step_ratio : 0.0, settings.min_ratio};
  auto controller = std::make_shared<control::VariableGainController>(p);
  return {[controller](double force_n, double dt_s) { return controller->step(force_n, dt_s); }, kSeedPeriodS, false, {}};
}

// The servo is made at its first step, when its period is known; until then the parameters wait.
struct LazyRobustServo {
  control::AdaptiveRobustServoParameters parameters;
  double process_gain = 0.0;
  std::unique_ptr<control::AdaptiveRobustServo> servo;

  double step(double force_n, double dt_s) {
    if (!servo) {
      // dt ≥ kRobustServoMinPeriodS > the drive's 0.08 s dead time: the second-order form exists.
      const std::optional<control::ArmaModel> start = control::arma_equivalent({}, dt_s, process_gain);
      assert(start);
      parameters.initial_model = *start;
      servo = std::make_unique<control::AdaptiveRobustServo>(parameters);
    }
    return servo->step(force_n, dt_s);
  }
};

ControlLaw robust_servo_law(const ControllerSettings& settings) {
  auto lazy = std::make_shared<LazyRobustServo>();
  lazy->parameters.reference_force_n = settings.target_force_n;
  lazy->parameters.programmed_feed_mm_per_min = kProgrammedFeedPercent;
  lazy->parameters.override_range = {settings.max_ratio, 0.01, settings.min_ratio};  // seed 002: 1 % steps
  lazy->process_gain = start_process_gain(settings);
  // The parameters the servo will be made with, checked now (the model is set at the first step).
  lazy->parameters.initial_model = *control::arma_equivalent({}, kRobustServoMinPeriodS, lazy->process_gain);
  if (auto problems = control::validate(lazy->parameters); !problems.empty()) throw InputError(std::move(problems));
  return {[lazy](double force_n, double dt_s) { return lazy->step(force_n, dt_s); }, kRobustServoMinPeriodS, true, {}};
}

ControlLaw seed_004_law(const ControllerSettings& settings) {
  ModelReferenceLawSettings m;
  m.variant = settings.kind == ControllerKind::kModelReference ? ModelReferenceVariant::kZeroOrderHold
              : settings.kind == ControllerKind::kMultiModel1  ? ModelReferenceVariant::kFixedBank
                                                                : ModelReferenceVariant::kNeighbourSearch;
  m.target_force_n = settings.target_force_n;
  m.spindle_rpm = settings.spindle_rpm;
  m.flutes = settings.flutes;
  m.min_ratio = settings.min_ratio;
  m.max_ratio = settings.max_ratio;
  return model_reference_law(m);
}

}  // namespace

bool is_model_reference(ControllerKind kind) {
  return kind == ControllerKind::kModelReference || kind == ControllerKind::kMultiModel1 ||
         kind == ControllerKind::kMultiModel2;
}

std::string_view to_string(ControllerKind kind) { return kControllerNames[static_cast<std::size_t>(kind)]; }

std::optional<ControllerKind> controller_named(std::string_view name) {
  for (std::size_t i = 0; i < kControllerNames.size(); ++i) {
    if (kControllerNames[i] == name) return static_cast<ControllerKind>(i);
  }
  return std::nullopt;
}

std::vector<InputProblem> validate(const ControllerSettings& settings, const std::string& field_prefix) {
  std::vector<InputProblem> problems;
  if (!(std::isfinite(settings.target_force_n) && settings.target_force_n > 0.0)) {
    add_problem(problems, field_prefix + "target_force_n", settings.target_force_n, "must be finite and > 0 N");
  }
  if (!(std::isfinite(settings.max_ratio) && settings.max_ratio > 0.0)) {
    add_problem(problems, field_prefix + "max_ratio", settings.max_ratio,
                "must be finite and > 0 (the largest override, 1.5 = 150 %)");
  }
  const bool max_ok = std::isfinite(settings.max_ratio) && settings.max_ratio > 0.0;
  if (!(std::isfinite(settings.min_ratio) && settings.min_ratio >= 0.0 && (!max_ok || settings.min_ratio <= settings.max_ratio))) {
    add_problem(problems, field_prefix + "min_ratio", settings.min_ratio,
                "must be finite and in [0, max_ratio] (the lowest override, 0.1 = 10 %)");
  }
  if (is_model_reference(settings.kind)) {
    if (!(std::isfinite(settings.spindle_rpm) && settings.spindle_rpm > 0.0)) {
      add_problem(problems, field_prefix + "spindle_rpm", settings.spindle_rpm,
                  "must be finite and > 0 rev/min — the model-reference controllers' plant needs the spindle speed");
    }
    if (settings.flutes < 1) {
      problems.push_back({field_prefix + "flutes", "= " + std::to_string(settings.flutes) +
                                                       ": must be ≥ 1 — the model-reference controllers' plant needs the tool's flutes"});
    }
  }
  const bool variable = settings.kind == ControllerKind::kVariableGain || settings.kind == ControllerKind::kVariableGainLathe;
  if (!(std::isfinite(settings.loop_gain_per_s) && (variable ? settings.loop_gain_per_s > 0.0 : settings.loop_gain_per_s >= 0.0))) {
    add_problem(problems, field_prefix + "loop_gain_per_s", settings.loop_gain_per_s,
                variable ? "must be finite and > 0 /s — the loop gain the variable-gain controller holds"
                         : "must be finite and ≥ 0 /s (0: no feedback)");
  }
  if (settings.kind == ControllerKind::kVariableGainLathe && settings.max_ratio < control::kLatheOverrideSteps.step_ratio) {
    add_problem(problems, field_prefix + "max_ratio", settings.max_ratio,
                "must be ≥ 0.15 — the lathe's override moves in 15 % steps");
  }
  return problems;
}

ControlLaw make_control_law(const ControllerSettings& settings) {
  if (auto problems = validate(settings); !problems.empty()) throw InputError(std::move(problems));
  switch (settings.kind) {
    case ControllerKind::kIntegral: return integral_law(settings);
    case ControllerKind::kVariableGain: return variable_gain_law(settings, false);
    case ControllerKind::kVariableGainLathe: return variable_gain_law(settings, true);
    case ControllerKind::kModelReference:
    case ControllerKind::kMultiModel1:
    case ControllerKind::kMultiModel2: return seed_004_law(settings);
    case ControllerKind::kRobustServo: break;
  }
  return robust_servo_law(settings);
}

}  // namespace feedplan::trial
