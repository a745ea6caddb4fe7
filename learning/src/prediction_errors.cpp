#include "feedplan/learning/prediction_errors.hpp"

#include <algorithm>
#include <cmath>

#include "feedplan/model/model_prediction.hpp"

namespace feedplan::learning {
namespace {

// Nearest-rank percentile of sorted values, p in (0, 100].
double percentile(const std::vector<double>& sorted, double p) {
  const auto rank = static_cast<std::size_t>(std::ceil(p / 100.0 * static_cast<double>(sorted.size())));
  return sorted[std::clamp<std::size_t>(rank, 1, sorted.size()) - 1];
}

}  // namespace

PredictionErrors prediction_errors(const std::vector<double>& measured_n, const std::vector<double>& predicted_n) {
  PredictionErrors out;
  std::vector<double> abs_percent;
  double sum_squares_n = 0.0;
  double sum_squares_percent = 0.0;
  double sum_percent = 0.0;
  for (std::size_t i = 0; i < std::min(measured_n.size(), predicted_n.size()); ++i) {
    if (!(measured_n[i] > 0.0)) continue;
    const double error_n = predicted_n[i] - measured_n[i];
    const double error_percent = 100.0 * error_n / measured_n[i];
    sum_squares_n += error_n * error_n;
    sum_squares_percent += error_percent * error_percent;
    sum_percent += error_percent;
    abs_percent.push_back(std::abs(error_percent));
  }
  out.n = static_cast<int>(abs_percent.size());
  if (out.n == 0) return out;
  std::sort(abs_percent.begin(), abs_percent.end());
  out.rms_n = std::sqrt(sum_squares_n / out.n);
  out.rms_percent = std::sqrt(sum_squares_percent / out.n);
  out.max_abs_percent = abs_percent.back();
  out.median_abs_percent = percentile(abs_percent, 50.0);
  out.p90_abs_percent = percentile(abs_percent, 90.0);
  out.p95_abs_percent = percentile(abs_percent, 95.0);
  out.mean_percent = sum_percent / out.n;
  return out;
}

PredictionErrors prediction_errors(const model::ResponseSurfaceModel& model, const std::vector<LearningSample>& samples) {
  std::vector<double> measured, predicted;
  for (const LearningSample& sample : samples) {
    measured.push_back(sample.force_n);
    predicted.push_back(model::predict(model, sample.chip_mm, sample.contact_length_mm).force_n);
  }
  return prediction_errors(measured, predicted);
}

}  // namespace feedplan::learning
