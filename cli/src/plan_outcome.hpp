#pragma once
// What `feedplan plan` read, chose, planned and wrote: the steps' results, shared by the command
// (plan_command.cpp), its baselines (plan_baselines.hpp) and its summary (plan_summary.hpp).

#include <optional>
#include <string>
#include <vector>

#include "model_choice.hpp"
#include "plan_command.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec.hpp"
#include "feedplan/gcode/writer.hpp"
#include "feedplan/planner/constant_feed.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/planner/target_sweep.hpp"
#include "feedplan/planner/target_advice.hpp"
#include "feedplan/trial/constant_feed_trial.hpp"
#include "feedplan/trial/plan_check.hpp"

namespace feedplan::cli {

//! What the user asked for, every flag checked.
struct PlanInputs {
  cycles::CycleSpec spec;                             //!< the cycle spec
  planner::PlanMode mode = planner::PlanMode::kSafe;  //!< --mode
  double target_force_n = 0.0;                        //!< --target-force, else the spec's, N
  gcode::WriterOptions writer;                        //!< --dialect and the format flags (no header yet)
  std::optional<planner::TargetRange> sweep;          //!< --target-sweep, when given
};

//! The model to plan with, the database it came from, and the caution it is planned with.
struct PlanModel {
  std::string db_path;             //!< --db, else $FEEDPLAN_DB, else the sample database: absolute, canonical
  ChosenModel chosen;              //!< the model, why, and how far it is borrowed
  double relative_uncertainty = 0.0;  //!< r of the cautious bound (0: planned on the model alone)
  bool uncertainty_requested = false;  //!< r came from --cautious (else from the borrowing)
  //! The mechanistic version planned with instead of the response surface (same tool and material).
  std::optional<model_db::ModelRecord> mechanistic;
  std::string kind_reason;  //!< which kind plans, and why, for people
  double max_chip_thickness_mm = 0.0;  //!< PlanOptions::max_chip_thickness_mm (model_kind_choice.hpp)
};

//! The cycle, its plan and how long engagement and planning took.
struct PlannedCycle {
  cycles::Cycle cycle;              //!< path and stock
  planner::PlanGeometry geometry;   //!< the engagement along the path
  planner::PlanSettings settings;   //!< what the plan was asked to do
  planner::PlanResult result;       //!< the plan
  double analyse_s = 0.0;           //!< wall time of the engagement analysis, s
  double plan_s = 0.0;              //!< wall time of the planning, s
  //! With controller-friendly blocks: the cycle time of the same plan with every acceleration ramp
  //! written out (PlanOptions::feed_step 0), s — what the coarser blocks cost.
  std::optional<double> ramps_written_out_s;
};

//! Which program is written: the plan's when the target can be met everywhere, or the constant-feed one.
struct ProgramChoice {
  bool planned = false;   //!< the plan's program
  bool constant = false;  //!< --constant-feed: the constant-feed program instead
  bool any() const { return planned || constant; }
};

//! The baselines the plan's time is quoted against, each labelled by where its feed comes from.
struct PlanBaselines {
  //! The spec's feed_mm_per_min (the feed a CAM programmer would use), predicted by the controller model.
  std::optional<planner::ConstantFeedPrediction> spec_feed;
  //! --simulate: the spec's feed on the virtual machine.
  std::optional<trial::ConstantFeedRun> spec_feed_simulated;
  //! --simulate: the constant feed whose simulated largest peak equals the plan's, and how it was found.
  std::optional<trial::EqualPeakFeed> equal_simulated_peak;
};

//! What the outputs step did.
struct PlanOutputs {
  ProgramChoice program;                  //!< which program was written
  std::optional<trial::PlanCheck> check;  //!< --simulate: the program run on the virtual machine
  PlanBaselines baselines;                //!< what the time saving is quoted against
  std::vector<std::string> written;       //!< the files written, in order
  std::vector<std::string> kept;          //!< existing files a failed plan left as they were
};

//! The plan `feedplan plan` makes for a spec with its default flags, and how it writes the program: what
//! another command (`feedplan compare`) runs as "the plan", so that its figures are `plan`'s.
struct PlanAsWritten {
  PlanInputs inputs;             //!< the spec, the target, the writer's format (linuxcnc, 3 decimals)
  PlanModel model;               //!< the model chosen, its kind and caution, as `plan` chooses them
  PlannedCycle planned;          //!< the cycle, its engagement, the settings and the plan
  gcode::WriterOptions writer;   //!< the options the plan's program is written with (header comments included)
};

//! What `feedplan plan SPEC_PATH [--db DB_PATH] [--target-force N]` plans for `spec` (read from
//! `spec_path`), without writing or simulating anything. Nothing, after saying why on stderr, when the
//! database has no model for the spec; throws as `plan` does for a database or model it cannot use.
std::optional<PlanAsWritten> plan_as_written(const std::string& spec_path, const cycles::CycleSpec& spec,
                                             double target_force_n, const std::string& db_path);

}  // namespace feedplan::cli
