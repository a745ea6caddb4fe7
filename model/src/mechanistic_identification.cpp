#include "feedplan/model/mechanistic_identification.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"
#include "feedplan/model/mechanistic_force.hpp"
#include "bin_regressors.hpp"
#include "identified_coefficients.hpp"
#include "peak_matching.hpp"
#include "runout_refinement.hpp"
#include "sensed_bin_rows.hpp"
#include "sensor_refinement.hpp"
#include "sensor_search.hpp"
#include "size_effect_search.hpp"

namespace feedplan::model {
namespace {

using namespace detail;

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr int kMinBins = 8;
constexpr int kUnknowns = 4;  // K_tc, K_rc, K_te, K_re
constexpr const char* kNames[kUnknowns] = {"K_tc", "K_rc", "K_te", "K_re"};
constexpr int kGoldenIterations = 30;

std::string test_name(const MechanisticCuttingTest& test, std::size_t index) {
  return test.name.empty() ? "tests[" + std::to_string(index) + "]" : test.name;
}

//! Sum of squared residuals of the least-squares fit of y by a's columns.
double fit_residual(const Eigen::MatrixXd& a, const Eigen::VectorXd& y) {
  const Eigen::VectorXd x = a.completeOrthogonalDecomposition().solve(y);
  return (a * x - y).squaredNorm();
}

//! The phase of one test: the best of the grid of sub-step offsets, then refined by golden-section search
//! between its neighbours, each phase scored by the test's own four-coefficient fit.
double find_phase(const MechanisticCuttingTest& test) {
  const int bins = bin_count(test);
  const int steps = bins * kPhaseStepsPerBin;
  const MechanisticModel plain;
  const auto table = regressor_table(test);
  const Eigen::VectorXd y = measured(test);
  int best = 0;
  double best_residual = INFINITY;
  for (int offset = 0; offset < steps; ++offset) {
    const double r = fit_residual(table_rows(table, bins, offset), y);
    if (r < best_residual) {
      best_residual = r;
      best = offset;
    }
  }
  const double step_rad = kTwoPi / steps;
  double lo = (best - 1) * step_rad, hi = (best + 1) * step_rad;
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  double p1 = hi - g * (hi - lo), p2 = lo + g * (hi - lo);
  double r1 = fit_residual(phase_rows(test, p1, plain), y), r2 = fit_residual(phase_rows(test, p2, plain), y);
  for (int i = 0; i < kGoldenIterations; ++i) {
    if (r1 < r2) {
      hi = p2, p2 = p1, r2 = r1;
      p1 = hi - g * (hi - lo);
      r1 = fit_residual(phase_rows(test, p1, plain), y);
    } else {
      lo = p1, p1 = p2, r1 = r2;
      p2 = lo + g * (hi - lo);
      r2 = fit_residual(phase_rows(test, p2, plain), y);
    }
  }
  const double phase = 0.5 * (lo + hi);
  return phase - kTwoPi * std::floor(phase / kTwoPi);
}

std::string coefficient_text(double value) { return six_digit_number_text(value); }

//! The weakest direction of the scaled regressors in words: the coefficients that take part in it.
std::string weakest_direction_text(const Eigen::VectorXd& v, double condition) {
  std::string combination;
  for (int c = 0; c < kUnknowns; ++c) {
    if (std::abs(v(c)) < 0.2) continue;
    if (!combination.empty()) combination += v(c) < 0 ? " − " : " + ";
    else if (v(c) < 0) combination += "−";
    combination += fixed_number_text(std::abs(v(c)), 2) + "·" + kNames[c];
  }
  return combination + " (in units of each coefficient's scale): the tests hardly change the force along this "
                       "combination (condition number " + coefficient_text(condition) + ")";
}

//! The note when every test has the same feed per tooth, or empty.
std::string single_feed_text(const std::vector<MechanisticCuttingTest>& tests, double tolerance) {
  double lo = INFINITY, hi = 0.0;
  for (const auto& t : tests) {
    lo = std::min(lo, t.feed_per_tooth_mm);
    hi = std::max(hi, t.feed_per_tooth_mm);
  }
  if (hi - lo > tolerance * hi) return {};
  return "K_tc against K_te and K_rc against K_re: every test is at f_z ≈ " + coefficient_text(hi) +
         " mm, so the cutting terms (growing with the chip) and the edge terms (not) cannot be separated by the feed; "
         "the fit tells them apart only by the shape of the force pulses, which the dynamometer's dynamics and the "
         "binning distort — add tests at a second feed (at least 1.5× apart)";
}

}  // namespace

ImmersionArc straight_cut_arc(StraightCutSide side, double radial_depth_mm, double radius_mm) {
  assert(radius_mm > 0.0 && radial_depth_mm > 0.0 && radial_depth_mm <= 2.0 * radius_mm + 1e-12);
  const double pi = std::numbers::pi;
  if (side == StraightCutSide::kSlot || radial_depth_mm >= 2.0 * radius_mm) return {0.0, pi};
  const double swept = std::acos(std::clamp(1.0 - radial_depth_mm / radius_mm, -1.0, 1.0));
  return side == StraightCutSide::kDown ? ImmersionArc{pi - swept, pi} : ImmersionArc{0.0, swept};
}

std::vector<InputProblem> validate(const std::vector<MechanisticCuttingTest>& tests, bool identify_runout,
                                   bool identify_sensor) {
  ProblemList problems("");
  if (tests.empty()) problems.add("tests", "is empty: at least one cutting test is needed");
  if (identify_runout && !tests.empty() && tests.front().cutter.flutes < 2) {
    problems.add(test_name(tests.front(), 0) + ".cutter.flutes", "= " + std::to_string(tests.front().cutter.flutes) +
                                                                    ": identifying runout needs at least 2 flutes");
  }
  for (std::size_t i = 0; i < tests.size(); ++i) {
    const MechanisticCuttingTest& t = tests[i];
    const std::string prefix = test_name(t, i) + ".";
    problems.add_all(validate(MechanisticModel{}, t.cutter, prefix));
    if (!(std::isfinite(t.arc.entry_rad) && std::isfinite(t.arc.exit_rad) && t.arc.entry_rad < t.arc.exit_rad)) {
      problems.add(prefix + "arc", "= [" + shortest_number_text(t.arc.entry_rad) + ", " +
                                       shortest_number_text(t.arc.exit_rad) + "] rad: must be finite with entry < exit");
    }
    if (identify_runout && t.cutter.flutes != tests.front().cutter.flutes) {
      problems.add(prefix + "cutter.flutes", "= " + std::to_string(t.cutter.flutes) + ": identifying runout needs one "
                   "cutter for all tests, and the first has " + std::to_string(tests.front().cutter.flutes));
    }
    problems.positive(prefix + "axial_depth_mm", t.axial_depth_mm);
    problems.positive(prefix + "feed_per_tooth_mm", t.feed_per_tooth_mm);
    if (identify_sensor && !(std::isfinite(t.spindle_rpm) && t.spindle_rpm > 0.0)) {
      problems.add(prefix + "spindle_rpm", "= " + shortest_number_text(t.spindle_rpm) +
                                               ": identifying the sensor needs the spindle speed (finite and > 0)");
    }
    if (t.synchronous_fx_n.size() != t.synchronous_fy_n.size()) {
      problems.add(prefix + "synchronous_fy_n", "has " + std::to_string(t.synchronous_fy_n.size()) +
                                                    " bins: must have as many as synchronous_fx_n (" +
                                                    std::to_string(t.synchronous_fx_n.size()) + ")");
    } else if (t.synchronous_fx_n.size() < static_cast<std::size_t>(kMinBins)) {
      problems.add(prefix + "synchronous_fx_n", "has " + std::to_string(t.synchronous_fx_n.size()) +
                                                    " bins: at least " + std::to_string(kMinBins) + " are needed");
    }
    for (std::size_t p = 0; p < t.revolution_peaks_n.size(); ++p) {
      if (!(std::isfinite(t.revolution_peaks_n[p]) && t.revolution_peaks_n[p] > 0.0)) {
        problems.add(prefix + "revolution_peaks_n[" + std::to_string(p) + "]",
                     "= " + shortest_number_text(t.revolution_peaks_n[p]) + ": must be finite and > 0");
        break;
      }
    }
    for (std::size_t b = 0; b < std::min(t.synchronous_fx_n.size(), t.synchronous_fy_n.size()); ++b) {
      if (!std::isfinite(t.synchronous_fx_n[b]) || !std::isfinite(t.synchronous_fy_n[b])) {
        problems.add(prefix + "synchronous force bin " + std::to_string(b), "is not finite");
        break;
      }
    }
  }
  return problems.take();
}

std::vector<InputProblem> validate(const MechanisticIdentificationOptions& options) {
  ProblemList problems("options.");
  if (!options.identify_sensor) return problems.take();
  problems.positive("sensor_min_frequency_hz", options.sensor_min_frequency_hz);
  problems.positive("sensor_max_frequency_hz", options.sensor_max_frequency_hz);
  if (options.sensor_max_frequency_hz <= options.sensor_min_frequency_hz) {
    problems.add_value("sensor_max_frequency_hz", shortest_number_text(options.sensor_max_frequency_hz),
                       "must be > sensor_min_frequency_hz = " + shortest_number_text(options.sensor_min_frequency_hz));
  }
  return problems.take();
}

namespace {

//! The regressors of every test at its phase with `model`'s runout, stacked, and the measured bins.
void stack_rows(const std::vector<MechanisticCuttingTest>& tests, const std::vector<double>& phases,
                const MechanisticModel& model, Eigen::MatrixXd& a, Eigen::VectorXd& y) {
  Eigen::Index rows = 0;
  for (const auto& t : tests) rows += 2 * bin_count(t);
  a.resize(rows, kUnknowns);
  y.resize(rows);
  Eigen::Index row = 0;
  for (std::size_t i = 0; i < tests.size(); ++i) {
    const Eigen::Index n = 2 * bin_count(tests[i]);
    a.middleRows(row, n) = phase_rows(tests[i], phases[i], model);
    y.segment(row, n) = measured(tests[i]);
    row += n;
  }
}

//! As stack_rows, with the kernel's force read through `sensor`.
void stack_sensed_rows(const std::vector<MechanisticCuttingTest>& tests, const std::vector<SensedBinning>& binnings,
                       const std::vector<double>& phases, const MechanisticModel& model, const SensorResponse& sensor,
                       Eigen::MatrixXd& a, Eigen::VectorXd& y) {
  stack_rows(tests, phases, model, a, y);
  Eigen::Index row = 0;
  for (std::size_t i = 0; i < tests.size(); ++i) {
    const Eigen::MatrixXd rows = binnings[i].rows(binnings[i].spectrum(tests[i], phases[i], model), sensor);
    a.middleRows(row, rows.rows()) = rows;
    row += rows.rows();
  }
}

//! The linear least-squares fit of the coefficients, its residuals, condition number and covariance.
Eigen::VectorXd fit_coefficients(const std::vector<MechanisticCuttingTest>& tests, const Eigen::MatrixXd& a,
                                 const Eigen::VectorXd& y, MechanisticIdentification& result, Eigen::VectorXd& weakest) {
  const auto rows = a.rows();
  // Columns scaled to unit norm so the condition number compares shapes, not units.
  Eigen::VectorXd scale = a.colwise().norm().transpose();
  for (int c = 0; c < kUnknowns; ++c) {
    if (scale(c) == 0.0) scale(c) = 1.0;
  }
  const Eigen::MatrixXd scaled = a * scale.cwiseInverse().asDiagonal();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd sv = svd.singularValues();
  result.condition_number = sv(kUnknowns - 1) > 0.0 ? sv(0) / sv(kUnknowns - 1) : INFINITY;
  const Eigen::VectorXd x = scale.cwiseInverse().asDiagonal() * scaled.completeOrthogonalDecomposition().solve(y);

  const Eigen::VectorXd residual = a * x - y;
  result.rms_residual_n = std::sqrt(residual.squaredNorm() / static_cast<double>(rows));
  result.test_rms_residual_n.clear();
  Eigen::Index row = 0;
  for (const auto& t : tests) {
    const Eigen::Index n = 2 * bin_count(t);
    result.test_rms_residual_n.push_back(std::sqrt(residual.segment(row, n).squaredNorm() / static_cast<double>(n)));
    row += n;
  }
  const double sigma2 = residual.squaredNorm() / static_cast<double>(std::max<Eigen::Index>(rows - kUnknowns, 1));
  const Eigen::MatrixXd v = svd.matrixV();
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(kUnknowns, kUnknowns);
  for (int k = 0; k < kUnknowns; ++k) {
    const double inv2 = sv(k) > 0.0 ? 1.0 / (sv(k) * sv(k)) : INFINITY;
    cov += inv2 * v.col(k) * v.col(k).transpose();
  }
  cov = sigma2 * scale.cwiseInverse().asDiagonal() * cov * scale.cwiseInverse().asDiagonal();
  for (int i = 0; i < kUnknowns; ++i) {
    for (int j = 0; j < kUnknowns; ++j) result.covariance[i][j] = cov(i, j);
  }
  weakest = v.col(kUnknowns - 1);
  return x;
}

//! Runout with the smallest at 0 (a common offset of all teeth changes no chip).
std::vector<double> lowest_at_zero(std::vector<double> runout_mm) {
  const double lowest = *std::min_element(runout_mm.begin(), runout_mm.end());
  for (double& r : runout_mm) r -= lowest;
  return runout_mm;
}

//! The sensor step of identify_mechanistic: search, then refine with the coefficients, phases and, when
//! `model` has them, runout and helix; `result` gets the sensor, phases, runout and helix, `x` the
//! coefficients and `a`, `y` the rows through the sensor.
void identify_sensor(const std::vector<MechanisticCuttingTest>& tests, const MechanisticIdentificationOptions& options,
                     MechanisticModel model, MechanisticIdentification& result, Eigen::VectorXd& x,
                     Eigen::MatrixXd& a, Eigen::VectorXd& y, std::vector<SensedBinning>& binnings) {
  double nyquist_hz = INFINITY;
  for (const auto& t : tests) {
    binnings.emplace_back(t);
    nyquist_hz = std::min(nyquist_hz, binnings.back().nyquist_hz());
  }
  double max_hz = options.sensor_max_frequency_hz;
  if (nyquist_hz < max_hz) {
    max_hz = nyquist_hz;
    result.unidentifiable.push_back(
        "sensor modes above " + six_digit_number_text(nyquist_hz) + " Hz: the synchronous averages' bins resolve the "
        "harmonics of the revolution only below their Nyquist frequency (bins/2 · rpm/60), so the search for the "
        "modes stops there instead of at " + six_digit_number_text(options.sensor_max_frequency_hz) + " Hz");
  }
  const double min_hz = std::min(options.sensor_min_frequency_hz, 0.5 * max_hz);

  SensorSearchData data;
  for (std::size_t i = 0; i < tests.size(); ++i) {
    data.binnings.push_back(&binnings[i]);
    data.spectra.push_back(binnings[i].spectrum(tests[i], result.phase_rad[i], model));
  }
  data.measured = y;
  SensorRefinementStart start;
  start.sensor = search_sensor(data, min_hz, max_hz);
  start.coefficients = {x(0), x(1), x(2), x(3)};
  start.phase_rad = result.phase_rad;
  start.runout_mm = model.runout_mm;
  start.helix_deg = model.helix_deg;
  start.size_exponent = model.size_exponent;
  start.size_reference_chip_mm = model.size_reference_chip_mm;
  const SensorRefinement refined = refine_sensor(tests, binnings, start, min_hz, max_hz);

  result.sensor = refined.sensor;
  result.sensor_converged = refined.converged;
  result.sensor_report = refined.message;
  result.phase_rad = refined.phase_rad;
  model.runout_mm = refined.runout_mm;
  model.helix_deg = refined.helix_deg;
  result.model.runout_mm = model.runout_mm;
  result.model.helix_deg = model.helix_deg;
  stack_sensed_rows(tests, binnings, result.phase_rad, model, refined.sensor, a, y);
  if (!refined.converged) result.unidentifiable.push_back("sensor: the refinement did not converge (" + refined.message + ")");
}

//! The size-effect step of identify_mechanistic: m by search_size_exponent with the runout, helix, phases and
//! (when identified, `binnings` holding the tests' binnings) sensor of `result` held, and h_ref the tests'
//! geometric mean feed; `result.model` gets m and h_ref, `x` the coefficients refitted with them and `a`, `y`
//! the rows. Returns whether the search stopped at its upper bound.
bool search_size_effect(const std::vector<MechanisticCuttingTest>& tests, const std::vector<SensedBinning>& binnings,
                        MechanisticIdentification& result, Eigen::VectorXd& x, Eigen::MatrixXd& a, Eigen::VectorXd& y,
                        Eigen::VectorXd& weakest) {
  MechanisticModel held = result.model;
  held.size_reference_chip_mm = size_reference_chip_mm(tests);
  const auto stack = [&](double exponent) {
    held.size_exponent = exponent;
    if (result.sensor) stack_sensed_rows(tests, binnings, result.phase_rad, held, *result.sensor, a, y);
    else stack_rows(tests, result.phase_rad, held, a, y);
  };
  const SizeEffectSearch search = search_size_exponent([&](double exponent) {
    stack(exponent);
    return fit_residual(a, y);
  });
  stack(search.exponent);
  x = fit_coefficients(tests, a, y, result, weakest);
  result.model.size_exponent = search.exponent;
  result.model.size_reference_chip_mm = held.size_reference_chip_mm;
  return search.at_upper_bound;
}

//! The last step of identify_mechanistic with peaks: the coefficients matched to the bins `a`, `y` and the
//! tests' mean peaks from the bins' own fit `x` (peak_matching.hpp); `result` gets the covariance and the
//! peaks' diagnostics.
Eigen::VectorXd matched_coefficients(const std::vector<MechanisticCuttingTest>& tests, const Eigen::MatrixXd& a,
                                     const Eigen::VectorXd& y, const Eigen::VectorXd& x,
                                     MechanisticIdentification& result) {
  const PeakMatching matched = match_peaks(tests, a, y, result.model, result.sensor, Eigen::Vector4d(x));
  result.covariance = matched.covariance;
  result.tests_peak_matched = matched.tests_matched;
  result.peak_rms_residual_n = matched.peak_rms_residual_n;
  result.peak_scatter_n = matched.peak_scatter_n;
  result.matched_rms_residual_n = matched.bins_rms_residual_n;
  return matched.coefficients;
}

}  // namespace

MechanisticModel refit_coefficients(const std::vector<MechanisticCuttingTest>& tests,
                                    const std::vector<double>& phase_rad, const MechanisticModel& fixed,
                                    bool match_peaks) {
  const std::vector<InputProblem> problems = validate(tests, false);
  if (!problems.empty()) throw InputError(problems);
  if (phase_rad.size() != tests.size()) {
    throw InputError("phase_rad", "has " + std::to_string(phase_rad.size()) + " values: must have one per test (" +
                                      std::to_string(tests.size()) + ")");
  }
  Eigen::MatrixXd a;
  Eigen::VectorXd y, weakest;
  stack_rows(tests, phase_rad, fixed, a, y);
  MechanisticIdentification scratch;
  scratch.model = fixed;
  Eigen::VectorXd x = fit_coefficients(tests, a, y, scratch, weakest);
  if (match_peaks && has_peaks(tests)) x = matched_coefficients(tests, a, y, x, scratch);
  MechanisticModel model = fixed;
  set_identified_coefficients(model, x);
  return model;
}

MechanisticIdentification identify_mechanistic(const std::vector<MechanisticCuttingTest>& tests,
                                               const MechanisticIdentificationOptions& options) {
  std::vector<InputProblem> problems = validate(tests, options.identify_runout, options.identify_sensor);
  const std::vector<InputProblem> option_problems = validate(options);
  problems.insert(problems.end(), option_problems.begin(), option_problems.end());
  if (!problems.empty()) throw InputError(problems);

  MechanisticIdentification result;
  for (const auto& t : tests) result.phase_rad.push_back(find_phase(t));
  Eigen::MatrixXd a;
  Eigen::VectorXd y, weakest;
  stack_rows(tests, result.phase_rad, MechanisticModel{}, a, y);
  Eigen::VectorXd x = fit_coefficients(tests, a, y, result, weakest);
  std::vector<SensedBinning> binnings;
  const bool one_feed = !single_feed_text(tests, options.same_feed_tolerance).empty();
  const bool size_effect = options.identify_size_effect && !one_feed;
  // A first exponent without runout: the runout's refinement starts from it and refines it with the rest.
  if (size_effect) search_size_effect(tests, binnings, result, x, a, y, weakest);

  if (options.identify_runout) {
    RunoutSizeEffect size{size_effect, result.model.size_exponent, result.model.size_reference_chip_mm};
    const RunoutRefinement refined =
        refine_runout(tests, result.phase_rad, {x(0), x(1), x(2), x(3)}, options.identify_helix, size);
    result.runout_converged = refined.converged;
    result.runout_report = refined.message;
    result.phase_rad = refined.phase_rad;
    result.model.size_exponent = refined.size_exponent;
    MechanisticModel with_runout;
    with_runout.runout_mm = refined.runout_mm;
    with_runout.helix_deg = refined.helix_deg;
    with_runout.size_exponent = refined.size_exponent;
    with_runout.size_reference_chip_mm = result.model.size_reference_chip_mm;
    result.model.helix_deg = refined.helix_deg;
    stack_rows(tests, result.phase_rad, with_runout, a, y);
    x = fit_coefficients(tests, a, y, result, weakest);
    result.model.runout_mm = lowest_at_zero(refined.runout_mm);
    result.unidentifiable.push_back(
        "which physical tooth is tooth 0, and a runout common to all teeth: the runout is reported with the "
        "smallest at 0, numbered from the tooth at the first test's phase");
    if (!refined.converged) result.unidentifiable.push_back("runout: the refinement did not converge (" + refined.message + ")");
  }
  if (options.identify_sensor) {
    MechanisticModel fitted;
    if (options.identify_runout) fitted.runout_mm = result.model.runout_mm;
    fitted.helix_deg = result.model.helix_deg;
    fitted.size_exponent = result.model.size_exponent;
    fitted.size_reference_chip_mm = result.model.size_reference_chip_mm;
    identify_sensor(tests, options, fitted, result, x, a, y, binnings);
    x = fit_coefficients(tests, a, y, result, weakest);
    if (options.identify_runout) result.model.runout_mm = lowest_at_zero(result.model.runout_mm);
  }
  if (size_effect && search_size_effect(tests, binnings, result, x, a, y, weakest)) {
    result.unidentifiable.push_back("size effect: the fit keeps improving up to the largest exponent searched (" +
                                    six_digit_number_text(kMaxSizeExponent) + "), where it is held; the tests' feeds "
                                    "do not separate the exponent from the edge coefficients");
  }
  if (options.identify_size_effect && one_feed) {
    result.unidentifiable.push_back("size effect: every test is at one feed per tooth, and the exponent shows only in "
                                    "how the force grows with the chip; it is left at 0");
  }
  if (options.match_peaks && has_peaks(tests)) x = matched_coefficients(tests, a, y, x, result);
  set_identified_coefficients(result.model, x);

  result.unidentifiable.push_back(
      "K_ac, K_ae: the synchronous averages hold only Fx and Fy, and the axial coefficients act only on Fz; "
      "they are left at 0");
  if (result.condition_number > options.max_condition_number) {
    result.status = IdentificationStatus::kIllConditioned;
    result.unidentifiable.push_back(weakest_direction_text(weakest, result.condition_number));
  }
  if (const std::string note = single_feed_text(tests, options.same_feed_tolerance); !note.empty()) {
    result.status = IdentificationStatus::kIllConditioned;
    result.unidentifiable.push_back(note);
  }
  return result;
}

}  // namespace feedplan::model
