#include "feedplan/sim/feed_override.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

#include "feedplan/core/number_text.hpp"

namespace feedplan::sim {

namespace {

// The delay line holds dead_time / step + 2 commands; more than this many is a mistake in the step.
constexpr double kMaxDelaySteps = 1e7;

// Appends "<field> = <value>: must be <rule>" unless `ok`.
void require(std::vector<InputProblem>& problems, bool ok, const std::string& field, double value,
             const std::string& rule) {
  if (!ok) problems.push_back({field, "= " + six_digit_number_text(value) + ": must be " + rule});
}

}  // namespace

std::vector<InputProblem> validate(const FeedOverrideOptions& options, double step_s) {
  std::vector<InputProblem> problems;
  const double tau = options.time_constant_s;
  const double dead = options.dead_time_s;
  const double max_ratio = options.max_ratio;
  const double initial = options.initial_ratio;
  require(problems, std::isfinite(tau) && tau >= 0.0, "feed_override.time_constant_s", tau, "≥ 0 s");
  require(problems, std::isfinite(dead) && dead >= 0.0, "feed_override.dead_time_s", dead, "≥ 0 s");
  const bool max_ok = std::isfinite(max_ratio) && max_ratio > 0.0;
  require(problems, max_ok, "feed_override.max_ratio", max_ratio, "> 0 (1.5 = 150 %)");
  if (max_ok) {
    require(problems, initial >= 0.0 && initial <= max_ratio, "feed_override.initial_ratio", initial,
            "in [0, max_ratio = " + six_digit_number_text(max_ratio) + "]");
  }
  const bool step_ok = std::isfinite(step_s) && step_s > 0.0;
  require(problems, step_ok, "feed_override.step_s", step_s, "> 0 s");
  if (step_ok && std::isfinite(dead) && dead / step_s > kMaxDelaySteps) {
    require(problems, false, "feed_override.step_s", step_s,
            "≥ dead_time_s / 1e7 = " + six_digit_number_text(dead / kMaxDelaySteps) +
                " s (the delay line would be too long)");
  }
  return problems;
}

FeedOverride::FeedOverride(const FeedOverrideOptions& options, double step_s) {
  std::vector<InputProblem> problems = validate(options, step_s);
  if (!problems.empty()) throw InputError(std::move(problems));
  max_ratio_ = options.max_ratio;
  step_s_ = step_s;
  // T_d = N Δt + δ, 0 ≤ δ < Δt. A δ within 1e-9 Δt of 0 or Δt is rounding of T_d / Δt (0.08 / 0.001
  // is not exactly 80): it snaps to whole steps, which matters for τ = 0, where the sampled pure
  // delay jumps by a whole step as δ crosses Δt.
  double whole = std::floor(options.dead_time_s / step_s);
  double delta_s = options.dead_time_s - whole * step_s;
  if (delta_s > step_s * (1.0 - 1e-9)) {
    whole += 1.0;
    delta_s = 0.0;
  }
  if (delta_s < step_s * 1e-9) delta_s = 0.0;
  delay_steps_ = static_cast<std::size_t>(whole);
  const double tau = options.time_constant_s;
  // e^(−x/τ), with its limit for τ = 0 (a pure dead time).
  auto decay = [tau](double x_s) { return tau > 0.0 ? std::exp(-x_s / tau) : (x_s > 0.0 ? 0.0 : 1.0); };
  alpha_ = decay(step_s);
  gain_older_ = decay(step_s - delta_s) * (1.0 - decay(delta_s));
  gain_newer_ = 1.0 - decay(step_s - delta_s);
  delay_.assign(delay_steps_ + 2, options.initial_ratio);
  commanded_ = options.initial_ratio;
  actual_ = options.initial_ratio;
}

void FeedOverride::command(double ratio) {
  assert(!std::isnan(ratio));
  commanded_ = std::clamp(ratio, 0.0, max_ratio_);
}

double FeedOverride::step() {
  const std::size_t size = delay_.size();
  delay_[head_] = commanded_;  // u_k
  const double newer = delay_[(head_ + size - delay_steps_) % size];       // u_{k−N}
  const double older = delay_[(head_ + size - delay_steps_ - 1) % size];   // u_{k−N−1}
  actual_ = alpha_ * actual_ + gain_older_ * older + gain_newer_ * newer;
  head_ = (head_ + 1) % size;
  ++steps_;
  return actual_;
}

}  // namespace feedplan::sim
