#include "program_operations.hpp"

#include <algorithm>
#include <cctype>
#include <optional>
#include <string_view>

namespace feedplan::cli {

namespace {

std::string lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.remove_suffix(1);
  return text;
}

// The text of a line that holds one comment and nothing else ("(PROFILE)", "; roughing"), else nothing.
std::optional<std::string> comment_only(std::string_view line) {
  line = trimmed(line);
  if (line.size() >= 2 && line.front() == '(' && line.back() == ')' &&
      line.find_first_of("()", 1) == line.size() - 1) {
    return std::string(trimmed(line.substr(1, line.size() - 2)));
  }
  if (!line.empty() && line.front() == ';') return std::string(trimmed(line.substr(1)));
  return std::nullopt;
}

// The name an opening comment gives, or nothing for a closing one ("finish operation: …", "END CUTTING").
std::optional<std::string> opening_name(const std::string& comment) {
  const std::string l = lower(comment);
  if (comment.empty() || l.rfind("finish", 0) == 0 || l.rfind("end", 0) == 0) return std::nullopt;
  for (const std::string_view prefix : {"begin operation:", "begin operation"}) {
    if (l.rfind(prefix, 0) == 0) return std::string(trimmed(std::string_view(comment).substr(prefix.size())));
  }
  return comment;
}

// The text's lines (without their endings), 1-based: lines[0] is empty.
std::vector<std::string_view> text_lines(const std::string& text) {
  std::vector<std::string_view> lines{std::string_view()};
  std::size_t begin = 0;
  while (begin <= text.size()) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + begin, end - begin);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    if (end == text.size()) break;
    begin = end + 1;
  }
  return lines;
}

// True when moves [first, end) hold a feed move (G1, G2, G3).
bool feed_moves_in(const std::vector<gcode::WrittenMove>& written, std::size_t first, std::size_t end) {
  for (std::size_t m = first; m < end; ++m) {
    if (written[m].motion != 0) return true;
  }
  return false;
}

std::string tool_name(int tool) {
  if (tool < 0) return "program";
  std::string name(1, 'T');  // built in place: GCC 12 warns falsely (-Wrestrict) on "T" + std::string
  name += std::to_string(tool);
  return name;
}

}  // namespace

std::vector<ProgramOperation> program_operations(const std::string& text, const std::vector<gcode::WrittenMove>& written) {
  const std::vector<std::string_view> lines = text_lines(text);
  std::vector<ProgramOperation> operations;
  int previous_line = 0;
  for (std::size_t m = 0; m < written.size(); ++m) {
    const int line = written[m].line;
    std::optional<std::string> name, begun;  // the first opening comment; the last "begin operation"
    bool comment_between = false;
    for (int k = previous_line + 1; k < line && k < static_cast<int>(lines.size()); ++k) {
      const std::optional<std::string> comment = comment_only(lines[static_cast<std::size_t>(k)]);
      if (!comment) continue;
      comment_between = true;
      if (!name) name = opening_name(*comment);
      if (lower(*comment).rfind("begin operation", 0) == 0) begun = opening_name(*comment);
    }
    if (begun) name = begun;  // FreeCAD opens operations without moves too (fixtures, tool changes)
    const bool new_tool = m > 0 && written[m].tool != written[m - 1].tool;
    const bool current_feeds = !operations.empty() && feed_moves_in(written, operations.back().first_move, m);
    if (operations.empty() || new_tool || (comment_between && name && current_feeds)) {
      ProgramOperation op;
      op.name = name ? *name : new_tool || operations.empty() ? tool_name(written[m].tool) : operations.back().name;
      op.first_move = m;
      op.first_line = line;
      operations.push_back(op);
    }
    if (comment_between && name && !new_tool && !current_feeds && !operations.empty() &&
        operations.back().name == tool_name(written[m].tool)) {
      operations.back().name = *name;  // an operation named after its tool takes a comment before its first feed move
    }
    operations.back().end_move = m + 1;
    operations.back().last_line = line;
    previous_line = std::max(previous_line, line);
  }
  return operations;
}

}  // namespace feedplan::cli
