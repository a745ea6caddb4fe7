#include "path_builder.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <utility>

#include "feedplan/core/angle.hpp"

namespace feedplan::cycles::detail {

using geometry::Move;
using geometry::MoveKind;
using geometry::Point2;
using geometry::Point3;

namespace {

double distance(const Point3& a, const Point3& b) {
  return std::hypot(std::hypot(a.x_mm - b.x_mm, a.y_mm - b.y_mm), a.z_mm - b.z_mm);
}

constexpr double kZeroLengthMm = 1e-12;

}  // namespace

void PathBuilder::begin_part(const std::string& name) {
  path_.part_names.push_back(name);
  part_ = static_cast<int>(path_.part_names.size()) - 1;
}

void PathBuilder::push(Move move) {
  assert(part_ >= 0 && "begin_part before the first move");
  move.part = part_;
  position_ = move.end;
  path_.moves.push_back(move);
}

void PathBuilder::rapid_to(const Point3& end) {
  if (distance(position_, end) <= kZeroLengthMm) return;
  Move move;
  move.kind = MoveKind::kRapid;
  move.start = position_;
  move.end = end;
  push(move);
}

void PathBuilder::line_to(const Point3& end, bool cutting, double axial_depth_mm) {
  if (distance(position_, end) <= kZeroLengthMm) return;
  Move move;
  move.kind = MoveKind::kLine;
  move.start = position_;
  move.end = end;
  move.cutting = cutting;
  move.axial_depth_mm = cutting ? axial_depth_mm : 0.0;
  push(move);
}

void PathBuilder::arc_to(const Point3& end, const Point2& center, bool ccw, double sweep_rad, bool cutting,
                         double axial_depth_mm) {
  assert(sweep_rad > 0.0);
  Move move;
  move.kind = MoveKind::kArc;
  move.start = position_;
  move.end = end;
  move.center = center;
  move.ccw = ccw;
  move.sweep_rad = sweep_rad;
  move.cutting = cutting;
  move.axial_depth_mm = cutting ? axial_depth_mm : 0.0;
  push(move);
}

void PathBuilder::circle(const Point2& center, bool ccw, bool cutting, double axial_depth_mm, double drop_mm) {
  const Point3 end{position_.x_mm, position_.y_mm, position_.z_mm - drop_mm};
  arc_to(end, center, ccw, kTwoPi, cutting, axial_depth_mm);
}

void PathBuilder::enter(const Point2& at, const ZLevels& z, double z_mm) {
  const double feed_plane = z.top_z_mm + kFeedPlaneAboveTopMm;
  position_ = {at.x_mm, at.y_mm, z.top_z_mm + z.clearance_z_mm};
  rapid_to({at.x_mm, at.y_mm, feed_plane});
  line_to({at.x_mm, at.y_mm, z_mm}, false, 0.0);
}

void PathBuilder::retract(const ZLevels& z) {
  rapid_to({position_.x_mm, position_.y_mm, z.top_z_mm + z.clearance_z_mm});
}

Point3 on_circle(const Point2& center, double radius_mm, double angle_rad, double z_mm) {
  return {center.x_mm + radius_mm * std::cos(angle_rad), center.y_mm + radius_mm * std::sin(angle_rad), z_mm};
}

Point2 mirrored(const Point2& point, const Point2& origin, const Point2& axis) {
  const double dx = point.x_mm - origin.x_mm;
  const double dy = point.y_mm - origin.y_mm;
  const double along = dx * axis.x_mm + dy * axis.y_mm;
  return {origin.x_mm + 2.0 * along * axis.x_mm - dx, origin.y_mm + 2.0 * along * axis.y_mm - dy};
}

namespace {

Point3 mirrored3(const Point3& point, const Point2& origin, const Point2& axis) {
  const Point2 m = mirrored(geometry::xy(point), origin, axis);
  return {m.x_mm, m.y_mm, point.z_mm};
}

}  // namespace

Move mirrored(const Move& move, const Point2& origin, const Point2& axis) {
  Move m = move;
  m.start = mirrored3(move.start, origin, axis);
  m.end = mirrored3(move.end, origin, axis);
  if (move.kind == MoveKind::kArc) {
    m.center = mirrored(move.center, origin, axis);
    m.ccw = !move.ccw;
  }
  return m;
}

geometry::ToolPath mirrored(const geometry::ToolPath& path, const Point2& origin, const Point2& axis) {
  geometry::ToolPath result = path;
  for (auto& move : result.moves) move = mirrored(move, origin, axis);
  return result;
}

geometry::Stock mirrored(const geometry::Stock& stock, const Point2& origin, const Point2& axis) {
  geometry::Stock result = stock;
  auto mirror_contour = [&](geometry::Contour& contour) {
    contour.center = mirrored(contour.center, origin, axis);
    for (auto& v : contour.vertices) v = mirrored(v, origin, axis);
    std::reverse(contour.vertices.begin(), contour.vertices.end());
  };
  for (auto& region : result.regions) {
    mirror_contour(region.outer);
    for (auto& hole : region.holes) mirror_contour(hole);
  }
  for (auto& swept : result.removed) swept.move = mirrored(swept.move, origin, axis);
  return result;
}

void append(geometry::ToolPath& into, const geometry::ToolPath& from, const std::string& prefix) {
  const int offset = static_cast<int>(into.part_names.size());
  for (const auto& name : from.part_names) into.part_names.push_back(prefix + name);
  if (from.moves.empty()) return;
  if (!into.moves.empty()) {
    const Point3 end = into.moves.back().end;
    const Point3 next = from.moves.front().start;
    assert(std::abs(end.z_mm - next.z_mm) < 1e-9 && "sub-cycles start and end at the clearance height");
    if (std::hypot(next.x_mm - end.x_mm, next.y_mm - end.y_mm) > kZeroLengthMm) {
      Move over;
      over.kind = MoveKind::kRapid;
      over.start = end;
      over.end = next;
      over.part = offset + from.moves.front().part;
      into.moves.push_back(over);
    }
  }
  for (Move move : from.moves) {
    move.part += offset;
    into.moves.push_back(move);
  }
}

geometry::Stock block_stock(std::vector<geometry::StockRegion> regions, const ZLevels& z, double cut_depth_mm) {
  geometry::Stock stock;
  stock.regions = std::move(regions);
  stock.z_top_mm = z.top_z_mm;
  stock.z_bottom_mm = z.top_z_mm - cut_depth_mm - kStockBelowCutMm;
  return stock;
}

}  // namespace feedplan::cycles::detail
