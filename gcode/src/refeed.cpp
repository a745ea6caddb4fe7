#include "feedplan/gcode/refeed.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string_view>

#include "comment_text.hpp"
#include "line_lexer.hpp"
#include "problem_log.hpp"

namespace feedplan::gcode {

namespace {

constexpr double kMmPerInch = 25.4;
constexpr double kPi = 3.14159265358979323846;
// Pieces shorter than this are not written, mm.
constexpr double kShortestPieceMm = 1e-6;
// Longest feed comment text inside its parentheses (Fanuc and Haas: a 60-character comment), characters.
constexpr std::size_t kFeedCommentLength = 58;
// Longest line LinuxCNC reads (its LINELEN), characters: no feed comment makes a line longer.
constexpr std::size_t kLongestLine = 255;

// A line of the text without its ending, and the ending ("\n", "\r\n" or "" on the last line).
struct TextLine {
  std::string body;
  std::string ending;
};

std::vector<TextLine> split_lines(const std::string& text) {
  std::vector<TextLine> lines;
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = text.find('\n', begin);
    TextLine line;
    if (end == std::string::npos) {
      line.body = text.substr(begin);
      begin = text.size();
    } else {
      line.body = text.substr(begin, end - begin);
      line.ending.assign(1, '\n');
      begin = end + 1;
    }
    if (!line.body.empty() && line.body.back() == '\r') {
      line.body.pop_back();
      line.ending.insert(0, 1, '\r');
    }
    lines.push_back(std::move(line));
  }
  return lines;
}

bool is_number_char(char c) { return std::isdigit(static_cast<unsigned char>(c)) || c == '.' || c == '+' || c == '-'; }

// `body` without the words of `letters` (upper case) outside comments: the letter, spaces and its number.
std::string without_words(const std::string& body, std::string_view letters) {
  std::string out;
  bool in_paren = false;
  for (std::size_t i = 0; i < body.size(); ++i) {
    const char c = body[i];
    if (in_paren) {
      out += c;
      if (c == ')') in_paren = false;
      continue;
    }
    if (c == '(') {
      in_paren = true;
      out += c;
      continue;
    }
    if (c == ';') {
      out += body.substr(i);
      break;
    }
    const char upper = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (letters.find(upper) != std::string_view::npos) {
      std::size_t j = i + 1;
      while (j < body.size() && (body[j] == ' ' || body[j] == '\t' || is_number_char(body[j]))) ++j;
      // Keep one space where the word sat between two others.
      while (!out.empty() && (out.back() == ' ' || out.back() == '\t') && j < body.size() &&
             (body[j] == ' ' || body[j] == '\t')) {
        out.pop_back();
      }
      i = j - 1;
      continue;
    }
    out += c;
  }
  while (!out.empty() && (out.back() == ' ' || out.back() == '\t')) out.pop_back();
  return out;
}

// `body` with `words` added right after its last word, before the comments that follow it.
std::string with_words(const std::string& body, const std::string& words) {
  bool in_paren = false;
  std::size_t after_last_word = 0;  // one past the last character of a word
  for (std::size_t i = 0; i < body.size(); ++i) {
    const char c = body[i];
    if (in_paren) {
      in_paren = c != ')';
    } else if (c == '(') {
      in_paren = true;
    } else if (c == ';') {
      break;
    } else if (c != ' ' && c != '\t') {
      after_last_word = i + 1;
    }
  }
  std::string out = body.substr(0, after_last_word);
  out += after_last_word > 0 ? " " : "";
  out += words;
  if (after_last_word < body.size()) {
    if (body[after_last_word] != ' ' && body[after_last_word] != '\t') out += ' ';
    out.append(body, after_last_word, std::string::npos);
  }
  return out;
}

// How feed comments are written (refeed.hpp): upper case when the program's own comments are.
struct FeedComments {
  bool upper_case = false;

  // `(F: <reason>)`, made safe; "" without a reason.
  std::string of(const FeedPiece& piece) const {
    if (piece.reason.empty()) return "";
    std::string body = "F: ";
    body += piece.reason;
    std::string comment = "(";
    comment += detail::safe_comment_text(body, upper_case, kFeedCommentLength);
    comment += ')';
    return comment;
  }
};

// True when no comment of `text` ("(…)" or "; …") holds a lower-case letter: a Fanuc or Haas post's program.
bool comments_upper_case(const std::string& text) {
  bool in_paren = false;
  bool in_semicolon = false;
  for (const char c : text) {
    if (c == '\n') {
      in_paren = in_semicolon = false;
    } else if (in_paren || in_semicolon) {
      if (std::islower(static_cast<unsigned char>(c))) return false;
      if (c == ')') in_paren = false;
    } else if (c == '(') {
      in_paren = true;
    } else if (c == ';') {
      in_semicolon = true;
    }
  }
  return true;
}

// `body` with `comment` right before its first comment, else after its last word (before a ';' comment);
// `body` as it is when `comment` is empty or the line would grow past kLongestLine.
std::string with_comment(const std::string& body, const std::string& comment) {
  if (comment.empty() || body.size() + comment.size() + 1 > kLongestLine) return body;
  for (std::size_t i = 0; i < body.size() && body[i] != ';'; ++i) {
    if (body[i] != '(') continue;
    std::string out = body.substr(0, i);
    if (!out.empty() && out.back() != ' ' && out.back() != '\t') out += ' ';
    out += comment;
    out += ' ';
    out.append(body, i, std::string::npos);
    return out;
  }
  return with_words(body, comment);
}

// `value` with `decimals` decimals, trailing zeros trimmed, always a decimal point, no "-0.".
std::string number_text(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  std::string text = buffer;
  while (!text.empty() && text.back() == '0') text.pop_back();
  if (text == "-.") text = "0.";
  if (text == "-0.") text = "0.";
  return text;
}

// What the controller has in effect while the text is copied.
struct OutputState {
  bool inch = false;
  double feed_mm_per_min = 0.0;  // the F in effect as the output sets it; 0: none (or reset by G94)
};

// The F words, units and feed mode of a line copied as it is: how they change the feed in effect.
void follow_copied_line(const std::string& body, int line, OutputState& state) {
  detail::ProblemLog ignored("", 1);
  const detail::LexedLine lexed = detail::lex_line(body, line, ignored);
  std::optional<double> f;
  for (const detail::Word& w : lexed.words) {
    if (w.letter == 'G' && std::abs(w.value - 20.0) < 1e-9) state.inch = true;
    if (w.letter == 'G' && std::abs(w.value - 21.0) < 1e-9) state.inch = false;
    if (w.letter == 'G' && std::abs(w.value - 94.0) < 1e-9) state.feed_mm_per_min = 0.0;
    if (w.letter == 'F') f = w.value;
  }
  if (f) state.feed_mm_per_min = *f * (state.inch ? kMmPerInch : 1.0);
}

// Writes the lengths of the line being rewritten in its units.
struct Units {
  bool inch = false;
  double of(double mm) const { return inch ? mm / kMmPerInch : mm; }
  int decimals() const { return inch ? 5 : 4; }
  std::string length(double mm) const { return number_text(of(mm), decimals()); }
  // F rounded down to 0.1 mm/min or 0.001 in/min.
  std::string feed(double mm_per_min) const {
    return inch ? number_text(std::floor(mm_per_min / kMmPerInch * 1000.0 + 1e-9) / 1000.0, 3)
                : number_text(std::floor(mm_per_min * 10.0 + 1e-9) / 10.0, 1);
  }
  double feed_as_written(double mm_per_min) const {
    return inch ? std::floor(mm_per_min / kMmPerInch * 1000.0 + 1e-9) / 1000.0 * kMmPerInch
                : std::floor(mm_per_min * 10.0 + 1e-9) / 10.0;
  }
};

// The F word for `feed_mm_per_min` when it changes the feed in effect ("" when not), and the new state.
std::string feed_word(double feed_mm_per_min, const Units& units, OutputState& state) {
  const double written = units.feed_as_written(feed_mm_per_min);
  if (std::abs(written - state.feed_mm_per_min) <= 1e-9 * std::max(1.0, written)) return "";
  state.feed_mm_per_min = written;
  std::string word = "F";
  word += units.feed(feed_mm_per_min);
  return word;
}

// The arc words of `piece` (its centre seen from its written start `start_mm`) in the line's format.
std::string arc_words(const geometry::Move& piece, const geometry::Point2& start_mm, const WrittenMove& w,
                      const Units& units) {
  if (w.radius_form) {
    const double r = std::hypot(piece.start.x_mm - piece.center.x_mm, piece.start.y_mm - piece.center.y_mm);
    std::string words = "R";
    words += units.length(piece.sweep_rad > kPi ? -r : r);
    return words;
  }
  const double i = w.absolute_arc_center ? piece.center.x_mm : piece.center.x_mm - start_mm.x_mm;
  const double j = w.absolute_arc_center ? piece.center.y_mm : piece.center.y_mm - start_mm.y_mm;
  std::string words = "I";
  words += units.length(i);
  words += " J";
  words += units.length(j);
  return words;
}

// A number printed and read back: the position the controller has after a written word.
double as_written(double mm, const Units& units) {
  const double value = std::stod(units.length(mm));
  return units.inch ? value * kMmPerInch : value;
}

// The words of one piece ending inside the move: X Y (Z when it moves in Z), the arc words, F. `start`
// is where the controller is (as written); returns the written end.
std::string inner_piece_words(const geometry::Move& piece, const WrittenMove& w, const Units& units,
                              geometry::Point2& start, OutputState& state, double feed_mm_per_min,
                              const std::string& comment) {
  std::string words = "X";
  words += units.length(piece.end.x_mm);
  words += " Y";
  words += units.length(piece.end.y_mm);
  if (piece.start.z_mm != piece.end.z_mm) {
    words += " Z";
    words += units.length(piece.end.z_mm);
  }
  if (piece.kind == geometry::MoveKind::kArc) {
    words += ' ';
    words += arc_words(piece, start, w, units);
  }
  const std::string f = feed_word(feed_mm_per_min, units, state);
  if (!f.empty()) {
    words += ' ';
    words += f;
    if (!comment.empty()) {
      words += ' ';
      words += comment;
    }
  }
  start = {as_written(piece.end.x_mm, units), as_written(piece.end.y_mm, units)};
  return words;
}

// The X Y Z words of `body` as written (the move's programmed end), in that order.
std::string end_words(const std::string& body, int line) {
  detail::ProblemLog ignored("", 1);
  const detail::LexedLine lexed = detail::lex_line(body, line, ignored);
  std::string words;
  for (const char axis : {'X', 'Y', 'Z'}) {
    for (const detail::Word& word : lexed.words) {
      if (word.letter != axis) continue;
      if (!words.empty()) words += " ";
      words += word.text;
    }
  }
  return words;
}

// True when the line holds G94, which resets the feed in effect before its F is read.
bool resets_feed(const std::string& body) {
  detail::ProblemLog ignored("", 1);
  const detail::LexedLine lexed = detail::lex_line(body, 0, ignored);
  return std::any_of(lexed.words.begin(), lexed.words.end(),
                     [](const detail::Word& w) { return w.letter == 'G' && std::abs(w.value - 94.0) < 1e-9; });
}

std::string motion_code(int motion) {
  std::string code = "G";
  code += std::to_string(motion);
  return code;
}

// The pieces of every move, indexed by move.
std::vector<std::vector<const FeedPiece*>> pieces_by_move(const geometry::Program& program,
                                                          const std::vector<WrittenMove>& written,
                                                          const std::vector<FeedPiece>& pieces) {
  std::vector<std::vector<const FeedPiece*>> by_move(program.path.moves.size());
  for (const FeedPiece& piece : pieces) {
    if (piece.move_index < 0 || static_cast<std::size_t>(piece.move_index) >= by_move.size()) {
      throw std::invalid_argument("refeed_text: a piece of move " + std::to_string(piece.move_index) +
                                  ", which the program does not have");
    }
    if (program.path.moves[static_cast<std::size_t>(piece.move_index)].kind == geometry::MoveKind::kRapid) {
      throw std::invalid_argument("refeed_text: a feed for rapid move " + std::to_string(piece.move_index));
    }
    if (written[static_cast<std::size_t>(piece.move_index)].fixed_feed) {
      throw std::invalid_argument("refeed_text: a feed for move " + std::to_string(piece.move_index) +
                                  ", whose feed is fixed (a drilling cycle's)");
    }
    if (!(piece.feed_mm_per_min > 0.0)) {
      throw std::invalid_argument("refeed_text: a piece of move " + std::to_string(piece.move_index) + " without a feed");
    }
    by_move[static_cast<std::size_t>(piece.move_index)].push_back(&piece);
  }
  return by_move;
}

// Writes `line` into `out` with only its F word changed: the feed `feed_mm_per_min` for all of it.
// With the F word, `comment` (FeedComments::of) before the line's first comment.
void rewrite_feed_only(const TextLine& line, const Units& units, double feed_mm_per_min, const std::string& comment,
                       OutputState& state, RefeedResult& result, std::vector<TextLine>& out) {
  std::string body = without_words(line.body, "F");
  if (resets_feed(line.body)) state.feed_mm_per_min = 0.0;
  const std::string f = feed_word(feed_mm_per_min, units, state);
  if (!f.empty()) body = with_comment(with_words(body, f), comment);
  if (body != line.body) ++result.lines_changed;
  out.push_back({body, line.ending});
}

// Rewrites a line that carries several moves, or one that must stay whole (`moves`: their indices, in
// order): at the lowest feed of all their pieces, only its F word changed. A line without pieces is copied.
void rewrite_whole_line(const TextLine& line, int line_number, const std::vector<int>& moves,
                        const std::vector<WrittenMove>& written,
                        const std::vector<std::vector<const FeedPiece*>>& by_move, const FeedComments& comments,
                        OutputState& state, RefeedResult& result, std::vector<TextLine>& out) {
  const Units units{written[static_cast<std::size_t>(moves.front())].inch};
  std::optional<double> lowest;
  const FeedPiece* slowest = nullptr;
  int moves_with_pieces = 0;
  bool same_feed = true;
  for (const int m : moves) {
    const std::vector<const FeedPiece*>& pieces = by_move[static_cast<std::size_t>(m)];
    if (!pieces.empty()) ++moves_with_pieces;
    for (const FeedPiece* p : pieces) {
      if (lowest && units.feed_as_written(p->feed_mm_per_min) != units.feed_as_written(*lowest)) same_feed = false;
      if (!lowest || p->feed_mm_per_min < *lowest) slowest = p;
      lowest = lowest ? std::min(*lowest, p->feed_mm_per_min) : p->feed_mm_per_min;
    }
  }
  if (!lowest) {
    follow_copied_line(line.body, line_number, state);
    out.push_back(line);
    return;
  }
  state.inch = units.inch;
  if (!same_feed) result.moves_at_lowest_feed += moves_with_pieces;
  rewrite_feed_only(line, units, *lowest, comments.of(*slowest), state, result, out);
}

// Rewrites the line of move `m` (its pieces `pieces`, at least one) into `out`.
void rewrite_move(const TextLine& line, const WrittenMove& w, const std::vector<const FeedPiece*>& all_pieces,
                  const FeedComments& comments, OutputState& state, RefeedResult& result, std::vector<TextLine>& out) {
  const Units units{w.inch};
  state.inch = w.inch;
  std::vector<const FeedPiece*> pieces;
  for (const FeedPiece* p : all_pieces) {
    if (geometry::length_mm(p->move) >= kShortestPieceMm) pieces.push_back(p);
  }
  if (pieces.empty()) pieces.push_back(all_pieces.front());
  bool single = pieces.size() == 1;
  double lowest = pieces.front()->feed_mm_per_min;
  const FeedPiece* slowest = pieces.front();
  for (const FeedPiece* p : pieces) {
    if (p->feed_mm_per_min < lowest) slowest = p;
    lowest = std::min(lowest, p->feed_mm_per_min);
  }
  // One F for the line only when every piece writes the lowest one (pieces that slow down along the move
  // are split too).
  const bool same_feed = std::all_of(pieces.begin(), pieces.end(), [&](const FeedPiece* p) {
    return units.feed_as_written(p->feed_mm_per_min) == units.feed_as_written(lowest);
  });
  if (!single && !same_feed && (w.turns || w.incremental)) {
    ++result.moves_at_lowest_feed;
    single = true;
  }
  if (single || same_feed) {
    rewrite_feed_only(line, units, lowest, comments.of(*slowest), state, result, out);
    return;
  }
  ++result.moves_split;
  ++result.lines_changed;
  if (resets_feed(line.body)) state.feed_mm_per_min = 0.0;
  const std::string code = motion_code(w.motion);
  geometry::Point2 start{pieces.front()->move.start.x_mm, pieces.front()->move.start.y_mm};
  // First piece: on the move's own line, with its other words.
  std::string first = without_words(line.body, "XYZIJKRPF");
  std::string words;
  if (!w.motion_word) {
    words += code;
    words += ' ';
  }
  const std::string first_comment = comments.of(*pieces.front());
  const double feed_before = state.feed_mm_per_min;
  words += inner_piece_words(pieces.front()->move, w, units, start, state, pieces.front()->feed_mm_per_min, "");
  first = with_words(first, words);
  if (state.feed_mm_per_min != feed_before) first = with_comment(first, first_comment);
  out.push_back({first, line.ending});
  for (std::size_t k = 1; k + 1 < pieces.size(); ++k) {
    std::string middle = code;
    middle += ' ';
    middle += inner_piece_words(pieces[k]->move, w, units, start, state, pieces[k]->feed_mm_per_min,
                                comments.of(*pieces[k]));
    out.push_back({middle, line.ending});
    ++result.lines_added;
  }
  // Last piece: the line's own end words.
  const geometry::Move& last = pieces.back()->move;
  std::string tail = code;
  tail += ' ';
  tail += end_words(line.body, 0);
  if (last.kind == geometry::MoveKind::kArc) {
    tail += ' ';
    tail += arc_words(last, start, w, units);
  }
  const std::string f = feed_word(pieces.back()->feed_mm_per_min, units, state);
  if (!f.empty()) {
    tail += ' ';
    tail += f;
    tail = with_comment(tail, comments.of(*pieces.back()));
  }
  out.push_back({tail, line.ending});
  ++result.lines_added;
}

}  // namespace

RefeedResult refeed_text(const std::string& text, const geometry::Program& program,
                         const std::vector<WrittenMove>& written, const std::vector<FeedPiece>& pieces) {
  if (written.size() != program.path.moves.size()) {
    throw std::invalid_argument("refeed_text: " + std::to_string(written.size()) + " written moves for " +
                                std::to_string(program.path.moves.size()) + " moves");
  }
  const std::vector<std::vector<const FeedPiece*>> by_move = pieces_by_move(program, written, pieces);
  std::vector<std::vector<int>> moves_of_line;  // per 1-based line: the indices of its moves, in order
  for (std::size_t m = 0; m < written.size(); ++m) {
    const auto line = static_cast<std::size_t>(written[m].line);
    if (moves_of_line.size() <= line) moves_of_line.resize(line + 1);
    moves_of_line[line].push_back(static_cast<int>(m));
  }
  const std::vector<TextLine> lines = split_lines(text);
  std::vector<TextLine> out;
  out.reserve(lines.size() + pieces.size());
  RefeedResult result;
  OutputState state;
  const FeedComments comments{comments_upper_case(text)};
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const int line_number = static_cast<int>(i) + 1;
    const std::vector<int> none;
    const std::vector<int>& moves = i + 1 < moves_of_line.size() ? moves_of_line[i + 1] : none;
    const bool whole = moves.size() > 1 || (moves.size() == 1 && written[static_cast<std::size_t>(moves[0])].keep_whole);
    if (whole) {
      rewrite_whole_line(lines[i], line_number, moves, written, by_move, comments, state, result, out);
    } else if (moves.size() == 1 && !by_move[static_cast<std::size_t>(moves[0])].empty()) {
      const auto move = static_cast<std::size_t>(moves[0]);
      rewrite_move(lines[i], written[move], by_move[move], comments, state, result, out);
    } else {
      follow_copied_line(lines[i].body, line_number, state);
      out.push_back(lines[i]);
    }
  }
  for (const TextLine& line : out) result.text += line.body + line.ending;
  return result;
}

}  // namespace feedplan::gcode
