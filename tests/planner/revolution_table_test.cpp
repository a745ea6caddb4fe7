// revolution_table_rows on a hand-made comparison: one line per revolution, in order, its numbers as given
// and the classification as 0/1, the label in the first column.

#include <gtest/gtest.h>

#include "feedplan/planner/revolution_table.hpp"

namespace feedplan::planner {
namespace {

TEST(RevolutionTable, OneLinePerRevolutionUnderTheHeader) {
  PeakComparison comparison;
  RevolutionComparison air;
  air.revolution = {0.0, 1.5, 0.0};
  air.error_percent = -100.0;
  RevolutionComparison steady;
  steady.revolution = {1.5, 1.75, 412.0};
  steady.in_cut = steady.held = steady.steady = true;
  steady.planned_force_n = 399.5;
  steady.error_percent = 3.0;
  steady.position = {-12.25, 4.0, -5.0};
  comparison.revolutions = {air, steady};

  EXPECT_EQ(revolution_table_header(),
            "cycle,s_start_mm,s_end_mm,x_mm,y_mm,peak_n,planned_force_n,target_n,error_percent,in_cut,held,steady\n");
  EXPECT_EQ(revolution_table_rows("best", comparison, 400.0),
            "best,0,1.5,0,0,0,0,400,-100,0,0,0\n"
            "best,1.5,1.75,-12.25,4,412,399.5,400,3,1,1,1\n");
  EXPECT_EQ(revolution_table_rows("2", PeakComparison{}, 400.0), "");
}

}  // namespace
}  // namespace feedplan::planner
