#include "feedplan/model_db/store_records.hpp"

#include <cctype>
#include <cmath>
#include <optional>
#include <string>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"
#include "feedplan/core/utf8_text.hpp"

namespace feedplan::model_db {
namespace {

// Built with append: GCC 12 warns falsely (-Wrestrict) on "'" + std::string when inlined.
std::string quoted(const std::string& text) {
  std::string shown = "'";
  shown.append(utf8_shown(text)).append("'");
  return shown;
}

// Physical ranges of what the store describes: beyond them a number is a typing slip or an attack,
// and would reach the planner as a tool or a cut that cannot exist (a 1e308 mm end mill was stored).
constexpr double kMaxToolDiameterMm = 1000.0;   // the largest face mills are about 500 mm
constexpr int kMaxFlutes = 100;                 // inserted face mills of the largest diameters
constexpr double kMaxSpindleRpm = 200000.0;     // high-speed spindles reach about 150 000 rev/min
constexpr double kMaxFeedMmPerMin = 200000.0;   // linear-motor machines reach about 120 m/min
constexpr double kMaxDepthMm = 1000.0;          // depths of cut, as the tool diameter

//! A problem unless `text` is UTF-8: it reaches JSON (`db list --json`, exports), which holds nothing else.
void check_utf8(ProblemList& problems, const std::string& field, const std::string& text) {
  if (const std::string problem = utf8_problem(text); !problem.empty()) problems.add_value(field, quoted(text), problem);
}

//! A problem unless `value` is finite and in (0, max], in `unit`.
void check_up_to(ProblemList& problems, const std::string& field, double value, double max, const std::string& unit) {
  if (!(value > 0.0 && value <= max)) {
    problems.add_value(field, shortest_number_text(value), "must be in (0, " + shortest_number_text(max) + "] " + unit);
  }
}

//! The highest hardness of each scale, or nothing for a scale the store does not know.
std::optional<double> max_hardness(const std::string& scale) {
  if (scale == "HB") return 1000.0;  // Brinell with a carbide ball ends near 650 HBW
  if (scale == "HV") return 2500.0;  // hard metals and ceramics
  if (scale == "HRC") return 70.0;
  if (scale == "HRB") return 100.0;
  return std::nullopt;
}

//! A problem unless `value` is a non-empty name without leading or trailing blanks.
void check_name(ProblemList& problems, const std::string& field, const std::string& value) {
  if (const std::string problem = utf8_problem(value); !problem.empty()) {
    problems.add_value(field, quoted(value), problem);
  } else if (value.empty() || std::isspace(static_cast<unsigned char>(value.front())) != 0 ||
      std::isspace(static_cast<unsigned char>(value.back())) != 0) {
    problems.add_value(field, quoted(value), "must be a non-empty name without leading or trailing blanks");
  }
}

}  // namespace

std::string to_string(IsoGroup group) {
  switch (group) {
    case IsoGroup::kP: return "P";
    case IsoGroup::kM: return "M";
    case IsoGroup::kK: return "K";
    case IsoGroup::kN: return "N";
    case IsoGroup::kS: return "S";
    case IsoGroup::kH: return "H";
  }
  return "?";
}

std::optional<IsoGroup> parse_iso_group(std::string_view text) {
  if (text.size() != 1) return std::nullopt;
  switch (std::toupper(static_cast<unsigned char>(text.front()))) {
    case 'P': return IsoGroup::kP;
    case 'M': return IsoGroup::kM;
    case 'K': return IsoGroup::kK;
    case 'N': return IsoGroup::kN;
    case 'S': return IsoGroup::kS;
    case 'H': return IsoGroup::kH;
    default: return std::nullopt;
  }
}

std::string to_string(ModelSource source) {
  switch (source) {
    case ModelSource::kCuttingTests: return "cutting_tests";
    case ModelSource::kLearned: return "learned";
    case ModelSource::kImported: return "imported";
  }
  return "?";
}

std::optional<ModelSource> parse_model_source(std::string_view text) {
  if (text == "cutting_tests") return ModelSource::kCuttingTests;
  if (text == "learned") return ModelSource::kLearned;
  if (text == "imported") return ModelSource::kImported;
  return std::nullopt;
}

std::string to_string(ModelKind kind) {
  switch (kind) {
    case ModelKind::kResponseSurface: return "response_surface";
    case ModelKind::kMechanistic: return "mechanistic";
  }
  return "?";
}

std::optional<ModelKind> parse_model_kind(std::string_view text) {
  if (text == "response_surface" || text == "response-surface") return ModelKind::kResponseSurface;
  if (text == "mechanistic") return ModelKind::kMechanistic;
  return std::nullopt;
}

std::vector<InputProblem> validate(const ToolRecord& tool) {
  ProblemList problems("tools.");
  check_name(problems, "name", tool.name);
  check_up_to(problems, "diameter_mm", tool.diameter_mm, kMaxToolDiameterMm, "mm");
  if (tool.flutes < 1 || tool.flutes > kMaxFlutes) {
    problems.add_value("flutes", std::to_string(tool.flutes), "must be in [1, " + std::to_string(kMaxFlutes) + "]");
  }
  if (!std::isfinite(tool.helix_deg) || tool.helix_deg < 0.0 || tool.helix_deg >= 90.0) {
    problems.add_value("helix_deg", shortest_number_text(tool.helix_deg), "must be in [0, 90)");
  }
  check_utf8(problems, "tool_material", tool.tool_material);
  check_utf8(problems, "coating", tool.coating);
  check_utf8(problems, "notes", tool.notes);
  return problems.take();
}

std::vector<InputProblem> validate(const MaterialRecord& material) {
  ProblemList problems("materials.");
  check_name(problems, "name", material.name);
  const std::string& scale = material.hardness_scale;
  if (const std::optional<double> max = max_hardness(scale)) {
    check_up_to(problems, "hardness_value", material.hardness_value, *max, "on the " + scale + " scale");
  } else {
    problems.positive("hardness_value", material.hardness_value);
    problems.add_value("hardness_scale", quoted(scale), "must be one of HB, HV, HRC, HRB");
  }
  check_utf8(problems, "notes", material.notes);
  return problems.take();
}

std::vector<InputProblem> validate(const ModelRecord& record) {
  ProblemList problems("models.");
  // The model's own numbers as the planner checks them, named after the table; any named quantity is
  // stored (the planner accepts only its own).
  const model::ModelCheckOptions model_checks{"models.", "", model::QuantityRule::kAnyNamed};
  std::vector<InputProblem> list = model::validate(record.model, model_checks);
  const ModelFitStatistics& fit = record.fit;
  if (fit.n < 0) problems.add_value("fit.n", std::to_string(fit.n), "must be ≥ 0");
  problems.non_negative("fit.rmse_n", fit.rmse_n);
  problems.finite("fit.r_squared", fit.r_squared);
  problems.non_negative("fit.loo_rmse_n", fit.loo_rmse_n);
  problems.non_negative("fit.engagement_cv_rmse_n", fit.engagement_cv_rmse_n);
  for (std::size_t i = 0; i < fit.covariance.entries().size(); ++i) {
    problems.finite("fit.covariance[" + std::to_string(i) + "]", fit.covariance.entries()[i]);
  }
  for (std::size_t i = 0; i < fit.standard_errors.size(); ++i) {
    problems.non_negative("fit.standard_errors[" + std::to_string(i) + "]", fit.standard_errors[i]);
  }
  check_utf8(problems, "note", record.note);
  if (record.kind == ModelKind::kMechanistic && !record.mechanistic) {
    problems.add_value("mechanistic", "(none)", "a mechanistic version needs its coefficients");
  }
  if (record.kind == ModelKind::kResponseSurface && record.mechanistic) {
    problems.add_value("mechanistic", "(given)", "a response-surface version holds no mechanistic coefficients");
  }
  if (record.mechanistic) {
    const MechanisticFit& fit_m = *record.mechanistic;
    for (std::size_t i = 0; i < 4; ++i) {
      for (std::size_t j = 0; j < 4; ++j) {
        problems.finite("mechanistic.covariance[" + std::to_string(4 * i + j) + "]", fit_m.covariance[i][j]);
      }
    }
    problems.non_negative("mechanistic.signal_rms_residual_n", fit_m.signal_rms_residual_n);
    problems.non_negative("mechanistic.condition_number", fit_m.condition_number);
    for (std::size_t i = 0; i < fit_m.unidentifiable.size(); ++i) {
      check_utf8(problems, "mechanistic.unidentifiable[" + std::to_string(i) + "]", fit_m.unidentifiable[i]);
    }
  }
  for (auto& problem : problems.take()) list.push_back(std::move(problem));
  if (record.mechanistic) {
    for (auto& problem : model::validate(record.mechanistic->model, "models.mechanistic.")) list.push_back(std::move(problem));
  }
  return list;
}

std::vector<InputProblem> validate(const CuttingTestRecord& test) {
  ProblemList problems("cutting_tests.");
  const CuttingTestConditions& conditions = test.conditions;
  check_name(problems, "tool_name", conditions.tool_name);
  check_name(problems, "material_name", conditions.material_name);
  check_up_to(problems, "spindle_rpm", conditions.spindle_rpm, kMaxSpindleRpm, "rev/min");
  check_up_to(problems, "feed_mm_per_min", conditions.feed_mm_per_min, kMaxFeedMmPerMin, "mm/min");
  check_up_to(problems, "radial_depth_mm", conditions.radial_depth_mm, kMaxDepthMm, "mm");
  check_up_to(problems, "axial_depth_mm", conditions.axial_depth_mm, kMaxDepthMm, "mm");
  check_utf8(problems, "source", test.source);
  for (std::size_t i = 0; i < test.notes.size(); ++i) check_utf8(problems, "notes[" + std::to_string(i) + "]", test.notes[i]);
  problems.non_negative("feed_per_tooth_mm", test.feed_per_tooth_mm);
  problems.non_negative("chip_mm", test.chip_mm);
  problems.non_negative("contact_length_mm", test.contact_length_mm);
  problems.non_negative("peak_mean_n", test.peak_mean_n);
  problems.non_negative("peak_std_n", test.peak_std_n);
  problems.non_negative("peak_min_n", test.peak_min_n);
  problems.non_negative("peak_max_n", test.peak_max_n);
  if (test.revolutions_total < 0) problems.add_value("revolutions_total", std::to_string(test.revolutions_total), "must be ≥ 0");
  if (test.revolutions_used < 0 || test.revolutions_used > test.revolutions_total) {
    problems.add_value("revolutions_used", std::to_string(test.revolutions_used),
                 "must be in [0, revolutions_total = " + std::to_string(test.revolutions_total) + "]");
  }
  for (std::size_t i = 0; i < test.steady_peaks_n.size(); ++i) {
    problems.non_negative("steady_peaks_n[" + std::to_string(i) + "]", test.steady_peaks_n[i]);
  }
  if (test.synchronous_fx_n.size() != test.synchronous_fy_n.size()) {
    problems.add_value("synchronous_fy_n", std::to_string(test.synchronous_fy_n.size()) + " values",
                       "must have as many as synchronous_fx_n (" + std::to_string(test.synchronous_fx_n.size()) + ")");
  }
  for (std::size_t i = 0; i < test.synchronous_fx_n.size(); ++i) {
    problems.finite("synchronous_fx_n[" + std::to_string(i) + "]", test.synchronous_fx_n[i]);
  }
  for (std::size_t i = 0; i < test.synchronous_fy_n.size(); ++i) {
    problems.finite("synchronous_fy_n[" + std::to_string(i) + "]", test.synchronous_fy_n[i]);
  }
  return problems.take();
}

std::vector<InputProblem> validate(const LearningEntry& entry) {
  ProblemList problems("learning_history.");
  if (entry.model_id_before <= 0) {
    problems.add_value("model_id_before", std::to_string(entry.model_id_before), "must name a stored model version");
  }
  if (entry.model_id_after < 0) problems.add_value("model_id_after", std::to_string(entry.model_id_after), "must be ≥ 0");
  if (entry.n_samples < 0) problems.add_value("n_samples", std::to_string(entry.n_samples), "must be ≥ 0");
  problems.non_negative("error_before_n", entry.error_before_n);
  problems.non_negative("error_after_n", entry.error_after_n);
  check_utf8(problems, "part_name", entry.part_name);
  check_utf8(problems, "note", entry.note);
  return problems.take();
}

}  // namespace feedplan::model_db
