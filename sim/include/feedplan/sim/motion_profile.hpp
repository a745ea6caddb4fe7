#pragma once
// How the virtual machine's controller executes a Program: the path speed v(t) along the whole
// program under the machine's limits, with look-ahead over every block (docs/method.md §5.5, §6.3).
//
// The model, step by step:
//   1. Speed caps per move (constant along the move): a feed move (kLine, kArc) runs at most at its
//      block's F, clamped to MachineLimits::max_feed_mm_per_min; a rapid runs at most at
//      MachineLimits::rapid_feed_mm_per_min. F is measured along the move in space
//      (geometry::length_mm: the helix length of helical arcs, the z length of a plunge).
//   2. Centripetal cap on arcs (limit_centripetal): v² ≤ a_max · R with R the XY radius of the arc.
//      For a helix the true radius of curvature (R² + (dz/dθ)²)/R is larger, so R is slightly
//      conservative. The tangential acceleration limit applies on arcs as everywhere else; the two
//      are checked separately, not as a vector sum.
//   3. Speed at junctions (point caps between consecutive moves), with t₁ the unit tangent (in space)
//      at the end of one move, t₂ at the start of the next, and φ the deflection angle between them:
//      - junction-deviation rule of grbl (Sungeun K. Jeon, grbl planner.c, plan_buffer_line; the
//        same rule in grblHAL, Smoothieware and Marlin): the corner is rounded by the circle tangent
//        to both moves that passes δ = junction_deviation_mm from the corner; with interior angle
//        θ = π − φ its radius is R_j = δ·sin(θ/2)/(1 − sin(θ/2)), and the junction speed is the
//        centripetal limit on it, v_j² = a·R_j = a·δ·cos(φ/2)/(1 − cos(φ/2));
//      - tangent-continuous junctions (φ ≤ kTangentJunctionToleranceRad, e.g. a trochoid's step into
//        its circle) are not limited beyond the two moves' caps;
//      - a full reversal (φ ≥ π − kTangentJunctionToleranceRad) stops (the rule gives 0 at φ = π);
//      - a switch between a rapid and a feed move stops (exact stop, as G0 ↔ G1 does on most
//        controllers), and so does a dwell;
//      - every junction speed is also capped by both moves' caps, so a slower block is entered at
//        no more than its F.
//   4. Look-ahead over the whole program (forward and backward pass on u = v² at the junctions,
//      u_{j+1} ≤ u_j + 2 a L_j and u_j ≤ u_{j+1} + 2 a L_j, docs/method.md §5.5), from rest at the start to
//      rest at the end.
//   5. Each move then runs the greatest profile between its entry and exit speeds under its cap:
//      accelerate at a, cruise at the cap, decelerate at a (a triangle when the cap is not reached).
//      Together this is the greatest (time-optimal) profile under all caps and the acceleration limit.
//   6. Dwells (BlockCommand::dwell_before_s, Program::dwell_at_end_s) wait at rest for exactly their
//      time. Moves shorter than kMinMoveLengthMm take no time and form no junction.
// The profile is exact: piecewise-constant acceleration phases evaluated in closed form.

#include <cstddef>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/geometry/machine_limits.hpp"
#include "feedplan/geometry/point.hpp"
#include "feedplan/geometry/program.hpp"

namespace feedplan::sim {

//! Junctions whose tangents deflect by at most this angle are tangent-continuous (not limited), and
//! those within it of π are reversals (a stop), rad.
inline constexpr double kTangentJunctionToleranceRad = 1e-6;

//! Moves shorter than this take no time and form no junction (their neighbours meet directly), mm.
inline constexpr double kMinMoveLengthMm = 1e-9;

//! The virtual machine's limits when a request names none: a slower machine than a spec's defaults
//! (2000 mm/s², rapids at 15 m/min, feeds up to 20 m/min), the machine the sample database's cutting
//! tests were run on.
inline constexpr geometry::MachineLimits kVirtualMachineLimits{
    .max_feed_mm_per_min = 20000.0, .max_accel_mm_per_s2 = 2000.0, .rapid_feed_mm_per_min = 15000.0};

//! Where the machine is at one instant.
struct MotionState {
  double t_s = 0.0;              //!< time since the program started, s
  double s_mm = 0.0;             //!< path length travelled since the start (rapids included), mm
  double speed_mm_per_s = 0.0;   //!< path speed, mm/s
  double accel_mm_per_s2 = 0.0;  //!< path (tangential) acceleration, mm/s²
  std::size_t move_index = 0;    //!< move being executed (or dwelt before), index into the path
  double fraction = 0.0;         //!< position within that move by length, in [0, 1]
  bool dwelling = false;         //!< true while a dwell is being executed
  geometry::Point3 position;     //!< tool tip position, mm
};

//! One phase of the profile: constant acceleration over a time interval, or a dwell at rest.
struct MotionSegment {
  double t0_s = 0.0;            //!< time the phase starts, s
  double s0_mm = 0.0;           //!< path length at its start, mm
  double v0_mm_per_s = 0.0;     //!< path speed at its start, mm/s
  double a_mm_per_s2 = 0.0;     //!< constant path acceleration during the phase, mm/s²
  double duration_s = 0.0;      //!< length of the phase, > 0, s
  std::size_t move_index = 0;   //!< move the phase belongs to (a dwell: the move it comes before)
  bool dwell = false;           //!< true for a dwell (v0 = a = 0)
};

//! How one move is executed.
struct MoveTiming {
  double start_s_mm = 0.0;            //!< path length where the move starts, mm
  double length_mm = 0.0;             //!< length of the move in space, mm
  double cap_mm_per_s = 0.0;          //!< the move's own speed cap (F, max feed, centripetal, rapid), mm/s
  double entry_speed_mm_per_s = 0.0;  //!< speed at its start (the junction speed), mm/s
  double exit_speed_mm_per_s = 0.0;   //!< speed at its end, mm/s
  double start_time_s = 0.0;          //!< time its motion starts (after any dwell before it), s
  double end_time_s = 0.0;            //!< time its motion ends, s
};

class MotionProfile;

//! Plans how the machine executes `program` under `limits` (the model described at the top of this
//! file). Needs a program with at least one move and one block per move (asserted). Throws
//! InputError listing the problems when the limits are invalid (validate), the program has no moves,
//! a feed move has no positive finite F, a dwell is negative or not finite, or a move's length is
//! not finite; problems are named after the block's source line ("line 12") or the move ("move 3").
//! Linear in the number of moves.
MotionProfile plan_motion(const geometry::Program& program,
                          const geometry::MachineLimits& limits = kVirtualMachineLimits);

//! The planned motion of one program: speed, acceleration and position at any time, exactly.
class MotionProfile {
 public:
  //! Total time from the start to the end of the last move or dwell, s.
  double duration_s() const { return duration_s_; }

  //! Total path length, rapids included, mm.
  double length_mm() const { return length_mm_; }

  //! Time spent moving on cutting feed moves (Move::cutting and not a rapid), s.
  double time_in_cut_s() const { return time_in_cut_s_; }

  //! Time spent moving on everything else (rapids, air feed moves), s.
  double time_in_air_s() const { return time_in_air_s_; }

  //! Time spent dwelling, s. time_in_cut_s + time_in_air_s + time_dwelling_s = duration_s.
  double time_dwelling_s() const { return time_dwelling_s_; }

  //! The machine's state at time `t_s`, clamped to [0, duration_s()]: the start (at rest at s = 0,
  //! move 0) before 0, the end (at rest at s = length_mm(), last move, fraction 1) from duration_s()
  //! on. `t_s` must not be NaN (asserted). O(log n) in the number of segments.
  MotionState state_at_time(double t_s) const;

  //! The planned path speed where the path length is `s_mm` (what the profile reaches there, with
  //! all caps and look-ahead applied), mm/s; `s_mm` is clamped to [0, length_mm()] and must not be
  //! NaN (asserted). Zero at the start, the end and every stop. O(log n).
  //!
  //! Because it is zero at stops, a feed override r(t) cannot be applied by integrating
  //! ds/dt = r · speed_cap_at(s) (the tool would never leave a stop); scale the profile's time
  //! instead: advance τ by r·Δt, read state_at_time(τ), and the speed is r times its speed.
  double speed_cap_at(double s_mm) const;

  //! The phases in time order (zero-length phases are omitted); their durations add up to
  //! duration_s().
  const std::vector<MotionSegment>& segments() const { return segments_; }

  //! Entry and exit speeds and times, one per move of the program (zero-length moves included).
  const std::vector<MoveTiming>& moves() const { return timings_; }

 private:
  friend MotionProfile plan_motion(const geometry::Program& program, const geometry::MachineLimits& limits);
  MotionProfile() = default;

  MotionState state_in_segment(const MotionSegment& segment, double t_s) const;

  std::vector<geometry::Move> path_moves_;
  std::vector<MoveTiming> timings_;
  std::vector<MotionSegment> segments_;
  double duration_s_ = 0.0;
  double length_mm_ = 0.0;
  double time_in_cut_s_ = 0.0;
  double time_in_air_s_ = 0.0;
  double time_dwelling_s_ = 0.0;
};

}  // namespace feedplan::sim
