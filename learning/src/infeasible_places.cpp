#include "feedplan/learning/infeasible_places.hpp"

#include <algorithm>
#include <cmath>

#include "feedplan/core/number_text.hpp"

namespace feedplan::learning {

InfeasiblePlaces infeasible_places(const planner::PlanResult& plan, const std::vector<MeasuredRevolutions>& measured,
                                   double target_force_n) {
  const auto& samples = plan.samples;
  InfeasiblePlaces out;
  out.first_s_mm = INFINITY;
  for (const MeasuredRevolutions& log : measured) {
    for (const planner::MeasuredRevolution& r : log.revolutions) {
      if (!(r.peak_n > target_force_n * (1.0 + kInfeasibleMargin))) continue;
      const auto first = std::lower_bound(samples.begin(), samples.end(), r.s_start_mm,
                                          [](const planner::PlannedSample& p, double s) { return p.s_mm < s; });
      bool engaged = false, all_at_min = true;
      for (auto it = first; it != samples.end() && it->s_mm <= r.s_end_mm; ++it) {
        if (!it->engaged) continue;
        engaged = true;
        all_at_min = all_at_min && it->limit_reason == planner::FeedLimitReason::kMinFeed;
      }
      if (!engaged || !all_at_min) continue;
      ++out.revolutions;
      out.first_s_mm = std::min(out.first_s_mm, r.s_start_mm);
      out.largest_peak_n = std::max(out.largest_peak_n, r.peak_n);
    }
  }
  if (out.revolutions == 0) out.first_s_mm = 0.0;
  return out;
}

std::string describe(const InfeasiblePlaces& places, double target_force_n) {
  if (places.revolutions == 0) return {};
  return std::to_string(places.revolutions) + " revolution" + (places.revolutions == 1 ? "" : "s") +
         " at the machine's minimum feed still above the target " + fixed_number_text(target_force_n, 0) +
         " N, the first at s = " + fixed_number_text(places.first_s_mm, 1) + " mm, the largest " +
         fixed_number_text(places.largest_peak_n, 1) + " N: there the force does not fall to the target at any feed the "
         "machine runs, and learning cannot change that; those places stay at the minimum feed, and a target of at "
         "least " + fixed_number_text(std::ceil(places.largest_peak_n), 0) + " N is one the logs say can be held "
         "everywhere (feedplan plan --target-sweep shows what each target costs)";
}

}  // namespace feedplan::learning
