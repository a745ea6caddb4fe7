#include "feedplan/sim/motion_profile.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <string>

#include "feedplan/core/angle.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/geometry/tool_path.hpp"

namespace feedplan::sim {

namespace {

using geometry::Move;
using geometry::MoveKind;
using Vec3 = std::array<double, 3>;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr std::size_t kMaxReportedMoves = 20;

// Appends "<field> = <value>: must be <rule>" unless `ok`.
void require(std::vector<InputProblem>& problems, bool ok, const std::string& field, double value,
             const std::string& rule) {
  if (!ok) problems.push_back({field, "= " + six_digit_number_text(value) + ": must be " + rule});
}

// Unit tangent in space at the start (fraction 0) or end (fraction 1) of a move of length `length`.
Vec3 unit_tangent(const Move& move, double fraction, double length) {
  const double dz = (move.end.z_mm - move.start.z_mm) / length;
  if (move.kind != MoveKind::kArc) {
    return {(move.end.x_mm - move.start.x_mm) / length, (move.end.y_mm - move.start.y_mm) / length, dz};
  }
  const double xy_share = geometry::xy_length_mm(move) / length;
  const double angle = geometry::tangent_angle_rad(move, fraction);
  return {std::cos(angle) * xy_share, std::sin(angle) * xy_share, dz};
}

// Junction-deviation speed² (see the header, step 3) between unit tangents t1 and t2.
double junction_speed_squared(const Vec3& t1, const Vec3& t2, double accel, double deviation_mm) {
  const Vec3 cross = {t1[1] * t2[2] - t1[2] * t2[1], t1[2] * t2[0] - t1[0] * t2[2], t1[0] * t2[1] - t1[1] * t2[0]};
  const double dot = t1[0] * t2[0] + t1[1] * t2[1] + t1[2] * t2[2];
  // atan2 keeps small deflections accurate, where acos(dot) would lose them.
  const double deflection_rad = std::atan2(std::hypot(cross[0], cross[1], cross[2]), dot);
  if (deflection_rad <= kTangentJunctionToleranceRad) return kInfinity;
  if (deflection_rad >= kPi - kTangentJunctionToleranceRad) return 0.0;  // a reversal: cos(φ/2) is 0 only in theory
  const double cos_half = std::max(0.0, std::cos(0.5 * deflection_rad));  // sin(θ/2), θ the interior angle
  const double sin_quarter = std::sin(0.25 * deflection_rad);
  return accel * deviation_mm * cos_half / (2.0 * sin_quarter * sin_quarter);  // 1 − cos(φ/2) = 2 sin²(φ/4)
}

bool is_rapid(const Move& move) { return move.kind == MoveKind::kRapid; }

std::string block_name(const geometry::BlockCommand& block, std::size_t index) {
  if (block.source_line > 0) return "line " + std::to_string(block.source_line);
  return "move " + std::to_string(index);
}

void check_program(const geometry::Program& program, const geometry::MachineLimits& limits) {
  std::vector<InputProblem> problems = geometry::validate(limits);
  if (program.path.moves.empty()) problems.push_back({"program", "has no moves: there is nothing to run"});
  std::size_t bad_moves = 0;
  for (std::size_t i = 0; i < program.path.moves.size(); ++i) {
    const Move& move = program.path.moves[i];
    const geometry::BlockCommand& block = program.blocks[i];
    std::vector<InputProblem> found;
    const std::string where = block_name(block, i);
    if (!is_rapid(move)) {
      const double f = block.feed_mm_per_min;
      require(found, std::isfinite(f) && f > 0.0, where + " F", f, "> 0 mm/min on a feed move");
    }
    const double dwell = block.dwell_before_s;
    require(found, std::isfinite(dwell) && dwell >= 0.0, where + " dwell", dwell, "≥ 0 s");
    const double length = geometry::length_mm(move);
    require(found, std::isfinite(length), where + " length", length, "a finite number of mm");
    if (found.empty()) continue;
    if (++bad_moves <= kMaxReportedMoves) problems.insert(problems.end(), found.begin(), found.end());
  }
  if (bad_moves > kMaxReportedMoves) {
    problems.push_back({"program", "has " + std::to_string(bad_moves - kMaxReportedMoves) + " more moves with problems"});
  }
  const double end_dwell = program.dwell_at_end_s;
  require(problems, std::isfinite(end_dwell) && end_dwell >= 0.0, "program.dwell_at_end_s", end_dwell, "≥ 0 s");
  if (!problems.empty()) throw InputError(std::move(problems));
}

// Steps 1–2: the speed cap of one move (its F, the machine's maximum feed, the centripetal limit on
// arcs, or the rapid rate), mm/s.
double speed_cap_mm_per_s(const Move& move, const geometry::BlockCommand& block, const geometry::MachineLimits& limits) {
  const double accel = limits.max_accel_mm_per_s2;
  double cap_mm_per_s = limits.rapid_feed_mm_per_min / 60.0;
  if (!is_rapid(move)) {
    cap_mm_per_s = std::min(block.feed_mm_per_min, limits.max_feed_mm_per_min) / 60.0;
    if (move.kind == MoveKind::kArc && limits.limit_centripetal) {
      cap_mm_per_s = std::min(cap_mm_per_s, std::sqrt(accel * geometry::arc_radius_mm(move)));
    }
  }
  return cap_mm_per_s;
}

// Steps 1–2 for every move: where it starts, its length and its cap, into `timings` (one per move).
// Returns the total path length, mm.
double measure_moves(const geometry::Program& program, const geometry::MachineLimits& limits, std::vector<MoveTiming>& timings) {
  double s_mm = 0.0;
  for (std::size_t i = 0; i < program.path.moves.size(); ++i) {
    const Move& move = program.path.moves[i];
    MoveTiming& timing = timings[i];
    timing.start_s_mm = s_mm;
    timing.length_mm = geometry::length_mm(move);
    s_mm += timing.length_mm;
    timing.cap_mm_per_s = speed_cap_mm_per_s(move, program.blocks[i], limits);
  }
  return s_mm;
}

// The moves that take time ("real" moves), in order: those at least kMinMoveLengthMm long.
std::vector<std::size_t> moves_taking_time(const std::vector<MoveTiming>& timings) {
  std::vector<std::size_t> real;
  for (std::size_t i = 0; i < timings.size(); ++i) {
    if (timings[i].length_mm >= kMinMoveLengthMm) real.push_back(i);
  }
  return real;
}

// Step 3: point caps at the junctions, as v² (mm²/s²). Junction j lies before real move j (j = 0 is
// the start, j = m the end, both at rest).
std::vector<double> junction_speeds_squared(const geometry::Program& program, const geometry::MachineLimits& limits,
                                            const std::vector<MoveTiming>& timings,
                                            const std::vector<std::size_t>& real) {
  const std::vector<Move>& moves = program.path.moves;
  const std::size_t m = real.size();
  std::vector<double> u(m + 1, 0.0);  // v² at the junctions, mm²/s²
  for (std::size_t j = 1; j < m; ++j) {
    const std::size_t p = real[j - 1];
    const std::size_t q = real[j];
    bool stop = is_rapid(moves[p]) != is_rapid(moves[q]);
    for (std::size_t k = p + 1; k <= q; ++k) stop = stop || program.blocks[k].dwell_before_s > 0.0;
    if (stop) continue;
    const double cap = std::min(timings[p].cap_mm_per_s, timings[q].cap_mm_per_s);
    const Vec3 t1 = unit_tangent(moves[p], 1.0, timings[p].length_mm);
    const Vec3 t2 = unit_tangent(moves[q], 0.0, timings[q].length_mm);
    u[j] = std::min(cap * cap, junction_speed_squared(t1, t2, limits.max_accel_mm_per_s2, limits.junction_deviation_mm));
  }
  return u;
}

// Step 4. Look-ahead: forward then backward pass on u = v² at the junctions (docs/method.md §5.5).
void look_ahead(std::vector<double>& u, const std::vector<MoveTiming>& timings, const std::vector<std::size_t>& real,
                double accel) {
  const std::size_t m = real.size();
  for (std::size_t j = 1; j <= m; ++j) {
    u[j] = std::min(u[j], u[j - 1] + 2.0 * accel * timings[real[j - 1]].length_mm);
  }
  for (std::size_t j = m; j-- > 0;) {
    u[j] = std::min(u[j], u[j + 1] + 2.0 * accel * timings[real[j]].length_mm);
  }
}

// Steps 5–6 as they are laid out in time: the phases so far, the time they end and the time spent
// in each kind of phase.
struct PhaseSchedule {
  std::vector<MotionSegment> segments;
  double t_s = 0.0;
  double time_in_cut_s = 0.0;
  double time_in_air_s = 0.0;
  double time_dwelling_s = 0.0;

  // Step 6: a dwell at rest for exactly `dwell_s` (none when it is not positive).
  void add_dwell(std::size_t move_index, double at_s_mm, double dwell_s) {
    if (dwell_s <= 0.0) return;
    segments.push_back({t_s, at_s_mm, 0.0, 0.0, dwell_s, move_index, true});
    t_s += dwell_s;
    time_dwelling_s += dwell_s;
  }
};

// Step 5: the phases of move `i` (accelerate, cruise, decelerate) between entry speed² `u0` and exit
// speed² `u1`; fills in its timing.
void add_move_phases(PhaseSchedule& schedule, const Move& move, std::size_t i, MoveTiming& timing, double u0,
                     double u1, double accel) {
  auto& segments = schedule.segments;
  double& t_s = schedule.t_s;
  const double length = timing.length_mm;
  const double cap = timing.cap_mm_per_s;
  // Greatest profile v² = min(u0 + 2as, cap², u1 + 2a(L − s)); the passes guarantee |u1 − u0| ≤ 2aL.
  const double u_triangle = 0.5 * (u0 + u1) + accel * length;  // peak when the cap is not reached
  const bool reaches_cap = cap * cap <= u_triangle;
  const double u_peak = reaches_cap ? cap * cap : std::max({u_triangle, u0, u1});
  const double v0 = std::sqrt(u0);
  const double v1 = std::sqrt(u1);
  const double v_peak = std::sqrt(u_peak);
  const double s_accel = (u_peak - u0) / (2.0 * accel);
  const double s_decel = (u_peak - u1) / (2.0 * accel);
  const double s_cruise = reaches_cap ? std::max(0.0, length - s_accel - s_decel) : 0.0;
  const double t_accel = (v_peak - v0) / accel;
  const double t_cruise = s_cruise / v_peak;
  const double t_decel = (v_peak - v1) / accel;
  timing.entry_speed_mm_per_s = v0;
  timing.exit_speed_mm_per_s = v1;
  const double time_before = t_s;
  const double s0 = timing.start_s_mm;
  if (t_accel > 0.0) segments.push_back({t_s, s0, v0, accel, t_accel, i, false});
  t_s += t_accel;
  if (t_cruise > 0.0) segments.push_back({t_s, s0 + s_accel, v_peak, 0.0, t_cruise, i, false});
  t_s += t_cruise;
  if (t_decel > 0.0) segments.push_back({t_s, s0 + s_accel + s_cruise, v_peak, -accel, t_decel, i, false});
  t_s += t_decel;
  timing.end_time_s = t_s;
  const bool cutting = move.cutting && !is_rapid(move);
  (cutting ? schedule.time_in_cut_s : schedule.time_in_air_s) += t_s - time_before;
}

// Steps 5–6 for every move in order: the dwell before it, then its phases; a move that takes no time
// passes through its junction at that junction's speed. The dwell at the program's end is not added.
PhaseSchedule schedule_phases(const geometry::Program& program, std::vector<MoveTiming>& timings,
                              const std::vector<std::size_t>& real, const std::vector<double>& u, double accel) {
  PhaseSchedule schedule;
  const std::size_t m = real.size();
  std::size_t j = 0;  // next junction
  for (std::size_t i = 0; i < timings.size(); ++i) {
    MoveTiming& timing = timings[i];
    schedule.add_dwell(i, timing.start_s_mm, program.blocks[i].dwell_before_s);
    timing.start_time_s = schedule.t_s;
    if (j == m || real[j] != i) {  // takes no time: passes through junction j
      timing.entry_speed_mm_per_s = timing.exit_speed_mm_per_s = std::sqrt(u[j]);
      timing.end_time_s = schedule.t_s;
      continue;
    }
    add_move_phases(schedule, program.path.moves[i], i, timing, u[j], u[j + 1], accel);
    ++j;
  }
  return schedule;
}

}  // namespace

MotionProfile plan_motion(const geometry::Program& program, const geometry::MachineLimits& limits) {
  assert(program.blocks.size() == program.path.moves.size());
  check_program(program, limits);
  const double accel = limits.max_accel_mm_per_s2;

  MotionProfile profile;
  profile.path_moves_ = program.path.moves;
  profile.timings_.resize(program.path.moves.size());
  profile.length_mm_ = measure_moves(program, limits, profile.timings_);
  const std::vector<std::size_t> real = moves_taking_time(profile.timings_);
  std::vector<double> u = junction_speeds_squared(program, limits, profile.timings_, real);
  look_ahead(u, profile.timings_, real, accel);
  PhaseSchedule schedule = schedule_phases(program, profile.timings_, real, u, accel);
  schedule.add_dwell(program.path.moves.size() - 1, profile.length_mm_, program.dwell_at_end_s);
  profile.segments_ = std::move(schedule.segments);
  profile.time_in_cut_s_ = schedule.time_in_cut_s;
  profile.time_in_air_s_ = schedule.time_in_air_s;
  profile.time_dwelling_s_ = schedule.time_dwelling_s;
  profile.duration_s_ = schedule.t_s;
  return profile;
}

MotionState MotionProfile::state_in_segment(const MotionSegment& segment, double t_s) const {
  const double tau = std::clamp(t_s - segment.t0_s, 0.0, segment.duration_s);
  MotionState state;
  state.t_s = t_s;
  state.move_index = segment.move_index;
  state.dwelling = segment.dwell;
  state.s_mm = segment.s0_mm + tau * (segment.v0_mm_per_s + 0.5 * segment.a_mm_per_s2 * tau);
  state.speed_mm_per_s = std::max(0.0, segment.v0_mm_per_s + segment.a_mm_per_s2 * tau);
  state.accel_mm_per_s2 = segment.a_mm_per_s2;
  const MoveTiming& timing = timings_[segment.move_index];
  state.fraction = timing.length_mm > 0.0 ? std::clamp((state.s_mm - timing.start_s_mm) / timing.length_mm, 0.0, 1.0)
                                          : 0.0;
  state.position = geometry::point_at(path_moves_[segment.move_index], state.fraction);
  return state;
}

MotionState MotionProfile::state_at_time(double t_s) const {
  assert(!std::isnan(t_s));
  if (t_s < duration_s_ && !segments_.empty()) {
    const double t = std::max(t_s, 0.0);
    auto after = std::upper_bound(segments_.begin(), segments_.end(), t,
                                  [](double time, const MotionSegment& segment) { return time < segment.t0_s; });
    if (after != segments_.begin()) --after;
    return state_in_segment(*after, t);
  }
  MotionState state;  // at rest at the end
  state.t_s = duration_s_;
  state.s_mm = length_mm_;
  state.move_index = path_moves_.size() - 1;
  state.fraction = 1.0;
  state.position = path_moves_.back().end;
  return state;
}

double MotionProfile::speed_cap_at(double s_mm) const {
  assert(!std::isnan(s_mm));
  const double s = std::clamp(s_mm, 0.0, length_mm_);
  auto after = std::upper_bound(segments_.begin(), segments_.end(), s,
                                [](double length, const MotionSegment& segment) { return length < segment.s0_mm; });
  if (after == segments_.begin()) return 0.0;
  const MotionSegment& segment = *std::prev(after);
  if (segment.dwell) return 0.0;
  const double v0 = segment.v0_mm_per_s;
  // Within the phase v² = v0² + 2a(s − s0); past its end (only at a stop or the program end) v is 0.
  const double v_end = std::max(0.0, v0 + segment.a_mm_per_s2 * segment.duration_s);
  const double s_end = segment.s0_mm + segment.duration_s * 0.5 * (v0 + v_end);
  if (s >= s_end) return segment.a_mm_per_s2 == 0.0 ? v0 : v_end;
  return std::sqrt(std::max(0.0, v0 * v0 + 2.0 * segment.a_mm_per_s2 * (s - segment.s0_mm)));
}

}  // namespace feedplan::sim
