#include "feedplan/model_db/cutting_test_import.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "feedplan/core/number_text.hpp"
#include "feedplan/geometry/analytic_engagement.hpp"
#include "feedplan/force_log/revolution_peaks.hpp"
#include "median.hpp"
#include "revolution_signals.hpp"
#include "steady_run.hpp"

namespace feedplan::model_db {

namespace {

using detail::find_steady;
using detail::median;
using detail::median_over;
using detail::revolution_signals;
using detail::RevolutionSignals;
using detail::SteadyRun;

// Relative difference below which a radial depth counts as the tool diameter (a slot).
constexpr double kSlotTolerance = 1e-9;
// Fewer log samples per tooth period than this and the sampled peak may read low: a note.
constexpr double kFewSamplesPerTooth = 20.0;
// Steady peaks scattering more than this (std / mean) earn a note.
constexpr double kLargeScatter = 0.05;

std::string number(double value) { return shortest_number_text(value); }
std::string measured(double value) { return six_digit_number_text(value); }

std::string percent(double fraction) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f %%", 100.0 * fraction);
  return buffer;
}

std::string to_string(CutMode mode) {
  switch (mode) {
    case CutMode::kDown:
      return "down";
    case CutMode::kUp:
      return "up";
    case CutMode::kSlot:
      return "slot";
  }
  return "unknown";
}

std::optional<double> parse_number(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) text.remove_suffix(1);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || result.ec != std::errc() || result.ptr != text.data() + text.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

void require_positive(std::vector<InputProblem>& problems, const std::string& field, double value,
                      const std::string& unit, const std::string& meaning) {
  if (std::isfinite(value) && value > 0.0) return;
  problems.push_back({field, "= " + number(value) + ": must be a finite number > 0 " + unit + " — " + meaning});
}

bool any_finite(const std::vector<double>& values) {
  return std::any_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

}  // namespace

std::vector<InputProblem> validate(const CuttingTestConditions& conditions, const geometry::Tool& tool) {
  std::vector<InputProblem> problems;
  require_positive(problems, "tool.diameter_mm", tool.diameter_mm, "mm", "the cutting diameter");
  if (tool.flutes < 1) {
    problems.push_back({"tool.flutes", "= " + std::to_string(tool.flutes) + ": must be at least 1"});
  }
  if (!(std::isfinite(tool.helix_deg) && tool.helix_deg >= 0.0 && tool.helix_deg < 90.0)) {
    problems.push_back({"tool.helix_deg", "= " + number(tool.helix_deg) + ": must be in [0, 90) deg"});
  }
  require_positive(problems, "conditions.spindle_rpm", conditions.spindle_rpm, "rev/min", "the spindle speed");
  require_positive(problems, "conditions.feed_mm_per_min", conditions.feed_mm_per_min, "mm/min", "the feed");
  require_positive(problems, "conditions.axial_depth_mm", conditions.axial_depth_mm, "mm", "a_p");
  const double d = tool.diameter_mm;
  const double ae = conditions.radial_depth_mm;
  const bool diameter_ok = std::isfinite(d) && d > 0.0;
  if (!(std::isfinite(ae) && ae > 0.0)) {
    problems.push_back({"conditions.radial_depth_mm", "= " + number(ae) + ": must be a finite number > 0 mm — a_e"});
  } else if (diameter_ok && ae > d * (1.0 + kSlotTolerance)) {
    problems.push_back({"conditions.radial_depth_mm", "= " + number(ae) + ": must be in (0, " + number(d) +
                                                          "] mm — at most the tool diameter (tool.diameter_mm = " +
                                                          number(d) + ")"});
  } else if (diameter_ok) {
    const bool full = std::abs(ae - d) <= kSlotTolerance * d;
    if (conditions.mode == CutMode::kSlot && !full) {
      problems.push_back({"conditions.mode", "= slot: a slot cuts the full tool diameter, but radial_depth_mm = " +
                                                 number(ae) + " is not tool.diameter_mm = " + number(d) +
                                                 " — use down or up for a partial radial depth"});
    } else if (conditions.mode != CutMode::kSlot && full) {
      problems.push_back({"conditions.mode", "= " + to_string(conditions.mode) + ": radial_depth_mm = " + number(ae) +
                                                 " is the tool diameter, which is a full slot — use slot"});
    }
  }
  return problems;
}

std::vector<InputProblem> validate(const CuttingTestImportOptions& options) {
  std::vector<InputProblem> problems;
  auto fraction = [&](const char* field, double value, bool zero_ok) {
    if (std::isfinite(value) && (zero_ok ? value >= 0.0 : value > 0.0) && value < 1.0) return;
    problems.push_back({field, "= " + number(value) + ": must be in " + (zero_ok ? "[0, 1)" : "(0, 1)")});
  };
  fraction("options.rpm_tolerance", options.rpm_tolerance, true);
  fraction("options.feed_tolerance", options.feed_tolerance, true);
  fraction("options.sample_rate_tolerance", options.sample_rate_tolerance, true);
  fraction("options.loaded_fraction", options.loaded_fraction, false);
  fraction("options.plateau_tolerance", options.plateau_tolerance, false);
  fraction("options.trim_min_fraction", options.trim_min_fraction, true);
  if (options.min_steady_revolutions < 1) {
    problems.push_back({"options.min_steady_revolutions",
                        "= " + std::to_string(options.min_steady_revolutions) + ": must be at least 1"});
  }
  if (options.trend_window_revolutions < 1 || options.trend_window_revolutions % 2 == 0) {
    problems.push_back({"options.trend_window_revolutions",
                        "= " + std::to_string(options.trend_window_revolutions) + ": must be an odd number ≥ 1"});
  }
  if (!(std::isfinite(options.trim_sigmas) && options.trim_sigmas >= 0.0)) {
    problems.push_back({"options.trim_sigmas", "= " + number(options.trim_sigmas) + ": must be a finite number ≥ 0"});
  }
  return problems;
}

CuttingTestRecord import_cutting_test(const force_log::ForceLog& log, const CuttingTestConditions& conditions,
                                      const geometry::Tool& tool, const CuttingTestImportOptions& options) {
  std::vector<InputProblem> problems = validate(conditions, tool);
  for (auto& p : validate(options)) problems.push_back(std::move(p));
  if (!problems.empty()) throw InputError(std::move(problems));

  const std::string source = options.source_name.empty() ? "force log" : options.source_name;
  const double rpm = conditions.spindle_rpm;
  const double feed = conditions.feed_mm_per_min;
  if (!log.has_forces) {
    throw InputError(source, "has no force columns (fx_n, fy_n): a cutting test needs measured forces — turn servo "
                             "currents into forces with a calibration first (DESIGN.md §6.4)");
  }
  if (log.rows.empty()) throw InputError(source, "has no samples");

  CuttingTestRecord record;
  record.conditions = conditions;
  record.source = source;

  // Metadata against the conditions and the time column.
  auto relative = [](double a, double b) { return std::abs(a - b) / std::abs(b); };
  bool rpm_checked = false;
  const std::string rpm_text = log.metadata_value("spindle_rpm");
  if (!rpm_text.empty()) {
    const std::optional<double> log_rpm = parse_number(rpm_text);
    if (!log_rpm || *log_rpm <= 0.0) {
      problems.push_back({source + " spindle_rpm", "= \"" + rpm_text + "\": must be a number > 0 rev/min"});
    } else {
      rpm_checked = true;
      if (relative(rpm, *log_rpm) > options.rpm_tolerance) {
        problems.push_back({"conditions.spindle_rpm",
                            "= " + number(rpm) + " rev/min, but " + source + " says " + measured(*log_rpm) +
                                " (# spindle_rpm): " + percent(relative(rpm, *log_rpm)) + " apart, more than " +
                                percent(options.rpm_tolerance)});
      }
    }
  }
  std::vector<double> t_s, fx_n, fy_n;
  t_s.reserve(log.rows.size());
  fx_n.reserve(log.rows.size());
  fy_n.reserve(log.rows.size());
  for (const auto& row : log.rows) {
    t_s.push_back(row.t_s);
    fx_n.push_back(row.fx_n);
    fy_n.push_back(row.fy_n);
  }
  double sample_rate_hz = std::nan("");
  if (t_s.size() >= 2) {
    std::vector<double> steps;
    steps.reserve(t_s.size() - 1);
    for (std::size_t i = 1; i < t_s.size(); ++i) steps.push_back(t_s[i] - t_s[i - 1]);
    sample_rate_hz = 1.0 / median(steps);
  }
  const std::string rate_text = log.metadata_value("sample_rate_hz");
  if (!rate_text.empty() && std::isfinite(sample_rate_hz)) {
    const std::optional<double> log_rate = parse_number(rate_text);
    if (!log_rate || *log_rate <= 0.0) {
      problems.push_back({source + " sample_rate_hz", "= \"" + rate_text + "\": must be a number > 0 Hz"});
    } else if (relative(*log_rate, sample_rate_hz) > options.sample_rate_tolerance) {
      problems.push_back({source + " sample_rate_hz",
                          "= " + measured(*log_rate) + " Hz, but the time column steps by " +
                              measured(1.0 / sample_rate_hz) + " s (" + measured(sample_rate_hz) + " Hz): " +
                              percent(relative(*log_rate, sample_rate_hz)) + " apart, more than " +
                              percent(options.sample_rate_tolerance)});
    }
  }

  // Per-revolution peaks and what the log says about each revolution.
  const std::vector<force_log::RevolutionPeak> peaks = force_log::revolution_peaks(t_s, fx_n, fy_n, rpm);
  const RevolutionSignals signals = revolution_signals(log, peaks);
  record.revolutions_total = static_cast<int>(peaks.size());

  // The steady part from the forces alone, to check the log's feed and spindle speed in it.
  const SteadyRun force_only = find_steady(peaks, std::vector<bool>(peaks.size(), true), options);
  if (!peaks.empty() && !force_only.any_force) {
    problems.push_back({source, "has no cutting force: every per-revolution peak of |F_xy| is 0 N"});
  }
  const bool has_feed_column = any_finite(signals.feed_column_mm_per_min);
  const bool has_feed_positions = any_finite(signals.feed_positions_mm_per_min);
  if (force_only.size() > 0) {
    const double column_rpm = median_over(signals.spindle_rpm, force_only);
    if (std::isfinite(column_rpm)) {
      rpm_checked = true;
      if (!(column_rpm > 0.0) || relative(rpm, column_rpm) > options.rpm_tolerance) {
        problems.push_back({"conditions.spindle_rpm",
                            "= " + number(rpm) + " rev/min, but the spindle_rpm column of " + source +
                                " reads " + measured(column_rpm) + " in the steady part: more than " +
                                percent(options.rpm_tolerance) + " apart"});
      }
    }
    const double column_feed = median_over(signals.feed_column_mm_per_min, force_only);
    if (std::isfinite(column_feed) && relative(feed, column_feed) > options.feed_tolerance) {
      problems.push_back({"conditions.feed_mm_per_min",
                          "= " + number(feed) + " mm/min, but the feed_mm_per_min column of " + source + " reads " +
                              measured(column_feed) + " in the steady part: " + percent(relative(feed, column_feed)) +
                              " apart, more than " + percent(options.feed_tolerance)});
    }
    const double position_feed = median_over(signals.feed_positions_mm_per_min, force_only);
    if (std::isfinite(position_feed) && relative(feed, position_feed) > options.feed_tolerance) {
      problems.push_back({"conditions.feed_mm_per_min",
                          "= " + number(feed) + " mm/min, but the positions (x_mm, y_mm) in " + source +
                              " move at " + measured(position_feed) + " mm/min in the steady part: " +
                              percent(relative(feed, position_feed)) + " apart, more than " +
                              percent(options.feed_tolerance)});
    }
  }
  if (!problems.empty()) throw InputError(std::move(problems));

  // Step 1: only revolutions at the given feed, where the log says.
  const std::vector<double>& feed_signal =
      has_feed_column ? signals.feed_column_mm_per_min : signals.feed_positions_mm_per_min;
  std::vector<bool> eligible(peaks.size(), true);
  int at_feed = 0;
  for (std::size_t k = 0; k < peaks.size(); ++k) {
    if (std::isfinite(feed_signal[k])) eligible[k] = relative(feed_signal[k], feed) <= options.feed_tolerance;
    at_feed += eligible[k] ? 1 : 0;
  }
  const SteadyRun steady = (has_feed_column || has_feed_positions) ? find_steady(peaks, eligible, options) : force_only;
  const int found = static_cast<int>(steady.size());
  if (found < options.min_steady_revolutions) {
    std::string where = "of " + std::to_string(peaks.size()) + " complete revolutions at " + number(rpm) + " rev/min";
    if (has_feed_column || has_feed_positions) where += ", " + std::to_string(at_feed) + " of them at the feed";
    throw InputError(source, "has " + std::to_string(found) + " steady revolution" + (found == 1 ? "" : "s") + " (" +
                                 where + "): at least " + std::to_string(options.min_steady_revolutions) +
                                 " are needed — record a longer cut at constant conditions");
  }

  // Statistics.
  record.revolutions_used = found;
  double sum = 0.0;
  record.peak_min_n = peaks[steady.begin].peak_xy_n;
  record.peak_max_n = peaks[steady.begin].peak_xy_n;
  for (std::size_t k = steady.begin; k < steady.end; ++k) {
    const double p = peaks[k].peak_xy_n;
    record.steady_peaks_n.push_back(p);
    sum += p;
    record.peak_min_n = std::min(record.peak_min_n, p);
    record.peak_max_n = std::max(record.peak_max_n, p);
  }
  record.peak_mean_n = sum / found;
  double squares = 0.0;
  for (double p : record.steady_peaks_n) squares += (p - record.peak_mean_n) * (p - record.peak_mean_n);
  record.peak_std_n = found > 1 ? std::sqrt(squares / (found - 1)) : 0.0;

  // Model inputs (DESIGN.md §5.1): straight cut, f_z at the tool centre.
  const double radius_mm = tool.radius_mm();
  const double engagement_rad = conditions.mode == CutMode::kSlot
                                    ? std::numbers::pi
                                    : geometry::straight_engagement_rad(radius_mm, conditions.radial_depth_mm);
  record.feed_per_tooth_mm = feed / (tool.flutes * rpm);
  record.chip_mm = record.feed_per_tooth_mm * geometry::steady_chip_factor(engagement_rad);
  record.contact_length_mm = radius_mm * engagement_rad;

  // Notes.
  const force_log::RevolutionPeak& first = peaks[steady.begin];
  const force_log::RevolutionPeak& last = peaks[steady.end - 1];
  record.notes.push_back("steady: " + std::to_string(found) + " of " + std::to_string(peaks.size()) +
                         " complete revolutions (numbers " + std::to_string(first.revolution) + "–" +
                         std::to_string(last.revolution) + ", t " + measured(first.t_start_s) + "–" +
                         measured(last.t_end_s) + " s); " + std::to_string(steady.begin - steady.plateau_begin) +
                         " trimmed at the start and " + std::to_string(steady.plateau_end - steady.end) +
                         " at the end of the plateau");
  if (has_feed_column || has_feed_positions) {
    const double measured_feed = median_over(feed_signal, steady);
    record.notes.push_back("feed: " + measured(measured_feed) + " mm/min from the " +
                           (has_feed_column ? "feed_mm_per_min column" : "positions") +
                           " in the steady part; revolutions at another feed were not used");
  } else {
    record.notes.push_back("feed: the log records neither feed nor positions (e.g. a Kistler export) — the feed "
                           "was not checked, and the steady part comes from the forces alone");
  }
  if (!rpm_checked) {
    record.notes.push_back("spindle speed: the log does not record it — not checked");
  }
  const double samples_per_tooth = sample_rate_hz * 60.0 / (rpm * tool.flutes);
  if (std::isfinite(samples_per_tooth) && samples_per_tooth < kFewSamplesPerTooth) {
    record.notes.push_back("sampling: " + measured(samples_per_tooth) +
                           " samples per tooth period — the sampled peaks may read low");
  }
  if (record.peak_mean_n > 0.0 && record.peak_std_n / record.peak_mean_n > kLargeScatter) {
    record.notes.push_back("scatter: the steady peaks vary by " + percent(record.peak_std_n / record.peak_mean_n) +
                           " (std / mean), " + measured(record.peak_min_n) + "–" + measured(record.peak_max_n) +
                           " N — runout, chatter or an unsteady process");
  }
  return record;
}

CuttingTestRecord import_cutting_test(const std::string& log_path, const CuttingTestConditions& conditions,
                                      const geometry::Tool& tool, const CuttingTestImportOptions& options) {
  CuttingTestImportOptions named = options;
  if (named.source_name.empty()) named.source_name = log_path;
  // Validate before reading so that bad conditions are reported without touching the file.
  std::vector<InputProblem> problems = validate(conditions, tool);
  for (auto& p : validate(named)) problems.push_back(std::move(p));
  if (!problems.empty()) throw InputError(std::move(problems));
  return import_cutting_test(force_log::load_force_log(log_path), conditions, tool, named);
}

}  // namespace feedplan::model_db
