#pragma once
// "Did you mean ...?" hints for misspelt names in user input (unknown spec fields, log columns,
// material names): the Levenshtein edit distance and the closest known name.

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace feedplan {

//! Levenshtein distance between `a` and `b`: the fewest single-character insertions, deletions
//! and substitutions that turn one into the other. Compares bytes, so letter case counts.
inline std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

//! Whether closest_name() tells "Pitch" from "pitch".
enum class LetterCase {
  kSensitive,  //!< compare as written
  kIgnored,    //!< compare ASCII letters lowercased (YAML keys, material names, log column headers)
};

//! The candidate closest to `word` by edit_distance(), if it is within 2 edits; on a tie the first
//! such candidate in `candidates`. Returns the candidate as written in `candidates`, or "" when
//! none is that close (or `candidates` is empty). Callers append " (did you mean <name>?)".
inline std::string closest_name(std::string_view word, const std::vector<std::string>& candidates,
                                LetterCase letter_case) {
  const auto folded = [letter_case](std::string_view text) {
    std::string result(text);
    if (letter_case == LetterCase::kIgnored) {
      std::transform(result.begin(), result.end(), result.begin(),
                     [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    }
    return result;
  };
  const std::string wanted = folded(word);
  std::string best;
  std::size_t best_distance = 3;  // suggest only within 2 edits
  for (const auto& candidate : candidates) {
    const std::size_t distance = edit_distance(wanted, folded(candidate));
    if (distance < best_distance) {
      best_distance = distance;
      best = candidate;
    }
  }
  return best;
}

}  // namespace feedplan
