#pragma once
// `feedplan learn PLAN.json LOG.csv [LOG2.csv …] -o NEXT.nc [--db PATH] [--report NEXT.json] [--plot NEXT.svg]`:
// the force logs of parts cut with a plan refit its model (RLS and a robust batch refit with a prior),
// the result is stored as a new model version with lineage, a learning entry and the per-revolution
// samples (one transaction), and the cycle is re-planned with it. The batch refit spans these logs and
// every sample stored by earlier learning steps of the same tool and material.

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "sensor_flags.hpp"

namespace feedplan::cli {

struct LearnOptions {
  std::string plan_path;               //!< the plan report the logs were cut with
  std::vector<std::string> log_paths;  //!< force logs (feedplan CSV or Kistler DynoWare)
  std::string program_path;            //!< -o: the re-planned program
  std::string db_path;                 //!< --db
  std::string report_path;             //!< --report: the re-planned plan's report
  std::string plot_path;               //!< --plot
  std::string html_path;               //!< --html: the re-planned plan and the learning history as one HTML file
  std::string note;                    //!< --note: stored with the new version
  std::string calibration_path;        //!< --calibration: turns current-only logs into force logs
  SensorFlags sensor;                  //!< --sensor-hz, --sensor-damping
  bool json = false;                   //!< --json
};

//! Registers the subcommand.
void add_learn_command(CLI::App& app, LearnOptions& options);

//! Runs it: 0 learned and re-planned; 1 failed (no usable sample in the logs; the database unchanged);
//! throws InputError (exit 2) on bad input — unreadable files, a log of another program or in inches —
//! before anything is written.
int run_learn_command(const LearnOptions& options);

}  // namespace feedplan::cli
