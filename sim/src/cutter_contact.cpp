#include "cutter_contact.hpp"

#include <algorithm>

#include "feedplan/core/angle.hpp"

namespace feedplan::sim::detail {

namespace {

// Teeth whose passage the chip depends on: the previous one, or with runout all of them.
std::size_t previous_teeth_of(const SimulationRequest& request) {
  return request.options.runout_mm.empty() ? 1 : static_cast<std::size_t>(request.tool.flutes);
}

}  // namespace

CutterContact::CutterContact(const SimulationRequest& request, const LayeredEngagement& layers, int steps_per_tooth)
    : layers_(layers),
      coefficients_(request.coefficients),
      cutter_{request.tool.radius_mm(), request.tool.flutes, request.tool.helix_deg, request.options.runout_mm},
      tooth_angle_rad_(kTwoPi / request.tool.flutes),
      steps_per_tooth_(steps_per_tooth),
      previous_teeth_(previous_teeth_of(request)),
      flute_top_(request.options.flute_length_mm > 0.0 ? request.options.flute_length_mm : 1e300),
      history_(static_cast<std::size_t>(steps_per_tooth) * (previous_teeth_ + 1) * 8 + 16),
      displacement_(previous_teeth_),
      band_arcs_(layers.band_count()),
      band_stamp_(layers.band_count(), -1) {}

void CutterContact::record(double spindle_angle_rad, const geometry::Point3& position) {
  history_.push(spindle_angle_rad, position.x_mm, position.y_mm);
}

ContactForce CutterContact::force(long long step, const MotionState& state, double spindle_angle_rad,
                                  double feed_direction_rad) {
  ContactForce result;
  if (layers_.layer_count() == 0) return result;
  collect_slices(step, state.position.z_mm, state.s_mm);
  if (slices_.empty()) return result;
  update_displacement(spindle_angle_rad, state.position);
  CutterState cutter_state;
  cutter_state.spindle_angle_rad = spindle_angle_rad;
  cutter_state.feed_direction_rad = feed_direction_rad;
  cutter_state.displacement_since_tooth_mm = displacement_;
  result.force = milling_force(cutter_, coefficients_, cutter_state, slices_);
  result.contact = result.force.fx_n != 0.0 || result.force.fy_n != 0.0 || result.force.fz_n != 0.0;
  return result;
}

// The slices of every layer the flutes reach, from the tip at `tip_mm` up to the flute length. Layers
// of one band share one engagement look-up per step.
void CutterContact::collect_slices(long long step, double tip_mm, double s_mm) {
  slices_.clear();
  const std::size_t sample = layers_.sample_at(s_mm, cursor_);
  for (int layer = 0; layer < layers_.layer_count(); ++layer) {
    const double lo = std::max(layers_.layer_bottom_mm(layer), tip_mm);
    const double hi = std::min(layers_.layer_top_mm(layer), tip_mm + flute_top_);
    if (hi <= lo) continue;
    const int band = layers_.band_of(layer);
    if (band_stamp_[band] != step) {
      band_arcs_[band] = layers_.band_intervals(band, sample);
      band_stamp_[band] = step;
    }
    if (band_arcs_[band].empty()) continue;
    slices_.push_back({0.5 * (lo + hi) - tip_mm, hi - lo, band_arcs_[band]});
  }
}

// The centre's XY displacement since each of the previous tooth passages.
void CutterContact::update_displacement(double spindle_angle_rad, const geometry::Point3& position) {
  for (std::size_t k = 1; k <= previous_teeth_; ++k) {
    const geometry::Point2 before =
        history_.position_at(spindle_angle_rad - static_cast<double>(k) * tooth_angle_rad_, k * steps_per_tooth_);
    displacement_[k - 1] = {position.x_mm - before.x_mm, position.y_mm - before.y_mm};
  }
}

}  // namespace feedplan::sim::detail
