#pragma once
// `feedplan compare SPEC.yaml [--cycles N] [--machine-scale K | --machine MACHINE.yaml] [--target-force N]
// [--constant-feed F] [--db PATH] [--out DIR] [--json]`: the strategies for holding the force on one cycle —
// constant feed, the feed-forward plan, the plan after learning, each feedback controller alone, and the
// hybrid — run on one virtual machine and judged the same way (trial/strategy_comparison.hpp); writes
// compare.md, compare.json and compare.svg into DIR and prints the table.

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace feedplan::cli {

//! The names of the files written into --out.
inline constexpr const char* kCompareMarkdownName = "compare.md";
inline constexpr const char* kCompareJsonName = "compare.json";
inline constexpr const char* kComparePlotName = "compare.svg";

struct CompareOptions {
  std::string spec_path;                   //!< the cycle spec
  int cycles = 3;                          //!< --cycles N: the learned row is the loop's cycle N (2–20)
  //! --machine-scale K: the virtual machine's cutting coefficients × K; unset: 1.4 (without --machine)
  std::optional<double> machine_scale;
  std::string machine_path;                //!< --machine: a machine file instead of the scaled material
  std::optional<double> target_force_n;    //!< --target-force; unset: the spec's
  //! --constant-feed F: the constant-feed rows' feed, mm/min; unset: the spec's feed_mm_per_min, else the
  //! constant feed the model predicts to peak where the plan does (the plan's baseline)
  std::optional<double> constant_feed_mm_per_min;
  std::string db_path;                     //!< --db; empty: $FEEDPLAN_DB, else the sample database
  std::string materials_path;              //!< --materials; empty: the bundled one
  std::string out_dir;                     //!< --out DIR; empty: compare-<spec name> in the current directory
  std::string html_path;                   //!< --html: the comparison as one self-contained HTML file
  bool json = false;                       //!< --json: print compare.json's content instead of the table
};

//! Registers the subcommand.
void add_compare_command(CLI::App& app, CompareOptions& options);

//! Runs it: 0 done, 1 failed (no model for the spec, an output not written); throws InputError on bad input
//! before anything runs or is written.
int run_compare_command(const CompareOptions& options);

}  // namespace feedplan::cli
