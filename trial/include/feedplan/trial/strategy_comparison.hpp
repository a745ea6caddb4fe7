#pragma once
// Strategies for holding a force on one cycle, compared on one virtual machine (`feedplan compare`): the
// table a process engineer asks for before trusting a feed-forward plan. Every row runs its program on the
// same machine and is judged the same way — on the machine's true per-revolution peaks of |F_xy|, which no
// strategy sees (control_judgement.hpp). The rows, in order:
//
//   constant feed        the cycle at one F on every feed move (planner::constant_feed_program);
//   feed-forward, 1      the plan from the given settings (the database model, as `feedplan plan` makes it);
//   feed-forward, N      cycle N of the learning loop (learning_loop.hpp) started from those settings: the
//                        loop runs cycles 1 … N − 1 (plan → cut → learn), and the plan it would cut next is
//                        cycle N's;
//   feedback alone       each controller asked for (feedback_controller.hpp) on the constant-feed program,
//                        reading the dynamometer's per-revolution peak, the override within 10–150 %;
//   hybrid, 1            the robust servo trimming the cycle-1 plan's program within 70–130 %
//                        (override_control.hpp, hybrid_override_settings);
//   hybrid, N            the same on the cycle-N plan's program (when asked for).
//
// Each program reaches the machine as the request's `as_received` gives it — the G-code text a post writes,
// read back, as a real machine receives it — so that a row equals running the same program alone (`feedplan
// simulate`, `feedplan plan --simulate`). The learning loop itself cuts its cycles 1 … N − 1 as it always
// does (the plan's program in memory).
//
// The rows are independent runs and are spread over the machine's cores (core/parallel_tasks.hpp): the loop
// and the learned rows on one thread, the other rows on the others; the figures do not depend on how many.

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "feedplan/geometry/program.hpp"
#include "feedplan/model/covariance.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/trial/control_judgement.hpp"
#include "feedplan/trial/feedback_controller.hpp"
#include "feedplan/trial/learning_loop.hpp"
#include "feedplan/trial/virtual_machine_run.hpp"

namespace feedplan::trial {

//! How a row holds the force.
enum class StrategyKind {
  kConstantFeed,  //!< one F on every feed move
  kFeedForward,   //!< a plan's program, the plan from the model (cycle 1) or after learning (cycle N)
  kFeedback,      //!< a feedback controller on the constant-feed program's override
  kHybrid,        //!< the robust servo trimming a plan's program's override
};

//! The kind's name in the JSON output: "constant-feed", "feed-forward", "feedback", "hybrid".
std::string_view to_string(StrategyKind kind);

//! Every controller, in kControllerNames' order: the feedback rows `feedplan compare` runs.
std::vector<ControllerKind> all_controllers();

//! What to compare.
struct ComparisonRequest {
  planner::PlanGeometry geometry;  //!< path, tool and engagement (analysed once)
  //! The cycle-1 plan's settings: model, target, spindle, machine limits, options (as `feedplan plan` plans);
  //! the learning loop starts from them.
  planner::PlanSettings settings;
  VirtualMachine machine;  //!< the one machine every row runs on (its override loop, log sink and progress unused)
  double constant_feed_mm_per_min = 0.0;  //!< F of the constant-feed program, mm/min (finite, > 0)
  //! A program as the machine receives it (e.g. written as G-code and read back); empty: as given. Called
  //! from several threads at once: it must not share what it writes.
  std::function<geometry::Program(const geometry::Program&)> as_received;
  int learning_cycles = 3;  //!< N, the learned row's cycle (≥ 2: at least one cycle learned from)
  //! Where the learning loop starts when not from `settings` (a plan of the mechanistic kind: the loop learns
  //! the response surface, as `feedplan loop` does); none: from `settings`.
  std::optional<planner::PlanSettings> learning_settings;
  //! The loop's cautious first cut (LoopRequest::first_cut_uncertainty; 0: off) and its z.
  double first_cut_uncertainty = 0.0;
  double sigmas = 2.0;                    //!< z of the loop's cautious bound
  model::Covariance start_fit_covariance; //!< the starting model's fit covariance, N² (the loop's cautious bound)
  std::vector<ControllerKind> controllers = all_controllers();  //!< the feedback rows, in this order
  bool hybrid_on_learned = true;  //!< also the hybrid on the cycle-N plan
  //! Called with the fraction of the rows done (0..1), one call at a time, from any thread; may be empty.
  std::function<void(double)> progress;
};

//! Every problem with the request's own numbers (constant feed, cycles, target), each named
//! "<field_prefix><field>" with its value and the rule. Empty when usable.
std::vector<InputProblem> validate(const ComparisonRequest& request, const std::string& field_prefix = "comparison.");

//! One strategy run and judged.
struct StrategyRow {
  StrategyKind kind = StrategyKind::kConstantFeed;  //!< how it holds the force
  std::string name;                                 //!< in words, e.g. "feedback alone: robust-servo"
  std::optional<ControllerKind> controller;         //!< the feedback or hybrid rows' controller
  int plan_cycle = 0;                 //!< the learning cycle whose plan ran (1, or N); 0: no plan
  double planned_cycle_time_s = 0.0;  //!< that plan's own prediction, s (0: no plan)
  planner::PlanStatus plan_status = planner::PlanStatus::kOk;  //!< that plan's status (kOk without a plan)
  ControlJudgement judgement;         //!< the true per-revolution peaks against the target
  std::vector<force_log::RevolutionPeak> revolutions;  //!< the true per-revolution peaks, on the run's clock
  int controller_steps = 0;           //!< the controller's steps in cut (feedback and hybrid rows)
  std::vector<std::string> warnings;  //!< the simulation's warnings
};

//! The comparison.
struct StrategyComparison {
  double target_force_n = 0.0;            //!< the target every row is judged against, N
  double constant_feed_mm_per_min = 0.0;  //!< F of the constant-feed rows, mm/min
  int learning_cycles = 0;                //!< N
  std::vector<StrategyRow> rows;          //!< in the order of the file comment
  //! The loop's cycles 1 … N − 1 as the loop reports them (its own runs, the programs in memory).
  std::vector<LoopCycle> learning;
};

//! Runs every row of the file comment. Throws InputError with validate()'s problems, and as
//! run_learning_loop, run_under_control and simulate_on do (invalid settings, an invalid machine).
StrategyComparison compare_strategies(const ComparisonRequest& request);

}  // namespace feedplan::trial
