#include "feedplan/control/froh_model_reference_controller.hpp"

#include <cassert>
#include <cmath>
#include <limits>

#include "feedplan/control/fractional_order_hold.hpp"
#include "feedplan/control/froh_discretisation.hpp"
#include "feedplan/control/tracking_index.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"

namespace feedplan::control {

std::vector<InputProblem> validate(const FrohModelReferenceParameters& parameters, const std::string& field_prefix) {
  ProblemList problems(field_prefix);
  problems.add_all(validate(parameters.plant, field_prefix + "plant."));
  problems.positive("initial_depth_mm", parameters.initial_depth_mm);
  problems.add_all(validate(parameters.reference_model, field_prefix + "reference_model."));
  problems.positive("reference_force_n", parameters.reference_force_n);
  if (parameters.scheme == SwitchingScheme::kFixedSet) {
    if (parameters.betas.empty()) problems.add_value("betas", "[]", "must hold at least one β (the model bank is empty)");
    for (std::size_t i = 0; i < parameters.betas.size(); ++i) {
      problems.add_all(validate_beta(parameters.betas[i], field_prefix + "betas[" + std::to_string(i) + "]"));
    }
  } else {
    problems.add_all(validate(parameters.neighbour_search, field_prefix + "neighbour_search."));
  }
  const double lambda = parameters.forgetting_factor;
  if (!(std::isfinite(lambda) && lambda > 0.0 && lambda <= 1.0)) {
    problems.add_value("forgetting_factor", shortest_number_text(lambda), "must be finite and in (0, 1]");
  }
  if (parameters.index_window_periods < 1) {
    problems.add_value("index_window_periods", std::to_string(parameters.index_window_periods), "must be ≥ 1");
  }
  if (parameters.residence_periods < 1) {
    problems.add_value("residence_periods", std::to_string(parameters.residence_periods), "must be ≥ 1");
  }
  const double radius = parameters.zero_cancellation_radius;
  if (!(std::isfinite(radius) && radius > 0.0 && radius <= 1.0)) {
    problems.add_value("zero_cancellation_radius", shortest_number_text(radius),
                       "must be finite and in (0, 1]: a zero outside the unit circle cannot be cancelled");
  }
  if (parameters.substeps_per_period < 1) {
    problems.add_value("substeps_per_period", std::to_string(parameters.substeps_per_period), "must be ≥ 1");
  }
  problems.positive("programmed_feed_mm_per_min", parameters.programmed_feed_mm_per_min);
  problems.add_all(validate(parameters.override_range, field_prefix + "override_range."));
  return problems.take();
}

namespace {

const FrohModelReferenceParameters& checked(const FrohModelReferenceParameters& parameters) {
  ProblemList problems;
  problems.add_all(validate(parameters));
  problems.throw_if_any();
  return parameters;
}

}  // namespace

FrohModelReferenceController::FrohModelReferenceController(const FrohModelReferenceParameters& parameters)
    : parameters_(checked(parameters)),
      period_s_(spindle_period_s(parameters.plant)),
      depth_mm_(parameters.initial_depth_mm),
      plant_copy_(milling_system(parameters.plant, parameters.initial_depth_mm), period_s_, parameters.substeps_per_period),
      reference_copy_(reference_system(parameters.reference_model, period_s_), period_s_, parameters.substeps_per_period),
      search_(parameters.scheme == SwitchingScheme::kNeighbourSearch ? parameters.neighbour_search
                                                                      : NeighbourSearchParameters{}) {
  ProblemList problems;
  if (parameters_.scheme == SwitchingScheme::kFixedSet) {
    active_beta_ = parameters_.betas.front();
    for (std::size_t i = 0; i < parameters_.betas.size(); ++i) {
      const ModelReferenceDesign& d = design_for(depth_mm_, parameters_.betas[i]);
      if (d.status != ModelReferenceStatus::kDesigned) {
        problems.add("froh_mrc.betas[" + std::to_string(i) + "]",
                     "= " + shortest_number_text(parameters_.betas[i]) + ": no model-following design: " + d.message);
      }
    }
  } else {
    active_beta_ = search_.active_beta();
    const ModelReferenceDesign& d = design_for(depth_mm_, active_beta_);
    if (d.status != ModelReferenceStatus::kDesigned) {
      problems.add("froh_mrc.neighbour_search.initial_beta",
                   "= " + shortest_number_text(active_beta_) + ": no model-following design: " + d.message);
    }
  }
  problems.throw_if_any();
}

void FrohModelReferenceController::set_depth_of_cut_mm(double depth_mm) {
  assert(std::isfinite(depth_mm) && depth_mm > 0.0);
  depth_mm_ = depth_mm;
  plant_copy_.set_system(milling_system(parameters_.plant, depth_mm));
}

void FrohModelReferenceController::start_in_steady_state(double force_n, double ratio) {
  assert(samples_ == 0 && std::isfinite(force_n) && std::isfinite(ratio) && ratio >= 0.0);
  const double feed_mm_per_s = applied_command(ratio * parameters_.programmed_feed_mm_per_min / 60.0);
  const double reference_n = parameters_.reference_force_n;
  reference_n_ = {reference_n, reference_n, reference_n};
  force_n_ = {force_n, force_n, force_n};
  commands_ = {feed_mm_per_s, feed_mm_per_s};
  plant_copy_.set_state({feed_mm_per_s, force_n});
  reference_copy_.set_state({reference_n, 0.0});
}

double FrohModelReferenceController::held_feed_mm_per_s(double fraction_of_period) const {
  return fractional_hold_output(commands_[0], commands_[1], active_beta_, fraction_of_period);
}

double FrohModelReferenceController::step(double measured_force_n, double dt_s) {
  assert(std::isfinite(measured_force_n) && std::isfinite(dt_s) && dt_s > 0.0);
  if (std::abs(dt_s - period_s_) > 1e-9 * period_s_) reset_period(dt_s);
  reference_n_ = {parameters_.reference_force_n, reference_n_[0], reference_n_[1]};
  force_n_ = {measured_force_n, force_n_[0], force_n_[1]};
  // The force is measured: the copy's force state takes it (the feed state depends on the commands alone).
  plant_copy_.set_state({plant_copy_.state()[0], measured_force_n});
  if (samples_ >= 1 && samples_ - last_switch_sample_ >= parameters_.residence_periods) choose_beta();

  const ModelReferenceDesign& design = design_for(depth_mm_, active_beta_);
  double command = commands_[0];
  if (design.status == ModelReferenceStatus::kDesigned) {
    command = applied_command(model_reference_command(design.controller, reference_n_, force_n_, commands_));
  } else {
    ++failed_designs_;
  }

  PeriodRecord record{plant_copy_, depth_mm_, {}, reference_n_, force_n_, commands_};
  reference_copy_.step(parameters_.reference_force_n, reference_n_[1], 0.0);
  record.reference_outputs = reference_copy_.period_outputs();
  records_.insert(records_.begin(), std::move(record));
  if (records_.size() > static_cast<std::size_t>(parameters_.index_window_periods) + 1) records_.pop_back();

  plant_copy_.step(command, commands_[0], active_beta_);
  commands_ = {command, commands_[0]};
  ++samples_;
  return command * 60.0 / parameters_.programmed_feed_mm_per_min;
}

const ModelReferenceDesign& FrohModelReferenceController::design_for(double depth_mm, double beta) {
  const std::pair<double, double> key{depth_mm, beta};
  const auto found = designs_.find(key);
  if (found != designs_.end()) return found->second;
  // Scheme 2 visits ever new β: keep the cache bounded.
  if (designs_.size() >= 4096) designs_.clear();
  const DiscreteTransferFunction plant = froh_transfer_function(milling_system(parameters_.plant, depth_mm), beta, period_s_);
  const DiscreteTransferFunction reference =
      froh_transfer_function(reference_system(parameters_.reference_model, period_s_), beta, period_s_);
  return designs_.emplace(key, design_model_reference(plant, reference, parameters_.zero_cancellation_radius)).first->second;
}

double FrohModelReferenceController::applied_command(double command_mm_per_s) const {
  const double programmed_mm_per_s = parameters_.programmed_feed_mm_per_min / 60.0;
  return programmed_mm_per_s * applied_override(parameters_.override_range, command_mm_per_s / programmed_mm_per_s);
}

double FrohModelReferenceController::candidate_index(double beta) {
  std::vector<double> areas;
  for (const PeriodRecord& record : records_) {
    const ModelReferenceDesign& design = design_for(record.depth_mm, beta);
    if (design.status != ModelReferenceStatus::kDesigned) return std::numeric_limits<double>::infinity();
    const double command =
        applied_command(model_reference_command(design.controller, record.reference_n, record.force_n, record.commands));
    HeldSystemSimulator plant = record.plant;
    plant.step(command, record.commands[0], beta);
    areas.push_back(period_absolute_area(record.reference_outputs, plant.period_outputs(), period_s_));
  }
  return tracking_index(areas, parameters_.forgetting_factor);
}

void FrohModelReferenceController::choose_beta() {
  last_indices_.clear();
  bool switched = false;
  if (parameters_.scheme == SwitchingScheme::kFixedSet) {
    for (double beta : parameters_.betas) last_indices_.push_back(candidate_index(beta));
    const std::size_t chosen = fixed_set_choice(last_indices_, active_position_);
    switched = parameters_.betas[chosen] != active_beta_;
    active_position_ = chosen;
    active_beta_ = parameters_.betas[chosen];
  } else {
    const std::array<double, 3> candidates = search_.candidates();
    std::array<double, 3> indices{};
    for (std::size_t i = 0; i < 3; ++i) indices[i] = candidate_index(candidates[i]);
    last_indices_.assign(indices.begin(), indices.end());
    switched = search_.update(indices);
    active_beta_ = search_.active_beta();
  }
  if (switched) {
    ++switches_;
    last_switch_sample_ = samples_;
  }
}

void FrohModelReferenceController::reset_period(double period_s) {
  period_s_ = period_s;
  designs_.clear();
  records_.clear();
  const int m = parameters_.substeps_per_period;
  HeldSystemSimulator plant(plant_copy_.system(), period_s, m);
  plant.set_state(plant_copy_.state());
  plant_copy_ = plant;
  HeldSystemSimulator reference(reference_system(parameters_.reference_model, period_s), period_s, m);
  reference.set_state(reference_copy_.state());
  reference_copy_ = reference;
}

}  // namespace feedplan::control
