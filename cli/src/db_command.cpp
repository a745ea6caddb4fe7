#include "db_command.hpp"

#include "database_path.hpp"
#include "number_flag.hpp"
#include "output_path.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>

#include "feedplan/core/angle.hpp"
#include "feedplan/core/atomic_file.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/geometry/analytic_engagement.hpp"
#include "feedplan/model_db/closest_model.hpp"
#include "feedplan/model_db/cutting_test_import.hpp"
#include "feedplan/model_db/engagement_groups.hpp"
#include "feedplan/model_db/model_exchange.hpp"
#include "feedplan/model_db/model_sync.hpp"
#include "feedplan/model/model_fit.hpp"
#include "feedplan/model_db/mechanistic_fit.hpp"
#include "feedplan/model/model_json.hpp"
#include "feedplan/model/model_prediction.hpp"
#include "feedplan/model/prediction_interval.hpp"
#include "feedplan/model/revolution_spread.hpp"
#include "feedplan/model_db/store.hpp"

namespace feedplan::cli {

namespace {

using nlohmann::json;
namespace mdb = model_db;

mdb::Store open_store(const DbOptions& options, mdb::OpenMode mode = mdb::OpenMode::kExisting) {
  return mdb::Store::open(database_path(options.db_path), mode);
}

geometry::Tool geometry_tool(const mdb::ToolRecord& tool) {
  return geometry::Tool{tool.name, tool.diameter_mm, tool.flutes, tool.helix_deg};
}

const mdb::ToolRecord require_tool(const mdb::Store& store, const std::string& name) {
  if (name.empty()) throw InputError("--tool", "is required: the tool's name in the database (see feedplan db list)");
  auto tool = store.find_tool(name);
  if (!tool) throw InputError("--tool", "= '" + name + "': no such tool in " + store.path().string() + " (see feedplan db list)");
  return *tool;
}

void require_material(const mdb::Store& store, const std::string& name) {
  if (name.empty()) throw InputError("--material", "is required: the material's name in the database");
  if (!store.find_material(name)) {
    throw InputError("--material", "= '" + name + "': no such material in " + store.path().string() + " (see feedplan db list)");
  }
}

json mechanistic_json(const mdb::MechanisticFit& fit) {
  const model::MechanisticModel& k = fit.model;
  return json{{"ktc_n_per_mm2", k.ktc_n_per_mm2},
              {"krc_n_per_mm2", k.krc_n_per_mm2},
              {"kac_n_per_mm2", k.kac_n_per_mm2},
              {"kte_n_per_mm", k.kte_n_per_mm},
              {"kre_n_per_mm", k.kre_n_per_mm},
              {"kae_n_per_mm", k.kae_n_per_mm},
              {"size_exponent", k.size_exponent},
              {"runout_mm", k.runout_mm},
              {"helix_deg", k.helix_deg ? json(*k.helix_deg) : json(nullptr)},
              {"standard_errors", {std::sqrt(fit.covariance[0][0]), std::sqrt(fit.covariance[1][1]),
                                   std::sqrt(fit.covariance[2][2]), std::sqrt(fit.covariance[3][3])}},
              {"signal_rms_residual_n", fit.signal_rms_residual_n},
              {"condition_number", fit.condition_number},
              {"identified", fit.identified},
              {"unidentifiable", fit.unidentifiable}};
}

json model_json(const mdb::ModelRecord& m) {
  const auto& r = m.model;
  json out = {{"id", m.id},
              {"tool", m.tool_name},
              {"material", m.material_name},
              {"version", m.version},
              {"kind", mdb::to_string(m.kind)},
              {"active", m.active},
              {"source", mdb::to_string(m.source)},
              {"created_at", m.created_at},
              {"note", m.note},
              {"beta_n", r.beta},
              {"standard_errors_n", m.fit.standard_errors},
              {"chip_center_mm", r.chip_center_mm},
              {"chip_scale_mm", r.chip_scale_mm},
              {"contact_length_center_mm", r.contact_length_center_mm},
              {"contact_length_scale_mm", r.contact_length_scale_mm},
              {"fitted_range", model::to_json(r.range)},
              {"axial_depth_mm", r.axial_depth_mm},
              {"spindle_rpm", r.spindle_rpm},
              {"n", m.fit.n},
              {"rmse_n", m.fit.rmse_n},
              {"r_squared", m.fit.r_squared},
              {"loo_rmse_n", m.fit.loo_rmse_n},
              {"engagement_cv_rmse_n", m.fit.engagement_cv_rmse_n}};
  if (m.parent_version) out["parent_version"] = *m.parent_version;
  if (m.mechanistic) {
    // A mechanistic version's response-surface fields are only the tests' range: not a model to show.
    for (const char* key : {"beta_n", "standard_errors_n", "chip_center_mm", "chip_scale_mm", "contact_length_center_mm",
                            "contact_length_scale_mm"}) {
      out.erase(key);
    }
    out["mechanistic"] = mechanistic_json(*m.mechanistic);
  }
  return out;
}

void print_mechanistic(const mdb::MechanisticFit& fit) {
  const model::MechanisticModel& k = fit.model;
  const auto sd = [&fit](int i) { return std::sqrt(fit.covariance[i][i]); };
  std::printf("  K_tc %10.1f N/mm²  ± %.1f\n", k.ktc_n_per_mm2, sd(0));
  std::printf("  K_rc %10.1f N/mm²  ± %.1f\n", k.krc_n_per_mm2, sd(1));
  std::printf("  K_te %10.2f N/mm   ± %.2f\n", k.kte_n_per_mm, sd(2));
  std::printf("  K_re %10.2f N/mm   ± %.2f\n", k.kre_n_per_mm, sd(3));
  if (k.size_exponent > 0.0) {
    std::printf("  size effect (h / %.3g mm)^-%.3g\n", k.size_reference_chip_mm, k.size_exponent);
  }
  if (k.helix_deg) std::printf("  helix %.2f deg (identified from the tests)\n", *k.helix_deg);
  if (!k.runout_mm.empty()) {
    std::printf("  runout per tooth");
    for (double r : k.runout_mm) std::printf(" %.1f", 1000.0 * r);
    std::printf(" µm\n");
  }
  std::printf("  synchronous force residual %.2f N RMS, condition number %.3g%s\n", fit.signal_rms_residual_n,
              fit.condition_number, fit.identified ? "" : " (poorly determined)");
  for (const auto& what : fit.unidentifiable) std::printf("  not identified: %s\n", what.c_str());
}

// ", leave-one-engagement-out RMSE 12.3 N", or nothing when it was not computed.
std::string engagement_cv_text(const mdb::ModelFitStatistics& fit) {
  if (!(fit.engagement_cv_rmse_n > 0.0)) return {};
  char text[64];
  std::snprintf(text, sizeof text, ", leave-one-engagement-out RMSE %.2f N", fit.engagement_cv_rmse_n);
  return text;
}

void print_model(const mdb::ModelRecord& m) {
  const auto& r = m.model;
  std::printf("model %s in %s, version %d, %s%s (%s, %s)%s%s\n", m.tool_name.c_str(), m.material_name.c_str(),
              m.version, mdb::to_string(m.kind).c_str(), m.active ? " [active]" : "", mdb::to_string(m.source).c_str(),
              m.created_at.c_str(), m.note.empty() ? "" : ": ", m.note.c_str());
  if (m.mechanistic) {
    print_mechanistic(*m.mechanistic);
    std::printf("  identified on t_m %.4g–%.4g mm, L %.4g–%.4g mm, a_p %.4g mm, %.0f rpm\n", r.range.chip_min_mm,
                r.range.chip_max_mm, r.range.contact_length_min_mm, r.range.contact_length_max_mm, r.axial_depth_mm,
                r.spindle_rpm);
    std::printf("  tests' mean peaks: n %d, RMSE %.2f N, R² %.4f, leave-one-out RMSE %.2f N%s\n", m.fit.n, m.fit.rmse_n,
                m.fit.r_squared, m.fit.loo_rmse_n, engagement_cv_text(m.fit).c_str());
    return;
  }
  static const char* names[6] = {"beta0", "beta1", "beta2", "beta11", "beta22", "beta12"};
  for (int i = 0; i < 6; ++i) {
    std::printf("  %-7s %12.3f N  ± %.3f\n", names[i], r.beta[i], m.fit.standard_errors[i]);
  }
  std::printf("  X1 = (t_m - %.5g) / %.5g mm, X2 = (L - %.5g) / %.5g mm\n", r.chip_center_mm, r.chip_scale_mm,
              r.contact_length_center_mm, r.contact_length_scale_mm);
  std::printf("  fitted on t_m %.4g–%.4g mm, L %.4g–%.4g mm, a_p %.4g mm, %.0f rpm\n", r.range.chip_min_mm,
              r.range.chip_max_mm, r.range.contact_length_min_mm, r.range.contact_length_max_mm, r.axial_depth_mm,
              r.spindle_rpm);
  std::printf("  n %d, RMSE %.2f N, R² %.4f, leave-one-out RMSE %.2f N%s\n", m.fit.n, m.fit.rmse_n, m.fit.r_squared,
              m.fit.loo_rmse_n, engagement_cv_text(m.fit).c_str());
}

// Straight-cut model inputs for radial depth a_e and feed per tooth f_z (docs/method.md §5.1).
std::pair<double, double> straight_cut_inputs(double tool_radius_mm, double radial_depth_mm, double feed_per_tooth_mm) {
  const double engagement = radial_depth_mm >= 2.0 * tool_radius_mm
                                ? kPi
                                : geometry::straight_engagement_rad(tool_radius_mm, radial_depth_mm);
  return {feed_per_tooth_mm * geometry::steady_chip_factor(engagement), tool_radius_mm * engagement};
}

mdb::CutMode parse_mode(const std::string& text) {
  if (text == "down") return mdb::CutMode::kDown;
  if (text == "up") return mdb::CutMode::kUp;
  if (text == "slot") return mdb::CutMode::kSlot;
  throw InputError("--mode", "= '" + text + "': must be down, up or slot");
}

std::string mode_text(mdb::CutMode mode) {
  return mode == mdb::CutMode::kDown ? "down" : mode == mdb::CutMode::kUp ? "up" : "slot";
}

int run_init(const DbOptions& o) {
  const mdb::Store store = open_store(o, mdb::OpenMode::kCreate);
  if (o.json) {
    std::cout << json{{"db", store.path().string()}, {"schema_version", store.schema_version()}}.dump(2) << "\n";
  } else {
    std::printf("database %s ready (schema version %d)\n", store.path().string().c_str(), store.schema_version());
  }
  return 0;
}

int run_list(const DbOptions& o) {
  const mdb::Store store = open_store(o, mdb::OpenMode::kReadOnly);
  const auto tools = store.tools();
  const auto materials = store.materials();
  auto models = store.active_models(mdb::ModelKind::kResponseSurface);
  for (auto& m : store.active_models(mdb::ModelKind::kMechanistic)) models.push_back(std::move(m));
  std::stable_sort(models.begin(), models.end(), [](const auto& a, const auto& b) {
    return std::tie(a.tool_name, a.material_name) < std::tie(b.tool_name, b.material_name);
  });
  if (o.json) {
    json out = {{"db", store.path().string()}, {"tools", json::array()}, {"materials", json::array()}, {"models", json::array()}};
    for (const auto& t : tools) {
      out["tools"].push_back({{"name", t.name}, {"diameter_mm", t.diameter_mm}, {"flutes", t.flutes}, {"helix_deg", t.helix_deg},
                              {"tool_material", t.tool_material}, {"coating", t.coating}});
    }
    for (const auto& m : materials) {
      out["materials"].push_back({{"name", m.name}, {"iso_group", mdb::to_string(m.iso_group)},
                                  {"hardness", m.hardness_value}, {"hardness_scale", m.hardness_scale}});
    }
    for (const auto& m : models) out["models"].push_back(model_json(m));
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  std::printf("%s\n\ntools\n", store.path().string().c_str());
  for (const auto& t : tools) {
    std::printf("  %-20s D%-6.4g %d flutes, helix %.3g deg, %s %s\n", t.name.c_str(), t.diameter_mm, t.flutes, t.helix_deg,
                t.tool_material.c_str(), t.coating.c_str());
  }
  std::printf("\nmaterials\n");
  for (const auto& m : materials) {
    std::printf("  %-20s ISO %s, %.4g %s\n", m.name.c_str(), mdb::to_string(m.iso_group).c_str(), m.hardness_value,
                m.hardness_scale.c_str());
  }
  std::printf("\nactive models\n");
  std::printf("  %-20s %-12s %4s %-16s %-13s %6s %9s %8s %9s\n", "tool", "material", "ver", "kind", "source", "n",
              "rmse_n", "r2", "loo_rmse");
  for (const auto& m : models) {
    std::printf("  %-20s %-12s %4d %-16s %-13s %6d %9.2f %8.4f %9.2f\n", m.tool_name.c_str(), m.material_name.c_str(),
                m.version, mdb::to_string(m.kind).c_str(), mdb::to_string(m.source).c_str(), m.fit.n, m.fit.rmse_n,
                m.fit.r_squared, m.fit.loo_rmse_n);
  }
  return 0;
}

int run_show(const DbOptions& o) {
  const mdb::Store store = open_store(o, mdb::OpenMode::kReadOnly);
  require_tool(store, o.tool);
  require_material(store, o.material);
  const auto versions = store.models_for(o.tool, o.material);
  const mdb::ModelRecord* chosen = nullptr;
  const auto show_kind = mdb::parse_model_kind(o.kind);
  if (!o.version && o.kind != "both" && !show_kind) {
    throw InputError("--kind", "= '" + o.kind + "': must be mechanistic or response-surface");
  }
  for (const auto& m : versions) {
    const bool kind_matches = !show_kind || m.kind == *show_kind;
    if ((!o.version && m.active && kind_matches && !chosen) || (o.version && m.version == *o.version)) chosen = &m;
  }
  if (!chosen) {
    throw InputError(o.version ? "--version" : "--tool/--material",
                     o.version ? "= " + std::to_string(*o.version) + ": no such version of " + o.tool + " in " + o.material
                               : "no model for " + o.tool + " in " + o.material + " (fit one: feedplan db fit)");
  }
  const auto tests = store.cutting_tests(o.tool, o.material);
  if (o.json) {
    json out = model_json(*chosen);
    if (!chosen->mechanistic) out["covariance_n2"] = chosen->fit.covariance.entries();
    out["cutting_tests"] = tests.size();
    std::cout << out.dump(2) << "\n";
  } else {
    print_model(*chosen);
    std::printf("  %zu cutting tests stored; %zu versions\n", tests.size(), versions.size());
  }
  return 0;
}

int run_add_tool(const DbOptions& o) {
  mdb::Store store = open_store(o);
  mdb::ToolRecord tool;
  tool.name = o.name;
  tool.diameter_mm = o.diameter_mm;
  tool.flutes = o.flutes;
  tool.helix_deg = o.helix_deg;
  tool.tool_material = o.tool_material;
  tool.coating = o.coating;
  tool.notes = o.notes;
  mdb::ToolRecord added;
  with_flag_names({{"tools.diameter_mm", "--diameter-mm"}, {"tools.flutes", "--flutes"}, {"tools.helix_deg", "--helix-deg"}},
                  [&] { added = store.add_tool(tool); });
  if (o.json) {
    std::cout << json{{"tool", added.name}, {"id", added.id}}.dump(2) << "\n";
  } else {
    std::printf("tool %s added\n", added.name.c_str());
  }
  return 0;
}

int run_add_material(const DbOptions& o) {
  mdb::Store store = open_store(o);
  mdb::MaterialRecord material;
  material.name = o.name;
  const auto group = mdb::parse_iso_group(o.iso_group);
  if (!group) throw InputError("--iso-group", "= '" + o.iso_group + "': must be one of P, M, K, N, S, H (ISO 513)");
  material.iso_group = *group;
  std::istringstream hardness(o.hardness);
  if (!(hardness >> material.hardness_value)) {
    throw InputError("--hardness", "= '" + o.hardness + "': expected a number and a scale, e.g. \"200 HB\"");
  }
  hardness >> material.hardness_scale;
  if (material.hardness_scale.empty()) material.hardness_scale = "HB";
  material.notes = o.notes;
  mdb::MaterialRecord added;
  with_flag_names({{"materials.hardness_value", "--hardness"}, {"materials.hardness_scale", "--hardness"}},
                  [&] { added = store.add_material(material); });
  if (o.json) {
    std::cout << json{{"material", added.name}, {"id", added.id}}.dump(2) << "\n";
  } else {
    std::printf("material %s added\n", added.name.c_str());
  }
  return 0;
}

int run_import_test(const DbOptions& o) {
  mdb::Store store = open_store(o);
  const mdb::ToolRecord tool = require_tool(store, o.tool);
  require_material(store, o.material);
  mdb::CuttingTestConditions conditions;
  conditions.tool_name = o.tool;
  conditions.material_name = o.material;
  conditions.spindle_rpm = o.spindle_rpm;
  conditions.feed_mm_per_min = o.feed_mm_per_min;
  conditions.radial_depth_mm = o.radial_depth_mm;
  conditions.axial_depth_mm = o.axial_depth_mm;
  conditions.mode = parse_mode(o.mode);
  mdb::CuttingTestRecord record;
  with_flag_names({{"conditions.spindle_rpm", "--spindle-rpm"},
                   {"conditions.feed_mm_per_min", "--feed-mm-per-min"},
                   {"conditions.radial_depth_mm", "--radial-depth-mm"},
                   {"conditions.axial_depth_mm", "--axial-depth-mm"}},
                  [&] { record = mdb::import_cutting_test(o.log_path, conditions, geometry_tool(tool)); });
  if (!o.no_store) store.add_cutting_test(record);
  if (o.json) {
    std::cout << json{{"log", o.log_path},
                      {"stored", !o.no_store},
                      {"feed_per_tooth_mm", record.feed_per_tooth_mm},
                      {"chip_mm", record.chip_mm},
                      {"contact_length_mm", record.contact_length_mm},
                      {"peak_mean_n", record.peak_mean_n},
                      {"peak_std_n", record.peak_std_n},
                      {"peak_min_n", record.peak_min_n},
                      {"peak_max_n", record.peak_max_n},
                      {"revolutions_total", record.revolutions_total},
                      {"revolutions_used", record.revolutions_used},
                      {"notes", record.notes}}
                     .dump(2)
              << "\n";
  } else {
    std::printf("%s: %s milling, f_z %.4g mm, t_m %.4g mm, L %.4g mm\n", o.log_path.c_str(), mode_text(conditions.mode).c_str(),
                record.feed_per_tooth_mm, record.chip_mm, record.contact_length_mm);
    std::printf("steady per-revolution peak %.1f N ± %.1f N (min %.1f, max %.1f) over %d of %d revolutions%s\n",
                record.peak_mean_n, record.peak_std_n, record.peak_min_n, record.peak_max_n, record.revolutions_used,
                record.revolutions_total, o.no_store ? " (not stored)" : "");
    for (const auto& note : record.notes) std::printf("note: %s\n", note.c_str());
  }
  return 0;
}

model::FitOptions fit_options(const DbOptions& o) {
  model::FitOptions options;
  if (o.loss == "huber") {
    options.loss = model::FitOptions::kHuber;
  } else if (o.loss == "cauchy") {
    options.loss = model::FitOptions::kCauchy;
  } else if (o.loss == "squared") {
    options.loss = model::FitOptions::kSquared;
  } else {
    throw InputError("--loss", "= '" + o.loss + "': must be huber, cauchy or squared");
  }
  return options;
}

// The response surface fitted on the pair's tests, as a version to store (nothing when the tests cannot
// fit one: the message goes to `refusal`).
std::optional<mdb::ModelRecord> fit_response_surface(const DbOptions& o, const std::vector<mdb::StoredCuttingTest>& tests,
                                                     std::vector<std::string>& notes, std::string& refusal) {
  const model::FitOptions options = fit_options(o);
  std::vector<model::FitSample> samples;
  std::vector<int> engagement;  // per sample
  std::vector<const mdb::CuttingTestRecord*> records;
  for (const auto& stored : tests) records.push_back(&stored.test);
  const mdb::EngagementGroups groups = mdb::engagement_groups(records);
  std::map<double, int> axial_depths, speeds;
  for (std::size_t i = 0; i < tests.size(); ++i) {
    const auto& t = tests[i].test;
    if (o.per_revolution) {
      for (const double peak : t.steady_peaks_n) samples.push_back({t.chip_mm, t.contact_length_mm, peak});
      engagement.resize(samples.size(), groups.group[i]);
    } else {
      samples.push_back({t.chip_mm, t.contact_length_mm, t.peak_mean_n});
      engagement.push_back(groups.group[i]);
    }
    ++axial_depths[t.conditions.axial_depth_mm];
    ++speeds[t.conditions.spindle_rpm];
  }
  const model::FitResult fit = model::fit_model(samples, options);
  if (fit.status == model::FitStatus::kInsufficientData || fit.status == model::FitStatus::kNotConverged) {
    refusal = fit.message;
    return std::nullopt;
  }
  mdb::ModelRecord record;
  record.tool_name = o.tool;
  record.material_name = o.material;
  record.model = fit.model;
  record.model.axial_depth_mm = axial_depths.size() == 1 ? axial_depths.begin()->first : 0.0;
  record.model.spindle_rpm = speeds.size() == 1 ? speeds.begin()->first : 0.0;
  record.fit.n = fit.n;
  record.fit.rmse_n = fit.rmse_n;
  record.fit.r_squared = fit.r_squared;
  record.fit.covariance = fit.covariance;
  record.fit.standard_errors = fit.standard_error_n;
  record.fit.loo_rmse_n = fit.loo_rmse_n;
  if (groups.count >= mdb::kMinCrossValidationEngagements) {
    record.fit.engagement_cv_rmse_n = model::leave_group_out_rmse_n(samples, engagement, options);
  }
  record.source = mdb::ModelSource::kCuttingTests;
  record.note = o.note.empty() ? fit.message : o.note + (fit.status == model::FitStatus::kOk ? "" : "; " + fit.message);
  if (fit.status != model::FitStatus::kOk) notes.push_back("response surface: " + fit.message);
  return record;
}

// The mechanistic model identified from the pair's tests, as a version to store.
mdb::ModelRecord fit_mechanistic_version(const DbOptions& o, const mdb::ToolRecord& tool,
                                         const std::vector<mdb::StoredCuttingTest>& tests,
                                         std::vector<std::string>& notes, json& per_test) {
  mdb::MechanisticFitOptions options;
  options.identify_runout = !o.no_runout;
  options.identify_helix = !o.no_helix;
  options.identify_size_effect = !o.no_size_effect;
  options.identify_sensor = o.sensor;
  options.match_peaks = !o.no_peak_matching;
  mdb::MechanisticFitResult fit = mdb::fit_mechanistic(tool, o.material, tests, options);
  for (const auto& note : fit.notes) notes.push_back("mechanistic: " + note);
  per_test = json::array();
  for (std::size_t i = 0; i < fit.predicted_peaks_n.size(); ++i) {
    per_test.push_back({{"measured_peak_n", fit.measured_peaks_n[i]}, {"predicted_peak_n", fit.predicted_peaks_n[i]}});
  }
  char summary[160];
  std::snprintf(summary, sizeof summary, "identified from %d cutting tests%s; tests' mean peaks RMSE %.2f N, R² %.4f",
                fit.tests_used,
                fit.record.mechanistic->model.helix_deg ? " with runout and helix"
                : fit.record.mechanistic->model.runout_mm.empty() ? "" : " with runout",
                fit.record.fit.rmse_n, fit.record.fit.r_squared);
  fit.record.note = o.note.empty() ? summary : o.note;
  return fit.record;
}

int run_fit(const DbOptions& o) {
  mdb::Store store = open_store(o);
  const mdb::ToolRecord tool = require_tool(store, o.tool);
  require_material(store, o.material);
  const auto kind = o.kind == "both" ? std::nullopt : mdb::parse_model_kind(o.kind);
  if (o.kind != "both" && !kind) {
    throw InputError("--kind", "= '" + o.kind + "': must be mechanistic, response-surface or both");
  }
  fit_options(o);  // --loss checked before any work
  const auto tests = store.cutting_tests(o.tool, o.material);
  std::vector<std::string> notes;
  std::vector<mdb::ModelRecord> records;
  json per_test;
  // Which kinds to fit, decided once from the flag's text.
  const bool one_kind = o.kind != "both";
  const bool fit_surface = !one_kind || mdb::parse_model_kind(o.kind) == mdb::ModelKind::kResponseSurface;
  const bool fit_mechanistic = !one_kind || mdb::parse_model_kind(o.kind) == mdb::ModelKind::kMechanistic;
  if (fit_surface) {
    std::string refusal;
    if (auto record = fit_response_surface(o, tests, notes, refusal)) {
      records.push_back(std::move(*record));
    } else if (one_kind) {
      std::cerr << "feedplan: no model stored: " << refusal << "\n";
      return 1;
    } else {
      notes.push_back("response surface: not fitted: " + refusal);
    }
  }
  if (fit_mechanistic) {
    const bool has_signal = std::any_of(tests.begin(), tests.end(),
                                        [](const auto& t) { return !t.test.synchronous_fx_n.empty(); });
    if (!one_kind && !has_signal) {
      notes.push_back("mechanistic: not identified: no stored test holds the force over a revolution (tests imported "
                      "before this feedplan kept it: import their logs again with feedplan db import-test)");
    } else if (one_kind) {
      records.push_back(fit_mechanistic_version(o, tool, tests, notes, per_test));
    } else {
      try {
        records.push_back(fit_mechanistic_version(o, tool, tests, notes, per_test));
      } catch (const InputError& error) {
        notes.push_back(std::string("mechanistic: not identified: ") + error.what());
      }
    }
  }
  if (records.empty()) {
    std::cerr << "feedplan: no model stored:\n";
    for (const auto& note : notes) std::cerr << "  " << note << "\n";
    return 1;
  }
  const std::vector<mdb::ModelRecord> stored = store.add_models(records);
  if (o.json) {
    json out = {{"models", json::array()}, {"notes", notes}};
    if (!per_test.is_null()) out["mechanistic_tests"] = per_test;
    for (const auto& m : stored) out["models"].push_back(model_json(m));
    std::cout << out.dump(2) << "\n";
  } else {
    for (const auto& m : stored) print_model(m);
    for (const auto& note : notes) std::printf("note: %s\n", note.c_str());
  }
  return 0;
}

// The leave-one-out RMS error of `version` relative to the mean peak of the tests it was fitted on (0 when
// unknown).
double cross_validated_rel(const mdb::ModelRecord& version, const std::vector<mdb::StoredCuttingTest>& tests) {
  double sum = 0.0;
  for (const auto& t : tests) sum += t.test.peak_mean_n;
  const double mean_n = tests.empty() ? 0.0 : sum / static_cast<double>(tests.size());
  return mean_n > 0.0 ? version.fit.loo_rmse_n / mean_n : 0.0;
}

// The pooled revolution-to-revolution spread of the pair's stored tests (0 when none has two peaks).
double tests_spread_rel(const std::vector<mdb::StoredCuttingTest>& tests) {
  std::vector<std::vector<double>> peaks;
  for (const auto& t : tests) {
    if (t.test.steady_peaks_n.size() >= 2) peaks.push_back(t.test.steady_peaks_n);
  }
  return peaks.empty() ? 0.0 : model::pooled_revolution_spread_rel(peaks);
}

json interval_json(const model::PredictionInterval& i) {
  return json{{"predicted_n", i.predicted_n}, {"lower_n", i.lower_n}, {"upper_n", i.upper_n},
              {"fit_sd_n", i.fit_sd_n}, {"spread_sd_n", i.spread_sd_n}};
}

std::string interval_text(const model::PredictionInterval& i) {
  char text[200];
  std::snprintf(text, sizeof text,
                "%.1f N, 95 %% of revolutions in %.1f … %.1f N (model σ %.1f N: fit or leave-one-out, the larger; "
                "revolution spread σ %.1f N)",
                i.predicted_n, i.lower_n, i.upper_n, i.fit_sd_n, i.spread_sd_n);
  return text;
}

int run_predict(const DbOptions& o) {
  const mdb::Store store = open_store(o, mdb::OpenMode::kReadOnly);
  const mdb::ToolRecord tool = require_tool(store, o.tool);
  require_material(store, o.material);
  const mdb::ClosestModel closest = mdb::closest_model(store, o.tool, o.material);
  if (closest.status != mdb::ClosestModelStatus::kFound || !closest.model) throw InputError("--tool/--material", "no model in " + store.path().string() + ": " + closest.explanation);
  if (!(std::isfinite(o.radial_depth_mm) && o.radial_depth_mm > 0 && o.radial_depth_mm <= tool.diameter_mm)) {
    throw InputError("--radial-depth-mm", "= " + shortest_number_text(o.radial_depth_mm) + ": must be in (0, tool diameter " +
                                              shortest_number_text(tool.diameter_mm) + "]");
  }
  if (!(std::isfinite(o.feed_per_tooth_mm) && o.feed_per_tooth_mm > 0)) {
    throw InputError("--feed-per-tooth-mm", "= " + shortest_number_text(o.feed_per_tooth_mm) + ": must be a finite number > 0");
  }
  const mdb::CutMode mode = parse_mode(o.mode);
  if (closest.match != mdb::ModelMatch::kExact) {
    std::cerr << "feedplan: warning: no model for " << o.tool << " in " << o.material << "; " << closest.explanation << "\n";
  }
  const mdb::ModelRecord& surface = *closest.model;
  const auto tests = store.cutting_tests(surface.tool_name, surface.material_name);
  const double spread_rel = tests_spread_rel(tests);
  const auto [chip, contact] = straight_cut_inputs(0.5 * tool.diameter_mm, o.radial_depth_mm, o.feed_per_tooth_mm);
  const model::ForcePrediction p = model::predict(surface.model, chip, contact);
  const model::PredictionInterval surface_interval = model::with_cross_validated_error(
      model::response_surface_interval(surface.model, surface.fit.covariance, chip, contact, spread_rel),
      cross_validated_rel(surface, tests));

  // The mechanistic version of the same pair, on the straight cut's arc with the asked tool's cutter.
  std::optional<model::PredictionInterval> mechanistic_interval;
  const auto mechanistic = store.active_model(surface.tool_name, surface.material_name, mdb::ModelKind::kMechanistic);
  const bool fits_cutter = mechanistic && (mechanistic->mechanistic->model.runout_mm.empty() ||
                                           mechanistic->mechanistic->model.runout_mm.size() ==
                                               static_cast<std::size_t>(tool.flutes));
  if (fits_cutter) {
    mdb::CuttingTestRecord cut;
    cut.conditions.radial_depth_mm = o.radial_depth_mm;
    cut.conditions.axial_depth_mm = surface.model.axial_depth_mm > 0.0 ? surface.model.axial_depth_mm : tool.diameter_mm;
    cut.conditions.mode = mode;
    cut.feed_per_tooth_mm = o.feed_per_tooth_mm;
    mechanistic_interval = model::with_cross_validated_error(
        mdb::predicted_test_interval(*mechanistic->mechanistic, tool, cut, spread_rel),
        cross_validated_rel(*mechanistic, tests));
  }
  if (o.json) {
    json out{{"model", model_json(surface)},
             {"match", closest.explanation},
             {"chip_mm", chip},
             {"contact_length_mm", contact},
             {"force_n", p.force_n},
             {"interval", interval_json(surface_interval)},
             {"revolution_spread_rel", spread_rel},
             {"chip_outside_fitted_range", p.chip_outside},
             {"contact_length_outside_fitted_range", p.contact_length_outside}};
    if (mechanistic_interval) {
      out["mechanistic"] = {{"model", model_json(*mechanistic)}, {"interval", interval_json(*mechanistic_interval)}};
    }
    std::cout << out.dump(2) << "\n";
  } else {
    std::printf("model: %s\n", closest.explanation.c_str());
    std::printf("t_m %.4g mm, L %.4g mm: predicted per-revolution peak %s%s\n", chip, contact,
                interval_text(surface_interval).c_str(),
                p.chip_outside || p.contact_length_outside ? " (outside the fitted range: extrapolated)" : "");
    if (mechanistic_interval) {
      std::printf("mechanistic v%d (%s milling, a_p %.4g mm): %s\n", mechanistic->version, mode_text(mode).c_str(),
                  surface.model.axial_depth_mm > 0.0 ? surface.model.axial_depth_mm : tool.diameter_mm,
                  interval_text(*mechanistic_interval).c_str());
    }
  }
  return 0;
}

int run_history(const DbOptions& o) {
  const mdb::Store store = open_store(o, mdb::OpenMode::kReadOnly);
  require_tool(store, o.tool);
  require_material(store, o.material);
  const auto versions = store.models_for(o.tool, o.material);
  const auto events = store.activation_history(o.tool, o.material);
  const auto learning = store.learning_history(o.tool, o.material);
  if (o.json) {
    json out = {{"versions", json::array()}, {"activations", json::array()}, {"learning", json::array()}};
    for (const auto& m : versions) out["versions"].push_back(model_json(m));
    for (const auto& e : events) {
      out["activations"].push_back({{"version", e.version}, {"created_at", e.created_at},
                                    {"previous_version", e.previous_version ? json(*e.previous_version) : json(nullptr)}});
    }
    for (const auto& l : learning) {
      out["learning"].push_back({{"part", l.part_name}, {"n_samples", l.n_samples}, {"error_before_n", l.error_before_n},
                                 {"error_after_n", l.error_after_n}, {"created_at", l.created_at}});
    }
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  std::printf("%s in %s: %zu versions\n", o.tool.c_str(), o.material.c_str(), versions.size());
  for (const auto& m : versions) {
    std::printf("  v%-3d %s %-16s %-13s n %-4d RMSE %7.2f N %s%s\n", m.version, m.created_at.c_str(),
                mdb::to_string(m.kind).c_str(), mdb::to_string(m.source).c_str(), m.fit.n, m.fit.rmse_n,
                m.active ? "[active] " : "", m.note.c_str());
  }
  for (const auto& e : events) {
    std::printf("  %s: version %d made active%s\n", e.created_at.c_str(), e.version,
                e.previous_version ? (" (was " + std::to_string(*e.previous_version) + ")").c_str() : "");
  }
  for (const auto& l : learning) {
    std::printf("  %s: learned from %s, %d samples, RMS error %.1f → %.1f N\n", l.created_at.c_str(), l.part_name.c_str(),
                l.n_samples, l.error_before_n, l.error_after_n);
  }
  return 0;
}

int run_rollback(const DbOptions& o) {
  mdb::Store store = open_store(o);
  require_tool(store, o.tool);
  require_material(store, o.material);
  mdb::ModelRecord active;
  with_flag_names({{"rollback.version", "--version"}}, [&] { active = store.rollback(o.tool, o.material, *o.version); });
  if (o.json) {
    std::cout << model_json(active).dump(2) << "\n";
  } else {
    std::printf("%s in %s: version %d is active again\n", o.tool.c_str(), o.material.c_str(), active.version);
  }
  return 0;
}

// FILE and the database must be two files: export would overwrite the database, import read it as JSON.
void check_exchange_file(const DbOptions& o, bool exporting) {
  std::vector<InputProblem> problems;
  const NamedPath file{"FILE", o.file};
  const NamedPath db{"--db", database_path(o.db_path)};
  if (exporting) {
    check_outputs({db}, {file}, problems);
  } else {
    check_outputs({file}, {db}, problems);
  }
  if (!problems.empty()) throw InputError(std::move(problems));
}

int run_export(const DbOptions& o) {
  check_exchange_file(o, true);
  const mdb::Store store = open_store(o, mdb::OpenMode::kReadOnly);
  mdb::ExportOptions options;
  options.active_models_only = !o.all_versions;
  const std::string text = mdb::export_json(store, options);
  if (const std::string error = write_file_atomically(o.file, text); !error.empty()) {
    std::cerr << "feedplan: failed: " << error << "\n";
    return 1;
  }
  if (!o.json) std::printf("exported %s to %s\n", store.path().string().c_str(), o.file.c_str());
  return 0;
}

// What an import or sync wrote and skipped, in one line.
std::string summary_text(const mdb::ImportSummary& s) {
  std::ostringstream text;
  text << s.tools_added << " tools, " << s.materials_added << " materials, " << s.models_added << " model versions, "
       << s.cutting_tests_added << " cutting tests, " << s.learning_entries_added << " learning entries added; "
       << s.tools_skipped + s.materials_skipped + s.models_skipped + s.cutting_tests_skipped + s.learning_entries_skipped
       << " identical records skipped";
  return text.str();
}

int run_import(const DbOptions& o) {
  check_exchange_file(o, false);
  mdb::Store store = open_store(o, mdb::OpenMode::kCreate);
  const mdb::ImportSummary s = mdb::import_from_file(store, o.file);
  const std::string text = summary_text(s);
  if (o.json) {
    std::cout << json{{"imported", o.file}, {"summary", text}, {"messages", s.messages}}.dump(2) << "\n";
  } else {
    std::printf("imported %s into %s: %s\n", o.file.c_str(), store.path().string().c_str(), text.c_str());
    for (const auto& message : s.messages) std::printf("  %s\n", message.c_str());
  }
  return 0;
}

// --from and --to must be two databases: syncing one into itself would only re-read it.
void check_sync_places(const DbOptions& o) {
  std::vector<InputProblem> problems;
  if (!mdb::is_server_url(o.sync_from) && !mdb::is_server_url(o.sync_to)) {
    check_outputs({{"--from", o.sync_from}}, {{"--to", o.sync_to}}, problems);
  } else if (o.sync_from == o.sync_to) {
    problems.push_back({"--to", "= '" + mdb::shown_location(o.sync_to) + "': is the same database as --from"});
  }
  if (!problems.empty()) throw InputError(std::move(problems));
}

int run_sync(const DbOptions& o) {
  check_sync_places(o);
  const mdb::Store from = mdb::Store::open(o.sync_from, mdb::OpenMode::kReadOnly);
  mdb::Store to = mdb::Store::open(o.sync_to, mdb::OpenMode::kCreate);
  const mdb::ImportSummary s = mdb::sync_models(from, to);
  const std::string text = summary_text(s);
  if (o.json) {
    std::cout << json{{"from", from.path().string()}, {"to", to.path().string()}, {"summary", text},
                      {"messages", s.messages}}.dump(2)
              << "\n";
  } else {
    std::printf("synced %s into %s: %s\n", from.path().string().c_str(), to.path().string().c_str(), text.c_str());
    for (const auto& message : s.messages) std::printf("  %s\n", message.c_str());
  }
  return 0;
}

}  // namespace

void add_db_command(CLI::App& app, DbOptions& o) {
  auto* db = app.add_subcommand("db", "Maintain the model database: tools, materials, cutting tests, fitted models");
  db->require_subcommand(1);
  auto common = [&o](CLI::App* cmd) {
    cmd->add_option("--db", o.db_path,
                    "Database file or postgresql://USER@HOST:PORT/DBNAME (default: $FEEDPLAN_DB, else the bundled sample database)");
    cmd->add_flag("--json", o.json, "Print the result as JSON");
  };
  auto tool_material = [&o](CLI::App* cmd) {
    cmd->add_option("--tool", o.tool, "Tool name")->required();
    cmd->add_option("--material", o.material, "Material name")->required();
  };
  common(db->add_subcommand("init", "Create a database (or migrate an older one)"));
  common(db->add_subcommand("list", "List tools, materials and active models"));
  auto* show = db->add_subcommand("show", "Show a model: coefficients with standard errors, range, fit statistics");
  common(show);
  tool_material(show);
  add_integer_flag(show, "--version", o.version, "Model version (default: the active one)");
  show->add_option("--kind", o.kind, "Which active version: response-surface or mechanistic (default: the first)");
  auto* add_tool = db->add_subcommand("add-tool", "Register a tool");
  common(add_tool);
  add_tool->add_option("name", o.name, "Unique tool name")->required();
  add_number_flag(add_tool, "--diameter-mm", o.diameter_mm, "Cutting diameter, mm")->required();
  add_integer_flag(add_tool, "--flutes", o.flutes, "Number of flutes")->required();
  add_number_flag(add_tool, "--helix-deg", o.helix_deg, "Helix angle, deg");
  add_tool->add_option("--tool-material", o.tool_material, "Substrate, e.g. \"solid carbide\"");
  add_tool->add_option("--coating", o.coating, "Coating, e.g. TiAlN");
  add_tool->add_option("--notes", o.notes, "Free text");
  auto* add_material = db->add_subcommand("add-material", "Register a workpiece material");
  common(add_material);
  add_material->add_option("name", o.name, "Unique material name")->required();
  add_material->add_option("--iso-group", o.iso_group, "ISO 513 group: P, M, K, N, S or H")->required();
  add_material->add_option("--hardness", o.hardness, "Hardness with its scale, e.g. \"200 HB\"")->required();
  add_material->add_option("--notes", o.notes, "Free text");
  auto* import_test = db->add_subcommand("import-test", "Import a cutting test: a force log and its conditions");
  common(import_test);
  import_test->add_option("log", o.log_path, "Force log (feedplan CSV or Kistler DynoWare export)")->required();
  tool_material(import_test);
  add_number_flag(import_test, "--spindle-rpm", o.spindle_rpm, "Spindle speed, rev/min")->required();
  add_number_flag(import_test, "--feed-mm-per-min", o.feed_mm_per_min, "Feed, mm/min")->required();
  add_number_flag(import_test, "--radial-depth-mm", o.radial_depth_mm, "Radial depth a_e, mm")->required();
  add_number_flag(import_test, "--axial-depth-mm", o.axial_depth_mm, "Axial depth a_p, mm")->required();
  import_test->add_option("--mode", o.mode, "down, up or slot");
  import_test->add_flag("--no-store", o.no_store, "Only measure the steady peak; do not store the test");
  auto* fit = db->add_subcommand("fit", "Fit a new model version from the stored cutting tests (Ceres, robust loss)");
  common(fit);
  tool_material(fit);
  fit->add_option("--loss", o.loss, "huber (default), cauchy or squared");
  fit->add_option("--note", o.note, "Free text stored with the version");
  fit->add_flag("--per-revolution", o.per_revolution,
                "Fit every steady per-revolution peak (the scatter then sets the uncertainty), not one mean per test");
  fit->add_option("--kind", o.kind,
                  "mechanistic (cutting coefficients and runout from the tests' force over a revolution), "
                  "response-surface (seed 003 Eq. 1 on the peaks) or both (default): each a version of its kind");
  fit->add_flag("--no-runout", o.no_runout, "Mechanistic: do not identify the per-tooth runout (nor the helix)");
  fit->add_flag("--no-helix", o.no_helix, "Mechanistic: keep the tool record's helix instead of identifying it");
  fit->add_flag("--no-size-effect", o.no_size_effect,
                "Mechanistic: no size effect (cutting coefficients independent of the chip thickness)");
  fit->add_flag("--no-peak-matching", o.no_peak_matching,
                "Mechanistic: fit the tests' force over a revolution alone, not also their mean per-revolution peaks");
  fit->add_flag("--sensor", o.sensor,
                "Mechanistic: identify the dynamometer's modes too, for tests read by a sensor that rings at the tooth "
                "pulses (no leave-one-out error then)");
  auto* predict = db->add_subcommand("predict", "Predict the per-revolution peak force of a straight cut");
  common(predict);
  tool_material(predict);
  add_number_flag(predict, "--radial-depth-mm", o.radial_depth_mm, "Radial depth a_e, mm")->required();
  add_number_flag(predict, "--feed-per-tooth-mm", o.feed_per_tooth_mm, "Feed per tooth f_z, mm")->required();
  predict->add_option("--mode", o.mode, "down (default), up or slot: the side the mechanistic kind cuts on");
  auto* export_cmd = db->add_subcommand("export", "Export tools, materials, models and cutting tests as JSON");
  common(export_cmd);
  export_cmd->add_option("file", o.file, "JSON file to write")->required();
  export_cmd->add_flag("--all-versions", o.all_versions, "Every model version, not only the active ones");
  auto* import_cmd = db->add_subcommand("import", "Import an exported JSON file (one transaction)");
  common(import_cmd);
  import_cmd->add_option("file", o.file, "JSON file to read")->required();
  auto* history = db->add_subcommand("history", "Versions, activations and learning steps of a model");
  common(history);
  tool_material(history);
  auto* rollback = db->add_subcommand("rollback", "Make an older model version active again");
  common(rollback);
  tool_material(rollback);
  add_integer_flag(rollback, "--version", o.version, "Version to make active")->required();
  auto* sync = db->add_subcommand("sync", "Copy tools, materials, model versions and history from one database into "
                                          "another (a file or a postgresql:// server); what is there already is skipped");
  sync->add_option("--from", o.sync_from, "Database to copy from: a file or postgresql://USER@HOST:PORT/DBNAME")->required();
  sync->add_option("--to", o.sync_to, "Database to copy into (created when missing): a file or a postgresql:// URL")
      ->required();
  sync->add_flag("--json", o.json, "Print the result as JSON");
}

int run_db_command(const CLI::App& app, const DbOptions& o) {
  const CLI::App* db = app.get_subcommand("db");
  const auto given = [db](const char* name) { return db->got_subcommand(name); };
  if (given("init")) return run_init(o);
  if (given("list")) return run_list(o);
  if (given("show")) return run_show(o);
  if (given("add-tool")) return run_add_tool(o);
  if (given("add-material")) return run_add_material(o);
  if (given("import-test")) return run_import_test(o);
  if (given("fit")) return run_fit(o);
  if (given("predict")) return run_predict(o);
  if (given("export")) return run_export(o);
  if (given("import")) return run_import(o);
  if (given("history")) return run_history(o);
  if (given("rollback")) return run_rollback(o);
  if (given("sync")) return run_sync(o);
  return 1;
}

}  // namespace feedplan::cli
