#pragma once
// Cutter radius compensation (G41, G42, G40) in the XY plane as LinuxCNC's interpreter computes it
// (interp_convert.cc: convert_straight_comp1/comp2, convert_arc_comp2, convert_cutter_compensation_off;
// interp_queue.cc: move_endpoint_and_flush), so that its canonical output is an oracle:
//   - the entry move (the first straight move after G41/G42) ends one tool radius from its programmed
//     end, perpendicular to the entry direction, on the compensation side; it must be longer than the
//     radius;
//   - each further move is the programmed one offset by the radius; at a convex corner the tool goes
//     round the programmed corner on an arc of the tool radius (a rapid: a straight traverse to the same
//     point), at a concave corner the previous move is trimmed to where the two offset paths meet
//     (line–line, line–arc, arc–line, arc–arc); a corner the tool cannot reach without gouging, or an
//     inside arc no larger than the tool, is refused;
//   - a move without XY motion (a plunge) keeps the tool's XY and waits with the move before it, whose
//     end a later concave corner may still move;
//   - G40 ends it: the waiting moves keep their ends, and the next move (which must be straight) runs
//     from the tool's position to its programmed end.
// The moves wait in a queue until the next move has decided their end; each carries a tag the caller
// uses to know which block it belongs to. Internal to the gcode module.

#include <string>
#include <vector>

#include "feedplan/geometry/move.hpp"
#include "feedplan/geometry/point.hpp"

namespace feedplan::gcode::detail {

//! Which side of the programmed path the tool runs on, looking along the motion.
enum class CompSide { kLeft, kRight };

//! A compensated move and the block it belongs to.
struct CompMove {
  geometry::Move move;  //!< the tool-centre move (rapid, line or arc)
  int tag = 0;          //!< the caller's tag of the block that made it
};

//! The programmed arc of a G2/G3 block, read from its words by the caller.
struct ProgrammedArc {
  geometry::Point2 center;   //!< centre, mm
  geometry::Point3 end;      //!< programmed end, mm
  bool ccw = true;           //!< G3
  int turns = 1;             //!< P (1 without)
};

//! The state of compensation while it is on, and its queue of moves whose end is not yet final.
class CutterCompensation {
 public:
  //! Compensation on `side` with tool radius `radius_mm` (> 0), the tool at `tool_position` and the
  //! programmed position `programmed` (the same, unless an arc end was moved).
  CutterCompensation(CompSide side, double radius_mm, const geometry::Point3& tool_position,
                     const geometry::Point3& programmed);

  //! A G0 (`rapid`) or G1 to programmed `end`. Moves whose end is final go to `done`. Returns the
  //! reason it cannot be compensated (empty when it can).
  std::string straight(bool rapid, const geometry::Point3& end, int tag, std::vector<CompMove>& done);

  //! A G2/G3 `arc` (its centre from the programmed start, programmed_position()). As straight().
  std::string arc(const ProgrammedArc& arc, int tag, std::vector<CompMove>& done);

  //! G40 (or the program end): every waiting move to `done`, ends as they are.
  void finish(std::vector<CompMove>& done);

  const geometry::Point3& tool_position() const { return tool_; }
  const geometry::Point3& programmed_position() const { return programmed_; }

 private:
  std::string move_ends_and_flush(const geometry::Point2& end, std::vector<CompMove>& done);
  void flush(std::vector<CompMove>& done);
  void emit(const geometry::Move& move, int tag, std::vector<CompMove>& done);
  void enqueue(const geometry::Move& move, const geometry::Point2& direction, double original_sweep_rad, int tag);
  void round_convex_corner(bool rapid, const geometry::Point2& corner_end, int tag, std::vector<CompMove>& done);

  // A waiting move: the move, the programmed direction of a line, an arc's signed sweep when queued.
  struct Waiting {
    CompMove move;
    geometry::Point2 direction;
    double original_sweep_rad = 0.0;
  };

  CompSide side_;
  double radius_mm_;
  bool first_move_ = true;         // the entry move is still to come
  geometry::Point3 tool_;          // where the tool centre is (the end of the last move)
  geometry::Point3 programmed_;    // the programmed position
  std::vector<Waiting> queue_;
  geometry::Point2 queue_start_;   // where the first waiting move starts
};

}  // namespace feedplan::gcode::detail
