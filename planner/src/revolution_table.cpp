#include "feedplan/planner/revolution_table.hpp"

#include "feedplan/core/number_text.hpp"

namespace feedplan::planner {

std::string revolution_table_header() {
  return "cycle,s_start_mm,s_end_mm,x_mm,y_mm,peak_n,planned_force_n,target_n,error_percent,in_cut,held,steady\n";
}

std::string revolution_table_rows(const std::string& cycle, const PeakComparison& comparison, double target_force_n) {
  std::string text;
  for (const RevolutionComparison& r : comparison.revolutions) {
    text += cycle + "," + shortest_number_text(r.revolution.s_start_mm) + "," +
            shortest_number_text(r.revolution.s_end_mm) + "," + shortest_number_text(r.position.x_mm) + "," +
            shortest_number_text(r.position.y_mm) + "," + shortest_number_text(r.revolution.peak_n) + "," +
            shortest_number_text(r.planned_force_n) + "," + shortest_number_text(target_force_n) + "," +
            shortest_number_text(r.error_percent) + "," + (r.in_cut ? "1" : "0") + "," + (r.held ? "1" : "0") + "," +
            (r.steady ? "1" : "0") + "\n";
  }
  return text;
}

}  // namespace feedplan::planner
