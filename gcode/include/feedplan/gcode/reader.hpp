#pragma once
// Reading RS274/NGC (LinuxCNC) G-code into a Program: the moves of the tool tip with the feed,
// spindle and dwells commanded for each (docs/method.md §2, gcode/ text ──► ToolPath). The reader takes
// the subset a CAM post or feedplan's own writer emits for 2.5D milling and refuses everything else
// by line and word — a skipped word could change the path the force model is computed on.
//
// What the reader does with each word (LinuxCNC's order of execution within a block: G94, F, S, T,
// M6, M3/M4/M5, coolant, G4, plane, units, cutter compensation, tool length offset, work offset,
// distance modes, motion, M0/M1, M2/M30):
//
// Supported
//   G0, G1            rapid and straight feed moves
//   G2, G3            clockwise / counter-clockwise arcs in XY, with I J (centre offsets from the
//                     start; absolute under G90.1) or R (negative R: the arc of more than 180°); a Z
//                     word makes a helix; start == end with I J is a full circle; P n adds n − 1 turns
//   G4 P              dwell, P in seconds; it runs before the motion of its block
//   G17               XY plane
//   G18, G19          XZ and YZ planes for G2/G3 (G0/G1 are unaffected): as in LinuxCNC, G18 takes Z as the
//                     first axis and X as the second (centre K I from the start, or R; Y moves along as a
//                     helix), G19 Y then Z (J K; X along), G3 turning from the first axis towards the
//                     second. A Move is an XY circle, so such an arc becomes straight feed moves along the
//                     exact arc: equal angular pieces, as many as keep every chord within 1 µm of the arc
//                     and every piece within 5°, whichever needs more (a radius that differs within the
//                     tolerance at the end: a spiral, as LinuxCNC drives it); all on the arc's line,
//                     marked WrittenMove::keep_whole; a note counts them. I (G19) or J (G18) is refused
//   G20, G21          inch / mm input; everything is converted to mm
//   G90, G91          absolute / incremental X Y Z
//   G90.1, G91.1      absolute / incremental I J (G91.1, incremental, is LinuxCNC's default)
//   G54 … G59.3       work offset selection, only before the first move or re-selecting the one in
//                     effect: the reader has no offset values, a change after moving would jump
//   G80               cancels the motion mode (axis words then need a new G0–G3); beside G0–G3
//                     in one block (a CAM safe-start line) the motion wins, as in LinuxCNC
//   G94               feed per minute, the only feed mode read; like LinuxCNC it resets the feed to
//                     0, so a feed move needs an F after it (in the same block or later)
//   F S               feed (per minute, in the length unit in effect when F is read) and spindle rpm
//   T, M6             tool selection and change (`T1 M6`, T in the same or an earlier block): once,
//                     before the first move (anywhere with ReaderOptions::tool_changes); a note
//                     records the tool number
//   G41, G42 [D]      cutter radius compensation left / right of the programmed path, as LinuxCNC computes
//                     it (the moves are the tool centre's): D is a tool number (Haas' D01: tool 1) whose
//                     diameter ReaderOptions::tool_diameters_mm gives; without D the tool in the spindle.
//                     The first straight move after G41/G42 enters (it must be longer than the radius);
//                     convex corners get an arc of the tool radius about the programmed corner (a G0: a
//                     straight rapid to the same point), concave ones are trimmed where the offset lines
//                     and arcs meet; moves without XY motion (plunges) and helical arcs are kept. Moves
//                     compensation makes belong to the line of the block the controller makes them for (a
//                     corner arc: the block after the corner), marked WrittenMove::keep_whole
//   G40               compensation off: the next move (straight) runs from where the tool is to its
//                     programmed end, marked keep_whole
//   G73, G81, G82,    drilling canned cycles in G17, expanded into the moves LinuxCNC makes for each hole
//   G83, G85, G86,    (drill_cycle.hpp lists them): R plane, Z bottom, P dwell (G82, G86, G89), Q peck
//   G89, G98, G99     (G73, G83), L repeats (under G91 each a step further), G98 retract to the initial
//                     level (the Z when the cycles began) or R if higher, G99 to R; R Z P Q stay in effect
//                     while the cycle does; absolute and incremental as LinuxCNC. Further X/Y lines drill
//                     more holes; G80 or G0–G3 ends the cycle. Every move of a hole is on the cycle's
//                     line, marked WrittenMove::keep_whole and fixed_feed (its F stays as written); G86
//                     retracts with the spindle stopped. A P on G81, G83, G73 or G85 is ignored with a
//                     note (Haas ignores it; LinuxCNC refuses it). A note counts the holes
//   G28, G30, G53     moves to machine positions. The reader has no machine coordinates, so each is read
//                     as taking the tool to a parked state above everything: a rapid straight up from
//                     where it is to the park height — ReaderOptions::park_z_mm, else the highest Z the
//                     program has reached before it (or the initial position's) plus 25 mm — X and Y kept
//                     (G53's X Y words move nothing; a G53 G1 does not cut). G28/G30 with axis words first
//                     go to that intermediate point (a rapid, in the distance mode in effect), as LinuxCNC
//                     does. The next move leaves the park height from there; it must be a G0 (a feed move
//                     would start at an unknown place). A note says how they were read when a move
//                     leaves from a park; parks with no move after them (the safe return at the end of
//                     feedplan's own programs and of most CAM posts' ones) get none: nothing is cut or
//                     moved from the guessed place, and the park's rapid — after the cut, never cutting
//                     — only adds its time to the cycle
//   G43 H             tool length offset on: the programmed Z is the tool tip, which is what the reader
//                     assumes anyway; H must be the tool in the spindle (without H: that tool). Other
//                     words may share the block (`G43 H1 Z5`). G43 with no M6 before it is taken to name
//                     the tool in the spindle (a note says so)
//   M3, M4, M5        spindle clockwise / counter-clockwise / off
//   M2, M30           program end; later lines are not read (a note says so when they hold words)
//   N, O              line numbers (first in their block), program-number lines like `O1000`
//   %                 alone on the first line opens the program, alone on a later line ends it
//   ( ) and ;         comments; blank lines; lowercase letters; spaces inside words
// Ignored: accepted, with no effect on the path, feeds or spindle
//   G49 (tool length offset off): the reader's Z is the tool tip either way; G97 (constant rpm): the default;
//   G61, G61.1, G64 [P Q] (path control): how the controller blends corners, the programmed path
//   stays the same; M0, M1 (program pause); M7, M8, M9, M88, M89 (coolant, Haas through-spindle
//   coolant); M31, M32, M33 (Haas chip conveyor; LinuxCNC refuses them); T without M6 (tool
//   preparation).
// Refused, by line and word
//   G17.1, G18.1, G19.1 (UVW planes); G18/G19 while cutter compensation is on; G41.1, G42.1
//   (compensation by a diameter in D); G41/G42 without a diameter for its tool in
//   ReaderOptions::tool_diameters_mm (the message names the tool) or with no D and no tool in the
//   spindle; what LinuxCNC refuses under compensation: an entry move no longer than the tool radius, an
//   inside arc whose radius is not larger than the tool's, a concave corner the tool cannot reach
//   without gouging, G41/G42 while it is on, an arc right after G40, M6 while it is on; an arc as the
//   entry move (LinuxCNC accepts it; the reader needs a straight entry); G43.1, G43.2 (dynamic and
//   added tool length offsets), G43 with an H that is not the tool in the spindle, H without G43; G93
//   inverse time and G95 feed per revolution; G96 constant surface speed; G28.1, G30.1 (storing
//   machine positions), G28/G30/G53 under cutter compensation, G28/G30 with G0–G3 in the block, a feed
//   move right after a park; G10, G52, G92 (offset changes); G5.x splines, G33 threading, G38.x
//   probing, G74 and G84 tapping, G87 back boring, G88; a drilling cycle outside G17 or under
//   compensation, one that starts without R or Z (or P, Q where it needs them), with an R below its
//   bottom, a Q ≤ 0, G86 with the spindle off; G7, G8; a second M6 or one after the first move (the
//   path is planned for one tool: split the program per tool), M6 with no T before it; every other G
//   or M code; A, B, C, U, V, W axes; K outside an arc; D outside a G41/G42 block; L outside a
//   drilling cycle; the letter E and the like; parameters and expressions (#1, [..]); O-word
//   subroutines and control flow; block delete `/` (whether the line runs depends on the operator's
//   switch).
//
// Problems found (all collected, up to a cap, into one InputError; each names the line and the
// word): unknown or refused words; numbers that are not plain decimals (`X1..2`, `Xabc`, `X`, no
// exponents); two words of one modal group, or a letter twice, in a block; a feed move with no
// positive F in effect, or with M3/M4 and an S0 in effect (the spindle would not turn); an arc
// without I J or R, with a zero radius, with I J whose end radius differs from its start radius by
// more than the tolerance, or with an R shorter than half the chord;
// unbalanced or nested comment parentheses; F in a block whose G20/G21 changes the units (LinuxCNC
// would read that F in the old unit); a file that ends without M2, M30 or a closing % (optional);
// what no machine takes: a number beyond ±1 000 000 (1 km in mm), a line of more than 4096 characters
// (LinuxCNC reads 255), an arc of more than ReaderOptions::max_arc_turns turns, more than
// ReaderOptions::max_moves moves, a file larger than ReaderOptions::max_file_bytes.
//
// What the output means: the moves are the tool tip's centre (under G41/G42 the compensated path).
// Every feed move (G1, G2, G3, a cycle's feeds, a plane arc's pieces) is `cutting` because a reader
// cannot know which feed moves cut and which move through air (that needs the stock:
// geometry/engagement does it); axial_depth_mm is 0 for the same reason. All moves belong to part 0, named "program". Moves of
// zero length (a G0/G1 to where the tool already is, or a block without axis words) are dropped.
// Program::coordinate_resolution_mm is the last digit of the finest X Y Z I J K R word of the moves
// (`X1.25` in G21: 0.01 mm; in G20: 0.254 mm); whole numbers (`X3`, `X3.`) do not count.

#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include "feedplan/geometry/point.hpp"
#include "feedplan/geometry/program.hpp"

namespace feedplan::gcode {

//! How read_program treats the parts of a program the text leaves open.
struct ReaderOptions {
  //! Largest |start radius − end radius| accepted on an I/J arc, and the largest amount by which
  //! an R may fall short of half the chord, mm. LinuxCNC accepts I/J mismatches of 0.05 mm and more:
  //! it keeps the programmed centre and end and drives a spiral; its limit for an R is 0.00005 in
  //! (0.00127 mm). A Move is a circle, so within the tolerance the reader moves the one of centre and
  //! end that moves less: the centre onto the perpendicular bisector of start and end (half circles:
  //! by half the mismatch), or the end along its ray onto the circle about the programmed centre
  //! (short arcs, whose bisector lies far from the centre; the next move starts there, and an end
  //! moves by at most this tolerance). R arcs short of half the chord are taken as the half circle. A
  //! note counts moves of more than 1 µm. An I/J arc whose words have a coarser last digit gets two of
  //! those digits instead (start, end and centre are each rounded to half a digit per axis), up to
  //! 5.08 µm, two digits of an inch program with 4 decimals.
  double arc_radius_tolerance_mm = 0.002;
  geometry::Point3 initial_position{0.0, 0.0, 0.0};  //!< where the tool tip is before the first move, mm
  bool require_program_end = true;  //!< the text must end the program with M2, M30 or a closing %
                                    //!< (LinuxCNC's rule; catches truncated files); false accepts snippets
  int max_problems = 50;            //!< problems collected before the reader stops looking for more
  //! Tool changes anywhere (M6 after moves, more than one): for a caller that plans each tool's moves on
  //! their own (WrittenMove::tool says which tool made a move). M6 switches the old tool's length offset
  //! off; G43 H<new tool> switches the new one on. False: one M6, before the first move.
  bool tool_changes = false;
  //! Tool diameters by tool number, mm, for cutter radius compensation (G41/G42): the D word names the tool
  //! (LinuxCNC: D is a tool number whose tool-table diameter is used; Haas' D01 is tool 1), or without D
  //! the tool in the spindle. A negative diameter compensates on the other side, 0 not at all (LinuxCNC).
  std::map<int, double> tool_diameters_mm;
  //! The diameter of every tool tool_diameters_mm does not list, mm: for a program of one tool whose number
  //! the caller does not know (feedplan optimize --tool). Empty: none.
  std::optional<double> any_tool_diameter_mm;
  //! Z of the parked state that moves to machine positions (G28, G30, G53) are read as, mm; without it,
  //! the highest Z the program has reached before the move (or the initial position's) plus 25 mm.
  std::optional<double> park_z_mm;
  //! Most turns of one G2/G3 (its P word): a deep helical bore takes a few hundred; a million turns
  //! is one move that the planner and the virtual machine sample into gigabytes.
  int max_arc_turns = 1000;
  //! Most moves in a program: feedplan's own plans of its cycles take a few thousand; beyond this the
  //! planner and the virtual machine need gigabytes (10⁵ tiny moves took more than 4 GB).
  int max_moves = 50000;
  //! Largest file load_program reads, bytes: a program of max_moves moves is a few MiB; /dev/zero or an
  //! endless pipe would otherwise be read until memory runs out.
  std::size_t max_file_bytes = std::size_t{64} << 20;
};

//! Parses RS274/NGC text (`source_name` — a file name, or e.g. "test" — prefixes every problem).
//!
//! Needs nothing but the text. Returns the moves with one BlockCommand each: the feed in mm/min in
//! effect for G1/G2/G3 (0 on rapids), the spindle rpm and direction in effect, any G4 dwell since the
//! previous move, and the 1-based text line of the move (of the block that makes it: a compensated corner
//! arc, a drilling cycle's moves, a plane arc's pieces); a dwell after the last move goes to
//! dwell_at_end_s, and Program::notes carries what the user should know that is not an error. The
//! path satisfies geometry::consistency_defects. On any problem it throws one feedplan::InputError
//! listing every problem found (up to options.max_problems), each as
//! `<source_name> line N: word Q5: not supported (…)` or `… line N: G1 before any F word: …`.
geometry::Program read_program(const std::string& text, const std::string& source_name,
                               const ReaderOptions& options = {});

//! How the line of a move was written: what rewriting the line (refeed.hpp) must keep.
struct WrittenMove {
  int line = 0;                      //!< 1-based text line (BlockCommand::source_line)
  int motion = 1;                    //!< 0, 1, 2, 3: G0 G1 G2 G3
  bool motion_word = false;          //!< the line has its own G0–G3 word (else the modal one moves)
  bool inch = false;                 //!< G20 in effect
  bool incremental = false;          //!< G91 in effect
  bool absolute_arc_center = false;  //!< G90.1 in effect (I J absolute)
  bool radius_form = false;          //!< an arc given by R
  bool turns = false;                //!< an arc with a P word (turns)
  int tool = -1;                     //!< the tool in the spindle (T M6, or G43 H without one); −1: none named
  //! The line must not be split: its moves are not the line's words alone (a compensated move, a plane
  //! arc written as straight pieces, a canned cycle's moves). refeed_text changes only its F.
  bool keep_whole = false;
  //! The move's feed is the one written and must not change (a drilling cycle's moves: the cycle's F is
  //! the drill's, not a milling feed); callers give such moves no pieces.
  bool fixed_feed = false;
};

//! read_program, and how each move's line was written (parallel to the program's moves).
geometry::Program read_program(const std::string& text, const std::string& source_name, const ReaderOptions& options,
                               std::vector<WrittenMove>& written);

//! Reads the file at `path` and parses it with read_program, the path as source name. A file that
//! does not exist, is a directory or cannot be read is an InputError naming the path.
geometry::Program load_program(const std::filesystem::path& path, const ReaderOptions& options = {});

}  // namespace feedplan::gcode
