#include "operation_figures.hpp"

#include <algorithm>

namespace feedplan::cli {

void add_operation_figures(const ToolRun& run, const planner::PlanResult& result, const planner::FeedPrediction& input,
                           const std::vector<std::size_t>& operation_of_move, std::vector<OperationFigures>& figures) {
  const auto& planned = result.samples;
  const std::size_t n = std::min({planned.size(), input.time_s.size(), input.force_n.size()});
  for (std::size_t i = 0; i < n; ++i) {
    OperationFigures& f = figures[operation_of_move[run.first + static_cast<std::size_t>(planned[i].move_index)]];
    f.planned = true;
    f.input_peak_n = std::max(f.input_peak_n, input.force_n[i]);
    f.refed_peak_n = std::max(f.refed_peak_n, planned[i].predicted_force_n);
    if (i + 1 < n) {
      f.input_s += input.time_s[i + 1] - input.time_s[i];
      f.refed_s += planned[i + 1].time_s - planned[i].time_s;
    }
  }
}

}  // namespace feedplan::cli
