#include "feedplan/force_log/revolution_peaks.hpp"

#include <array>
#include <cassert>
#include <charconv>
#include <cmath>
#include <string>

#include "feedplan/core/atomic_file.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"

namespace feedplan::force_log {

namespace {

// Samples within this many turns before a boundary count in the next revolution (rounding of t).
constexpr double kBoundaryTolerance_turns = 1e-6;

void check_times(const std::vector<double>& t_s) {
  std::vector<InputProblem> problems;
  for (std::size_t i = 0; i < t_s.size(); ++i) {
    const bool finite = std::isfinite(t_s[i]);
    if (finite && (i == 0 || !std::isfinite(t_s[i - 1]) || t_s[i] > t_s[i - 1])) continue;
    const std::string field = "t_s[" + std::to_string(i) + "]";
    if (!finite) {
      problems.push_back({field, "= " + shortest_number_text(t_s[i]) + ": must be a finite time in s"});
    } else if (i > 0 && std::isfinite(t_s[i - 1]) && !(t_s[i] > t_s[i - 1])) {
      problems.push_back({field, "= " + shortest_number_text(t_s[i]) + ": must be after t_s[" + std::to_string(i - 1) +
                                     "] = " + shortest_number_text(t_s[i - 1]) + " — times must increase"});
    }
    if (problems.size() >= 20) break;
  }
  if (!problems.empty()) throw InputError(std::move(problems));
}

void check_forces(const std::vector<double>& f_n, const char* name) {
  for (std::size_t i = 0; i < f_n.size(); ++i) {
    if (std::isfinite(f_n[i])) continue;
    throw InputError(std::string(name) + "[" + std::to_string(i) + "]",
                     "= " + shortest_number_text(f_n[i]) + ": must be a finite force in N — was the force recorded?");
  }
}

void check_rpm(double rpm, const std::string& field) {
  if (std::isfinite(rpm) && rpm > 0.0) return;
  throw InputError(field,
                   "= " + shortest_number_text(rpm) + ": must be a finite number > 0 rev/min — the spindle speed");
}

// The peaks given each sample's spindle angle in turns since the first sample (non-decreasing).
// `time_at(k)` is the time the angle reaches k turns.
template <typename TimeAt>
std::vector<RevolutionPeak> peaks_from_angles(const std::vector<double>& t_s, const std::vector<double>& fx_n,
                                              const std::vector<double>& fy_n, const std::vector<double>& angle_turns,
                                              const TimeAt& time_at) {
  std::vector<RevolutionPeak> peaks;
  const std::size_t n = t_s.size();
  if (n < 2) return peaks;
  auto window_of = [&](std::size_t i) {
    return static_cast<long>(std::floor(angle_turns[i] + kBoundaryTolerance_turns));
  };
  std::size_t i = 0;
  while (i < n) {
    const long k = window_of(i);
    RevolutionPeak p;
    p.revolution = k;
    p.t_start_s = k == 0 ? t_s.front() : time_at(static_cast<double>(k));
    p.t_end_s = time_at(static_cast<double>(k + 1));
    double sum = 0.0;
    p.peak_xy_n = -1.0;
    for (; i < n && window_of(i) == k; ++i) {
      const double f = std::hypot(fx_n[i], fy_n[i]);
      sum += f;
      if (f > p.peak_xy_n) {
        p.peak_xy_n = f;
        p.t_peak_s = t_s[i];
      }
      ++p.samples;
    }
    p.mean_xy_n = sum / static_cast<double>(p.samples);
    peaks.push_back(p);
  }
  // The last window counts only when the data reach its end: the next sample, one mean spacing on,
  // would fall into the next revolution.
  const double mean_step_turns = (angle_turns.back() - angle_turns.front()) / static_cast<double>(n - 1);
  const double reach_turns = angle_turns.back() + mean_step_turns + kBoundaryTolerance_turns;
  if (reach_turns < static_cast<double>(peaks.back().revolution + 1)) peaks.pop_back();
  return peaks;
}

}  // namespace

std::vector<RevolutionPeak> revolution_peaks(const std::vector<double>& t_s, const std::vector<double>& fx_n,
                                             const std::vector<double>& fy_n, double spindle_rpm) {
  assert(fx_n.size() == t_s.size() && fy_n.size() == t_s.size());
  check_rpm(spindle_rpm, "spindle_rpm");
  check_times(t_s);
  check_forces(fx_n, "fx_n");
  check_forces(fy_n, "fy_n");
  if (t_s.size() < 2) return {};
  const double t0 = t_s.front();
  const double turns_per_s = spindle_rpm / 60.0;
  std::vector<double> angle_turns(t_s.size());
  for (std::size_t i = 0; i < t_s.size(); ++i) angle_turns[i] = (t_s[i] - t0) * turns_per_s;
  return peaks_from_angles(t_s, fx_n, fy_n, angle_turns, [&](double turns) { return t0 + turns / turns_per_s; });
}

std::vector<RevolutionPeak> revolution_peaks(const std::vector<double>& t_s, const std::vector<double>& fx_n,
                                             const std::vector<double>& fy_n, const std::vector<double>& spindle_rpm) {
  assert(fx_n.size() == t_s.size() && fy_n.size() == t_s.size() && spindle_rpm.size() == t_s.size());
  for (std::size_t i = 0; i < spindle_rpm.size(); ++i) {
    if (!(std::isfinite(spindle_rpm[i]) && spindle_rpm[i] > 0.0)) check_rpm(spindle_rpm[i], "spindle_rpm[" + std::to_string(i) + "]");
  }
  check_times(t_s);
  check_forces(fx_n, "fx_n");
  check_forces(fy_n, "fy_n");
  if (t_s.size() < 2) return {};
  // Trapezoidal integration of the speed.
  std::vector<double> angle_turns(t_s.size(), 0.0);
  for (std::size_t i = 1; i < t_s.size(); ++i) {
    angle_turns[i] = angle_turns[i - 1] + 0.5 * (spindle_rpm[i - 1] + spindle_rpm[i]) / 60.0 * (t_s[i] - t_s[i - 1]);
  }
  // Time at which the angle reaches `turns`: linear between samples, extrapolated at the last speed.
  auto time_at = [&](double turns) {
    const std::size_t last = t_s.size() - 1;
    if (turns >= angle_turns[last]) return t_s[last] + (turns - angle_turns[last]) / (spindle_rpm[last] / 60.0);
    std::size_t lo = 0, hi = last;  // angle_turns[lo] ≤ turns < angle_turns[hi]
    while (hi - lo > 1) {
      const std::size_t mid = (lo + hi) / 2;
      (angle_turns[mid] <= turns ? lo : hi) = mid;
    }
    const double share = (turns - angle_turns[lo]) / (angle_turns[hi] - angle_turns[lo]);
    return t_s[lo] + share * (t_s[hi] - t_s[lo]);
  };
  return peaks_from_angles(t_s, fx_n, fy_n, angle_turns, time_at);
}

std::string format_revolution_peaks(const std::vector<RevolutionPeak>& peaks) {
  std::string out = "revolution,t_start_s,t_end_s,t_peak_s,peak_xy_n,mean_xy_n\n";
  for (const auto& peak : peaks) {
    out += std::to_string(peak.revolution);
    for (const auto& [value, decimals] : {std::pair{peak.t_start_s, 6}, std::pair{peak.t_end_s, 6}, std::pair{peak.t_peak_s, 6},
                                          std::pair{peak.peak_xy_n, 3}, std::pair{peak.mean_xy_n, 3}}) {
      out += ',';
      append_fixed_number_text(out, value, decimals);
    }
    out += '\n';
  }
  return out;
}

std::string write_revolution_peaks(const std::string& path, const std::vector<RevolutionPeak>& peaks) {
  return write_file_atomically(path, format_revolution_peaks(peaks));
}

}  // namespace feedplan::force_log
