#pragma once
// The spindle speed a force log was recorded at: the median of its spindle_rpm column, else its
// "# spindle_rpm:" metadata.

#include "feedplan/sim/force_log.hpp"

namespace feedplan::learning {

//! The log's spindle speed, rev/min, by the rule above; 0 when the log does not say.
double logged_spindle_rpm(const sim::ForceLog& log);

}  // namespace feedplan::learning
