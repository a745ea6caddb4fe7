#include "feedplan/model_db/mechanistic_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "feedplan/core/input_error.hpp"
#include "feedplan/model/mechanistic_force.hpp"
#include "feedplan/model/mechanistic_identification.hpp"
#include "feedplan/model_db/engagement_groups.hpp"

namespace feedplan::model_db {
namespace {

model::CutterGeometry cutter_of(const ToolRecord& tool) {
  return model::CutterGeometry{0.5 * tool.diameter_mm, tool.flutes, tool.helix_deg};
}

model::StraightCutSide side_of(CutMode mode) {
  switch (mode) {
    case CutMode::kDown: return model::StraightCutSide::kDown;
    case CutMode::kUp: return model::StraightCutSide::kUp;
    case CutMode::kSlot: return model::StraightCutSide::kSlot;
  }
  return model::StraightCutSide::kDown;
}

model::ImmersionArc arc_of(const ToolRecord& tool, const CuttingTestConditions& conditions) {
  const double radius_mm = 0.5 * tool.diameter_mm;
  return model::straight_cut_arc(side_of(conditions.mode), std::min(conditions.radial_depth_mm, 2.0 * radius_mm),
                                 radius_mm);
}

model::MechanisticIdentificationOptions identification_options(const ToolRecord& tool,
                                                               const MechanisticFitOptions& options) {
  model::MechanisticIdentificationOptions o;
  o.identify_runout = options.identify_runout && tool.flutes >= 2;
  o.identify_helix = o.identify_runout && options.identify_helix;
  o.identify_size_effect = options.identify_size_effect;
  o.identify_sensor = options.identify_sensor;
  o.match_peaks = options.match_peaks;
  return o;
}

// The fitted range of the tests (t_m, L, a_p, rpm) in the fields every version has: a mechanistic
// version's response-surface part is never a force model (β = 0), only what the tests covered.
model::ResponseSurfaceModel test_range(const std::vector<const StoredCuttingTest*>& tests) {
  model::ResponseSurfaceModel range_model;
  range_model.beta = {};
  auto& r = range_model.range;
  r.chip_min_mm = r.contact_length_min_mm = INFINITY;
  r.chip_max_mm = r.contact_length_max_mm = -INFINITY;
  double depth_min = INFINITY, depth_max = -INFINITY, rpm_min = INFINITY, rpm_max = -INFINITY;
  for (const StoredCuttingTest* stored : tests) {
    const CuttingTestRecord& t = stored->test;
    r.chip_min_mm = std::min(r.chip_min_mm, t.chip_mm);
    r.chip_max_mm = std::max(r.chip_max_mm, t.chip_mm);
    r.contact_length_min_mm = std::min(r.contact_length_min_mm, t.contact_length_mm);
    r.contact_length_max_mm = std::max(r.contact_length_max_mm, t.contact_length_mm);
    depth_min = std::min(depth_min, t.conditions.axial_depth_mm);
    depth_max = std::max(depth_max, t.conditions.axial_depth_mm);
    rpm_min = std::min(rpm_min, t.conditions.spindle_rpm);
    rpm_max = std::max(rpm_max, t.conditions.spindle_rpm);
  }
  range_model.chip_center_mm = 0.5 * (r.chip_min_mm + r.chip_max_mm);
  range_model.chip_scale_mm = std::max(0.5 * (r.chip_max_mm - r.chip_min_mm), 1e-6);
  range_model.contact_length_center_mm = 0.5 * (r.contact_length_min_mm + r.contact_length_max_mm);
  range_model.contact_length_scale_mm = std::max(0.5 * (r.contact_length_max_mm - r.contact_length_min_mm), 1e-6);
  range_model.axial_depth_mm = depth_min == depth_max ? depth_min : 0.0;
  range_model.spindle_rpm = rpm_min == rpm_max ? rpm_min : 0.0;
  return range_model;
}

MechanisticFit stored_fit(const model::MechanisticIdentification& identification) {
  MechanisticFit fit;
  fit.model = identification.model;
  fit.covariance = identification.covariance;
  fit.signal_rms_residual_n = identification.rms_residual_n;
  fit.condition_number = identification.condition_number;
  fit.identified = identification.status == model::IdentificationStatus::kIdentified;
  fit.unidentifiable = identification.unidentifiable;
  return fit;
}

// RMSE and R² of predicted against measured peaks.
void peak_statistics(const std::vector<double>& predicted, const std::vector<double>& measured, ModelFitStatistics& fit) {
  const std::size_t n = measured.size();
  double mean = 0.0;
  for (double m : measured) mean += m;
  mean /= static_cast<double>(n);
  double residual = 0.0, total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    residual += (predicted[i] - measured[i]) * (predicted[i] - measured[i]);
    total += (measured[i] - mean) * (measured[i] - mean);
  }
  fit.n = static_cast<int>(n);
  fit.rmse_n = std::sqrt(residual / static_cast<double>(n));
  fit.r_squared = total > 0.0 ? 1.0 - residual / total : 0.0;
}

// The RMS error of each test's peak predicted by the coefficients refitted without its group (`group[i]` is
// test i's), with the phases and runout the identification found on all of them held
// (model::refit_coefficients).
double leave_group_out_rmse_n(const ToolRecord& tool, const std::vector<const StoredCuttingTest*>& used,
                              const std::vector<model::MechanisticCuttingTest>& tests,
                              const model::MechanisticIdentification& identification, const std::vector<int>& group) {
  double sum = 0.0;
  const int groups = *std::max_element(group.begin(), group.end()) + 1;
  for (int left_out = 0; left_out < groups; ++left_out) {
    std::vector<model::MechanisticCuttingTest> others;
    std::vector<double> phases;
    for (std::size_t i = 0; i < tests.size(); ++i) {
      if (group[i] == left_out) continue;
      others.push_back(tests[i]);
      phases.push_back(identification.phase_rad[i]);
    }
    const model::MechanisticModel refitted =
        model::refit_coefficients(others, phases, identification.model, identification.tests_peak_matched > 0);
    for (std::size_t i = 0; i < tests.size(); ++i) {
      if (group[i] != left_out) continue;
      const double error = predicted_test_peak_n(refitted, tool, used[i]->test) - used[i]->test.peak_mean_n;
      sum += error * error;
    }
  }
  return std::sqrt(sum / static_cast<double>(tests.size()));
}

}  // namespace

model::MechanisticCuttingTest identification_test(const ToolRecord& tool, const StoredCuttingTest& stored, int index) {
  const CuttingTestRecord& test = stored.test;
  model::MechanisticCuttingTest t;
  t.cutter = cutter_of(tool);
  t.arc = arc_of(tool, test.conditions);
  t.axial_depth_mm = test.conditions.axial_depth_mm;
  t.feed_per_tooth_mm = test.feed_per_tooth_mm;
  t.synchronous_fx_n = test.synchronous_fx_n;
  t.synchronous_fy_n = test.synchronous_fy_n;
  t.spindle_rpm = test.conditions.spindle_rpm;
  t.revolution_peaks_n = test.steady_peaks_n;
  char name[96];
  std::snprintf(name, sizeof name, "cutting_tests[%d] (a_e %.4g mm, f_z %.4g mm)", index,
                test.conditions.radial_depth_mm, test.feed_per_tooth_mm);
  t.name = name;
  return t;
}

double predicted_test_peak_n(const model::MechanisticModel& model, const ToolRecord& tool, const CuttingTestRecord& test) {
  const model::ImmersionArc arc = arc_of(tool, test.conditions);
  const model::EngagedSection section{0.0, test.conditions.axial_depth_mm, std::span<const model::ImmersionArc>(&arc, 1)};
  return model::predicted_peak_force_n(model, std::span<const model::EngagedSection>(&section, 1), cutter_of(tool),
                                       test.feed_per_tooth_mm);
}

model::PredictionInterval predicted_test_interval(const MechanisticFit& fit, const ToolRecord& tool,
                                                  const CuttingTestRecord& test, double revolution_spread_rel) {
  const model::ImmersionArc arc = arc_of(tool, test.conditions);
  const model::EngagedSection section{0.0, test.conditions.axial_depth_mm, std::span<const model::ImmersionArc>(&arc, 1)};
  return model::mechanistic_peak_interval(fit.model, fit.covariance, std::span<const model::EngagedSection>(&section, 1),
                                          cutter_of(tool), test.feed_per_tooth_mm, revolution_spread_rel);
}

MechanisticFitResult fit_mechanistic(const ToolRecord& tool, const std::string& material_name,
                                     const std::vector<StoredCuttingTest>& tests, const MechanisticFitOptions& options) {
  MechanisticFitResult result;
  std::vector<const StoredCuttingTest*> used;
  std::vector<model::MechanisticCuttingTest> identification_tests;
  for (std::size_t i = 0; i < tests.size(); ++i) {
    const CuttingTestRecord& t = tests[i].test;
    if (t.synchronous_fx_n.empty() || t.synchronous_fx_n.size() != t.synchronous_fy_n.size()) {
      ++result.tests_without_signal;
      continue;
    }
    used.push_back(&tests[i]);
    identification_tests.push_back(identification_test(tool, tests[i], static_cast<int>(i)));
  }
  if (used.size() < 2) {
    throw InputError("cutting_tests", "= " + std::to_string(used.size()) + " of " + std::to_string(tests.size()) +
                                          " tests of " + tool.name + " in " + material_name +
                                          " hold the force over a revolution: a mechanistic model needs at least 2 "
                                          "(import each test's force log with feedplan db import-test)");
  }
  result.tests_used = static_cast<int>(used.size());
  if (result.tests_without_signal > 0) {
    result.notes.push_back(std::to_string(result.tests_without_signal) +
                           " stored tests hold only their peaks, not the force over a revolution: left out");
  }
  const model::MechanisticIdentificationOptions identification_options_used = identification_options(tool, options);
  const model::MechanisticIdentification identification =
      model::identify_mechanistic(identification_tests, identification_options_used);

  ModelRecord& record = result.record;
  record.tool_name = tool.name;
  record.material_name = material_name;
  record.kind = ModelKind::kMechanistic;
  record.source = ModelSource::kCuttingTests;
  record.model = test_range(used);
  record.mechanistic = stored_fit(identification);
  for (const StoredCuttingTest* stored : used) {
    result.predicted_peaks_n.push_back(predicted_test_peak_n(identification.model, tool, stored->test));
    result.measured_peaks_n.push_back(stored->test.peak_mean_n);
  }
  peak_statistics(result.predicted_peaks_n, result.measured_peaks_n, record.fit);
  if (options.leave_one_out && !options.identify_sensor && used.size() >= 3) {
    std::vector<int> each(used.size());
    for (std::size_t i = 0; i < used.size(); ++i) each[i] = static_cast<int>(i);
    record.fit.loo_rmse_n = leave_group_out_rmse_n(tool, used, identification_tests, identification, each);
    std::vector<const CuttingTestRecord*> records;
    for (const StoredCuttingTest* stored : used) records.push_back(&stored->test);
    const EngagementGroups groups = engagement_groups(records);
    if (groups.count >= kMinCrossValidationEngagements) {
      record.fit.engagement_cv_rmse_n =
          leave_group_out_rmse_n(tool, used, identification_tests, identification, groups.group);
    }
  }
  if (identification.tests_peak_matched > 0) {
    char note[320];
    std::snprintf(note, sizeof note,
                  "fitted to the force over a revolution and to the mean per-revolution peaks of %d tests: the peaks "
                  "are met within %.3g N RMS (their scatter about the model beyond their standard errors %.3g N); "
                  "the force over a revolution within %.3g N RMS (%.3g N fitted alone)",
                  identification.tests_peak_matched, identification.peak_rms_residual_n, identification.peak_scatter_n,
                  identification.matched_rms_residual_n, identification.rms_residual_n);
    result.notes.push_back(note);
  }
  for (const std::string& what : identification.unidentifiable) result.notes.push_back(what);
  return result;
}

}  // namespace feedplan::model_db
