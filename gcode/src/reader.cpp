#include "feedplan/gcode/reader.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "arc_geometry.hpp"
#include "code_catalog.hpp"
#include "cutter_compensation.hpp"
#include "drill_cycle.hpp"
#include "feedplan/core/bounded_read.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/geometry/tool_path.hpp"
#include "line_lexer.hpp"
#include "plane_arc.hpp"
#include "problem_log.hpp"

namespace feedplan::gcode {

using detail::CodeInfo;
using detail::CodeUse;
using detail::Word;
using geometry::Move;
using geometry::MoveKind;
using geometry::Point2;
using geometry::Point3;
using geometry::SpindleDirection;

namespace {

constexpr double kMmPerInch = 25.4;
constexpr double kReportedShiftMm = 1e-6;  // centre moves above this are counted in a note
constexpr std::size_t kMaxLineCharacters = 4096;  // LinuxCNC's limit is 255; CAM comments stay far below
constexpr double kParkClearanceMm = 25.0;  // the park height above the highest Z reached (ReaderOptions::park_z_mm)

// Motion modes in tenths of their G number; kNoMotion after G80 and at the start (as LinuxCNC).
constexpr int kNoMotion = -1;
constexpr int kG0 = 0;
constexpr int kG1 = 10;
constexpr int kG2 = 20;
constexpr int kG3 = 30;
constexpr int kG4 = 40;
constexpr int kG17 = 170;
constexpr int kG18 = 180;
// G19 (190) is the plane that is neither of these.
constexpr int kG20 = 200;
constexpr int kG40 = 400;
constexpr int kG41 = 410;
constexpr int kG42 = 420;
constexpr int kG43 = 430;
constexpr int kG49 = 490;
constexpr int kG64 = 640;
constexpr int kG80 = 800;
constexpr int kG94 = 940;
constexpr int kG90 = 900;
constexpr int kG90_1 = 901;
constexpr int kG91 = 910;
constexpr int kG91_1 = 911;
constexpr int kG54 = 540;
constexpr int kG28 = 280;
constexpr int kG30 = 300;
constexpr int kG53 = 530;

bool is_arc(int motion) { return motion == kG2 || motion == kG3; }
bool is_motion(int motion) { return motion == kG0 || motion == kG1 || is_arc(motion); }
// The drilling canned cycles the reader expands: G73, G81, G82, G83, G85, G86, G89.
bool is_cycle(int motion) {
  return motion == 730 || motion == 810 || motion == 820 || motion == 830 || motion == 850 || motion == 860 ||
         motion == 890;
}
bool cycle_dwells(int motion) { return motion == 820 || motion == 860 || motion == 890; }
bool cycle_pecks(int motion) { return motion == 730 || motion == 830; }

// Value words the reader reads (G, M, N and O are handled separately).
bool is_value_letter(char letter) {
  switch (letter) {
    case 'D': case 'F': case 'H': case 'L': case 'I': case 'J': case 'K': case 'P': case 'Q': case 'R': case 'S': case 'T': case 'X': case 'Y': case 'Z':
      return true;
    default:
      return false;
  }
}

// One block after the words are sorted: the codes by modal group and the value words by letter.
struct Block {
  int line = 0;
  std::array<std::optional<int>, 16> g_by_group;    // G code (tenths) per modal group
  std::array<std::optional<int>, 16> m_by_group;    // M code per modal group
  std::array<const Word*, 26> letters{};            // value word per letter, nullptr when absent

  const Word* word(char letter) const { return letters[static_cast<std::size_t>(letter - 'A')]; }
  bool has(char letter) const { return word(letter) != nullptr; }
  bool has_g(int tenths, int group) const { return g_by_group[group] == tenths; }
  bool has_m(int code, int group) const { return m_by_group[group] == code; }
};

// How many arcs the reader had to move a point of (by more than kReportedShiftMm), and the largest move.
struct ArcMoves {
  int count = 0;
  double largest_mm = 0.0;
  int largest_line = 0;

  void add(double shift_mm, int line) {
    if (shift_mm <= kReportedShiftMm) return;
    ++count;
    if (shift_mm > largest_mm) {
      largest_mm = shift_mm;
      largest_line = line;
    }
  }
  std::string text(const char* one, const char* many) const { return std::to_string(count) + (count == 1 ? one : many); }
  std::string largest_text() const {
    return "; the largest move is " + six_digit_number_text(largest_mm) + " mm, on line " + std::to_string(largest_line);
  }
};

// The modal state of the controller while the program runs, and the program built so far.
class Interpreter {
 public:
  Interpreter(const ReaderOptions& options, detail::ProblemLog& problems) : options_(options), problems_(problems) {
    position_mm_ = options.initial_position;
    path_end_xy_ = geometry::xy(options.initial_position);
    highest_z_mm_ = options.initial_position.z_mm;
    program_.path.part_names = {"program"};
  }

  // Reads the text line by line until the program ends.
  void run(const std::string& text) {
    std::size_t begin = 0;
    int line = 0;
    while (begin <= text.size() && !problems_.full()) {
      std::size_t end = text.find('\n', begin);
      if (end == std::string::npos) end = text.size();
      const std::string_view raw(text.data() + begin, end - begin);
      ++line;
      if (!ended_) {
        read_line(raw, line);
        if (too_many_moves_) break;
      } else if (note_text_after_end(raw, line)) {
        break;
      }
      if (end == text.size()) break;
      begin = end + 1;
    }
    finish_compensation();
    if (!ended_ && options_.require_program_end && !problems_.full()) {
      problems_.add(std::max(last_content_line_, 1),
                    "end of text: the program ends without M2, M30 or a closing %, so the file may be truncated "
                    "(ReaderOptions::require_program_end = false accepts it)");
    }
    program_.dwell_at_end_s = pending_dwell_s_;
    // Only when a move left from a park: a park with nothing after it (a safe return at the end, as
    // feedplan's writer and CAM posts end a program) moves no later move, and cuts nothing.
    if (machine_position_moves_ > 0 && parks_left_ > 0) {
      note(std::to_string(machine_position_moves_) +
           (machine_position_moves_ == 1 ? " move" : " moves") + " to machine positions (G28, G30, G53) were read as "
           "retracts above the part: a rapid straight up to a park height (" +
           (options_.park_z_mm ? "Z " + six_digit_number_text(*options_.park_z_mm) + " mm, ReaderOptions::park_z_mm"
                               : "the highest Z reached before it plus 25 mm, at most Z " +
                                     six_digit_number_text(highest_park_z_mm_) + " mm; ReaderOptions::park_z_mm sets it") +
           "), X and Y kept — the reader has no machine coordinates; the next "
           "move leaves from there");
    }
    if (drilled_holes_ > 0) {
      note(std::to_string(drilled_holes_) + (drilled_holes_ == 1 ? " hole" : " holes") +
           " of drilling cycles (G73, G81–G89) became their moves as LinuxCNC makes them; their feeds are the "
           "program's and stay as written (WrittenMove::fixed_feed)");
    }
    if (plane_arcs_ > 0) {
      note(std::to_string(plane_arcs_) + (plane_arcs_ == 1 ? " arc" : " arcs") +
           " in the XZ or YZ plane (G18, G19) became " + std::to_string(plane_arc_pieces_) +
           " straight feed moves along the arc (chords within 1 µm of it, at most 5° each), kept on their lines");
    }
    if (moved_centres_.count > 0) {
      note(moved_centres_.text(" arc centre was", " arc centres were") +
           " moved so that start and end lie on one circle (their radii differed within "
           "ReaderOptions::arc_radius_tolerance_mm)" + moved_centres_.largest_text());
    }
    if (moved_ends_.count > 0) {
      note(moved_ends_.text(" arc end was", " arc ends were") +
           " moved onto the circle about the programmed centre, a smaller move than the centre's "
           "(their radii differed within ReaderOptions::arc_radius_tolerance_mm; LinuxCNC keeps both and drives a "
           "spiral); the next move starts there" + moved_ends_.largest_text());
    }
  }

  geometry::Program take_program() { return std::move(program_); }
  std::vector<WrittenMove> take_written() { return std::move(written_); }

  // Why a tool change is refused: the path is planned for one tool (the catalog's old reason).
  static constexpr const char* kOneToolReason = "tool change: the path is planned for one tool; split the program per tool";

 private:
  void end_program(int line, const char* how) {
    finish_compensation();
    ended_ = true;
    end_line_ = line;
    end_word_ = how;
  }

  void read_line(std::string_view raw, int line) {
    if (raw.size() > kMaxLineCharacters) {
      problems_.add(line, std::to_string(raw.size()) + " characters: more than " + std::to_string(kMaxLineCharacters) +
                              " on one line, which no G-code block needs (LinuxCNC reads 255)");
      last_content_line_ = line;
      return;
    }
    const detail::LexedLine lexed = detail::lex_line(raw, line, problems_);
    if (lexed.percent) {
      if (last_content_line_ == 0) {
        percent_opened_ = true;
      } else if (percent_opened_) {
        end_program(line, "%");
      } else {
        problems_.add(line, "'%': a closing % needs an opening % alone on the first line");
      }
    } else if (lexed.ok && !lexed.words.empty()) {
      execute(lexed.words, line);
    }
    if (lexed.percent || !lexed.words.empty() || !lexed.ok) last_content_line_ = line;
  }

  // Lines after the program end are not read, as on a controller. Returns true (and notes it) at
  // the first such line that holds more than blanks or a closing %.
  bool note_text_after_end(std::string_view raw, int line) {
    std::string content;
    for (char c : raw) {
      if (c != ' ' && c != '\t' && c != '\r') content += c;
    }
    if (content.empty() || content == "%") return false;
    note("line " + std::to_string(line) + " and later are not read: the program ended with " + end_word_ +
         " on line " + std::to_string(end_line_));
    return true;
  }

  void note(std::string text) { program_.notes.push_back(std::move(text)); }

  double unit_mm() const { return inch_ ? kMmPerInch : 1.0; }

  // Sorts the words of a block, reporting unknown, refused and repeated ones. False on any problem.
  bool sort_words(const std::vector<Word>& words, Block& block) {
    bool ok = true;
    std::array<const Word*, 16> g_words{};
    std::array<const Word*, 16> m_words{};
    for (std::size_t i = 0; i < words.size(); ++i) {
      const Word& w = words[i];
      const int line = block.line;
      if (w.letter == 'N') {
        if (i != 0) {
          problems_.add(line, "word " + w.text + ": a line number must be the first word of its block");
          ok = false;
        }
        continue;
      }
      if (w.letter == 'O') continue;  // the lexer made sure it stands alone
      if (w.letter == 'G' || w.letter == 'M') {
        std::optional<CodeInfo> info;
        std::optional<int> code;
        if (w.letter == 'G') {
          code = detail::g_code_tenths(w.value);
          if (code) info = detail::find_g_code(*code);
        } else {
          info = detail::find_m_code(w.value);
          if (info) code = static_cast<int>(w.value);
        }
        if (!info) {
          problems_.add(line, "word " + w.text + ": not supported (not " + (w.letter == 'G' ? "a G" : "an M") +
                                  " code the reader knows)");
          ok = false;
          continue;
        }
        if (info->use == CodeUse::kRefused) {
          problems_.add(line, "word " + w.text + ": not supported (" + info->reason + ")");
          ok = false;
          continue;
        }
        auto& seen = w.letter == 'G' ? g_words : m_words;
        auto& by_group = w.letter == 'G' ? block.g_by_group : block.m_by_group;
        if (seen[info->group] != nullptr) {
          problems_.add(line, "word " + w.text + ": same modal group (" + info->group_name + ") as " +
                                  seen[info->group]->text + " in this block; use one");
          ok = false;
          continue;
        }
        seen[info->group] = &w;
        by_group[info->group] = *code;
        continue;
      }
      if (!is_value_letter(w.letter)) {
        problems_.add(line, "word " + w.text + ": not supported (" + detail::letter_refusal(w.letter) + ")");
        ok = false;
        continue;
      }
      const Word*& slot = block.letters[static_cast<std::size_t>(w.letter - 'A')];
      if (slot != nullptr) {
        problems_.add(line, "word " + w.text + ": a second " + std::string(1, w.letter) + " word in the block (the first is " +
                                slot->text + ")");
        ok = false;
        continue;
      }
      slot = &w;
    }
    return ok;
  }

  // The motion the block executes: its own G0–G3, or the modal one when it has axis words and no
  // G80 (LinuxCNC's rule); kNoMotion otherwise.
  int executed_motion(const Block& block) const {
    if (const std::optional<int> own = block.g_by_group[1]) return *own;
    if (goes_home(block)) return kNoMotion;  // G28/G30 read the axis words
    const bool axis_words = block.has('X') || block.has('Y') || block.has('Z');
    if (axis_words && !block.has_g(kG80, 11) && (is_motion(motion_) || is_cycle(motion_))) return motion_;
    return kNoMotion;
  }

  static bool goes_home(const Block& block) { return block.has_g(kG28, 0) || block.has_g(kG30, 0); }

  // G28, G30 and G53 (machine positions): not under cutter compensation (LinuxCNC refuses it too); G53
  // with G0 or G1; G28/G30 without a motion of its own in the block (both would read the axis words).
  bool check_machine_position_words(const Block& block, int motion) {
    bool ok = true;
    auto fail = [&](const std::string& message) {
      problems_.add(block.line, message);
      ok = false;
    };
    const bool home = goes_home(block);
    const bool g53 = block.has_g(kG53, 0);
    if (!home && !g53) return true;
    const std::string name = detail::g_code_name(*block.g_by_group[0]);
    if (comp_on_) {
      fail("word " + name + ": a move to a machine position under cutter compensation (G" +
           std::to_string(comp_code_ / 10) + " on line " + std::to_string(comp_line_) +
           "); G40 first (LinuxCNC refuses it too)");
    }
    if (home && block.g_by_group[1]) {
      fail("word " + name + ": " + detail::g_code_name(*block.g_by_group[1]) +
           " in the same block: both would read the axis words; put them in separate blocks");
    }
    if (g53 && motion != kNoMotion && motion != kG0 && motion != kG1) {
      fail("word G53: " + detail::g_code_name(motion) + " in effect; G53 moves with G0 or G1 (LinuxCNC refuses it too)");
    }
    return ok;
  }

  // Checks that every word of a sorted block has a code that reads it and a value it accepts.
  bool check_block(const Block& block) {
    bool ok = true;
    const int line = block.line;
    auto fail = [&](const std::string& message) {
      problems_.add(line, message);
      ok = false;
    };
    const std::optional<int> own_motion = block.g_by_group[1];
    const bool cancel = block.has_g(kG80, 11);
    const int motion = executed_motion(block);
    const bool dwell = block.has_g(kG4, 0);
    const bool blend = block.has_g(kG64, 13);

    for (char axis : {'X', 'Y', 'Z'}) {
      const Word* w = block.word(axis);
      if (w == nullptr) continue;
      if (cancel && !own_motion) {
        fail("word " + w->text + ": axis words cannot be used with G80, which cancels the motion mode");
      } else if (!own_motion && dwell) {
        fail("word " + w->text + ": axis words in a G4 block need G0, G1, G2 or G3 in the same block");
      } else if (motion == kNoMotion && !goes_home(block)) {
        fail("word " + w->text + ": axis words need a motion mode, and no G0, G1, G2 or G3 is in effect");
      }
      break;
    }
    const std::string motion_name = motion == kNoMotion ? std::string("no motion") : detail::g_code_name(motion);
    for (char letter : {'I', 'J', 'K', 'R'}) {
      const Word* w = block.word(letter);
      if (letter == 'R' && is_cycle(motion)) continue;  // the cycle's R plane
      if (w != nullptr && !is_arc(motion)) {
        fail("word " + w->text + ": " + std::string(1, letter) + " is read only with G2 or G3 (" + motion_name +
             " in this block)");
      }
    }
    const int plane = block.g_by_group[2].value_or(plane_);
    const std::string centre_letters = plane == kG17 ? "IJ" : plane == kG18 ? "IK" : "JK";
    const std::string centre_names = plane == kG17 ? "I, J" : plane == kG18 ? "I, K" : "J, K";
    const bool centre_words = block.has(centre_letters[0]) || block.has(centre_letters[1]);
    if (is_arc(motion) && block.has('R') && (block.has('I') || block.has('J') || (plane != kG17 && block.has('K')))) {
      fail("word " + block.word('R')->text + ": R and " + (plane == kG17 ? "I/J" : plane == kG18 ? "I/K" : "J/K") +
           " in one arc; use one format");
    }
    if (is_arc(motion) && !block.has('R') && !centre_words) {
      fail(detail::g_code_name(motion) + " without " + centre_names + " or R: an arc needs its centre (" + centre_names +
           ") or its radius (R)");
    }
    if (is_arc(motion) && plane != kG17) {
      const char off_plane = plane == kG18 ? 'J' : 'I';
      if (const Word* w = block.word(off_plane)) {
        fail("word " + w->text + ": " + std::string(1, off_plane) + " is not read in the " +
             (plane == kG18 ? "XZ plane (G18), whose arc centre is I (X) and K (Z)" : "YZ plane (G19), whose arc centre is J (Y) and K (Z)") +
             " (LinuxCNC refuses it too)");
      }
    }
    if (const std::optional<int> new_plane = block.g_by_group[2]; new_plane && *new_plane != kG17 && comp_on_) {
      fail("word " + detail::g_code_name(*new_plane) + ": cutter compensation (G" + std::to_string(comp_code_ / 10) +
           " on line " + std::to_string(comp_line_) + ") is read in the XY plane (G17) only; G40 first");
    }
    if (const Word* p = block.word('P')) {
      if (dwell && (is_arc(motion) || blend)) {
        fail("word G4: not allowed with G2, G3 or G64 in the same block (they all read P)");
      } else if (dwell) {
        if (p->value < 0.0) fail("word " + p->text + ": a G4 dwell must be ≥ 0 s");
      } else if (is_arc(motion)) {
        if (p->value < 1.0 || p->value != std::floor(p->value)) {
          fail("word " + p->text + ": the number of turns of G2/G3 must be a whole number ≥ 1");
        } else if (p->value > options_.max_arc_turns) {
          fail("word " + p->text + ": more than " + std::to_string(options_.max_arc_turns) +
               " turns in one arc (ReaderOptions::max_arc_turns)");
        }
      } else if (is_cycle(motion)) {
        if (p->value < 0.0) fail("word " + p->text + ": a cycle's dwell must be ≥ 0 s");
      } else if (!blend) {
        fail("word " + p->text + ": not supported here (P is read with G4, G2, G3, G64 and drilling cycles)");
      }
    } else if (dwell) {
      fail("G4 without P: a dwell needs P, its time in seconds");
    }
    if (const Word* q = block.word('Q'); q != nullptr && !blend) {
      if (!cycle_pecks(motion)) {
        fail("word " + q->text + ": not supported here (Q is read only with G64, G73 and G83)");
      } else if (!(q->value > 0.0)) {
        fail("word " + q->text + ": the peck depth Q must be > 0 (LinuxCNC refuses it too)");
      }
    }
    if (const Word* l = block.word('L')) {
      if (!is_cycle(motion)) {
        fail("word " + l->text + ": L is read only with drilling cycles (their repeats)");
      } else if (l->value < 1.0 || l->value != std::floor(l->value) || l->value > 10000.0) {
        fail("word " + l->text + ": a cycle's repeats L must be a whole number from 1 to 10000");
      }
    }
    if (is_cycle(motion) && !check_cycle_words(block, motion)) ok = false;
    if (!check_machine_position_words(block, motion)) ok = false;
    if (const Word* f = block.word('F'); f != nullptr && f->value < 0.0) {
      fail("word " + f->text + ": a feed must be ≥ 0");
    }
    if (const Word* s = block.word('S'); s != nullptr && s->value < 0.0) {
      fail("word " + s->text + ": a spindle speed must be ≥ 0 rpm");
    }
    if (const Word* t = block.word('T'); t != nullptr && (t->value < 0.0 || t->value != std::floor(t->value))) {
      fail("word " + t->text + ": a tool number must be a whole number ≥ 0");
    }
    if (const std::optional<int> offset = block.g_by_group[12]; offset && *offset != work_offset_ && moved_) {
      fail("word " + detail::g_code_name(*offset) + ": not supported after the first move (changing the work "
           "offset moves the program origin, and the reader has no offset values)");
    }
    if (const std::optional<int> units = block.g_by_group[6]; units && block.has('F') && (*units == kG20) != inch_) {
      fail("word " + block.word('F')->text + ": F in a block whose " + detail::g_code_name(*units) +
           " changes the units (LinuxCNC reads this F in the previous unit); put F in a later block");
    }
    if (!check_tool_words(block)) ok = false;
    if (!check_compensation_words(block)) ok = false;
    return ok;
  }

  // The tool whose diameter a G41/G42 block compensates for: its D word (a tool number, as in LinuxCNC),
  // else the tool in the spindle. nullopt when neither names one.
  std::optional<int> compensation_tool(const Block& block) const {
    if (const Word* d = block.word('D')) return static_cast<int>(d->value);
    if (block.has_m(6, 6) && block.has('T')) return tool_of(block.word('T'));
    if (tool_in_spindle_) return tool_in_spindle_;
    return g43_tool_;
  }

  // D only with G41/G42, a whole tool number whose diameter the options give; no second G41/G42, no tool
  // change while compensation is on (LinuxCNC refuses both too).
  bool check_compensation_words(const Block& block) {
    bool ok = true;
    auto fail = [&](const std::string& message) {
      problems_.add(block.line, message);
      ok = false;
    };
    const std::optional<int> comp = block.g_by_group[7];
    const bool turns_on = comp && (*comp == kG41 || *comp == kG42);
    const Word* d = block.word('D');
    if (d != nullptr && !turns_on) {
      fail("word " + d->text + ": D is read only with G41 or G42 (the tool whose diameter compensation uses)");
      return false;
    }
    if (comp_on_ && block.has_m(6, 6) && (!comp || *comp != kG40)) {
      fail("word M6: a tool change while cutter compensation is on (G" + std::to_string(comp_code_ / 10) + " on line " +
           std::to_string(comp_line_) + "); G40 first (LinuxCNC refuses it too)");
    }
    if (!turns_on) return ok;
    const std::string code = detail::g_code_name(*comp);
    if (block.g_by_group[2].value_or(plane_) != kG17) {
      fail("word " + code + ": cutter compensation is read in the XY plane (G17) only");
      return false;
    }
    if (comp_on_) {
      fail("word " + code + ": cutter compensation is already on (G" + std::to_string(comp_code_ / 10) + " on line " +
           std::to_string(comp_line_) + "); turn it off with G40 first (LinuxCNC refuses it too)");
      return false;
    }
    if (d != nullptr && (d->value < 0.0 || d->value != std::floor(d->value) || d->value > 1e6)) {
      fail("word " + d->text + ": D must be a whole tool number ≥ 0 (LinuxCNC: the tool whose diameter is used)");
      return false;
    }
    const std::optional<int> tool = compensation_tool(block);
    if (!tool) {
      fail("word " + code + ": no D word and no tool in the spindle (T M6 or G43 H before it): the reader cannot tell "
           "which tool's radius to compensate for; write " + code + " D<tool>");
      return false;
    }
    const std::optional<double> diameter = tool_diameter_mm(*tool);
    if (!diameter) {
      const std::string subject = d != nullptr ? "word " + d->text : "word " + code;
      fail(subject + ": cutter compensation needs the diameter of tool " + std::to_string(*tool) +
           ", which is not given: give the diameter of tool " + std::to_string(*tool) +
           " (ReaderOptions::tool_diameters_mm; feedplan optimize --tools)");
      return false;
    }
    if (!std::isfinite(*diameter)) {
      fail("word " + code + ": the diameter given for tool " + std::to_string(*tool) + " is not a finite number");
      return false;
    }
    return ok;
  }

  // A drilling cycle's block: in G17, without cutter compensation; R and Z when the cycle starts (a change
  // of cycle code, or after G80 or G0–G3), P for those that dwell, Q for those that peck (LinuxCNC's rules);
  // G86 with the spindle turning.
  bool check_cycle_words(const Block& block, int motion) {
    bool ok = true;
    auto fail = [&](const std::string& message) {
      problems_.add(block.line, message);
      ok = false;
    };
    const std::string name = detail::g_code_name(motion);
    if (block.g_by_group[2].value_or(plane_) != kG17) {
      fail("word " + name + ": drilling cycles are read in the XY plane (G17) only");
    }
    if (comp_on_) {
      fail("word " + name + ": a drilling cycle under cutter compensation (G" + std::to_string(comp_code_ / 10) +
           " on line " + std::to_string(comp_line_) + "); G40 first (LinuxCNC refuses it too)");
    }
    const bool starts = motion_ != motion;
    if (starts && !block.has('R')) fail("word " + name + ": the cycle starts here and needs R, its R plane");
    if (starts && !block.has('Z')) fail("word " + name + ": the cycle starts here and needs Z, its bottom");
    if (starts && cycle_dwells(motion) && !block.has('P')) {
      fail("word " + name + ": the cycle starts here and needs P, its dwell at the bottom in seconds");
    }
    if (starts && cycle_pecks(motion) && !block.has('Q')) {
      fail("word " + name + ": the cycle starts here and needs Q, its peck depth");
    }
    if (motion == 860 && spindle_ == SpindleDirection::kOff && !block.has_m(3, 7) && !block.has_m(4, 7)) {
      fail("word " + name + ": G86 needs the spindle turning (M3 or M4; LinuxCNC refuses it too)");
    }
    return ok;
  }

  // The tool a T word selects, when it is a whole number ≥ 0 (check_block reports it otherwise).
  static std::optional<int> tool_of(const Word* t) {
    if (t == nullptr || t->value < 0.0 || t->value != std::floor(t->value) || t->value > 1e6) return std::nullopt;
    return static_cast<int>(t->value);
  }

  // M6 once, before the first move, of a selected tool; G43 with the H of the tool in the spindle.
  // LinuxCNC's order within a block: T, then M6, then G43.
  bool check_tool_words(const Block& block) {
    bool ok = true;
    const int line = block.line;
    auto fail = [&](const std::string& message) {
      problems_.add(line, message);
      ok = false;
    };
    std::optional<int> tool = tool_in_spindle_;
    if (block.has_m(6, 6)) {
      const std::optional<int> selected = block.has('T') ? tool_of(block.word('T')) : selected_tool_;
      if (moved_ && !options_.tool_changes) {
        fail(std::string("word M6: not supported after the first move (") + kOneToolReason + ")");
      } else if (tool_in_spindle_ && !options_.tool_changes) {
        fail("word M6: a second tool change (T" + std::to_string(*tool_in_spindle_) + " M6 on line " +
             std::to_string(tool_line_) + ") is not supported (" + kOneToolReason + ")");
      } else if (!selected) {
        if (!block.has('T')) fail("word M6: no tool selected: a T word must come before M6 or with it");
      } else if (g43_tool_ && *g43_tool_ != *selected && !options_.tool_changes) {
        fail("word M6: G43 H" + std::to_string(*g43_tool_) + " (line " + std::to_string(g43_line_) +
             ") stays in effect after the change, the length offset of another tool; switch it on after M6");
      } else {
        tool = selected;
      }
    }
    const Word* h = block.word('H');
    if (h != nullptr && !block.has_g(kG43, 8)) {
      fail("word " + h->text + ": H is read only with G43 (the tool length offset number)");
    } else if (block.has_g(kG43, 8)) {
      if (h != nullptr && (h->value < 0.0 || h->value != std::floor(h->value) || h->value > 1e6)) {
        fail("word " + h->text + ": a tool length offset number must be a whole number ≥ 0");
      } else if (h == nullptr && !tool) {
        fail("word G43: without H and with no tool change (T M6) before it, the reader cannot tell which "
             "tool's length offset is meant; write G43 H<tool>");
      } else if (h != nullptr && tool && static_cast<int>(h->value) != *tool) {
        fail("word " + h->text + ": G43 " + h->text + " is the length offset of tool " +
             std::to_string(static_cast<int>(h->value)) + ", but tool " + std::to_string(*tool) +
             " is in the spindle: H must be the tool in the spindle, or Z is no longer the tool tip");
      }
    }
    return ok;
  }

  // Executes a block in LinuxCNC's order: G94, F, S, T, M6, M3/M4/M5, G4, units, tool length
  // offset, work offset, distance modes, motion, program end.
  void execute(const std::vector<Word>& words, int line) {
    Block block;
    block.line = line;
    if (!sort_words(words, block) || !check_block(block)) return;

    const int motion = executed_motion(block);
    if (block.has_g(kG94, 5)) {
      feed_mm_per_min_ = 0.0;
      feed_line_ = line;
      feed_reset_by_g94_ = true;
      feed_problem_reported_ = false;
    }
    if (const Word* f = block.word('F')) {
      feed_mm_per_min_ = f->value * unit_mm();
      feed_line_ = line;
      feed_reset_by_g94_ = false;
      feed_problem_reported_ = false;
    }
    if (const Word* s = block.word('S')) {
      spindle_rpm_ = s->value;
      s_zero_line_ = s->value == 0.0 ? line : 0;
      s_zero_reported_ = false;
    }
    if (block.has('T')) selected_tool_ = tool_of(block.word('T'));
    if (block.has_m(6, 6)) {
      tool_in_spindle_ = selected_tool_;
      tool_line_ = line;
      if (options_.tool_changes) {
        g43_tool_.reset();  // the old tool's length offset: G43 H<new tool> switches the new one on
        note("line " + std::to_string(line) + ": T" + std::to_string(*tool_in_spindle_) + " M6: tool " +
             std::to_string(*tool_in_spindle_) + " from here");
      } else {
        note("line " + std::to_string(line) + ": T" + std::to_string(*tool_in_spindle_) + " M6: the program is for tool " +
             std::to_string(*tool_in_spindle_));
      }
    }
    if (block.has_m(3, 7)) spindle_ = SpindleDirection::kClockwise;
    if (block.has_m(4, 7)) spindle_ = SpindleDirection::kCounterClockwise;
    if (block.has_m(5, 7)) spindle_ = SpindleDirection::kOff;
    if (block.has_g(kG4, 0)) pending_dwell_s_ += block.word('P')->value;
    if (const std::optional<int> plane = block.g_by_group[2]) plane_ = *plane;
    if (const std::optional<int> units = block.g_by_group[6]) {
      inch_ = *units == kG20;
      units_set_ = true;
    }
    if (const std::optional<int> comp = block.g_by_group[7]) set_compensation(block, *comp);
    if (const std::optional<int> offset = block.g_by_group[12]) work_offset_ = *offset;
    if (block.has_g(kG43, 8)) {
      g43_tool_ = block.has('H') ? static_cast<int>(block.word('H')->value) : *tool_in_spindle_;
      g43_line_ = line;
      if (!tool_in_spindle_) {
        note("line " + std::to_string(line) + ": G43 H" + std::to_string(*g43_tool_) +
             " with no tool change (T M6) before it: the program is taken to be for tool " + std::to_string(*g43_tool_));
      }
    }
    if (block.has_g(kG49, 8)) g43_tool_.reset();
    if (block.has_g(kG90, 3)) absolute_ = true;
    if (block.has_g(kG91, 3)) absolute_ = false;
    if (block.has_g(kG90_1, 4)) absolute_arc_center_ = true;
    if (block.has_g(kG91_1, 4)) absolute_arc_center_ = false;
    if (block.has_g(980, 10)) retract_to_r_ = false;
    if (block.has_g(990, 10)) retract_to_r_ = true;
    if (block.has_g(kG80, 11)) motion_ = kNoMotion;
    if (const std::optional<int> own = block.g_by_group[1]) motion_ = *own;
    if (!is_cycle(motion_)) cycle_initial_z_mm_.reset();  // the next cycle begins a new initial level
    if (goes_home(block)) go_home(block);
    if (motion != kNoMotion) move(block, motion);
    if (block.has_m(2, 4) || block.has_m(30, 4)) end_program(line, block.has_m(2, 4) ? "M2" : "M30");
  }

  // Checks that a feed move has a positive F; reports once until the next F word.
  bool feed_ok(int line, int motion) {
    if (feed_mm_per_min_ > 0.0) return true;
    // After a rejected block the missing F is most likely that block's own F word: reporting it again
    // would only send the user after a consequence.
    if (feed_line_ == 0 && !problems_.empty()) feed_problem_reported_ = true;
    if (!feed_problem_reported_) {
      const std::string name = detail::g_code_name(motion);
      if (feed_line_ == 0) {
        problems_.add(line, name + " before any F word: feed moves need a positive F");
      } else if (feed_reset_by_g94_) {
        problems_.add(line, name + " with no F since G94 on line " + std::to_string(feed_line_) +
                                " (G94 resets the feed to 0, as in LinuxCNC): feed moves need a positive F");
      } else {
        problems_.add(line, name + " with F0 in effect (set on line " + std::to_string(feed_line_) +
                                "): feed moves need a positive F");
      }
      feed_problem_reported_ = true;
    }
    return false;
  }

  // Checks that a feed move under M3/M4 does not run at an explicit S0: the spindle would not turn
  // (LinuxCNC) while a reader of BlockCommand takes 0 as "no S given" and a speed of its own (the
  // virtual machine: the spec's). Reports once per S0 word.
  bool spindle_ok(int line, int motion) {
    if (s_zero_line_ == 0 || spindle_ == SpindleDirection::kOff) return true;
    if (!s_zero_reported_) {
      problems_.add(line, detail::g_code_name(motion) + " with the spindle on at S0 (set on line " +
                              std::to_string(s_zero_line_) + "): a feed move needs the spindle turning; give S > 0");
      s_zero_reported_ = true;
    }
    return false;
  }

  // False (after a problem that stops the reading) when the program has max_moves moves already.
  bool room_for_move(int line, double count = 1.0) {
    if (static_cast<double>(program_.path.moves.size()) + count <= static_cast<double>(std::max(options_.max_moves, 0))) {
      return true;
    }
    problems_.add(line, "more than " + std::to_string(options_.max_moves) +
                            " moves (ReaderOptions::max_moves): the planner and the virtual machine would need "
                            "gigabytes for them; split the program");
    too_many_moves_ = true;
    return false;
  }

  // The program's coordinate grid: the finest last digit of the block's X Y Z I J R words.
  void note_resolution(const Block& block) {
    for (const char letter : {'X', 'Y', 'Z', 'I', 'J', 'K', 'R'}) {
      if (letter == 'K' && plane_ == kG17) continue;  // ignored in XY arcs
      const Word* w = block.word(letter);
      const std::size_t point = w != nullptr ? w->text.find('.') : std::string::npos;
      if (point == std::string::npos || point + 1 == w->text.size()) continue;  // a whole number: exact
      const double step_mm = std::pow(10.0, -static_cast<double>(w->text.size() - point - 1)) * unit_mm();
      double& resolution = program_.coordinate_resolution_mm;
      resolution = resolution > 0.0 ? std::min(resolution, step_mm) : step_mm;
    }
  }

  // The last digit of an inch program with 4 decimals, mm.
  static constexpr double kInchProgramDigitMm = 0.0001 * 25.4;

  // The largest last digit of the block's X Y I J words written with decimals, mm (0 when none has any).
  double coarsest_digit_mm(const Block& block, const char* letters = "XYIJ") const {
    double coarsest = 0.0;
    for (const char* letter_at = letters; *letter_at != '\0'; ++letter_at) {
      const char letter = *letter_at;
      const Word* w = block.word(letter);
      const std::size_t point = w != nullptr ? w->text.find('.') : std::string::npos;
      if (point == std::string::npos || point + 1 == w->text.size()) continue;
      coarsest = std::max(coarsest, std::pow(10.0, -static_cast<double>(w->text.size() - point - 1)) * unit_mm());
    }
    return coarsest;
  }

  // Makes `m` (start and programmed end set) the arc of a G2/G3 block: its circle from R or from I J
  // (arc_geometry.hpp), its end moved onto the circle when that moves less than the centre would.
  // False, with the problem logged, when the words give no arc.
  bool make_arc(const Block& block, int motion, Move& m) {
    const bool ccw = motion == kG3;
    const int turns = block.has('P') ? static_cast<int>(block.word('P')->value) : 1;
    const Point2 start_xy = geometry::xy(m.start);
    const Point2 end_xy = geometry::xy(m.end);
    detail::ArcCircle arc;
    std::string subject = detail::g_code_name(motion);
    if (const Word* r = block.word('R')) {
      subject += " " + r->text;
      arc = detail::arc_from_radius(start_xy, end_xy, r->value * unit_mm(), ccw, turns, options_.arc_radius_tolerance_mm);
    } else {
      const Word* i = block.word('I');
      const Word* j = block.word('J');
      for (const Word* w : {i, j}) {
        if (w != nullptr) subject += " " + w->text;
      }
      const double i_mm = i != nullptr ? i->value * unit_mm() : 0.0;
      const double j_mm = j != nullptr ? j->value * unit_mm() : 0.0;
      // LinuxCNC: I J are offsets from the programmed start, not from where a moved arc end left the path.
      const Point2 programmed_start = geometry::xy(position_mm_);
      const Point2 center = absolute_arc_center_ ? Point2{i_mm, j_mm}
                                                 : Point2{programmed_start.x_mm + i_mm, programmed_start.y_mm + j_mm};
      // Each of start, end and centre is within half a last digit per axis of where its writer meant it,
      // so the radii of an arc written exactly can differ by about two last digits of the block's words —
      // up to those of an inch program with 4 decimals (coarser words are taken as meant).
      const double digit_mm = std::min(coarsest_digit_mm(block), kInchProgramDigitMm);
      const double tolerance_mm = std::max(options_.arc_radius_tolerance_mm, 2.0 * digit_mm);
      arc = detail::arc_from_center(programmed_start, start_xy, end_xy, center, ccw, turns, tolerance_mm);
    }
    if (!arc.problem.empty()) {
      problems_.add(block.line, subject + ": " + arc.problem);
      return false;
    }
    moved_centres_.add(arc.center_shift_mm, block.line);
    moved_ends_.add(arc.end_shift_mm, block.line);
    m.end.x_mm = arc.end.x_mm;
    m.end.y_mm = arc.end.y_mm;
    m.kind = MoveKind::kArc;
    m.center = arc.center;
    m.ccw = ccw;
    m.sweep_rad = arc.sweep_rad;
    return true;
  }

  void move(const Block& block, int motion) {
    const int line = block.line;
    note_resolution(block);
    Point3 end = programmed_end(block);
    if (is_arc(motion) && plane_ != kG17) {
      plane_arc_move(block, motion, end);
      return;
    }
    if (block.has('K') && !k_note_given_) {
      note("line " + std::to_string(line) + ": K words of arcs in the XY plane are ignored, as grbl does (they offset "
           "the centre along Z, which an XY arc does not have); LinuxCNC refuses them");
      k_note_given_ = true;
    }
    if (!units_set_ && !unit_note_given_) {
      note("line " + std::to_string(line) + ": no G20 or G21 before the first move; lengths are read as mm");
      unit_note_given_ = true;
    }

    Move m;
    m.start = {path_end_xy_.x_mm, path_end_xy_.y_mm, position_mm_.z_mm};
    m.end = end;
    m.part = 0;
    const bool feed = motion != kG0;
    if (block.has_g(kG53, 0)) {  // a move in machine coordinates: read as a park, which does not cut
      park(block.line);
      return;
    }
    if (feed && (!feed_ok(line, motion) || !spindle_ok(line, motion))) {
      go_to(end);
      return;
    }
    if (parked_line_ != 0) {
      const int parked = parked_line_;
      parked_line_ = 0;
      if (feed) {
        problems_.add(line, detail::g_code_name(motion) + " right after a move to a machine position (line " +
                                std::to_string(parked) + "): the reader does not know where the machine put the tool "
                                "and reads such moves as a retract above the part; move there with G0 first");
        go_to(end);
        return;
      }
    }
    if (is_arc(motion) && after_compensation_line_ != 0) {
      problems_.add(line, detail::g_code_name(motion) + ": the move just after G40 (line " +
                              std::to_string(after_compensation_line_) +
                              ") must be straight, not an arc (LinuxCNC refuses it too)");
      go_to(end);
      return;
    }
    if (is_cycle(motion)) {
      drill(block, motion);
      return;
    }
    if (compensation_) {
      compensated_move(block, motion, end);
      return;
    }
    if (!is_arc(motion)) {
      if (end.x_mm == position_mm_.x_mm && end.y_mm == position_mm_.y_mm && end.z_mm == position_mm_.z_mm) return;
      if (end.x_mm == m.start.x_mm && end.y_mm == m.start.y_mm && end.z_mm == m.start.z_mm) {
        go_to(end);  // back onto the programmed position, where a moved arc end had left the path
        return;
      }
      m.kind = feed ? MoveKind::kLine : MoveKind::kRapid;
    } else if (!make_arc(block, motion, m)) {
      go_to(end);
      return;
    }
    if (!room_for_move(line)) return;
    WrittenMove written = written_move(block, motion);
    written.keep_whole = after_compensation_line_ != 0;  // the exit move starts off the programmed path
    after_compensation_line_ = 0;
    add_move(m, block_command(line, motion), written);
    position_mm_ = end;
    path_end_xy_ = geometry::xy(m.end);
  }

  // The command of a move of `motion` read on `line` (takes the pending dwell).
  geometry::BlockCommand block_command(int line, int motion) {
    geometry::BlockCommand command;
    command.feed_mm_per_min = motion != kG0 ? feed_mm_per_min_ : 0.0;
    command.spindle_rpm = spindle_rpm_;
    command.spindle = spindle_;
    command.dwell_before_s = pending_dwell_s_;
    command.source_line = line;
    pending_dwell_s_ = 0.0;
    return command;
  }

  WrittenMove written_move(const Block& block, int motion) const {
    return {block.line, motion == kG0 ? 0 : motion == kG1 ? 1 : motion == kG2 ? 2 : 3,
            block.g_by_group[1].has_value(), inch_, !absolute_, absolute_arc_center_, block.has('R'),
            block.has('P'), tool_in_spindle_ ? *tool_in_spindle_ : g43_tool_ ? *g43_tool_ : -1};
  }

  void add_move(Move m, const geometry::BlockCommand& command, const WrittenMove& written, bool park = false) {
    if (!park) {  // a move after parks leaves from them
      parks_left_ += parks_not_left_;
      parks_not_left_ = 0;
    }
    // The park height is above the part, not above itself: moves that stay at it (a rapid across after a
    // park) do not raise it.
    if (!park && !(machine_position_moves_ > 0 && m.end.z_mm == last_park_z_mm_)) {
      highest_z_mm_ = std::max(highest_z_mm_, m.end.z_mm);
    }
    m.part = 0;
    m.cutting = m.kind != MoveKind::kRapid;
    written_.push_back(written);
    program_.path.moves.push_back(m);
    program_.blocks.push_back(command);
    moved_ = true;
  }

  // The diameter of `tool` for cutter compensation: ReaderOptions::tool_diameters_mm, else
  // ReaderOptions::any_tool_diameter_mm when given.
  std::optional<double> tool_diameter_mm(int tool) const {
    if (const auto it = options_.tool_diameters_mm.find(tool); it != options_.tool_diameters_mm.end()) return it->second;
    return options_.any_tool_diameter_mm;
  }

  // G40, G41, G42 (LinuxCNC: after units, before the tool length offset). check_compensation_words made
  // sure a G41/G42 has its tool's diameter.
  void set_compensation(const Block& block, int code) {
    if (code == kG40) {
      if (compensation_) after_compensation_line_ = block.line;
      finish_compensation();
      comp_on_ = false;
      return;
    }
    const double diameter_mm = *tool_diameter_mm(*compensation_tool(block));
    detail::CompSide side = code == kG41 ? detail::CompSide::kLeft : detail::CompSide::kRight;
    if (diameter_mm < 0.0) {  // LinuxCNC: a negative diameter compensates on the other side
      side = side == detail::CompSide::kLeft ? detail::CompSide::kRight : detail::CompSide::kLeft;
    }
    comp_on_ = true;
    comp_code_ = code;
    comp_line_ = block.line;
    if (diameter_mm != 0.0) {  // a zero radius compensates nothing (LinuxCNC)
      compensation_.emplace(side, std::abs(diameter_mm) / 2.0, Point3{path_end_xy_.x_mm, path_end_xy_.y_mm, position_mm_.z_mm},
                            position_mm_);
    }
  }

  // A move under G41/G42: the tool-centre moves compensation makes of it (cutter_compensation.hpp), each
  // kept whole on the line of the block the controller makes it for.
  void compensated_move(const Block& block, int motion, const Point3& end) {
    const int line = block.line;
    const int tag = static_cast<int>(compensation_blocks_.size());
    std::vector<detail::CompMove> done;
    std::string problem;
    if (is_arc(motion)) {
      Move programmed;
      programmed.start = position_mm_;
      programmed.end = end;
      if (!make_arc(block, motion, programmed)) {
        go_to(end);
        return;
      }
      const int turns = block.has('P') ? static_cast<int>(block.word('P')->value) : 1;
      problem = compensation_->arc({programmed.center, programmed.end, motion == kG3, turns}, tag, done);
    } else {
      problem = compensation_->straight(motion == kG0, end, tag, done);
    }
    if (!problem.empty()) {
      problems_.add(line, detail::g_code_name(motion) + " under cutter compensation (G" + std::to_string(comp_code_ / 10) +
                              " on line " + std::to_string(comp_line_) + "): " + problem);
      compensation_.reset();  // the rest is read uncompensated: one problem, not a cascade
      go_to(end);
      return;
    }
    WrittenMove written = written_move(block, motion);
    written.keep_whole = true;
    compensation_blocks_.push_back({block_command(line, motion), written});
    add_compensated(done);
    position_mm_ = compensation_->programmed_position();
    path_end_xy_ = geometry::xy(compensation_->tool_position());
  }

  // Moves whose compensated end is final, each with the command of the block that made it.
  void add_compensated(const std::vector<detail::CompMove>& done) {
    for (const detail::CompMove& c : done) {
      const Move& m = c.move;
      if (m.kind != MoveKind::kArc && m.start.x_mm == m.end.x_mm && m.start.y_mm == m.end.y_mm &&
          m.start.z_mm == m.end.z_mm) {
        continue;
      }
      if (!room_for_move(compensation_blocks_[static_cast<std::size_t>(c.tag)].command.source_line)) return;
      const CompensatedBlock& block = compensation_blocks_[static_cast<std::size_t>(c.tag)];
      geometry::BlockCommand command = block.command;
      if (m.kind == MoveKind::kRapid) command.feed_mm_per_min = 0.0;
      add_move(m, command, block.written);
      compensation_blocks_[static_cast<std::size_t>(c.tag)].command.dwell_before_s = 0.0;
    }
  }

  // G40 or the program end: the moves compensation holds back keep their ends; the tool is where the last
  // one ends, the programmed position where it was programmed.
  void finish_compensation() {
    if (!compensation_) return;
    std::vector<detail::CompMove> done;
    compensation_->finish(done);
    add_compensated(done);
    path_end_xy_ = geometry::xy(compensation_->tool_position());
    position_mm_ = compensation_->programmed_position();
    compensation_.reset();
    compensation_blocks_.clear();
  }

  // A G2/G3 in the XZ (G18) or YZ (G19) plane: its circle from R or from the plane's centre words, as
  // LinuxCNC reads them (plane_arc.hpp), as straight feed moves along it, all on the block's line and kept
  // whole.
  void plane_arc_move(const Block& block, int motion, const Point3& end) {
    const detail::ArcPlane plane = plane_ == kG18 ? detail::ArcPlane::kXZ : detail::ArcPlane::kYZ;
    const bool ccw = motion == kG3;
    const int turns = block.has('P') ? static_cast<int>(block.word('P')->value) : 1;
    const Point3 start{path_end_xy_.x_mm, path_end_xy_.y_mm, position_mm_.z_mm};
    const Point2 start_2 = detail::in_plane(plane, start);
    const Point2 end_2 = detail::in_plane(plane, end);
    detail::ArcCircle arc;
    std::string subject = detail::g_code_name(motion);
    if (const Word* r = block.word('R')) {
      subject += " " + r->text;
      arc = detail::arc_from_radius(start_2, end_2, r->value * unit_mm(), ccw, turns, options_.arc_radius_tolerance_mm);
    } else {
      // The plane's centre words: G18 K (Z) then I (X); G19 J (Y) then K (Z), as LinuxCNC pairs them.
      const char first = plane == detail::ArcPlane::kXZ ? 'K' : 'J';
      const char second = plane == detail::ArcPlane::kXZ ? 'I' : 'K';
      double offset[2] = {0.0, 0.0};
      int k = 0;
      for (const char letter : {first, second}) {
        if (const Word* w = block.word(letter)) {
          subject += " " + w->text;
          offset[k] = w->value * unit_mm();
        }
        ++k;
      }
      const Point2 programmed_start = detail::in_plane(plane, position_mm_);
      const Point2 center = absolute_arc_center_ ? Point2{offset[0], offset[1]}
                                                 : Point2{programmed_start.x_mm + offset[0], programmed_start.y_mm + offset[1]};
      const double digit_mm = std::min(coarsest_digit_mm(block, plane == detail::ArcPlane::kXZ ? "XZIK" : "YZJK"),
                                       kInchProgramDigitMm);
      const double tolerance_mm = std::max(options_.arc_radius_tolerance_mm, 2.0 * digit_mm);
      arc = detail::arc_from_center(programmed_start, start_2, end_2, center, ccw, turns, tolerance_mm);
    }
    if (!arc.problem.empty()) {
      problems_.add(block.line, subject + ": " + arc.problem);
      go_to(end);
      return;
    }
    if (!room_for_move(block.line, detail::plane_arc_piece_count(plane, start, end, arc.center, arc.sweep_rad))) return;
    const std::vector<Point3> points = detail::plane_arc_points(plane, start, end, arc.center, ccw, arc.sweep_rad);
    WrittenMove written = written_move(block, motion);
    written.keep_whole = true;
    Point3 from = start;
    for (const Point3& to : points) {
      if (!room_for_move(block.line)) return;
      Move m;
      m.kind = MoveKind::kLine;
      m.start = from;
      m.end = to;
      add_move(m, block_command(block.line, motion), written);
      from = to;
    }
    ++plane_arcs_;
    plane_arc_pieces_ += static_cast<int>(points.size());
    go_to(end);
  }

  // A block of a drilling cycle: its holes as LinuxCNC drills them (drill_cycle.hpp), every move on the
  // block's line, kept whole, its feed the program's and fixed.
  void drill(const Block& block, int motion) {
    const double u = unit_mm();
    auto raw = [&](char letter, double& sticky) {
      if (const Word* w = block.word(letter)) sticky = w->value;
      return sticky;
    };
    const double r_raw = raw('R', cycle_r_);
    const double z_raw = raw('Z', cycle_z_);
    const double p_raw = raw('P', cycle_p_);
    const double q_raw = raw('Q', cycle_q_);
    detail::DrillRequest request;
    request.code = motion;
    request.position = position_mm_;
    request.unit_mm = u;
    if (!cycle_initial_z_mm_) cycle_initial_z_mm_ = position_mm_.z_mm;
    request.initial_level = *cycle_initial_z_mm_ / u;
    request.retract_to_r = retract_to_r_;
    request.peck = q_raw;
    request.dwell_s = cycle_dwells(motion) ? p_raw : 0.0;
    request.repeats = block.has('L') ? static_cast<int>(block.word('L')->value) : 1;
    const double x_word = block.has('X') ? block.word('X')->value * u : 0.0;
    const double y_word = block.has('Y') ? block.word('Y')->value * u : 0.0;
    if (absolute_) {
      request.r = r_raw;
      request.bottom = z_raw;
      request.first_hole = {block.has('X') ? x_word : position_mm_.x_mm, block.has('Y') ? y_word : position_mm_.y_mm};
    } else {
      request.r = r_raw + request.initial_level;
      request.bottom = request.r + z_raw;
      request.step = {x_word, y_word};
      request.first_hole = {position_mm_.x_mm + x_word, position_mm_.y_mm + y_word};
    }
    if (request.r < request.bottom) {
      problems_.add(block.line, detail::g_code_name(motion) + ": the R plane is below the bottom Z of the cycle (LinuxCNC "
                                                              "refuses it too)");
      return;
    }
    if (block.has('P') && !cycle_dwells(motion) && !p_note_given_) {
      note("line " + std::to_string(block.line) + ": " + block.word('P')->text + " on " + detail::g_code_name(motion) +
           " is ignored: the cycle does not dwell (Haas ignores it; LinuxCNC refuses it)");
      p_note_given_ = true;
    }
    if (!room_for_move(block.line, detail::drill_move_count(request))) return;
    Point3 end;
    const std::vector<detail::DrillMove> moves = detail::drill_moves(request, end);
    WrittenMove written = written_move(block, motion);
    written.keep_whole = true;
    written.fixed_feed = true;
    Point3 from{path_end_xy_.x_mm, path_end_xy_.y_mm, position_mm_.z_mm};
    for (const detail::DrillMove& d : moves) {
      pending_dwell_s_ += d.dwell_before_s;
      if (d.end.x_mm == from.x_mm && d.end.y_mm == from.y_mm && d.end.z_mm == from.z_mm) continue;
      if (!room_for_move(block.line)) return;
      Move m;
      m.kind = d.feed ? MoveKind::kLine : MoveKind::kRapid;
      m.start = from;
      m.end = d.end;
      geometry::BlockCommand command = block_command(block.line, d.feed ? kG1 : kG0);
      if (d.spindle_stopped) command.spindle = SpindleDirection::kOff;
      written.motion = d.feed ? 1 : 0;
      add_move(m, command, written);
      from = d.end;
    }
    drilled_holes_ += request.repeats;
    go_to(end);
  }

  // G28, G30: LinuxCNC goes to the intermediate point of the axis words first (in the distance mode in
  // effect), then to the stored machine position, which the reader does not know: it parks instead.
  // Where the block's X Y Z words put the tool (absolute or incremental, in the units in effect), mm; axes
  // without a word keep the programmed position.
  Point3 programmed_end(const Block& block) const {
    Point3 end = position_mm_;
    auto axis = [&](char letter, double start_mm, double& target_mm) {
      if (const Word* w = block.word(letter)) target_mm = (absolute_ ? 0.0 : start_mm) + w->value * unit_mm();
    };
    axis('X', position_mm_.x_mm, end.x_mm);
    axis('Y', position_mm_.y_mm, end.y_mm);
    axis('Z', position_mm_.z_mm, end.z_mm);
    return end;
  }

  void go_home(const Block& block) {
    if (block.has('X') || block.has('Y') || block.has('Z')) {
      const Point3 end = programmed_end(block);
      const Point3 start{path_end_xy_.x_mm, path_end_xy_.y_mm, position_mm_.z_mm};
      if ((end.x_mm != start.x_mm || end.y_mm != start.y_mm || end.z_mm != start.z_mm) && room_for_move(block.line)) {
        Move m;
        m.kind = MoveKind::kRapid;
        m.start = start;
        m.end = end;
        WrittenMove written = written_move(block, kG0);
        written.keep_whole = true;
        add_move(m, block_command(block.line, kG0), written);
      }
      go_to(end);
    }
    park(block.line);
  }

  // A move to a machine position (G28, G30, G53): the reader has no machine coordinates, so the tool goes
  // to a parked state above everything — a rapid straight up to the park height (ReaderOptions::park_z_mm,
  // else the highest Z reached so far plus 25 mm), X and Y kept.
  void park(int line) {
    const double park_z_mm = options_.park_z_mm ? *options_.park_z_mm : highest_z_mm_ + kParkClearanceMm;
    const Point3 start{path_end_xy_.x_mm, path_end_xy_.y_mm, position_mm_.z_mm};
    if (start.z_mm < park_z_mm && room_for_move(line)) {  // already above it: the tool stays
      Move m;
      m.kind = MoveKind::kRapid;
      m.start = start;
      m.end = {start.x_mm, start.y_mm, park_z_mm};
      WrittenMove written = written_move_for_line(line);
      add_move(m, block_command(line, kG0), written, true);
      go_to(m.end);
    }
    parked_line_ = line;
    ++machine_position_moves_;
    ++parks_not_left_;
    last_park_z_mm_ = position_mm_.z_mm;
    highest_park_z_mm_ = std::max(highest_park_z_mm_, last_park_z_mm_);
  }

  WrittenMove written_move_for_line(int line) const {
    WrittenMove written;
    written.line = line;
    written.motion = 0;
    written.inch = inch_;
    written.incremental = !absolute_;
    written.absolute_arc_center = absolute_arc_center_;
    written.tool = tool_in_spindle_ ? *tool_in_spindle_ : g43_tool_ ? *g43_tool_ : -1;
    written.keep_whole = true;
    return written;
  }

  // The programmed position and the path both at `end` (after a block that adds no move).
  void go_to(const Point3& end) {
    position_mm_ = end;
    path_end_xy_ = geometry::xy(end);
  }

  // The command and the written form of a block whose moves compensation may still hold back.
  struct CompensatedBlock {
    geometry::BlockCommand command;
    WrittenMove written;
  };

  const ReaderOptions& options_;
  detail::ProblemLog& problems_;
  bool comp_on_ = false;         // G41/G42 in effect (possibly with a zero radius)
  int comp_code_ = kG40;         // the G41 or G42 in effect
  int comp_line_ = 0;            // its line
  std::optional<detail::CutterCompensation> compensation_;  // on, with a radius
  std::vector<CompensatedBlock> compensation_blocks_;       // by tag, while compensation_ is on
  int after_compensation_line_ = 0;  // the G40 line while the move after it is still to come
  geometry::Program program_;
  std::vector<WrittenMove> written_;  // parallel to program_.path.moves

  Point3 position_mm_;  // the programmed position (LinuxCNC's current point), mm
  Point2 path_end_xy_;  // where the last move ends in XY: the programmed position, or an arc end moved onto its circle
  bool inch_ = false;
  bool units_set_ = false;
  bool unit_note_given_ = false;
  bool k_note_given_ = false;
  int plane_ = kG17;           // G17, G18 or G19 in effect
  bool retract_to_r_ = false;  // G99 (else G98, LinuxCNC's default)
  double cycle_r_ = 0.0;       // the cycles' sticky R, Z, P, Q words, in the program's unit as written
  double cycle_z_ = 0.0;
  double cycle_p_ = 0.0;
  double cycle_q_ = 0.0;
  bool p_note_given_ = false;
  std::optional<double> cycle_initial_z_mm_;  // Z when the cycles began (LinuxCNC's cycle_il), mm
  int drilled_holes_ = 0;
  double highest_z_mm_ = 0.0;        // the highest Z of the initial position and the moves (parks excepted)
  int parked_line_ = 0;              // the line of the last park while no move has followed it
  int machine_position_moves_ = 0;   // G28, G30, G53 blocks read as parks
  int parks_left_ = 0;               // of them, those a later move left from
  int parks_not_left_ = 0;           // of them, those no move has left from yet
  double last_park_z_mm_ = 0.0;     // Z of the last park
  double highest_park_z_mm_ = -1e300;
  int plane_arcs_ = 0;         // arcs in G18/G19 read as straight pieces
  int plane_arc_pieces_ = 0;   // their pieces
  bool absolute_ = true;
  bool absolute_arc_center_ = false;
  int motion_ = kNoMotion;
  int work_offset_ = kG54;
  bool moved_ = false;
  double feed_mm_per_min_ = 0.0;
  int feed_line_ = 0;  // line of the F word (or G94) that set the feed; 0 before any
  bool feed_reset_by_g94_ = false;
  bool feed_problem_reported_ = false;
  double spindle_rpm_ = 0.0;
  int s_zero_line_ = 0;  // line of the S0 word in effect; 0 when the S in effect is > 0 or none was given
  bool s_zero_reported_ = false;
  SpindleDirection spindle_ = SpindleDirection::kOff;
  std::optional<int> selected_tool_;    // the last T word
  std::optional<int> tool_in_spindle_;  // set by the one M6
  int tool_line_ = 0;                   // line of that M6
  std::optional<int> g43_tool_;         // H of the G43 in effect
  int g43_line_ = 0;
  double pending_dwell_s_ = 0.0;
  ArcMoves moved_centres_;  // arcs put on one circle by moving the centre
  ArcMoves moved_ends_;     // … by moving the end point
  bool percent_opened_ = false;
  bool too_many_moves_ = false;  // max_moves reached: reading stops
  bool ended_ = false;
  int end_line_ = 0;
  const char* end_word_ = "";  // M2, M30 or %
  int last_content_line_ = 0;  // last line with words, a %, or a problem
};

}  // namespace

geometry::Program read_program(const std::string& text, const std::string& source_name, const ReaderOptions& options) {
  std::vector<WrittenMove> written;
  return read_program(text, source_name, options, written);
}

geometry::Program read_program(const std::string& text, const std::string& source_name, const ReaderOptions& options,
                               std::vector<WrittenMove>& written) {
  detail::ProblemLog problems(source_name, options.max_problems);
  if (!(options.arc_radius_tolerance_mm >= 0.0) || !std::isfinite(options.arc_radius_tolerance_mm)) {
    throw InputError("ReaderOptions::arc_radius_tolerance_mm",
                     "= " + six_digit_number_text(options.arc_radius_tolerance_mm) + ": must be a finite number ≥ 0");
  }
  Interpreter interpreter(options, problems);
  interpreter.run(text);
  problems.throw_if_any();
  geometry::Program program = interpreter.take_program();
  written = interpreter.take_written();
  program.source_name = source_name;
  // The reader builds each move from the previous end: a defect here is a reader bug, not bad input.
  [[maybe_unused]] const std::vector<std::string> defects = geometry::consistency_defects(program.path);
  assert(defects.empty());
  return program;
}

geometry::Program load_program(const std::filesystem::path& path, const ReaderOptions& options) {
  const std::string text =
      read_input_file(path, {"a G-code program of a milling job", options.max_file_bytes, "ReaderOptions::max_file_bytes"});
  return read_program(text, path.string(), options);
}

}  // namespace feedplan::gcode
