#include "feedplan/geometry/engagement.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <sstream>

#include "angle_set.hpp"
#include "candidate_index.hpp"
#include "feedplan/core/angle.hpp"
#include "feedplan/core/parallel_tasks.hpp"
#include "feedplan/geometry/chip_area_ratio.hpp"
#include "move_chain.hpp"
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
constexpr double kGrazingDepthMm = 0.001;  // contact of air moves shallower than this is grazing (1 µm)
// Heights closer than this to the tip or the stock faces are not evaluated (a face is not material).
constexpr double kLayerOffsetMm = 1e-6;

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

// The earlier sweeps and the path as short pieces (split_into_pieces). The path's moves are cut into
// pieces by chain (move_chain.hpp): a move written as many blocks is as few pieces as the move itself.
struct PathPieces {
  std::vector<SweptPiece> pieces;
  std::size_t first_path_piece = 0;                  // the stock's pieces come before it
  std::vector<detail::ChainPlace> places;            // every move's place on its chain
  std::vector<std::size_t> chain_first_piece;        // first piece of every chain
  std::vector<std::vector<double>> chain_fractions;  // every chain's piece bounds, as fractions of it
};

// Earlier sweeps as short pieces, in the order they were cut: the stock's, then the path's.
PathPieces split_into_pieces(const ToolPath& path, const Stock& stock, double r) {
  PathPieces split;
  std::vector<SweptPiece>& pieces = split.pieces;
  const double max_piece_mm = 2.0 * r;
  for (const auto& swept : stock.removed) {
    detail::split_move(swept.move, swept.tool_radius_mm, max_piece_mm, pieces, nullptr);
  }
  split.first_path_piece = pieces.size();
  detail::MoveChains chains = detail::join_continuations(path.moves);
  split.places = std::move(chains.places);
  split.chain_first_piece.resize(chains.joined.size());
  split.chain_fractions.resize(chains.joined.size());
  for (std::size_t c = 0; c < chains.joined.size(); ++c) {
    split.chain_first_piece[c] = pieces.size();
    detail::split_move(chains.joined[c], r, max_piece_mm, pieces, &split.chain_fractions[c]);
  }
  return split;
}

// Sampling the path: what every sample reads, and what carries over from one sample to the next.
struct Sampler {
  const ToolPath& path;
  const Stock& stock;
  const double r;
  const EngagementOptions& options;
  const PathPieces& split;
  const std::vector<std::vector<std::uint32_t>>& candidates;  // earlier pieces per piece
  EngagementProfile& profile;                                 // the samples so far
  AngleIntervals cuts;                                        // exclusions not yet subtracted (reused)
  double last_direction_rad = 0.0;                            // of the last sample with XY travel
  std::vector<bool> warned;                                   // per move: its contact with material is reported
};

// The move being sampled.
struct MoveSampling {
  std::size_t index;
  const Move& move;
  double s_start_mm;     // arc length at its start
  double length_mm;      // in space
  double xy_length_mm;
  bool cutting;          // a cutting move (not air, not a rapid)
  MoveFrame frame;
};

// The sample at fraction f of the move: where the tool is and how it travels there.
EngagementSample place_sample(Sampler& sampler, const MoveSampling& m, double f) {
  const double move_length = m.length_mm;
  const double move_xy_length = m.xy_length_mm;
  EngagementSample sample;
  sample.s_mm = m.s_start_mm + f * move_length;
  const double direction = m.frame.evaluate(f, sample.position);
  sample.move_index = static_cast<int>(m.index);
  sample.part = m.move.part;
  sample.cutting = m.cutting;
  sample.axial_depth_mm = m.move.axial_depth_mm;
  sample.xy_speed_ratio = move_length > 0.0 ? move_xy_length / move_length : 0.0;
  if (std::isnan(direction) || move_xy_length <= 0.0) {
    sample.feed_direction_rad = sampler.last_direction_rad;
    sample.xy_speed_ratio = 0.0;
  } else {
    sample.feed_direction_rad = direction;
    sampler.last_direction_rad = direction;
  }
  return sample;
}

// The piece being travelled, from its start up to the tool (at fraction f of the move), taken from
// `remaining`. Returns the piece's index.
// The piece the tool travels at fraction f of the move: its index, and how far along it the tool is.
struct TravelledPiece {
  std::size_t index;
  double g;  // fraction of the piece travelled
};

TravelledPiece travelled_piece(const Sampler& sampler, const MoveSampling& m, double f) {
  const detail::ChainPlace& place = sampler.split.places[m.index];
  const double at = std::clamp(place.start + f * place.share, 0.0, 1.0);  // fraction of the chain
  const auto& fractions = sampler.split.chain_fractions[place.chain];
  std::size_t piece_in_chain = 0;
  while (piece_in_chain + 2 < fractions.size() && at >= fractions[piece_in_chain + 1]) ++piece_in_chain;
  return {sampler.split.chain_first_piece[place.chain] + piece_in_chain,
          (at - fractions[piece_in_chain]) / (fractions[piece_in_chain + 1] - fractions[piece_in_chain])};
}

std::size_t exclude_travelled_piece(Sampler& sampler, const MoveSampling& m, double f, Vec2 p, double r,
                                    double height, AngleIntervals& remaining) {
  AngleIntervals& cuts = sampler.cuts;
  const auto [current, g] = travelled_piece(sampler, m, f);
  cuts.clear();
  if (g > 0.0) {
    const SweptPiece& piece = sampler.split.pieces[current];
    const bool reversed = piece.is_arc && !m.move.ccw;  // clockwise arcs are stored counter-clockwise
    if (reversed) {
      detail::append_excluded(detail::sub_piece(piece, 1.0 - g, 1.0), p, r, height, false, true, cuts);
    } else {
      detail::append_excluded(detail::sub_piece(piece, 0.0, g), p, r, height, true, false, cuts);
    }
    remaining = detail::subtract_union(remaining, cuts, 1e-12);
    cuts.clear();
  }
  return current;
}

// Earlier pieces, most recent first, culled by the box of what is still engaged, taken from `remaining`.
void exclude_earlier_pieces(Sampler& sampler, std::size_t current, Vec2 p, double r, double height,
                            AngleIntervals& remaining) {
  AngleIntervals& cuts = sampler.cuts;
  Box box = arcs_box(remaining, p, r);
  int contributed = 0;
  for (const std::uint32_t j : sampler.candidates[current]) {
    if (remaining.empty()) break;
    const SweptPiece& piece = sampler.split.pieces[j];
    if (!sweep_may_reach(box, piece)) continue;
    if (detail::append_excluded(piece, p, r, height, true, true, cuts) && ++contributed == kCompactEvery) {
      remaining = detail::subtract_union(remaining, cuts, 1e-12);
      cuts.clear();
      box = arcs_box(remaining, p, r);
      contributed = 0;
    }
  }
  remaining = detail::subtract_union(remaining, cuts, kMinEngagedRad);
}

// The world angles of the circle of radius `radius_mm` about the sample (the tool circle, or one inside
// it) that lie in material on height `height`: the initial material there, less what the travelled piece
// and the earlier pieces swept.
AngleIntervals material_angles(Sampler& sampler, const MoveSampling& m, double f, const EngagementSample& sample,
                               double radius_mm, double height) {
  const Vec2 p = detail::to_vec(sample.position);
  AngleIntervals remaining;
  if (height > sample.position.z_mm) remaining = detail::initial_material(sampler.stock, p, radius_mm, height);
  if (!remaining.empty()) {
    const std::size_t current = exclude_travelled_piece(sampler, m, f, p, radius_mm, height, remaining);
    exclude_earlier_pieces(sampler, current, p, radius_mm, height, remaining);
  }
  return remaining;
}

// The engaged world angles of the tool circle at the sample on height `height`.
AngleIntervals engaged_angles(Sampler& sampler, const MoveSampling& m, double f, const EngagementSample& sample,
                              double height) {
  return material_angles(sampler, m, f, sample, sampler.r, height);
}

// Circles inside the tool, as fractions of its radius, on which the end face looks for material.
constexpr double kEndFaceCircles[] = {0.05, 0.25, 0.5, 0.75, 0.95};

// True when the tool descends at the sample and its end face meets material inside the tool circle just
// above the tip (the material it is plunging through) — material the circle does not reach (an island
// under the tool, the rim of a pre-drilled hole). The piece being travelled is not subtracted: while
// descending, its earlier part had its tip higher up and removed nothing down here, and its last
// instants (tips within the height offset) would cover the whole disc.
bool end_face_in_material(Sampler& sampler, const MoveSampling& m, double f, const EngagementSample& sample) {
  if (!(m.move.end.z_mm < m.move.start.z_mm)) return false;
  const double height = std::max(sample.position.z_mm, sampler.stock.z_bottom_mm) + kLayerOffsetMm;
  if (!(height < sampler.stock.z_top_mm - kLayerOffsetMm)) return false;
  const Vec2 p = detail::to_vec(sample.position);
  const std::size_t current = travelled_piece(sampler, m, f).index;
  for (const double fraction : kEndFaceCircles) {
    AngleIntervals remaining = detail::initial_material(sampler.stock, p, fraction * sampler.r, height);
    if (remaining.empty()) continue;
    exclude_earlier_pieces(sampler, current, p, fraction * sampler.r, height, remaining);
    if (!remaining.empty()) return true;
  }
  return false;
}

// The sample's totals from its engaged intervals (the last ones of the profile).
void summarise_intervals(const EngagementProfile& profile, double r, EngagementSample& sample) {
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
}

// Two engaged sets whose interval ends differ by less than this are the same set.
constexpr double kSameSetRad = 1e-9;

bool same_set(const AngleIntervals& a, const AngleIntervals& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::abs(a[i].lo - b[i].lo) > kSameSetRad || std::abs(a[i].hi - b[i].hi) > kSameSetRad) return false;
  }
  return true;
}

// One height of the bisection and the engaged set there.
struct HeightSet {
  double z_mm;
  AngleIntervals set;
};

// A band found by the bisection: the set at its bottom, and the height where it ends.
struct Band {
  HeightSet bottom;
  double top_z_mm;
};

// The bands between two evaluated heights: equal sets (or heights closer than the resolution) make
// one band with the lower set; otherwise the middle is evaluated. Appends the bands' bottoms in order.
void bisect_layers(Sampler& sampler, const MoveSampling& m, double f, const EngagementSample& sample,
                   const HeightSet& lower, const HeightSet& upper, std::vector<Band>& bands) {
  if (lower.set.empty()) return;  // nothing above an empty height either
  if (same_set(lower.set, upper.set) || upper.z_mm - lower.z_mm <= sampler.options.layer_resolution_mm) {
    if (!bands.empty() && same_set(bands.back().bottom.set, lower.set)) {
      bands.back().top_z_mm = upper.z_mm;
    } else {
      bands.push_back({lower, upper.z_mm});
    }
    return;
  }
  const double middle_z = 0.5 * (lower.z_mm + upper.z_mm);
  const HeightSet middle{middle_z, engaged_angles(sampler, m, f, sample, middle_z)};
  bisect_layers(sampler, m, f, sample, lower, middle, bands);
  if (!middle.set.empty()) bisect_layers(sampler, m, f, sample, middle, upper, bands);
}

// Appends one layer (its intervals and totals) to the profile.
EngagementLayer store_layer(Sampler& sampler, const Band& band, double bottom_z_mm, double top_z_mm,
                            double feed_direction_rad) {
  EngagementProfile& profile = sampler.profile;
  EngagementLayer layer;
  layer.bottom_z_mm = bottom_z_mm;
  layer.top_z_mm = top_z_mm;
  layer.interval_begin = static_cast<int>(profile.intervals.size());
  to_immersion(band.bottom.set, feed_direction_rad, profile.intervals);
  layer.interval_count = static_cast<int>(profile.intervals.size()) - layer.interval_begin;
  const EngagedInterval* first = profile.intervals.data() + layer.interval_begin;
  for (int k = 0; k < layer.interval_count; ++k) layer.engagement_rad += first[k].exit_rad - first[k].entry_rad;
  layer.chip_factor = chip_factor(first, first + layer.interval_count);
  return layer;
}

// Every layer of material the tool meets at the sample, from just above the tip (or the stock bottom)
// up to the stock top; the sample's own intervals and totals are the lowest layer's.
void engage_layers(Sampler& sampler, const MoveSampling& m, double f, EngagementSample& sample) {
  const Stock& stock = sampler.stock;
  const double low_z = std::max(sample.position.z_mm, stock.z_bottom_mm) + kLayerOffsetMm;
  const double high_z = stock.z_top_mm - kLayerOffsetMm;
  EngagementProfile& profile = sampler.profile;
  if (!(high_z > low_z)) {
    summarise_intervals(profile, sampler.r, sample);
    return;
  }
  const HeightSet lower{low_z, engaged_angles(sampler, m, f, sample, low_z)};
  std::vector<Band> bands;
  if (!lower.set.empty()) {
    const HeightSet upper{high_z, engaged_angles(sampler, m, f, sample, high_z)};
    bisect_layers(sampler, m, f, sample, lower, upper, bands);
  }
  to_immersion(lower.set, sample.feed_direction_rad, profile.intervals);
  summarise_intervals(profile, sampler.r, sample);
  if (bands.empty()) return;
  sample.layer_begin = static_cast<int>(profile.layers.size());
  for (std::size_t k = 0; k < bands.size(); ++k) {
    const double bottom_z = k == 0 ? low_z - kLayerOffsetMm : bands[k].bottom.z_mm;
    const double top_z = k + 1 == bands.size() && bands[k].top_z_mm >= high_z ? stock.z_top_mm : bands[k].top_z_mm;
    profile.layers.push_back(store_layer(sampler, bands[k], bottom_z, top_z, sample.feed_direction_rad));
  }
  sample.layer_count = static_cast<int>(bands.size());
  sample.material_height_mm = profile.layers.back().top_z_mm - sample.position.z_mm;
  sample.axial_depth_mm = sample.material_height_mm;
}

// A rapid or air move that meets material: one warning, at its first such sample. Its first sample (step 0)
// is where the move before it ended, so contact there is the earlier move's; and a straight retract (up,
// without XY travel) moves the tool out of the hole it stands in: at the end of a slot half its circle lies
// on the slot's end wall, touching the material without moving into it.
void warn_of_contact_in_air(Sampler& sampler, const MoveSampling& m, const EngagementSample& sample, int step) {
  const std::size_t i = m.index;
  const bool retract = m.xy_length_mm <= 0.0 && m.move.end.z_mm > m.move.start.z_mm;
  // Material reaching less than kGrazingDepthMm into the tool circle (against a wall: r·(1 − cos(α/2))) is
  // the sliver a retraced cut leaves between the stock's polygons and the path, not a collision.
  const bool grazing = !sample.end_face_in_material &&
                       sampler.r * (1.0 - std::cos(0.5 * sample.engagement_rad)) <= kGrazingDepthMm;
  if (step > 0 && !retract && !grazing && !m.cutting && sample.engagement_rad > kAirContactRad && !sampler.warned[i]) {
    sampler.warned[i] = true;
    std::ostringstream out;
    out << describe(m.move, i, sampler.path.part_names) << " meets material at s = " << sample.s_mm
        << " mm (engagement " << rad_to_deg(sample.engagement_rad) << " deg): a collision or a gouge";
    sampler.profile.warnings.push_back(out.str());
  }
}

// Steps a move is sampled in: every ds_mm or less.
int sample_steps(const Move& move, double ds_mm) {
  return std::max(1, static_cast<int>(std::ceil(length_mm(move) / ds_mm - 1e-9)));
}

// The samples of move i, every ds_mm or less; its end point is the next move's first sample (the
// last move's is its own).
void sample_move(Sampler& sampler, std::size_t i, double s_start_mm) {
  const Move& move = sampler.path.moves[i];
  const double move_length = length_mm(move);
  const int steps = sample_steps(move, sampler.options.ds_mm);
  const int last_step = i + 1 == sampler.path.moves.size() ? steps : steps - 1;
  const MoveSampling m{i, move, s_start_mm, move_length, xy_length_mm(move),
                       move.cutting && move.kind != MoveKind::kRapid, MoveFrame(move)};
  EngagementProfile& profile = sampler.profile;
  for (int k = 0; k <= last_step; ++k) {
    const double f = static_cast<double>(k) / steps;
    EngagementSample sample = place_sample(sampler, m, f);
    sample.interval_begin = static_cast<int>(profile.intervals.size());
    if (sampler.options.evaluation_z_mm) {
      to_immersion(engaged_angles(sampler, m, f, sample, *sampler.options.evaluation_z_mm), sample.feed_direction_rad,
                   profile.intervals);
      summarise_intervals(profile, sampler.r, sample);
    } else {
      engage_layers(sampler, m, f, sample);
      if (sample.engagement_rad <= 0.0) sample.end_face_in_material = end_face_in_material(sampler, m, f, sample);
    }
    warn_of_contact_in_air(sampler, m, sample, k);
    profile.samples.push_back(sample);
  }
}

// The direction of XY travel of the last sample before move `first` that has one (sample_move's
// samples and place_sample's rule), 0 when none has.
double direction_before(const ToolPath& path, std::size_t first, double ds_mm) {
  for (std::size_t j = first; j-- > 0;) {
    const Move& move = path.moves[j];
    if (!(xy_length_mm(move) > 0.0)) continue;
    const int steps = sample_steps(move, ds_mm);
    const int last_step = j + 1 == path.moves.size() ? steps : steps - 1;
    const MoveFrame frame(move);
    Point3 position;
    for (int k = last_step; k >= 0; --k) {
      const double direction = frame.evaluate(static_cast<double>(k) / steps, position);
      if (!std::isnan(direction)) return direction;
    }
  }
  return 0.0;
}

// Move indices where the path is cut into stretches computed apart: bounds[k] to bounds[k + 1]. About
// kStretchesPerWorker stretches per worker so that a stretch in air and one in material even out, none
// with fewer than kMinStretchSamples samples; one stretch on a short path or one core.
constexpr int kStretchesPerWorker = 4;
constexpr double kMinStretchSamples = 400.0;

std::vector<std::size_t> stretch_bounds(const ToolPath& path, double ds_mm) {
  const std::size_t n = path.moves.size();
  std::vector<double> samples_before(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) samples_before[i + 1] = samples_before[i] + sample_steps(path.moves[i], ds_mm);
  const double total = samples_before[n];
  const int workers = worker_count();
  const int stretches = workers <= 1 ? 1
                                     : std::max(1, std::min(kStretchesPerWorker * workers,
                                                            static_cast<int>(total / kMinStretchSamples)));
  std::vector<std::size_t> bounds{0};
  for (int k = 1; k < stretches; ++k) {
    const double at = total * k / stretches;
    const auto i = static_cast<std::size_t>(std::lower_bound(samples_before.begin(), samples_before.end(), at) -
                                            samples_before.begin());
    if (i > bounds.back() && i < n) bounds.push_back(i);
  }
  bounds.push_back(n);
  return bounds;
}

// The stretches' profiles as one: samples, intervals, layers and warnings in path order, indices shifted.
EngagementProfile joined(std::vector<EngagementProfile> stretches) {
  EngagementProfile profile = std::move(stretches.front());
  for (std::size_t k = 1; k < stretches.size(); ++k) {
    EngagementProfile& next = stretches[k];
    const int interval_offset = static_cast<int>(profile.intervals.size());
    const int layer_offset = static_cast<int>(profile.layers.size());
    for (EngagementSample& sample : next.samples) {
      sample.interval_begin += interval_offset;
      if (sample.layer_count > 0) sample.layer_begin += layer_offset;
      profile.samples.push_back(sample);
    }
    for (EngagementLayer& layer : next.layers) {
      layer.interval_begin += interval_offset;
      profile.layers.push_back(layer);
    }
    profile.intervals.insert(profile.intervals.end(), next.intervals.begin(), next.intervals.end());
    for (std::string& warning : next.warnings) profile.warnings.push_back(std::move(warning));
  }
  return profile;
}

}  // namespace

EngagementProfile compute_engagement(const ToolPath& path, const Stock& stock, double tool_radius_mm,
                                     const EngagementOptions& options) {
  assert(tool_radius_mm > 0.0 && options.ds_mm > 0.0);
  const double r = tool_radius_mm;
  const PathPieces split = split_into_pieces(path, stock, r);
  // Candidate earlier pieces for every piece of the path.
  const auto candidates = detail::earlier_candidates(split.pieces, r, split.first_path_piece);
  std::vector<double> move_start_mm(path.moves.size() + 1, 0.0);
  for (std::size_t i = 0; i < path.moves.size(); ++i) move_start_mm[i + 1] = move_start_mm[i] + length_mm(path.moves[i]);
  // Stretches of the path computed apart, on the cores there are: a sample reads only the path, the
  // stock and the pieces, and the direction of the last sample before it with XY travel.
  const std::vector<std::size_t> bounds = stretch_bounds(path, options.ds_mm);
  std::vector<EngagementProfile> stretches(bounds.size() - 1);
  run_tasks(stretches.size(), [&](std::size_t k) {
    Sampler sampler{path, stock, r, options, split, candidates, stretches[k], {}, direction_before(path, bounds[k], options.ds_mm),
                    std::vector<bool>(path.moves.size(), false)};
    for (std::size_t i = bounds[k]; i < bounds[k + 1]; ++i) sample_move(sampler, i, move_start_mm[i]);
  });
  EngagementProfile profile = joined(std::move(stretches));
  profile.tool_radius_mm = r;
  profile.ds_mm = options.ds_mm;
  profile.part_names = path.part_names;
  return profile;
}

}  // namespace feedplan::geometry
