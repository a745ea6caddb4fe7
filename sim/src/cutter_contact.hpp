#pragma once
// Internal to the virtual machine (milling_simulation.cpp): the cutter in the stock at one internal
// step — a slice for every layer its flutes reach where the layer's engagement has arcs, and the true
// force on them (milling_forces.hpp), with the tool-centre displacement since earlier tooth passages.

#include <cstddef>
#include <span>
#include <vector>

#include "feedplan/geometry/engagement.hpp"
#include "feedplan/geometry/point.hpp"
#include "feedplan/sim/layered_engagement.hpp"
#include "feedplan/sim/milling_forces.hpp"
#include "feedplan/sim/milling_simulation.hpp"
#include "passage_history.hpp"

namespace feedplan::sim::detail {

//! The true force at one step, and whether it is not zero (some tooth in the material).
struct ContactForce {
  Force3 force;
  bool contact = false;
};

//! The cutter of one run against its layered stock.
class CutterContact {
 public:
  //! The cutter of `request` (tool, runout, flute length, coefficients) on `layers`, stepped with
  //! `steps_per_tooth` steps per tooth period. `request` and `layers` must outlive the object.
  CutterContact(const SimulationRequest& request, const LayeredEngagement& layers, int steps_per_tooth);

  //! Records the tool centre at spindle angle `spindle_angle_rad`; called once per step, before force().
  void record(double spindle_angle_rad, const geometry::Point3& position);

  //! The force at step `step` with the machine at `state`, the spindle at `spindle_angle_rad` and the
  //! tool feeding along `feed_direction_rad`. Zero (no contact) when no layer holds engaged arcs at the
  //! flutes' heights.
  ContactForce force(long long step, const MotionState& state, double spindle_angle_rad, double feed_direction_rad);

 private:
  void collect_slices(long long step, double tip_mm, double s_mm);
  void update_displacement(double spindle_angle_rad, const geometry::Point3& position);

  const LayeredEngagement& layers_;
  const CuttingCoefficients& coefficients_;
  CutterGeometry cutter_;
  double tooth_angle_rad_;
  int steps_per_tooth_;
  std::size_t previous_teeth_;
  double flute_top_;
  PassageHistory history_;
  std::vector<geometry::Point2> displacement_;
  std::vector<ForceSlice> slices_;
  LayeredEngagement::Cursor cursor_;
  std::vector<std::span<const geometry::EngagedInterval>> band_arcs_;
  std::vector<long long> band_stamp_;
};

}  // namespace feedplan::sim::detail
