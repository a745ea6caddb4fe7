#include "calibration_command.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "output_path.hpp"
#include "feedplan/core/atomic_file.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/force_log/force_log.hpp"

namespace feedplan::cli {
namespace {

constexpr const char* kFormat = "feedplan-current-calibration";

nlohmann::json axis_json(const learning::AxisCalibration& axis) {
  return {{"a_a", axis.a_a}, {"b_a_per_n", axis.b_a_per_n}, {"r_squared", axis.r_squared}, {"windows", axis.windows}};
}

}  // namespace

void add_calibration_command(CLI::App& app, CalibrationOptions& options) {
  auto* cmd = app.add_subcommand("calibrate-currents",
                                 "Fit the servo-current calibration I = a + b·|F| per axis (seed 002) from a log with both\n"
                                 "forces and currents");
  cmd->add_option("log", options.log_path, "Force log with fx_n, fy_n and ix_a, iy_a columns")->required();
  cmd->add_option("-o,--output", options.output_path, "Write the calibration (JSON) for feedplan learn --calibration");
  cmd->add_flag("--json", options.json, "Print the calibration as JSON");
}

int run_calibration_command(const CalibrationOptions& o) {
  std::vector<InputProblem> path_problems;
  check_outputs({{"LOG", o.log_path}}, {{"-o", o.output_path}}, path_problems);
  if (!path_problems.empty()) throw InputError(std::move(path_problems));
  const force_log::ForceLog log = force_log::load_force_log(o.log_path);
  const learning::CurrentCalibration calibration = learning::fit_current_calibration(log);
  nlohmann::json out{{"format", kFormat}, {"format_version", 1}, {"log", o.log_path},
                     {"x", axis_json(calibration.x)}, {"y", axis_json(calibration.y)}, {"z", axis_json(calibration.z)}};
  if (!o.output_path.empty()) {
    if (auto error = write_file_atomically(o.output_path, out.dump(2) + "\n"); !error.empty()) {
      std::cerr << "feedplan: failed: " << error << "\n";
      return 1;
    }
  }
  if (o.json) {
    std::cout << out.dump(2) << "\n";
  } else {
    for (const auto& [name, axis] : {std::pair{"x", calibration.x}, std::pair{"y", calibration.y}, std::pair{"z", calibration.z}}) {
      std::printf("%s: I = %.4f A + %.6f A/N · |F|   (R² %.4f over %d windows of whole revolutions)\n", name, axis.a_a,
                  axis.b_a_per_n, axis.r_squared, axis.windows);
    }
    if (!o.output_path.empty()) std::printf("wrote %s\n", o.output_path.c_str());
  }
  return 0;
}

learning::CurrentCalibration load_current_calibration(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("--calibration", "= '" + path + "': cannot read the file");
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json doc = nlohmann::json::parse(text.str(), nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) throw InputError("--calibration", "= '" + path + "': not a JSON object");
  std::vector<InputProblem> problems;
  if (!doc.contains("format") || doc["format"] != kFormat) {
    problems.push_back({path + ": format", std::string("must be \"") + kFormat + "\" (written by feedplan calibrate-currents)"});
  }
  learning::CurrentCalibration calibration;
  const auto axis = [&](const char* name, learning::AxisCalibration& out, bool required) {
    if (!doc.contains(name) || !doc[name].is_object()) {
      problems.push_back({path + ": " + name, "is missing"});
      return;
    }
    const auto& node = doc[name];
    for (const char* key : {"a_a", "b_a_per_n"}) {
      if (!node.contains(key) || !node[key].is_number() || !std::isfinite(node[key].get<double>())) {
        problems.push_back({path + ": " + name + "." + key, "must be a finite number"});
        return;
      }
    }
    out.a_a = node["a_a"].get<double>();
    out.b_a_per_n = node["b_a_per_n"].get<double>();
    if (required && !(out.b_a_per_n > 0.0)) {
      problems.push_back({path + ": " + std::string(name) + ".b_a_per_n",
                          "= " + shortest_number_text(out.b_a_per_n) + ": must be > 0 A/N"});
    }
  };
  axis("x", calibration.x, true);
  axis("y", calibration.y, true);
  axis("z", calibration.z, false);
  if (!problems.empty()) throw InputError(std::move(problems));
  return calibration;
}

}  // namespace feedplan::cli
