#pragma once
// The engagement profile as CSV, one row per sample (docs/method.md §4 naming: units in column names,
// degrees for angles because users read it).

#include <string>

#include "feedplan/geometry/engagement.hpp"

namespace feedplan::geometry {

//! Column header of the engagement CSV.
inline constexpr const char* kEngagementCsvHeader =
    "s_mm,x_mm,y_mm,z_mm,cutting,part,move,feed_direction_deg,engagement_deg,entry_deg,exit_deg,"
    "chip_factor,contact_length_mm,axial_depth_mm,intervals";

//! Formats the profile as CSV text with kEngagementCsvHeader. `intervals` lists every engaged
//! interval as entry:exit in degrees, separated by spaces (empty when not engaged).
std::string engagement_csv(const EngagementProfile& profile);

}  // namespace feedplan::geometry
