#pragma once
// Re-feeding a program another system wrote: the same text with only its F words changed or added.
//
// Every line, comment and word of the input stays as it was, except on the lines of feed moves (G1, G2,
// G3) whose feed the plan sets:
//   - a move run at one feed keeps its line; its F word is replaced (or removed, when the feed in effect
//     is already the planned one; or added, when the line had none and the feed changes there);
//   - a move whose feed must change along it is split where it changes, and only there. The first piece
//     stays on the move's own line — with every other word of the line (G codes, S, M, dwells, comments),
//     so they act before the motion as they did — its axis and arc words replaced by the first piece's;
//     each further piece is a new line after it, `G1` or `G2`/`G3` with the motion's explicit code; the
//     last piece ends on the line's own X Y Z words, as written. Arcs become exact sub-arcs of the same
//     circle in the program's own arc format: I J from the piece's start (G91.1) or the centre itself
//     (G90.1), or R (negative beyond 180°). Split points are written with 4 decimals in mm and 5 in
//     inches (within 0.13 µm of the path), in the units in effect;
//   - a move that cannot be split this way — an arc of several turns (P) or a move in incremental
//     distance mode (G91) — runs at the lowest feed of its pieces, on its own line;
//   - a line that carries several moves of the program (cutter compensation's corner arcs, a canned
//     cycle's moves, an arc outside the XY plane read as straight pieces) or whose move is marked
//     WrittenMove::keep_whole runs at the lowest feed of all the pieces of all its moves: only its F
//     word changes. Moves marked WrittenMove::fixed_feed (drilling cycles) take no pieces; a line of
//     them is copied as it is;
// F is modal: it is written where the feed in effect (from F words on any line, as read; G94 resets it)
// differs from the planned one, in the units in effect (mm/min, or in/min under G20), rounded down to
// 0.1 mm/min or 0.001 in/min — never faster than planned. Rapids and every other line are copied byte
// for byte; line endings (LF or CR LF) are kept.
//
// Feed comments (FeedPiece::reason, `feedplan optimize --explain`): a line that writes a piece's F word
// also gets `(F: <reason>)` — the reason of the piece whose feed the F is (the lowest, on a line run at its
// lowest feed), made safe as the writer makes user text (writer.hpp), upper-cased when the program's own
// comments have no lower-case letter (as Fanuc and Haas posts write them), at most 58 characters. It goes
// right before the line's first comment — LinuxCNC acts on the last comment of a line only, so an existing
// one (a `(MSG, …)` too) stays the one it acts on — or, on a line without one, after its last word (before
// a `;` comment). A line that would pass 255 characters with it (LinuxCNC's longest) gets none.

#include <string>
#include <utility>
#include <vector>

#include "feedplan/gcode/reader.hpp"
#include "feedplan/geometry/program.hpp"
#include "feedplan/geometry/tool_path.hpp"

namespace feedplan::gcode {

//! A stretch of one move of the program run at one feed (a planner's block).
struct FeedPiece {
  FeedPiece() = default;
  //! A piece without a reason unless one is given (the reason is what `--explain` adds).
  FeedPiece(int move_index, geometry::Move move, double feed_mm_per_min, std::string reason = {})
      : move_index(move_index), move(std::move(move)), feed_mm_per_min(feed_mm_per_min), reason(std::move(reason)) {}

  int move_index = 0;               //!< the move of the read program it is part of
  geometry::Move move;              //!< the stretch; the pieces of a move follow one another end to start
  double feed_mm_per_min = 0.0;     //!< its F, mm/min (> 0)
  std::string reason;               //!< why the feed is what it is, written as `(F: <reason>)` with its F word; "" for none
};

//! The re-fed text and what changed.
struct RefeedResult {
  std::string text;                 //!< the program with its F words set
  int lines_changed = 0;            //!< input lines whose text changed
  int lines_added = 0;              //!< lines inserted for the pieces of split moves
  int moves_split = 0;              //!< moves written as more than one piece
  int moves_at_lowest_feed = 0;     //!< moves that could not be split and run at their lowest feed (of
                                    //!< their line's pieces, when the line carries several moves)
};

//! Writes `text` (the program `program` and `written` were read from by read_program) with the feeds
//! of `pieces`: for every feed move of the program, its pieces in order (moves without pieces keep their
//! F). Rapids and moves marked WrittenMove::fixed_feed must have none. Throws std::invalid_argument when
//! the pieces do not belong to the program.
RefeedResult refeed_text(const std::string& text, const geometry::Program& program,
                         const std::vector<WrittenMove>& written, const std::vector<FeedPiece>& pieces);

}  // namespace feedplan::gcode
