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
#include "feedplan/force_log/synchronous_average.hpp"
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
  problems.push_back(
      {field, "= " + shortest_number_text(value) + ": must be a finite number > 0 " + unit + " — " + meaning});
}

bool any_finite(const std::vector<double>& values) {
  return std::any_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

//! Throws feedplan::InputError listing every problem with the conditions, the tool and the options.
void check_input(const CuttingTestConditions& conditions, const geometry::Tool& tool,
                 const CuttingTestImportOptions& options) {
  std::vector<InputProblem> problems = validate(conditions, tool);
  for (auto& p : validate(options)) problems.push_back(std::move(p));
  if (!problems.empty()) throw InputError(std::move(problems));
}

//! Throws feedplan::InputError when the log has no forces or no samples.
void require_force_samples(const force_log::ForceLog& log, const std::string& source) {
  if (!log.has_forces) {
    throw InputError(source, "has no force columns (fx_n, fy_n): a cutting test needs measured forces — turn servo "
                             "currents into forces with a calibration first (docs/method.md §6.4)");
  }
  if (log.rows.empty()) throw InputError(source, "has no samples");
}

//! One import under way: its inputs and what the checks against the log found so far.
struct Import {
  Import(const force_log::ForceLog& log, const CuttingTestConditions& conditions, const geometry::Tool& tool,
         const CuttingTestImportOptions& options)
      : log(log), conditions(conditions), tool(tool), options(options),
        source(options.source_name.empty() ? "force log" : options.source_name) {}

  const force_log::ForceLog& log;
  const CuttingTestConditions& conditions;
  const geometry::Tool& tool;
  const CuttingTestImportOptions& options;
  std::string source;                    // names the log in messages
  std::vector<InputProblem> problems;    // where the conditions contradict the log
  bool rpm_checked = false;              // the log records the spindle speed, and it was compared
  double sample_rate_hz = std::nan("");  // 1 / median step of the time column; NaN for one sample
};

double relative(double a, double b) { return std::abs(a - b) / std::abs(b); }

//! The log's `# spindle_rpm:` metadata against the conditions.
void check_metadata_spindle_rpm(Import& import) {
  const double rpm = import.conditions.spindle_rpm;
  const std::string rpm_text = import.log.metadata_value("spindle_rpm");
  if (rpm_text.empty()) return;
  const std::optional<double> log_rpm = parse_number(rpm_text);
  if (!log_rpm || *log_rpm <= 0.0) {
    import.problems.push_back({import.source + " spindle_rpm", "= \"" + rpm_text + "\": must be a number > 0 rev/min"});
  } else {
    import.rpm_checked = true;
    if (relative(rpm, *log_rpm) > import.options.rpm_tolerance) {
      import.problems.push_back(
          {"conditions.spindle_rpm", "= " + shortest_number_text(rpm) + " rev/min, but " + import.source + " says " +
                                         six_digit_number_text(*log_rpm) + " (# spindle_rpm): " +
                                         percent(relative(rpm, *log_rpm)) + " apart, more than " +
                                         percent(import.options.rpm_tolerance)});
    }
  }
}

//! The time and XY force columns of the log.
struct ForceColumns {
  std::vector<double> t_s;
  std::vector<double> fx_n;
  std::vector<double> fy_n;
};

ForceColumns force_columns(const force_log::ForceLog& log) {
  ForceColumns columns;
  columns.t_s.reserve(log.rows.size());
  columns.fx_n.reserve(log.rows.size());
  columns.fy_n.reserve(log.rows.size());
  for (const auto& row : log.rows) {
    columns.t_s.push_back(row.t_s);
    columns.fx_n.push_back(row.fx_n);
    columns.fy_n.push_back(row.fy_n);
  }
  return columns;
}

//! 1 / the median step of the time column, Hz; NaN for fewer than two samples.
double time_column_rate_hz(const std::vector<double>& t_s) {
  double sample_rate_hz = std::nan("");
  if (t_s.size() >= 2) {
    std::vector<double> steps;
    steps.reserve(t_s.size() - 1);
    for (std::size_t i = 1; i < t_s.size(); ++i) steps.push_back(t_s[i] - t_s[i - 1]);
    sample_rate_hz = 1.0 / median(steps);
  }
  return sample_rate_hz;
}

//! The log's `# sample_rate_hz:` metadata against the rate of its time column.
void check_metadata_sample_rate(Import& import) {
  const double sample_rate_hz = import.sample_rate_hz;
  const std::string rate_text = import.log.metadata_value("sample_rate_hz");
  if (rate_text.empty() || !std::isfinite(sample_rate_hz)) return;
  const std::optional<double> log_rate = parse_number(rate_text);
  if (!log_rate || *log_rate <= 0.0) {
    import.problems.push_back({import.source + " sample_rate_hz", "= \"" + rate_text + "\": must be a number > 0 Hz"});
  } else if (relative(*log_rate, sample_rate_hz) > import.options.sample_rate_tolerance) {
    import.problems.push_back({import.source + " sample_rate_hz",
                               "= " + six_digit_number_text(*log_rate) + " Hz, but the time column steps by " +
                                   six_digit_number_text(1.0 / sample_rate_hz) + " s (" +
                                   six_digit_number_text(sample_rate_hz) + " Hz): " +
                                   percent(relative(*log_rate, sample_rate_hz)) + " apart, more than " +
                                   percent(import.options.sample_rate_tolerance)});
  }
}

//! The complete revolutions of the log: their force peaks and what the log says about each.
struct LogRevolutions {
  std::vector<force_log::RevolutionPeak> peaks;
  RevolutionSignals signals;
  bool has_feed_column = false;     // the feed_mm_per_min column says something
  bool has_feed_positions = false;  // the positions give a feed

  bool has_feed() const { return has_feed_column || has_feed_positions; }
  //! The per-revolution feed step 1 selects by: the column's, else the positions'.
  const std::vector<double>& feed_signal() const {
    return has_feed_column ? signals.feed_column_mm_per_min : signals.feed_positions_mm_per_min;
  }
};

LogRevolutions log_revolutions(const force_log::ForceLog& log, const ForceColumns& columns, double rpm) {
  LogRevolutions revolutions;
  revolutions.peaks = force_log::revolution_peaks(columns.t_s, columns.fx_n, columns.fy_n, rpm);
  revolutions.signals = revolution_signals(log, revolutions.peaks);
  revolutions.has_feed_column = any_finite(revolutions.signals.feed_column_mm_per_min);
  revolutions.has_feed_positions = any_finite(revolutions.signals.feed_positions_mm_per_min);
  return revolutions;
}

//! The spindle_rpm column over the steady part against the conditions.
void check_spindle_rpm_column(Import& import, const LogRevolutions& revolutions, const SteadyRun& steady) {
  const double rpm = import.conditions.spindle_rpm;
  const double column_rpm = median_over(revolutions.signals.spindle_rpm, steady);
  if (!std::isfinite(column_rpm)) return;
  import.rpm_checked = true;
  if (!(column_rpm > 0.0) || relative(rpm, column_rpm) > import.options.rpm_tolerance) {
    import.problems.push_back({"conditions.spindle_rpm",
                               "= " + shortest_number_text(rpm) + " rev/min, but the spindle_rpm column of " +
                                   import.source + " reads " + six_digit_number_text(column_rpm) +
                                   " in the steady part: more than " + percent(import.options.rpm_tolerance) +
                                   " apart"});
  }
}

//! The feed_mm_per_min column and the feed from positions over the steady part against the conditions.
void check_feed_columns(Import& import, const LogRevolutions& revolutions, const SteadyRun& steady) {
  const double feed = import.conditions.feed_mm_per_min;
  const double tolerance = import.options.feed_tolerance;
  const double column_feed = median_over(revolutions.signals.feed_column_mm_per_min, steady);
  if (std::isfinite(column_feed) && relative(feed, column_feed) > tolerance) {
    import.problems.push_back({"conditions.feed_mm_per_min",
                               "= " + shortest_number_text(feed) + " mm/min, but the feed_mm_per_min column of " +
                                   import.source + " reads " + six_digit_number_text(column_feed) +
                                   " in the steady part: " + percent(relative(feed, column_feed)) +
                                   " apart, more than " + percent(tolerance)});
  }
  const double position_feed = median_over(revolutions.signals.feed_positions_mm_per_min, steady);
  if (std::isfinite(position_feed) && relative(feed, position_feed) > tolerance) {
    import.problems.push_back({"conditions.feed_mm_per_min",
                               "= " + shortest_number_text(feed) + " mm/min, but the positions (x_mm, y_mm) in " +
                                   import.source + " move at " + six_digit_number_text(position_feed) +
                                   " mm/min in the steady part: " + percent(relative(feed, position_feed)) +
                                   " apart, more than " + percent(tolerance)});
  }
}

//! The log's forces, spindle speed and feed in the steady part found from the forces alone.
void check_steady_part(Import& import, const LogRevolutions& revolutions, const SteadyRun& force_only) {
  if (!revolutions.peaks.empty() && !force_only.any_force) {
    import.problems.push_back({import.source, "has no cutting force: every per-revolution peak of |F_xy| is 0 N"});
  }
  if (force_only.size() > 0) {
    check_spindle_rpm_column(import, revolutions, force_only);
    check_feed_columns(import, revolutions, force_only);
  }
}

//! Step 1 of the steady-state rule: which revolutions are at the given feed, where the log says.
struct AtFeed {
  std::vector<bool> eligible;  // one per revolution
  int count = 0;               // eligible revolutions
};

AtFeed revolutions_at_feed(const Import& import, const LogRevolutions& revolutions) {
  const std::vector<double>& feed_signal = revolutions.feed_signal();
  const std::size_t n = revolutions.peaks.size();
  AtFeed at_feed{std::vector<bool>(n, true), 0};
  for (std::size_t k = 0; k < n; ++k) {
    if (std::isfinite(feed_signal[k])) {
      const double feed_mm_per_min = import.conditions.feed_mm_per_min;
      at_feed.eligible[k] = relative(feed_signal[k], feed_mm_per_min) <= import.options.feed_tolerance;
    }
    at_feed.count += at_feed.eligible[k] ? 1 : 0;
  }
  return at_feed;
}

//! Steps 1–5 of the steady-state rule: the steady run among the revolutions at the feed (that from the
//! forces alone when the log records no feed). Throws feedplan::InputError when it is too short.
SteadyRun steady_revolutions(const Import& import, const LogRevolutions& revolutions, const SteadyRun& force_only) {
  const AtFeed at_feed = revolutions_at_feed(import, revolutions);
  const SteadyRun steady =
      revolutions.has_feed() ? find_steady(revolutions.peaks, at_feed.eligible, import.options) : force_only;
  const int found = static_cast<int>(steady.size());
  if (found < import.options.min_steady_revolutions) {
    std::string where = "of " + std::to_string(revolutions.peaks.size()) + " complete revolutions at " +
                        shortest_number_text(import.conditions.spindle_rpm) + " rev/min";
    if (revolutions.has_feed()) where += ", " + std::to_string(at_feed.count) + " of them at the feed";
    throw InputError(import.source, "has " + std::to_string(found) + " steady revolution" +
                                        (found == 1 ? "" : "s") + " (" + where + "): at least " +
                                        std::to_string(import.options.min_steady_revolutions) +
                                        " are needed — record a longer cut at constant conditions");
  }
  return steady;
}

//! The steady peaks of the record and their mean, sample standard deviation, min and max.
void fill_statistics(const std::vector<force_log::RevolutionPeak>& peaks, const SteadyRun& steady,
                     CuttingTestRecord& record) {
  const int found = static_cast<int>(steady.size());
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
}

//! The force over a revolution averaged over the steady revolutions.
void fill_synchronous_average(const ForceColumns& columns, const std::vector<force_log::RevolutionPeak>& peaks,
                              const SteadyRun& steady, CuttingTestRecord& record) {
  const std::vector<force_log::RevolutionPeak> steady_peaks(peaks.begin() + static_cast<long>(steady.begin),
                                                            peaks.begin() + static_cast<long>(steady.end));
  force_log::SynchronousAverage average =
      force_log::synchronous_average(columns.t_s, columns.fx_n, columns.fy_n, steady_peaks);
  record.synchronous_fx_n = std::move(average.fx_n);
  record.synchronous_fy_n = std::move(average.fy_n);
}

//! Model inputs (docs/method.md §5.1): straight cut, f_z at the tool centre.
void fill_model_inputs(const CuttingTestConditions& conditions, const geometry::Tool& tool,
                       CuttingTestRecord& record) {
  const double radius_mm = tool.radius_mm();
  const double engagement_rad = conditions.mode == CutMode::kSlot
                                    ? std::numbers::pi
                                    : geometry::straight_engagement_rad(radius_mm, conditions.radial_depth_mm);
  record.feed_per_tooth_mm = conditions.feed_mm_per_min / (tool.flutes * conditions.spindle_rpm);
  record.chip_mm = record.feed_per_tooth_mm * geometry::steady_chip_factor(engagement_rad);
  record.contact_length_mm = radius_mm * engagement_rad;
}

//! Which revolutions are steady, and how many were trimmed off the plateau.
std::string steady_note(const std::vector<force_log::RevolutionPeak>& peaks, const SteadyRun& steady) {
  const force_log::RevolutionPeak& first = peaks[steady.begin];
  const force_log::RevolutionPeak& last = peaks[steady.end - 1];
  return "steady: " + std::to_string(steady.size()) + " of " + std::to_string(peaks.size()) +
         " complete revolutions (numbers " + std::to_string(first.revolution) + "–" +
         std::to_string(last.revolution) + ", t " + six_digit_number_text(first.t_start_s) + "–" +
         six_digit_number_text(last.t_end_s) + " s); " + std::to_string(steady.begin - steady.plateau_begin) +
         " trimmed at the start and " + std::to_string(steady.plateau_end - steady.end) + " at the end of the plateau";
}

//! How the feed was checked, or why not.
std::string feed_note(const LogRevolutions& revolutions, const SteadyRun& steady) {
  if (!revolutions.has_feed()) {
    return "feed: the log records neither feed nor positions (e.g. a Kistler export) — the feed "
           "was not checked, and the steady part comes from the forces alone";
  }
  const double measured_feed = median_over(revolutions.feed_signal(), steady);
  return "feed: " + six_digit_number_text(measured_feed) + " mm/min from the " +
         (revolutions.has_feed_column ? "feed_mm_per_min column" : "positions") +
         " in the steady part; revolutions at another feed were not used";
}

//! The notes of the record: the steady revolutions, the feed and spindle speed checks, sparse sampling and
//! large scatter.
void add_notes(const Import& import, const LogRevolutions& revolutions, const SteadyRun& steady,
               CuttingTestRecord& record) {
  record.notes.push_back(steady_note(revolutions.peaks, steady));
  record.notes.push_back(feed_note(revolutions, steady));
  if (!import.rpm_checked) {
    record.notes.push_back("spindle speed: the log does not record it — not checked");
  }
  const double samples_per_tooth = import.sample_rate_hz * 60.0 / (import.conditions.spindle_rpm * import.tool.flutes);
  if (std::isfinite(samples_per_tooth) && samples_per_tooth < kFewSamplesPerTooth) {
    record.notes.push_back("sampling: " + six_digit_number_text(samples_per_tooth) +
                           " samples per tooth period — the sampled peaks may read low");
  }
  if (record.peak_mean_n > 0.0 && record.peak_std_n / record.peak_mean_n > kLargeScatter) {
    record.notes.push_back("scatter: the steady peaks vary by " + percent(record.peak_std_n / record.peak_mean_n) +
                           " (std / mean), " + six_digit_number_text(record.peak_min_n) + "–" +
                           six_digit_number_text(record.peak_max_n) +
                           " N — runout, chatter or an unsteady process");
  }
}

}  // namespace

std::vector<InputProblem> validate(const CuttingTestConditions& conditions, const geometry::Tool& tool) {
  std::vector<InputProblem> problems;
  require_positive(problems, "tool.diameter_mm", tool.diameter_mm, "mm", "the cutting diameter");
  if (tool.flutes < 1) {
    problems.push_back({"tool.flutes", "= " + std::to_string(tool.flutes) + ": must be at least 1"});
  }
  if (!(std::isfinite(tool.helix_deg) && tool.helix_deg >= 0.0 && tool.helix_deg < 90.0)) {
    problems.push_back({"tool.helix_deg", "= " + shortest_number_text(tool.helix_deg) + ": must be in [0, 90) deg"});
  }
  require_positive(problems, "conditions.spindle_rpm", conditions.spindle_rpm, "rev/min", "the spindle speed");
  require_positive(problems, "conditions.feed_mm_per_min", conditions.feed_mm_per_min, "mm/min", "the feed");
  require_positive(problems, "conditions.axial_depth_mm", conditions.axial_depth_mm, "mm", "a_p");
  const double d = tool.diameter_mm;
  const double ae = conditions.radial_depth_mm;
  const bool diameter_ok = std::isfinite(d) && d > 0.0;
  if (!(std::isfinite(ae) && ae > 0.0)) {
    problems.push_back(
        {"conditions.radial_depth_mm", "= " + shortest_number_text(ae) + ": must be a finite number > 0 mm — a_e"});
  } else if (diameter_ok && ae > d * (1.0 + kSlotTolerance)) {
    problems.push_back({"conditions.radial_depth_mm", "= " + shortest_number_text(ae) + ": must be in (0, " +
                                                          shortest_number_text(d) +
                                                          "] mm — at most the tool diameter (tool.diameter_mm = " +
                                                          shortest_number_text(d) + ")"});
  } else if (diameter_ok) {
    const bool full = std::abs(ae - d) <= kSlotTolerance * d;
    if (conditions.mode == CutMode::kSlot && !full) {
      problems.push_back({"conditions.mode", "= slot: a slot cuts the full tool diameter, but radial_depth_mm = " +
                                                 shortest_number_text(ae) + " is not tool.diameter_mm = " +
                                                 shortest_number_text(d) + " — use down or up for a partial radial depth"});
    } else if (conditions.mode != CutMode::kSlot && full) {
      problems.push_back({"conditions.mode", "= " + to_string(conditions.mode) + ": radial_depth_mm = " +
                                                 shortest_number_text(ae) +
                                                 " is the tool diameter, which is a full slot — use slot"});
    }
  }
  return problems;
}

std::vector<InputProblem> validate(const CuttingTestImportOptions& options) {
  std::vector<InputProblem> problems;
  auto fraction = [&](const char* field, double value, bool zero_ok) {
    if (std::isfinite(value) && (zero_ok ? value >= 0.0 : value > 0.0) && value < 1.0) return;
    problems.push_back({field, "= " + shortest_number_text(value) + ": must be in " + (zero_ok ? "[0, 1)" : "(0, 1)")});
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
    problems.push_back({"options.trim_sigmas",
                        "= " + shortest_number_text(options.trim_sigmas) + ": must be a finite number ≥ 0"});
  }
  return problems;
}

CuttingTestRecord import_cutting_test(const force_log::ForceLog& log, const CuttingTestConditions& conditions,
                                      const geometry::Tool& tool, const CuttingTestImportOptions& options) {
  check_input(conditions, tool, options);
  Import import(log, conditions, tool, options);
  require_force_samples(log, import.source);
  CuttingTestRecord record;
  record.conditions = conditions;
  record.source = import.source;

  check_metadata_spindle_rpm(import);
  const ForceColumns columns = force_columns(log);
  import.sample_rate_hz = time_column_rate_hz(columns.t_s);
  check_metadata_sample_rate(import);
  const LogRevolutions revolutions = log_revolutions(log, columns, conditions.spindle_rpm);
  record.revolutions_total = static_cast<int>(revolutions.peaks.size());
  // The steady part from the forces alone, to check the log's feed and spindle speed in it.
  const SteadyRun force_only =
      find_steady(revolutions.peaks, std::vector<bool>(revolutions.peaks.size(), true), options);
  check_steady_part(import, revolutions, force_only);
  if (!import.problems.empty()) throw InputError(std::move(import.problems));

  const SteadyRun steady = steady_revolutions(import, revolutions, force_only);
  fill_statistics(revolutions.peaks, steady, record);
  fill_synchronous_average(columns, revolutions.peaks, steady, record);
  fill_model_inputs(conditions, tool, record);
  add_notes(import, revolutions, steady, record);
  return record;
}

CuttingTestRecord import_cutting_test(const std::string& log_path, const CuttingTestConditions& conditions,
                                      const geometry::Tool& tool, const CuttingTestImportOptions& options) {
  CuttingTestImportOptions named = options;
  if (named.source_name.empty()) named.source_name = log_path;
  // Validate before reading so that bad conditions are reported without touching the file.
  check_input(conditions, tool, named);
  return import_cutting_test(force_log::load_force_log(log_path), conditions, tool, named);
}

}  // namespace feedplan::model_db
