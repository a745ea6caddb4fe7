#pragma once
// `feedplan cycle SPEC.yaml [--ds MM] [--engagement OUT.csv] [--json]`: generate a canned cycle from
// its spec, compute the engagement along it, print a summary, optionally write the profile.

#include <CLI/CLI.hpp>

#include <string>

namespace feedplan::cli {

struct CycleOptions {
  std::string spec_path;        //!< the cycle spec (YAML)
  double ds_mm = 0.05;          //!< engagement sample spacing, mm
  std::string engagement_path;  //!< CSV output; empty = do not write
  bool json = false;            //!< print the summary as JSON instead of text
};

//! Registers the subcommand; `run` is called when it was given.
void add_cycle_command(CLI::App& app, CycleOptions& options);

//! Runs the command. Returns the exit code (0 ok, 1 failed, 2 bad input); messages go to stderr.
int run_cycle_command(const CycleOptions& options);

}  // namespace feedplan::cli
