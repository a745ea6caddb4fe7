#include "feedplan/learning/current_calibration.hpp"

#include "feedplan/force_log/logged_spindle_speed.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"

namespace feedplan::learning {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Smallest spread of the window mean forces a slope can be fitted on, N.
constexpr double kMinForceSpreadN = 1.0;
// A window needs at least this share of the rows it should hold.
constexpr double kMinRowShare = 0.5;


struct AxisData {
  double force_log::ForceLogRow::*force;
  double force_log::ForceLogRow::*current;
  const char* name;
};

// Window means (|mean force|, mean current) of one axis.
void window_means(const force_log::ForceLog& log, const AxisData& axis, double window_s, std::vector<double>& force,
                  std::vector<double>& current) {
  const auto& rows = log.rows;
  if (rows.size() < 2) return;
  const double t0 = rows.front().t_s;
  const double step_s = (rows.back().t_s - t0) / static_cast<double>(rows.size() - 1);
  const double expected_rows = window_s / step_s;
  long window = -1;
  double sum_f = 0, sum_i = 0;
  int count = 0;
  auto close = [&]() {
    if (window >= 0 && count >= kMinRowShare * expected_rows && count > 0) {
      force.push_back(std::abs(sum_f / count));
      current.push_back(sum_i / count);
    }
    sum_f = sum_i = 0;
    count = 0;
  };
  for (const auto& row : rows) {
    const long w = static_cast<long>(std::floor((row.t_s - t0) / window_s));
    if (w != window) {
      close();
      window = w;
    }
    const double f = row.*(axis.force), i = row.*(axis.current);
    if (!std::isfinite(f) || !std::isfinite(i)) continue;
    sum_f += f;
    sum_i += i;
    ++count;
  }
  // The last window only when complete.
  if (rows.back().t_s - (t0 + static_cast<double>(window) * window_s) >= window_s - 1.5 * step_s) close();
}

// Least squares current = a + b·force with R²; problems when it cannot be fitted.
AxisCalibration fit_axis(const force_log::ForceLog& log, const AxisData& axis, double window_s, bool required,
                         std::vector<InputProblem>& problems) {
  std::vector<double> f, i;
  window_means(log, axis, window_s, f, i);
  AxisCalibration calibration;
  const std::string field = std::string("log ") + axis.name;
  if (f.size() < 3) {
    if (required) {
      problems.push_back({field, "has " + std::to_string(f.size()) + " complete " + six_digit_number_text(window_s) +
                                     " s windows with force and current: need at least 3"});
    }
    return calibration;
  }
  const auto [f_min, f_max] = std::minmax_element(f.begin(), f.end());
  if (*f_max - *f_min < kMinForceSpreadN) {
    if (required) {
      problems.push_back({field, "force varies by " + six_digit_number_text(*f_max - *f_min) +
                                     " N over the log: need at least " + six_digit_number_text(kMinForceSpreadN) +
                                     " N (cutting and not cutting) to fit a slope"});
    }
    return calibration;
  }
  const double n = static_cast<double>(f.size());
  double mf = 0, mi = 0;
  for (std::size_t k = 0; k < f.size(); ++k) {
    mf += f[k];
    mi += i[k];
  }
  mf /= n;
  mi /= n;
  double sff = 0, sfi = 0, sii = 0;
  for (std::size_t k = 0; k < f.size(); ++k) {
    sff += (f[k] - mf) * (f[k] - mf);
    sfi += (f[k] - mf) * (i[k] - mi);
    sii += (i[k] - mi) * (i[k] - mi);
  }
  calibration.b_a_per_n = sfi / sff;
  calibration.a_a = mi - calibration.b_a_per_n * mf;
  calibration.windows = static_cast<int>(f.size());
  double residual = 0;
  for (std::size_t k = 0; k < f.size(); ++k) {
    const double e = i[k] - (calibration.a_a + calibration.b_a_per_n * f[k]);
    residual += e * e;
  }
  calibration.r_squared = sii > 0.0 ? std::clamp(1.0 - residual / sii, 0.0, 1.0) : 0.0;
  if (!(calibration.b_a_per_n > 0.0)) {
    if (required) {
      problems.push_back({field, "current falls as the force rises (slope " +
                                     six_digit_number_text(calibration.b_a_per_n) +
                                     " A/N): not a current of this axis?"});
    }
    return AxisCalibration{};
  }
  return calibration;
}

}  // namespace

CurrentCalibration fit_current_calibration(const force_log::ForceLog& log) {
  std::vector<InputProblem> problems;
  if (!log.has_forces) {
    problems.push_back({"log", "has no forces (fx_n, fy_n): a calibration needs forces and currents"});
  }
  if (!log.has_currents) {
    problems.push_back({"log", "has no servo currents (ix_a, iy_a): a calibration needs forces and currents"});
  }
  if (!problems.empty()) throw InputError(std::move(problems));
  const double rpm = logged_spindle_rpm(log);
  double window_s = kCalibrationWindowS;
  if (rpm > 0.0) {
    const double period_s = 60.0 / rpm;
    window_s = period_s * std::max(1.0, std::round(kCalibrationWindowS / period_s));
  }
  CurrentCalibration calibration;
  calibration.x = fit_axis(log, {&force_log::ForceLogRow::fx_n, &force_log::ForceLogRow::ix_a, "x axis"}, window_s, true, problems);
  calibration.y = fit_axis(log, {&force_log::ForceLogRow::fy_n, &force_log::ForceLogRow::iy_a, "y axis"}, window_s, true, problems);
  calibration.z =
      fit_axis(log, {&force_log::ForceLogRow::fz_n, &force_log::ForceLogRow::iz_a, "z axis"}, window_s, false, problems);
  if (!problems.empty()) throw InputError(std::move(problems));
  return calibration;
}

force_log::ForceLog forces_from_currents(const force_log::ForceLog& current_log, const CurrentCalibration& calibration) {
  std::vector<InputProblem> problems;
  if (!current_log.has_currents) problems.push_back({"log", "has no servo currents (ix_a, iy_a)"});
  if (!(calibration.x.b_a_per_n > 0.0)) {
    problems.push_back(
        {"calibration.x.b_a_per_n", "= " + shortest_number_text(calibration.x.b_a_per_n) + ": must be > 0"});
  }
  if (!(calibration.y.b_a_per_n > 0.0)) {
    problems.push_back(
        {"calibration.y.b_a_per_n", "= " + shortest_number_text(calibration.y.b_a_per_n) + ": must be > 0"});
  }
  if (!problems.empty()) throw InputError(std::move(problems));
  force_log::ForceLog log = current_log;
  const bool with_z = calibration.z.b_a_per_n > 0.0;
  for (auto& row : log.rows) {
    row.fx_n = (row.ix_a - calibration.x.a_a) / calibration.x.b_a_per_n;
    row.fy_n = (row.iy_a - calibration.y.a_a) / calibration.y.b_a_per_n;
    row.fz_n = with_z ? (row.iz_a - calibration.z.a_a) / calibration.z.b_a_per_n : kNaN;
  }
  log.has_forces = true;
  char text[200];
  std::snprintf(text, sizeof text,
                "from servo currents, |F| = (I - a)/b with x %.4g + %.4g F, y %.4g + %.4g F (seed 002): mean forces, "
                "not tooth peaks",
                calibration.x.a_a, calibration.x.b_a_per_n, calibration.y.a_a, calibration.y.b_a_per_n);
  log.metadata.emplace_back("forces", text);
  return log;
}

}  // namespace feedplan::learning
