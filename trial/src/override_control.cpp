#include "feedplan/trial/override_control.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "feedplan/core/number_text.hpp"

namespace feedplan::trial {

namespace {

void add_problem(std::vector<InputProblem>& problems, std::string field, double value, const std::string& rule) {
  std::string message = "= ";
  message += shortest_number_text(value);
  message += ": ";
  message += rule;
  problems.push_back({std::move(field), std::move(message)});
}

// The loop's state between calls: the sensor's revolutions, the controller and what it commanded.
class OverrideController {
 public:
  OverrideController(const OverrideControlSettings& settings, ControlLaw law, std::shared_ptr<ControlTrace> trace)
      : settings_(settings), law_(std::move(law)), meter_(settings.sensor), trace_(std::move(trace)) {
    command_ = bounded(1.0);
  }

  double operator()(const sim::ControlInput& input) {
    const std::optional<SensedRevolution> revolution = meter_.add(input.t_s, input.spindle_rpm, input.reading);
    if (revolution && trace_) trace_->revolutions.push_back(*revolution);
    if (law_.per_revolution) {
      if (revolution) per_revolution(*revolution, input);
    } else {
      if (revolution) latest_ = revolution;
      per_period(input);
    }
    if (holding_ && law_.hold) command_ = bounded(law_.hold((input.t_s - step_t_s_) / step_dt_s_));
    return command_;
  }

 private:
  bool in_cut(double force_n) const { return force_n >= settings_.contact_fraction * settings_.target_force_n; }

  double bounded(double ratio) const { return std::clamp(ratio, settings_.min_ratio, settings_.max_ratio); }

  // A controller stepped every period with the latest revolution's force.
  void per_period(const sim::ControlInput& input) {
    if (!next_step_s_) next_step_s_ = input.t_s + law_.period_s;
    if (input.t_s < *next_step_s_) return;
    while (*next_step_s_ <= input.t_s) *next_step_s_ += law_.period_s;
    const double force_n = latest_ ? latest_->force_n : 0.0;
    act(input, force_n, law_.period_s);
  }

  // A controller stepped at the end of every n-th revolution with their largest force, n the fewest
  // revolutions (of the latest one's length) spanning the law's period.
  void per_revolution(const SensedRevolution& revolution, const sim::ControlInput& input) {
    if (group_revolutions_ == 0) {
      group_start_s_ = revolution.t_start_s;
      group_largest_n_ = 0.0;
    }
    ++group_revolutions_;
    group_largest_n_ = std::max(group_largest_n_, revolution.force_n);
    const double duration_s = revolution.t_end_s - revolution.t_start_s;
    // A revolution measured on the sample grid may come out a sample short of the period it spans.
    const double needed = duration_s > 0.0 ? std::max(1.0, std::ceil(law_.period_s / duration_s - 0.01)) : 1.0;
    if (group_revolutions_ < needed) return;
    group_revolutions_ = 0;
    act(input, group_largest_n_, revolution.t_end_s - group_start_s_);
  }

  // Steps the controller on `force_n` when in cut, else holds it and commands 100 %.
  void act(const sim::ControlInput& input, double force_n, double dt_s) {
    const bool cutting = in_cut(force_n) && dt_s > 0.0;
    command_ = bounded(cutting ? law_.step(force_n, dt_s) : 1.0);
    holding_ = cutting;
    step_t_s_ = input.t_s;
    step_dt_s_ = dt_s;
    if (trace_) trace_->steps.push_back({input.t_s, force_n, command_, input.override_ratio, cutting});
  }

  OverrideControlSettings settings_;
  ControlLaw law_;
  RevolutionForceMeter meter_;
  std::shared_ptr<ControlTrace> trace_;
  std::optional<SensedRevolution> latest_;
  std::optional<double> next_step_s_;
  int group_revolutions_ = 0;
  double group_start_s_ = 0.0;
  double group_largest_n_ = 0.0;
  double command_ = 1.0;
  bool holding_ = false;   // the law's hold shapes the override until its next step
  double step_t_s_ = 0.0;  // time of the latest step, s
  double step_dt_s_ = 1.0; // its time step, s
};

}  // namespace

OverrideControlSettings hybrid_override_settings(const ForceSensorSettings& sensor, double target_force_n) {
  OverrideControlSettings settings;
  settings.sensor = sensor;
  settings.target_force_n = target_force_n;
  settings.min_ratio = 0.7;
  settings.max_ratio = 1.3;
  return settings;
}

std::vector<InputProblem> validate(const OverrideControlSettings& settings, const std::string& field_prefix) {
  std::vector<InputProblem> problems = validate(settings.sensor, field_prefix + "sensor.");
  if (!(std::isfinite(settings.target_force_n) && settings.target_force_n > 0.0)) {
    add_problem(problems, field_prefix + "target_force_n", settings.target_force_n, "must be finite and > 0 N");
  }
  const bool max_ok = std::isfinite(settings.max_ratio) && settings.max_ratio > 0.0;
  if (!max_ok) {
    add_problem(problems, field_prefix + "max_ratio", settings.max_ratio, "must be finite and > 0 (1.5 = 150 %)");
  }
  if (!(std::isfinite(settings.min_ratio) && settings.min_ratio >= 0.0 && (!max_ok || settings.min_ratio <= settings.max_ratio))) {
    add_problem(problems, field_prefix + "min_ratio", settings.min_ratio, "must be finite and in [0, max_ratio]");
  }
  if (!(std::isfinite(settings.contact_fraction) && settings.contact_fraction > 0.0 && settings.contact_fraction < 1.0)) {
    add_problem(problems, field_prefix + "contact_fraction", settings.contact_fraction,
                "must be in (0, 1) — the share of the target that counts as cutting");
  }
  if (!(std::isfinite(settings.sample_period_s) && settings.sample_period_s > 0.0)) {
    add_problem(problems, field_prefix + "sample_period_s", settings.sample_period_s, "must be finite and > 0 s");
  }
  sim::FeedOverrideOptions channel = settings.channel;
  channel.max_ratio = max_ok ? settings.max_ratio : 1.0;
  channel.initial_ratio = std::min(1.0, channel.max_ratio);
  for (InputProblem& p : sim::validate(channel, 1e-4)) problems.push_back(std::move(p));
  return problems;
}

sim::OverrideLoop make_override_loop(const OverrideControlSettings& settings, ControlLaw law,
                                     std::shared_ptr<ControlTrace> trace) {
  if (auto problems = validate(settings); !problems.empty()) throw InputError(std::move(problems));
  sim::OverrideLoop loop;
  loop.period_s = settings.sample_period_s;
  loop.channel = settings.channel;
  loop.channel.max_ratio = settings.max_ratio;
  loop.channel.initial_ratio = std::clamp(1.0, settings.min_ratio, settings.max_ratio);
  OverrideController controller(settings, std::move(law), std::move(trace));
  loop.controller = [state = std::make_shared<OverrideController>(std::move(controller))](const sim::ControlInput& input) {
    return (*state)(input);
  };
  return loop;
}

}  // namespace feedplan::trial
