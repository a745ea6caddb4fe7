#pragma once
// What `feedplan plan` prints: the human summary (stdout), the JSON summary (--json), and the plan's
// notes and the virtual machine's warnings (stderr). The summary says how the model matches (exact or
// borrowed, and the caution that buys), leads the virtual machine's part with the largest
// per-revolution peak anywhere and where it is, and quotes the time saved only against labelled
// baselines: the spec's feed, the constant feed with the plan's predicted peak (the model's), and with
// --simulate the constant feed with the plan's simulated peak (found on the virtual machine).

#include "plan_outcome.hpp"

namespace feedplan::cli {

//! The summary for people, on stdout.
void print_plan_text(const PlanCommandOptions& o, const PlanInputs& in, const PlanModel& model,
                     const PlannedCycle& planned, const PlanOutputs& outputs);

//! The summary as JSON, on stdout.
void print_plan_json(const PlanCommandOptions& o, const PlanInputs& in, const PlanModel& model,
                     const PlannedCycle& planned, const PlanOutputs& outputs);

//! The virtual machine's warnings and the plan's notes, on stderr.
void print_plan_notes(const planner::PlanResult& result, const PlanOutputs& outputs);

//! "ok, model exact" / "ok, model borrowed (planned cautiously, r = 0.125)": the plan's status with the
//! model match, as the status line and the report say it.
std::string plan_status_text(const planner::PlanResult& result, const PlanModel& model);

}  // namespace feedplan::cli
