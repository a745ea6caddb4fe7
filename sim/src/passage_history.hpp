#pragma once
// Internal to the virtual machine (cutter_contact.hpp): where the tool centre was when earlier teeth
// passed, for the chip thickness (milling_forces.hpp, CutterState::displacement_since_tooth_mm).

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <vector>

#include "feedplan/geometry/point.hpp"

namespace feedplan::sim::detail {

// Tool-centre XY positions by spindle angle over the last few tooth periods, for the displacement
// since earlier tooth passages.
class PassageHistory {
 public:
  explicit PassageHistory(std::size_t capacity) : angle_(capacity), x_(capacity), y_(capacity) {}

  void push(double spindle_angle_rad, double x_mm, double y_mm) {
    head_ = (head_ + 1) % angle_.size();
    angle_[head_] = spindle_angle_rad;
    x_[head_] = x_mm;
    y_[head_] = y_mm;
    size_ = std::min(size_ + 1, angle_.size());
  }

  //! Centre position when the spindle angle was `angle_rad` (linear between steps; the oldest kept
  //! position before the history starts, which is where the tool stood before the program began).
  geometry::Point2 position_at(double angle_rad, std::size_t steps_back_hint) const {
    assert(size_ > 0);
    std::size_t back = std::min(steps_back_hint, size_ - 1);
    // Walk to the newest entry at or before the angle.
    while (back + 1 < size_ && at(back).angle > angle_rad) ++back;
    while (back > 0 && at(back - 1).angle <= angle_rad) --back;
    const Entry older = at(back);
    if (back == 0 || older.angle > angle_rad) return {older.x, older.y};
    const Entry newer = at(back - 1);
    const double span = newer.angle - older.angle;
    const double w = span > 0.0 ? (angle_rad - older.angle) / span : 0.0;
    return {older.x + w * (newer.x - older.x), older.y + w * (newer.y - older.y)};
  }

 private:
  struct Entry {
    double angle;
    double x;
    double y;
  };
  Entry at(std::size_t back) const {
    const std::size_t i = (head_ + angle_.size() - back) % angle_.size();
    return {angle_[i], x_[i], y_[i]};
  }
  std::vector<double> angle_;
  std::vector<double> x_;
  std::vector<double> y_;
  std::size_t head_ = 0;
  std::size_t size_ = 0;
};

}  // namespace feedplan::sim::detail
