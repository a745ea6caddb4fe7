#include "feedplan/geometry/engagement.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <sstream>

#include "angle_set.hpp"
#include "candidate_index.hpp"
#include "feedplan/core/angle.hpp"
#include "feedplan/geometry/chip_area_ratio.hpp"
#include "stock_section.hpp"
#include "swept_piece.hpp"
#include "vec2.hpp"

namespace feedplan::geometry {

namespace {

using detail::AngleInterval;
using detail::AngleIntervals;
using detail::SweptPiece;
using detail::Vec2;

// Engaged pieces shorter than this are tangencies, not engagement.
constexpr double kMinEngagedRad = 1e-9;
// Subtract the accumulated exclusions after this many contributing pieces (keeps the remaining
// set small so later, older pieces can be culled by its bounding box).
constexpr int kCompactEvery = 4;
// Air samples with more engagement than this are reported as meeting material.
constexpr double kAirContactRad = 1e-6;

struct Box {
  Vec2 lo{1e300, 1e300};
  Vec2 hi{-1e300, -1e300};
  void add(Vec2 q) {
    lo = {std::min(lo.x, q.x), std::min(lo.y, q.y)};
    hi = {std::max(hi.x, q.x), std::max(hi.y, q.y)};
  }
};

// Bounding box of the tool-circle arcs p + r e(θ), θ in the intervals.
Box arcs_box(const AngleIntervals& arcs, Vec2 p, double r) {
  Box box;
  for (const auto& arc : arcs) {
    box.add(p + r * detail::unit_at(arc.lo));
    box.add(p + r * detail::unit_at(arc.hi));
    for (int k = 0; k <= 4; ++k) {
      const double axis = k * 0.5 * kPi;
      if (axis > arc.lo && axis < arc.hi) box.add(p + r * detail::unit_at(axis));
    }
  }
  return box;
}

// False when the piece's sweep certainly misses the box: its bounding box, grown by the sweep
// radius, misses it, or (a tighter bound) the box lies farther than the sweep radius from the
// piece's circle (arcs) or from the segment (lines, via the box centre and half-diagonal).
bool sweep_may_reach(const Box& box, const SweptPiece& piece) {
  const double g = piece.sweep_radius_mm;
  if (piece.box_min.x - g > box.hi.x || piece.box_max.x + g < box.lo.x || piece.box_min.y - g > box.hi.y ||
      piece.box_max.y + g < box.lo.y) {
    return false;
  }
  if (piece.is_arc) {
    const double dx_near = std::max({box.lo.x - piece.center.x, 0.0, piece.center.x - box.hi.x});
    const double dy_near = std::max({box.lo.y - piece.center.y, 0.0, piece.center.y - box.hi.y});
    const double dx_far = std::max(std::abs(box.lo.x - piece.center.x), std::abs(box.hi.x - piece.center.x));
    const double dy_far = std::max(std::abs(box.lo.y - piece.center.y), std::abs(box.hi.y - piece.center.y));
    const double nearest = std::sqrt(dx_near * dx_near + dy_near * dy_near);
    const double farthest = std::sqrt(dx_far * dx_far + dy_far * dy_far);
    return nearest - piece.radius_mm < g && piece.radius_mm - farthest < g;
  }
  const Vec2 mid{0.5 * (box.lo.x + box.hi.x), 0.5 * (box.lo.y + box.hi.y)};
  const double half_diagonal = 0.5 * detail::norm(box.hi - box.lo);
  return detail::distance_to_path_mm(piece, mid) - half_diagonal < g;
}

// Converts engaged world angles θ (counter-clockwise from +X) to immersion angles φ = ψ + π/2 − θ
// in [−π/2, 3π/2), sorted and merged.
void to_immersion(const AngleIntervals& world, double feed_direction_rad, std::vector<EngagedInterval>& out) {
  boost::container::small_vector<EngagedInterval, 6> pieces;
  for (const auto& w : world) {
    const double length = w.hi - w.lo;
    const double lo = detail::wrap_two_pi(feed_direction_rad + 0.5 * kPi - w.hi + 0.5 * kPi) - 0.5 * kPi;
    const double hi = lo + length;
    if (hi <= 1.5 * kPi) {
      pieces.push_back({lo, hi});
    } else {
      pieces.push_back({lo, 1.5 * kPi});
      pieces.push_back({-0.5 * kPi, hi - 2.0 * kPi});
    }
  }
  std::sort(pieces.begin(), pieces.end(),
            [](const EngagedInterval& a, const EngagedInterval& b) { return a.entry_rad < b.entry_rad; });
  const std::size_t first = out.size();
  for (const auto& piece : pieces) {
    if (out.size() > first && piece.entry_rad <= out.back().exit_rad + 1e-12) {
      out.back().exit_rad = std::max(out.back().exit_rad, piece.exit_rad);
    } else {
      out.push_back(piece);
    }
  }
}

// Position and feed direction along one move, with the move's constants (arc radius and start
// angle, line direction) computed once: the same formulas as point_at and tangent_angle_rad.
class MoveFrame {
 public:
  explicit MoveFrame(const Move& move) : move_(move) {
    if (move.kind == MoveKind::kArc) {
      radius_mm_ = arc_radius_mm(move);
      start_angle_rad_ = std::atan2(move.start.y_mm - move.center.y_mm, move.start.x_mm - move.center.x_mm);
      sign_ = move.ccw ? 1.0 : -1.0;
    } else {
      line_direction_rad_ = tangent_angle_rad(move, 0.0);
    }
  }

  //! Sets the position at fraction f and returns the feed direction there (NaN on a vertical line).
  double evaluate(double f, Point3& position) const {
    const Move& m = move_;
    const double z = m.start.z_mm + f * (m.end.z_mm - m.start.z_mm);
    if (m.kind != MoveKind::kArc) {
      position = {m.start.x_mm + f * (m.end.x_mm - m.start.x_mm), m.start.y_mm + f * (m.end.y_mm - m.start.y_mm), z};
      return line_direction_rad_;
    }
    const double angle = start_angle_rad_ + sign_ * f * m.sweep_rad;
    position = {m.center.x_mm + radius_mm_ * std::cos(angle), m.center.y_mm + radius_mm_ * std::sin(angle), z};
    return angle + sign_ * 0.5 * kPi;
  }

 private:
  const Move& move_;
  double radius_mm_ = 0.0;
  double start_angle_rad_ = 0.0;
  double sign_ = 1.0;
  double line_direction_rad_ = 0.0;
};

std::string describe(const Move& move, std::size_t index, const std::vector<std::string>& part_names) {
  std::ostringstream out;
  out << "move " << index << " (" << (move.kind == MoveKind::kRapid ? "rapid" : "air feed");
  if (move.part >= 0 && static_cast<std::size_t>(move.part) < part_names.size()) {
    out << ", part '" << part_names[move.part] << "'";
  }
  out << ")";
  return out.str();
}

}  // namespace

EngagementProfile compute_engagement(const ToolPath& path, const Stock& stock, double tool_radius_mm,
                                     const EngagementOptions& options) {
  assert(tool_radius_mm > 0.0 && options.ds_mm > 0.0);
  const double r = tool_radius_mm;
  EngagementProfile profile;
  profile.tool_radius_mm = r;
  profile.ds_mm = options.ds_mm;
  profile.part_names = path.part_names;

  // 1. Earlier sweeps as short pieces, in the order they were cut: the stock's, then the path's.
  const double max_piece_mm = 2.0 * r;
  std::vector<SweptPiece> pieces;
  for (const auto& swept : stock.removed) {
    detail::split_move(swept.move, swept.tool_radius_mm, max_piece_mm, pieces, nullptr);
  }
  const std::size_t first_path_piece = pieces.size();
  std::vector<std::size_t> move_first_piece(path.moves.size());
  std::vector<std::vector<double>> move_fractions(path.moves.size());
  for (std::size_t i = 0; i < path.moves.size(); ++i) {
    move_first_piece[i] = pieces.size();
    detail::split_move(path.moves[i], r, max_piece_mm, pieces, &move_fractions[i]);
  }

  // 2. Candidate earlier pieces for every piece of the path.
  const auto candidates = detail::earlier_candidates(pieces, r, first_path_piece);

  // 3. Samples.
  AngleIntervals cuts;
  double s_start_mm = 0.0;
  double last_direction_rad = 0.0;
  std::vector<bool> warned(path.moves.size(), false);
  for (std::size_t i = 0; i < path.moves.size(); ++i) {
    const Move& move = path.moves[i];
    const double move_length = length_mm(move);
    const double move_xy_length = xy_length_mm(move);
    const int steps = std::max(1, static_cast<int>(std::ceil(move_length / options.ds_mm - 1e-9)));
    const int last_step = i + 1 == path.moves.size() ? steps : steps - 1;
    const auto& fractions = move_fractions[i];
    const bool is_cutting = move.cutting && move.kind != MoveKind::kRapid;
    const MoveFrame frame(move);
    for (int k = 0; k <= last_step; ++k) {
      const double f = static_cast<double>(k) / steps;
      EngagementSample sample;
      sample.s_mm = s_start_mm + f * move_length;
      const double direction = frame.evaluate(f, sample.position);
      sample.move_index = static_cast<int>(i);
      sample.part = move.part;
      sample.cutting = is_cutting;
      sample.axial_depth_mm = move.axial_depth_mm;
      sample.xy_speed_ratio = move_length > 0.0 ? move_xy_length / move_length : 0.0;
      if (std::isnan(direction) || move_xy_length <= 0.0) {
        sample.feed_direction_rad = last_direction_rad;
        sample.xy_speed_ratio = 0.0;
      } else {
        sample.feed_direction_rad = direction;
        last_direction_rad = direction;
      }
      sample.interval_begin = static_cast<int>(profile.intervals.size());

      const Vec2 p = detail::to_vec(sample.position);
      const double height = options.evaluation_z_mm
                                ? *options.evaluation_z_mm
                                : sample.position.z_mm + std::max(0.5 * move.axial_depth_mm, 1e-6);
      AngleIntervals remaining;
      if (height > sample.position.z_mm) remaining = detail::initial_material(stock, p, r, height);
      if (!remaining.empty()) {
        // The piece being travelled, from its start up to the tool.
        std::size_t piece_in_move = 0;
        while (piece_in_move + 2 < fractions.size() && f >= fractions[piece_in_move + 1]) ++piece_in_move;
        const std::size_t current = move_first_piece[i] + piece_in_move;
        const double g = (f - fractions[piece_in_move]) / (fractions[piece_in_move + 1] - fractions[piece_in_move]);
        cuts.clear();
        if (g > 0.0) {
          const SweptPiece& piece = pieces[current];
          const bool reversed = piece.is_arc && !move.ccw;  // clockwise arcs are stored counter-clockwise
          if (reversed) {
            detail::append_excluded(detail::sub_piece(piece, 1.0 - g, 1.0), p, r, height, false, true, cuts);
          } else {
            detail::append_excluded(detail::sub_piece(piece, 0.0, g), p, r, height, true, false, cuts);
          }
          remaining = detail::subtract_union(remaining, cuts, 1e-12);
          cuts.clear();
        }
        // Earlier pieces, most recent first, culled by the box of what is still engaged.
        Box box = arcs_box(remaining, p, r);
        int contributed = 0;
        for (const std::uint32_t j : candidates[current]) {
          if (remaining.empty()) break;
          const SweptPiece& piece = pieces[j];
          if (!sweep_may_reach(box, piece)) continue;
          if (detail::append_excluded(piece, p, r, height, true, true, cuts) && ++contributed == kCompactEvery) {
            remaining = detail::subtract_union(remaining, cuts, 1e-12);
            cuts.clear();
            box = arcs_box(remaining, p, r);
            contributed = 0;
          }
        }
        remaining = detail::subtract_union(remaining, cuts, kMinEngagedRad);
        to_immersion(remaining, sample.feed_direction_rad, profile.intervals);
      }

      sample.interval_count = static_cast<int>(profile.intervals.size()) - sample.interval_begin;
      if (sample.interval_count > 0) {
        const EngagedInterval* first = profile.intervals.data() + sample.interval_begin;
        const EngagedInterval* end = first + sample.interval_count;
        for (const auto* e = first; e != end; ++e) sample.engagement_rad += e->exit_rad - e->entry_rad;
        sample.entry_rad = first->entry_rad;
        sample.exit_rad = (end - 1)->exit_rad;
        sample.chip_factor = sample.xy_speed_ratio > 0.0 ? chip_factor(first, end) : 0.0;
        sample.chip_area_ratio = chip_area_ratio(first, end);
      }
      sample.contact_length_mm = r * sample.engagement_rad;
      if (!is_cutting && sample.engagement_rad > kAirContactRad && !warned[i]) {
        warned[i] = true;
        std::ostringstream out;
        out << describe(move, i, path.part_names) << " meets material at s = " << sample.s_mm
            << " mm (engagement " << rad_to_deg(sample.engagement_rad) << " deg): a collision or a gouge";
        profile.warnings.push_back(out.str());
      }
      profile.samples.push_back(sample);
    }
    s_start_mm += move_length;
  }
  return profile;
}

}  // namespace feedplan::geometry
