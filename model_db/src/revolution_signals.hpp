#pragma once
// Internal: what a force log says about each complete spindle revolution besides its force peak — the
// feed and spindle speed the cutting-test import checks the conditions against and step 1 of the
// steady-state rule selects revolutions by (cutting_test_import.hpp).

#include <vector>

#include "feedplan/force_log/force_log.hpp"
#include "feedplan/force_log/revolution_peaks.hpp"

namespace feedplan::model_db::detail {

//! What the log says per revolution, NaN where it says nothing.
struct RevolutionSignals {
  std::vector<double> feed_column_mm_per_min;     // mean of the feed_mm_per_min column
  std::vector<double> feed_positions_mm_per_min;  // distance first → last sample over their time
  std::vector<double> spindle_rpm;                // mean of the spindle_rpm column
};

//! The signals of each of `peaks`, from the log rows in [t_start_s, t_end_s).
RevolutionSignals revolution_signals(const force_log::ForceLog& log,
                                     const std::vector<force_log::RevolutionPeak>& peaks);

}  // namespace feedplan::model_db::detail
