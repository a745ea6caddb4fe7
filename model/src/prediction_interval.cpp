#include "feedplan/model/prediction_interval.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"
#include "feedplan/model/mechanistic_force.hpp"
#include "feedplan/model/model_prediction.hpp"
#include "feedplan/model/sensed_peak.hpp"
#include "identified_coefficients.hpp"

namespace feedplan::model {
namespace {


void check_spread_and_z(ProblemList& problems, double revolution_spread_rel, double z) {
  problems.non_negative("revolution_spread_rel", revolution_spread_rel);
  problems.positive("z", z);
}

PredictionInterval make_interval(double predicted_n, double fit_variance_n2, double revolution_spread_rel, double z) {
  PredictionInterval interval;
  interval.predicted_n = predicted_n;
  // A covariance with a non-negative diagonal may still not be positive semi-definite (rounding, or a
  // covariance assembled by hand): a negative quadratic form is taken as 0, not as a NaN.
  interval.fit_sd_n = std::sqrt(std::max(fit_variance_n2, 0.0));
  interval.spread_sd_n = revolution_spread_rel * std::abs(predicted_n);
  const double half_width_n = z * std::hypot(interval.fit_sd_n, interval.spread_sd_n);
  interval.lower_n = predicted_n - half_width_n;
  interval.upper_n = predicted_n + half_width_n;
  return interval;
}

}  // namespace

PredictionInterval response_surface_interval(const ResponseSurfaceModel& model, const Covariance& covariance,
                                             double chip_mm, double contact_length_mm, double revolution_spread_rel,
                                             double z) {
  ProblemList problems;
  problems.non_negative("chip_mm", chip_mm);
  problems.non_negative("contact_length_mm", contact_length_mm);
  check_spread_and_z(problems, revolution_spread_rel, z);
  for (std::size_t k = 0; k < covariance.entries().size(); ++k) {
    problems.finite("covariance[" + std::to_string(k) + "]", covariance.entries()[k]);
  }
  for (std::size_t j = 0; j < Covariance::kSize; ++j) {
    const double v = covariance.variance(j);
    if (v < 0.0) {
      problems.add_value("covariance[" + std::to_string(j * Covariance::kSize + j) + "]", shortest_number_text(v),
                         "must be ≥ 0 — a variance (diagonal entry)");
    }
  }
  problems.add_all(validate(model));
  problems.throw_if_any();

  const std::array<double, 6> psi = regressors(model, chip_mm, contact_length_mm);
  const double predicted_n = predict(model, chip_mm, contact_length_mm).force_n;
  return make_interval(predicted_n, covariance.quadratic_form(psi), revolution_spread_rel, z);
}

namespace {

//! The problems of a mechanistic interval's inputs shared by both kinds of peak.
void check_mechanistic(ProblemList& problems, const MechanisticModel& model,
                       const std::array<std::array<double, 4>, 4>& covariance, std::span<const EngagedSection> sections,
                       const CutterGeometry& cutter, double feed_per_tooth_mm) {
  problems.add_all(validate(model, cutter));
  for (std::size_t i = 0; i < sections.size(); ++i) {
    const EngagedSection& s = sections[i];
    const std::string prefix = "sections[" + std::to_string(i) + "].";
    problems.finite(prefix + "bottom_mm", s.bottom_mm);
    problems.finite(prefix + "top_mm", s.top_mm);
    if (std::isfinite(s.bottom_mm) && std::isfinite(s.top_mm) && s.top_mm < s.bottom_mm) {
      problems.add_value(prefix + "top_mm", shortest_number_text(s.top_mm),
                         "must be ≥ bottom_mm = " + shortest_number_text(s.bottom_mm));
    }
    for (std::size_t a = 0; a < s.arcs.size(); ++a) {
      const ImmersionArc& arc = s.arcs[a];
      if (!(std::isfinite(arc.entry_rad) && std::isfinite(arc.exit_rad) && arc.entry_rad <= arc.exit_rad)) {
        problems.add(prefix + "arcs[" + std::to_string(a) + "]",
                     "= [" + shortest_number_text(arc.entry_rad) + ", " + shortest_number_text(arc.exit_rad) +
                         "] rad: must be finite with entry ≤ exit");
      }
    }
  }
  problems.positive("feed_per_tooth_mm", feed_per_tooth_mm);
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      problems.finite("covariance[" + std::to_string(i) + "][" + std::to_string(j) + "]", covariance[i][j]);
    }
    if (covariance[i][i] < 0.0) {
      problems.add_value("covariance[" + std::to_string(i) + "][" + std::to_string(i) + "]",
                         shortest_number_text(covariance[i][i]), "must be ≥ 0 — a variance (diagonal entry)");
    }
  }
}

//! gᵀ C g with g = uᵀR restricted to K_tc, K_rc, K_te, K_re: R the 2×6 XY regressors at the peak's angle, u
//! the unit XY force there (∂|F_xy|/∂K_c = u · (row_x[c], row_y[c])).
double peak_variance_n2(const std::array<double, 6>& row_x, const std::array<double, 6>& row_y,
                        const MechanisticModel& model, const std::array<std::array<double, 4>, 4>& covariance) {
  const std::array<double, 4> g = detail::peak_gradient(row_x, row_y, model);
  double variance_n2 = 0.0;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) variance_n2 += g[i] * covariance[i][j] * g[j];
  }
  return variance_n2;
}

}  // namespace

PredictionInterval mechanistic_peak_interval(const MechanisticModel& model,
                                             const std::array<std::array<double, 4>, 4>& covariance,
                                             std::span<const EngagedSection> sections, const CutterGeometry& cutter,
                                             double feed_per_tooth_mm, double revolution_spread_rel, double z) {
  ProblemList problems;
  check_mechanistic(problems, model, covariance, sections, cutter, feed_per_tooth_mm);
  check_spread_and_z(problems, revolution_spread_rel, z);
  problems.throw_if_any();

  const MechanisticPeak peak = predicted_peak(model, sections, cutter, feed_per_tooth_mm);
  if (!(peak.force_n > 0.0)) return make_interval(0.0, 0.0, revolution_spread_rel, z);
  const ForceRegressors r = regressors(model, sections, cutter, feed_per_tooth_mm, peak.spindle_angle_rad);
  return make_interval(peak.force_n, peak_variance_n2(r.rows[0], r.rows[1], model, covariance), revolution_spread_rel, z);
}

PredictionInterval mechanistic_sensed_peak_interval(const MechanisticModel& model,
                                                    const std::array<std::array<double, 4>, 4>& covariance,
                                                    std::span<const EngagedSection> sections,
                                                    const CutterGeometry& cutter, double feed_per_tooth_mm,
                                                    const SensorResponse& sensor, double spindle_rpm,
                                                    double revolution_spread_rel, double z) {
  ProblemList problems;
  check_mechanistic(problems, model, covariance, sections, cutter, feed_per_tooth_mm);
  problems.add_all(validate(sensor));
  problems.positive("spindle_rpm", spindle_rpm);
  check_spread_and_z(problems, revolution_spread_rel, z);
  problems.throw_if_any();

  const SensedPeak peak = predicted_sensed_peak(model, sections, cutter, feed_per_tooth_mm, sensor, spindle_rpm);
  if (!(peak.force_n > 0.0)) return make_interval(0.0, 0.0, revolution_spread_rel, z);
  return make_interval(peak.force_n, peak_variance_n2(peak.regressors[0], peak.regressors[1], model, covariance),
                       revolution_spread_rel, z);
}

PredictionInterval with_cross_validated_error(const PredictionInterval& interval, double cross_validated_rel,
                                              double z) {
  if (!(std::isfinite(cross_validated_rel) && cross_validated_rel >= 0.0)) {
    throw InputError("cross_validated_rel", "= " + shortest_number_text(cross_validated_rel) + ": must be finite and ≥ 0");
  }
  if (!(std::isfinite(z) && z > 0.0)) throw InputError("z", "= " + shortest_number_text(z) + ": must be finite and > 0");
  PredictionInterval widened = interval;
  widened.fit_sd_n = std::max(interval.fit_sd_n, cross_validated_rel * std::abs(interval.predicted_n));
  const double half_width_n = z * std::hypot(widened.fit_sd_n, widened.spread_sd_n);
  widened.lower_n = interval.predicted_n - half_width_n;
  widened.upper_n = interval.predicted_n + half_width_n;
  return widened;
}

}  // namespace feedplan::model
