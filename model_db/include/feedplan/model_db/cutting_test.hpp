#pragma once
// A cutting test as the model database keeps it: the conditions of a straight cut at constant radial
// depth, axial depth, feed and spindle speed, and the steady per-revolution peak force measured (or
// simulated) in it — one point (t_m, L, F) for fitting the response-surface model.

#include <string>
#include <vector>

namespace feedplan::model_db {

//! Which side of the tool the material is on (M3 spindle).
enum class CutMode {
  kDown,  //!< climb milling: material on the right of the feed
  kUp,    //!< conventional milling: material on the left
  kSlot,  //!< full slot (radial depth = tool diameter)
};

//! The conditions of a straight cutting test.
struct CuttingTestConditions {
  std::string tool_name;            //!< tool, by name in the store
  std::string material_name;        //!< workpiece material, by name in the store
  double spindle_rpm = 0.0;         //!< spindle speed, rev/min
  double feed_mm_per_min = 0.0;     //!< feed, mm/min
  double radial_depth_mm = 0.0;     //!< a_e, mm (the tool diameter for a slot)
  double axial_depth_mm = 0.0;      //!< a_p, mm
  CutMode mode = CutMode::kDown;    //!< down, up or slot
};

//! The steady-state per-revolution peaks of one cutting test and the model inputs they belong to.
struct CuttingTestRecord {
  CuttingTestConditions conditions;
  double feed_per_tooth_mm = 0.0;        //!< f_z = F / (N · S), mm
  double chip_mm = 0.0;                  //!< t_m = f_z · sin(min(α_en, π/2)), mm (docs/method.md §5.1)
  double contact_length_mm = 0.0;        //!< L = r · α_en, mm
  double peak_mean_n = 0.0;              //!< mean of the steady per-revolution peaks |F_xy|, N
  double peak_std_n = 0.0;               //!< their standard deviation, N
  double peak_min_n = 0.0;               //!< smallest steady peak, N
  double peak_max_n = 0.0;               //!< largest steady peak, N
  int revolutions_total = 0;             //!< complete revolutions in the log
  int revolutions_used = 0;              //!< steady revolutions the statistics are over
  std::vector<double> steady_peaks_n;    //!< the steady per-revolution peaks, N, in time order
  //! The revolution-synchronous average of Fx and Fy over the steady revolutions (force_log/
  //! synchronous_average.hpp): equal spindle-angle bins from each revolution's start, N. Both empty when the
  //! log samples a revolution too sparsely, or the test was stored without it.
  std::vector<double> synchronous_fx_n;
  std::vector<double> synchronous_fy_n;  //!< see synchronous_fx_n
  std::string source;                    //!< where the log came from (file name, "simulated", …)
  std::vector<std::string> notes;        //!< what the import wants the user to know
};

}  // namespace feedplan::model_db
