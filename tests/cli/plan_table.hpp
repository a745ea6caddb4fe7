#pragma once
// Test helpers for the files `feedplan plan` and `feedplan optimize` write: a CSV read into named columns,
// and the F words of a G-code program with the comment each carries. Test-only code.

#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace feedplan::cli_test {

//! A CSV with a header row: the cells of every row by column name.
struct CsvTable {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;

  std::size_t column(const std::string& name) const {
    for (std::size_t i = 0; i < columns.size(); ++i) {
      if (columns[i] == name) return i;
    }
    return columns.size();  // absent: cell() then gives ""
  }
  std::string cell(std::size_t row, const std::string& name) const {
    const std::size_t c = column(name);
    return c < rows[row].size() ? rows[row][c] : std::string();
  }
  double number(std::size_t row, const std::string& name) const { return std::strtod(cell(row, name).c_str(), nullptr); }
};

inline std::vector<std::string> csv_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

inline CsvTable read_csv(const std::string& text) {
  CsvTable table;
  std::stringstream in(text);
  std::string line;
  if (std::getline(in, line)) table.columns = csv_cells(line);
  while (std::getline(in, line)) {
    if (!line.empty()) table.rows.push_back(csv_cells(line));
  }
  return table;
}

//! One F word of a program with the comment that follows it on its line ("" when none).
struct FeedWord {
  int line = 0;             //!< 1-based line
  double feed = 0.0;        //!< its value
  std::string comment;      //!< the text of the first "(F: …)" comment of the line, without "(F: " and ")"
};

//! The F words of `text` (outside comments), in order, each with the line's "(F: …)" comment.
inline std::vector<FeedWord> feed_words(const std::string& text) {
  std::vector<FeedWord> words;
  std::stringstream in(text);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    bool in_comment = false;
    std::optional<double> feed;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char c = line[i];
      if (c == ';') break;
      if (c == '(') in_comment = true;
      if (c == ')') in_comment = false;
      if (!in_comment && (c == 'F' || c == 'f')) feed = std::strtod(line.c_str() + i + 1, nullptr);
    }
    const std::size_t open = line.find("(F: ");
    std::string comment;
    if (open != std::string::npos) comment = line.substr(open + 4, line.find(')', open) - open - 4);
    if (feed || !comment.empty()) words.push_back({number, feed.value_or(NAN), comment});
  }
  return words;
}

//! `text` with every " (F: …)" feed comment taken out.
inline std::string without_feed_comments(std::string text) {
  for (std::size_t at = text.find(" (F: "); at != std::string::npos; at = text.find(" (F: ", at)) {
    text.erase(at, text.find(')', at) - at + 1);
  }
  return text;
}

}  // namespace feedplan::cli_test
