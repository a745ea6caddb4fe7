#pragma once
// The HTML reports the commands write (report/plan_page.hpp, comparison_page.hpp) from what each command
// knows: `plan --html` from the plan it just made, `report` from a plan report read back (and the plan
// re-made from it), `loop --html` from the loop's cycles, `compare --html` and `report` from compare.json.

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "plan_outcome.hpp"
#include "feedplan/planner/plan_report.hpp"
#include "feedplan/report/plan_page.hpp"

namespace feedplan::cli {

//! The page of `plan --html`: the summary with the model's match and caution, the plan's notes and the
//! virtual machine's warnings, and with --simulate its per-revolution peaks as the measured force.
report::PlanPage plan_command_page(const PlanInputs& in, const PlanModel& model, const PlannedCycle& planned,
                                   const PlanOutputs& out);

//! The page of a plan report (`report`, `learn --html`): `plan` is the plan re-made from it; the measured
//! force and the learning history come from its path_learning, when it has one.
report::PlanPage plan_report_page(const planner::PlanReport& report, const planner::PlanResult& plan,
                                  const std::string& source_name);

//! The comparison page from compare.json's document (comparison_report.hpp); `source_name` names it in
//! errors. Throws InputError naming the field when the document lacks what the page shows.
std::string comparison_page_html(const nlohmann::json& comparison, const std::string& source_name);

}  // namespace feedplan::cli
