#pragma once
// A machine program: a tool path plus what the controller is told per block — the programmed feed,
// the spindle, dwells and where each move came from. The planner produces one (F words chosen per
// stretch), the G-code reader produces one from text, the virtual machine runs one.

#include <string>
#include <vector>

#include "feedplan/geometry/tool_path.hpp"

namespace feedplan::geometry {

//! Spindle state commanded for a move (M3/M4/M5 with S).
enum class SpindleDirection {
  kOff,        //!< M5 (or never started)
  kClockwise,  //!< M3: teeth turn clockwise seen from the spindle, the sense the engagement angles assume
  kCounterClockwise,  //!< M4
};

//! What the controller is told for one move, parallel to ToolPath::moves.
struct BlockCommand {
  double feed_mm_per_min = 0.0;  //!< programmed F for feed moves (path speed, mm/min); 0 on rapids
  double spindle_rpm = 0.0;      //!< programmed S in effect, rev/min (0 when none was given)
  SpindleDirection spindle = SpindleDirection::kOff;  //!< M3/M4/M5 state in effect during the move
  double dwell_before_s = 0.0;   //!< G4 dwell executed before this move starts, s
  int source_line = 0;           //!< 1-based line in the program text the move came from; 0 if generated
};

//! A tool path with its per-move commands.
struct Program {
  ToolPath path;                      //!< the moves, in execution order
  std::vector<BlockCommand> blocks;   //!< one per path.moves entry
  double dwell_at_end_s = 0.0;        //!< G4 dwell after the last move, s
  std::vector<std::string> notes;     //!< what a reader or planner wants the user to know (not errors)
  //! The grid the coordinates were written on, mm: the last digit of the finest X Y Z I J R word of
  //! a program read from text (0.001 for 3 decimals in mm). Every written point lies within half of
  //! it, per axis, of where its writer meant it. 0 when the moves are not rounded (a generated path,
  //! or text whose coordinates are all whole numbers).
  double coordinate_resolution_mm = 0.0;
  std::string source_name;            //!< where the program came from (a file name), for messages; may be empty
};

}  // namespace feedplan::geometry
