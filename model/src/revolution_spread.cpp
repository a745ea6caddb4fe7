#include "feedplan/model/revolution_spread.hpp"

#include <cmath>
#include <string>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"

namespace feedplan::model {

double pooled_revolution_spread_rel(const std::vector<std::vector<double>>& peaks_per_test_n) {
  ProblemList problems;
  bool any_pair = false;
  for (std::size_t t = 0; t < peaks_per_test_n.size(); ++t) {
    const std::vector<double>& peaks = peaks_per_test_n[t];
    double sum_n = 0.0;
    bool all_usable = true;
    for (std::size_t k = 0; k < peaks.size(); ++k) {
      const std::string field = "peaks_per_test_n[" + std::to_string(t) + "][" + std::to_string(k) + "]";
      if (!(std::isfinite(peaks[k]) && peaks[k] >= 0.0)) {
        problems.add_value(field, shortest_number_text(peaks[k]), "must be finite and ≥ 0 — a peak force, N");
        all_usable = false;
      }
      sum_n += peaks[k];
    }
    if (all_usable && peaks.size() >= 2 && !(sum_n > 0.0)) {
      problems.add("peaks_per_test_n[" + std::to_string(t) + "]",
                   "has mean 0 N: the relative spread needs a test that cut (mean > 0)");
    }
    any_pair = any_pair || peaks.size() >= 2;
  }
  if (!any_pair) {
    problems.add("peaks_per_test_n", "has no test with at least two peaks: a spread needs two revolutions of one test");
  }
  problems.throw_if_any();

  double squares = 0.0;
  std::size_t degrees_of_freedom = 0;
  for (const std::vector<double>& peaks : peaks_per_test_n) {
    if (peaks.size() < 2) continue;
    double mean_n = 0.0;
    for (double p : peaks) mean_n += p;
    mean_n /= static_cast<double>(peaks.size());
    for (double p : peaks) squares += (p / mean_n - 1.0) * (p / mean_n - 1.0);
    degrees_of_freedom += peaks.size() - 1;
  }
  return std::sqrt(squares / static_cast<double>(degrees_of_freedom));
}

}  // namespace feedplan::model
