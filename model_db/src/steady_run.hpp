#pragma once
// Internal: steps 2–4 of the steady-state rule of cutting_test_import.hpp — trend, plateau and end
// trimming — over the revolutions step 1 left eligible.

#include <cstddef>
#include <vector>

#include "feedplan/force_log/revolution_peaks.hpp"
#include "feedplan/model_db/cutting_test_import.hpp"

namespace feedplan::model_db::detail {

//! A run [begin, end) of revolutions (indices into the peaks).
struct SteadyRun {
  std::size_t begin = 0;
  std::size_t end = 0;
  std::size_t plateau_begin = 0;  // the plateau before end trimming
  std::size_t plateau_end = 0;
  double level_n = 0.0;           // median peak of the plateau
  bool any_force = false;         // some eligible revolution has a peak > 0

  std::size_t size() const { return end - begin; }
};

//! Steps 2–4 of the steady-state rule over the revolutions marked eligible (one flag per peak). An empty
//! run when no eligible revolution has a force (any_force false) or none lies on a plateau.
SteadyRun find_steady(const std::vector<force_log::RevolutionPeak>& peaks, const std::vector<bool>& eligible,
                      const CuttingTestImportOptions& options);

//! Median of `values` (one per peak) over the run's revolutions.
double median_over(const std::vector<double>& values, const SteadyRun& run);

}  // namespace feedplan::model_db::detail
