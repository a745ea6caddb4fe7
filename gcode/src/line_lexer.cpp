#include "line_lexer.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace feedplan::gcode::detail {

namespace {

constexpr double kMaxWordValue = 1e6;

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
bool is_number_char(char c) { return std::isdigit(static_cast<unsigned char>(c)) || c == '.' || c == '+' || c == '-'; }

// Optional sign, then digits with at most one decimal point and at least one digit.
bool is_plain_decimal(const std::string& text) {
  std::size_t i = 0;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  int digits = 0;
  int points = 0;
  for (; i < text.size(); ++i) {
    if (std::isdigit(static_cast<unsigned char>(text[i]))) {
      ++digits;
    } else if (text[i] == '.') {
      ++points;
    } else {
      return false;
    }
  }
  return digits > 0 && points <= 1;
}

// A character outside any word, named with the reason LinuxCNC programs use it.
std::string stray_character_message(char c) {
  const std::string quoted = std::string("'") + c + "'";
  switch (c) {
    case '#': return "character " + quoted + ": not supported (numbered and named parameters)";
    case '[': case ']': return "character " + quoted + ": not supported (expressions in [ ])";
    case '<': case '>': return "character " + quoted + ": not supported (named parameters)";
    case '=': return "character " + quoted + ": not supported (parameter assignment)";
    case '%': return "character " + quoted + ": % must be alone on its line (first line, or the program end)";
    case '/': return "character " + quoted + ": not supported (block delete: whether the line runs depends "
                     "on the operator's switch, so the path would be ambiguous)";
    default: break;
  }
  if (is_number_char(c)) return "number without a letter: every number must follow a word letter (X, F, …)";
  if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) {
    return "a character that is not printable ASCII (byte " + std::to_string(static_cast<unsigned char>(c)) +
           "): not part of any G-code word";
  }
  return "character " + quoted + ": not part of any G-code word";
}

// Pass 1: the line without comments and spaces, upper-cased; nullopt (and a problem) when a comment
// is not closed, nested or has no '('.
std::optional<std::string> code_of(std::string_view text, int line, ProblemLog& problems) {
  std::string code;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == ';') break;
    if (c == '(') {
      const std::size_t close = text.find(')', i + 1);
      const std::size_t nested = text.find('(', i + 1);
      if (close == std::string_view::npos) {
        problems.add(line, "comment: '(' at column " + std::to_string(i + 1) +
                               " is not closed; a comment must end with ')' on the same line");
        return std::nullopt;
      }
      if (nested < close) {
        problems.add(line, "comment: '(' at column " + std::to_string(nested + 1) +
                               " inside a comment; comments cannot be nested");
        return std::nullopt;
      }
      i = close;
      continue;
    }
    if (c == ')') {
      problems.add(line, "comment: ')' at column " + std::to_string(i + 1) + " has no matching '('");
      return std::nullopt;
    }
    if (is_space(c)) continue;
    code += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  }
  return code;
}

// Pass 2: the word starting at code[i] (after the `words` before it); advances `i` past it. Nullopt
// (and a problem) when there is no letter, no number or a bad one, or an O word out of place.
std::optional<Word> next_word(const std::string& code, std::size_t& i, const std::vector<Word>& words, int line,
                              ProblemLog& problems) {
  const char letter = code[i];
  if (letter < 'A' || letter > 'Z') {
    problems.add(line, stray_character_message(letter));
    return std::nullopt;
  }
  std::size_t end = i + 1;
  while (end < code.size() && is_number_char(code[end])) ++end;
  const std::string number = code.substr(i + 1, end - i - 1);
  const std::string word = code.substr(i, end - i);
  if (letter == 'O' && number.empty()) {
    problems.add(line, "word O: not supported (named O words are subroutines and control flow, which the reader "
                       "does not run; an O word may only number the program, like O1000)");
    return std::nullopt;
  }
  if (number.empty()) {
    std::string found;
    for (std::size_t k = end; k < code.size() && k < end + 12 && !is_number_char(code[k]); ++k) found += code[k];
    problems.add(line, "word " + std::string(1, letter) + ": needs a number after the letter" +
                           (found.empty() ? std::string() : ", found \"" + found + "\""));
    return std::nullopt;
  }
  if (!is_plain_decimal(number)) {
    problems.add(line, "word " + word + ": \"" + number +
                           "\" is not a number (an optional sign, digits and at most one decimal point)");
    return std::nullopt;
  }
  const double value = std::strtod(number.c_str(), nullptr);
  // Line and program numbers only label; every other number is a length, feed, speed, time or code, and
  // beyond this bound arcs lose their precision (an I of 60 digits put an arc's end off its circle).
  if (letter != 'N' && letter != 'O' && !(std::abs(value) <= kMaxWordValue)) {
    const std::string shown = word.size() > 24 ? word.substr(0, 20) + "…" : word;
    problems.add(line, "word " + shown + ": out of range: numbers are at most ±1000000 (1 km in mm), more than any "
                                         "machine travels, feeds or turns");
    return std::nullopt;
  }
  const bool only_line_number_before = words.empty() || (words.size() == 1 && words[0].letter == 'N');
  if (letter == 'O' && (end < code.size() || !only_line_number_before)) {
    problems.add(line, "word " + word + ": not supported here (an O word may only number the program, "
                           "alone on its line; O-word subroutines and control flow are not supported)");
    return std::nullopt;
  }
  i = end;
  return Word{letter, value, word};
}

}  // namespace

LexedLine lex_line(std::string_view text, int line, ProblemLog& problems) {
  LexedLine result;
  if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
  const std::optional<std::string> code = code_of(text, line, problems);
  if (!code) {
    result.ok = false;
    return result;
  }
  if (*code == "%") {
    result.percent = true;
    return result;
  }
  std::size_t i = 0;
  while (i < code->size()) {
    std::optional<Word> word = next_word(*code, i, result.words, line, problems);
    if (!word) {
      result.ok = false;
      return result;
    }
    result.words.push_back(std::move(*word));
  }
  return result;
}

}  // namespace feedplan::gcode::detail
