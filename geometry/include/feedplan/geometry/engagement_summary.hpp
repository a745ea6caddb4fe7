#pragma once
// Figures that describe an engagement profile at a glance: lengths, and the engagement per cycle
// part (what `feedplan cycle` prints).

#include <string>
#include <vector>

#include "feedplan/geometry/engagement.hpp"
#include "feedplan/geometry/tool_path.hpp"

namespace feedplan::geometry {

//! Engagement statistics of one cycle part, over its cutting samples.
struct PartSummary {
  std::string name;                  //!< part name from the ToolPath
  double length_mm = 0.0;            //!< path length of the part (all its moves), mm
  double cutting_length_mm = 0.0;    //!< length of its cutting moves, mm
  int cutting_samples = 0;           //!< cutting samples the statistics are taken over
  double engagement_min_rad = 0.0;   //!< smallest engagement angle, rad (0 when no cutting samples)
  double engagement_max_rad = 0.0;   //!< largest engagement angle, rad
  double engagement_mean_rad = 0.0;  //!< mean engagement angle over the cutting samples, rad
  double chip_factor_max = 0.0;      //!< largest chip-thickness factor t_m / f_z
};

//! Whole-path summary.
struct EngagementSummary {
  double length_mm = 0.0;          //!< total path length (in space), mm
  double cutting_length_mm = 0.0;  //!< length of cutting moves, mm
  double air_length_mm = 0.0;      //!< length of non-cutting feed moves, mm
  double rapid_length_mm = 0.0;    //!< length of rapids, mm
  int samples = 0;                 //!< number of engagement samples
  double engagement_max_rad = 0.0; //!< largest engagement over all cutting samples, rad
  std::vector<PartSummary> parts;  //!< one per part name, in path order of first appearance
};

//! Summarises `profile`, which must have been computed from `path`.
EngagementSummary summarize(const ToolPath& path, const EngagementProfile& profile);

}  // namespace feedplan::geometry
