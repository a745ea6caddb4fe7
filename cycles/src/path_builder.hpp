#pragma once
// Appending moves to a ToolPath one after another, so that each starts exactly where the previous
// one ended, and whole-path transforms the generators share (mirroring, concatenation). Internal to
// the cycles module.

#include <string>

#include "feedplan/cycles/cycle.hpp"
#include "feedplan/geometry/move.hpp"
#include "feedplan/geometry/point.hpp"
#include "feedplan/geometry/stock.hpp"
#include "feedplan/geometry/tool_path.hpp"

namespace feedplan::cycles::detail {

//! Builds a path from a start position. Moves of zero length are dropped.
class PathBuilder {
 public:
  explicit PathBuilder(const geometry::Point3& start) : position_(start) {}

  //! Moves appended from now on belong to a new part called `name`.
  void begin_part(const std::string& name);

  //! Current tool tip position.
  const geometry::Point3& position() const { return position_; }

  //! Rapid (G0) to `end`.
  void rapid_to(const geometry::Point3& end);

  //! Straight feed move to `end`; `cutting` false for air moves, which get axial depth 0.
  void line_to(const geometry::Point3& end, bool cutting, double axial_depth_mm);

  //! Arc (helix when z changes) about `center` by `sweep_rad` to `end`, which the caller computed
  //! on the circle through the current position.
  void arc_to(const geometry::Point3& end, const geometry::Point2& center, bool ccw, double sweep_rad, bool cutting,
              double axial_depth_mm);

  //! Full circle (sweep 2π) about `center` from the current position, descending `drop_mm` (a helix
  //! turn when > 0).
  void circle(const geometry::Point2& center, bool ccw, bool cutting, double axial_depth_mm, double drop_mm = 0.0);

  //! The standard start of a cycle at `at`: the path begins at the clearance height, rapids down to
  //! the feed plane and feeds in air down to `z_mm`.
  void enter(const geometry::Point2& at, const ZLevels& z, double z_mm);

  //! Rapid straight up to the clearance height.
  void retract(const ZLevels& z);

  //! The finished path.
  geometry::ToolPath finish() { return std::move(path_); }

 private:
  void push(geometry::Move move);
  geometry::ToolPath path_;
  geometry::Point3 position_;
  int part_ = -1;
};

//! Point on the circle about `center` of radius `radius_mm` at `angle_rad`, at height `z_mm`.
geometry::Point3 on_circle(const geometry::Point2& center, double radius_mm, double angle_rad, double z_mm);

//! Reflection of `point` in the line through `origin` along the unit vector `axis`.
geometry::Point2 mirrored(const geometry::Point2& point, const geometry::Point2& origin, const geometry::Point2& axis);

//! Reflection of a move: positions and centre reflected, turning sense reversed.
geometry::Move mirrored(const geometry::Move& move, const geometry::Point2& origin, const geometry::Point2& axis);

//! Reflection of every move of a path.
geometry::ToolPath mirrored(const geometry::ToolPath& path, const geometry::Point2& origin, const geometry::Point2& axis);

//! Reflection of a stock (contours, with polygon vertex order reversed to keep their orientation, and
//! the removed moves).
geometry::Stock mirrored(const geometry::Stock& stock, const geometry::Point2& origin, const geometry::Point2& axis);

//! Appends `from` to `into`, prefixing its part names with `prefix` ("boring: "). When `into` is not
//! empty, first a rapid joins its end to the start of `from` (at the clearance height both share),
//! assigned to the first part of `from`.
void append(geometry::ToolPath& into, const geometry::ToolPath& from, const std::string& prefix);

//! The z range every implied stock uses: top at z.top_z_mm, bottom kStockBelowCutMm below the cut.
geometry::Stock block_stock(std::vector<geometry::StockRegion> regions, const ZLevels& z, double cut_depth_mm);

}  // namespace feedplan::cycles::detail
