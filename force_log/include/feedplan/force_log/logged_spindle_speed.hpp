#pragma once
// The spindle speed a force log was recorded at: the median of its spindle_rpm column, else its
// "# spindle_rpm:" metadata.

#include "feedplan/force_log/force_log.hpp"

namespace feedplan::force_log {

//! The log's spindle speed, rev/min, by the rule above; 0 when the log does not say.
double logged_spindle_rpm(const ForceLog& log);

}  // namespace feedplan::force_log
