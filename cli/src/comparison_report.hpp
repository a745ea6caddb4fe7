#pragma once
// What `feedplan compare` writes and prints: the comparison as a Markdown table (compare.md, and the
// command's summary) and as JSON (compare.json, and --json). Both carry the same figures; the table rounds
// them (forces to 0.1 N, shares to 1 %, times to 0.01 s).

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "feedplan/trial/strategy_comparison.hpp"

namespace feedplan::cli {

//! What the figures are about, in words.
struct ComparisonContext {
  std::string spec_path;            //!< as given
  std::string cycle;                //!< the spec's cycle kind, e.g. "trochoid"
  std::string machine;              //!< the virtual machine, e.g. "S50C × 1.4 (the material's cutting coefficients × 1.4)"
  std::string model;                //!< the model the plan was made with, e.g. "id 1 v1 (exact match)"
  std::string constant_feed_source; //!< where the constant feed comes from, e.g. "the spec's feed_mm_per_min"
  std::vector<std::string> notes;   //!< said under the table
};

//! The Markdown text: a heading line, the table (one row per strategy), the learning cycles before the
//! learned one, and the notes.
std::string comparison_markdown(const ComparisonContext& context, const trial::StrategyComparison& comparison);

//! The JSON document: the context, every row with its figures unrounded, the learning cycles, the notes.
nlohmann::json comparison_json(const ComparisonContext& context, const trial::StrategyComparison& comparison);

}  // namespace feedplan::cli
