#pragma once
// The demo a user runs before trusting feedplan on a machine (`feedplan loop`): plan → cut on the
// virtual machine → learn from its force log → re-plan, N times, from a model that is deliberately
// wrong for the machine's true physics. Per cycle: the per-revolution force error against the target
// and the cycle time.

#include <functional>
#include <optional>
#include <vector>

#include "feedplan/model/covariance.hpp"
#include "feedplan/learning/infeasible_places.hpp"
#include "feedplan/learning/model_update.hpp"
#include "feedplan/learning/sensor_dynamics.hpp"
#include "feedplan/trial/virtual_machine_run.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/planner/path_history.hpp"

namespace feedplan::trial {

//! What to loop.
struct LoopRequest {
  planner::PlanGeometry geometry;     //!< path, tool and engagement (analysed once)
  planner::PlanSettings settings;     //!< the starting model, target, spindle, machine limits, options
  VirtualMachine machine;             //!< the true physics the cycles are cut with
  int cycles = 3;                     //!< repetitions (≥ 1)
  //! Cautious first cut: plan on F̂ + z·σ with the starting model's fit covariance and this relative
  //! uncertainty r (planner::ForceUncertainty); later cycles use the refit's covariance alone. 0: off.
  double first_cut_uncertainty = 0.0;
  double sigmas = 2.0;                //!< z of the cautious bound
  model::Covariance start_fit_covariance;         //!< the starting model's own fit covariance, N²
  learning::ModelUpdateOptions update;          //!< how to learn
  //! Also learn along the path: the next plan scales the model by a correction per place, learned per
  //! tooth period (path_correction.hpp) — what repeated parts of one program allow beyond the model.
  bool path_correction = true;
  //! The force sensor's first mode as its owner knows it (a tap test): peaks are corrected for it before
  //! anything learns from them (learning/sensor_dynamics.hpp). None: taken as read.
  std::optional<learning::SensorDynamics> sensor;
  //! The tool's mechanistic model (the database's, from cutting tests): with a sensor, the shape of the
  //! force where the engagement is steady, for the sensor's factor there (learning::SensorKernel). None: the
  //! chip's shape everywhere.
  std::optional<model::MechanisticModel> sensor_kernel;
  //! Called after each cycle with its number (1-based); may be empty.
  std::function<void(int)> on_cycle_done;
  //! Called with the fraction of the whole loop done (0..1) while the virtual machine cuts and after
  //! each cycle's learning; may be empty.
  std::function<void(double)> progress;
};

//! One cycle.
struct LoopCycle {
  int cycle = 0;                          //!< 1-based
  planner::PlanStatus plan_status = planner::PlanStatus::kOk;  //!< the plan's status
  double planned_cycle_time_s = 0.0;      //!< the plan's prediction, s
  double simulated_cycle_time_s = 0.0;    //!< on the virtual machine, s
  planner::PeakComparison comparison;     //!< true per-revolution peaks against the target
  learning::PredictionErrors model_errors_before;   //!< the model it was planned with, on this cycle's samples
  learning::PredictionErrors model_errors_after;    //!< the learned model, on the same samples
  learning::ModelUpdateStatus update_status = learning::ModelUpdateStatus::kNoEvidence;  //!< whether learning gave a model
  learning::InfeasiblePlaces infeasible;  //!< revolutions the log shows above the target at the minimum feed
  std::vector<std::string> messages;      //!< plan and learning messages
  model::ResponseSurfaceModel model_used;  //!< the model the cycle was planned with
};

//! The whole loop.
struct LoopResult {
  std::vector<LoopCycle> cycles;             //!< in order
  model::ResponseSurfaceModel final_model; //!< after the last cycle's learning
  model::Covariance final_covariance;         //!< its covariance, N²
  //! Learning along the path cycle by cycle (the newest planner::kPathHistoryCycles; empty without it).
  std::vector<planner::PathHistoryCycle> history;
  planner::PlanSettings next_settings;  //!< what the part after the last cycle would be planned with
};

//! Runs the loop. Throws InputError on invalid settings (planner::validate) or cycles < 1.
LoopResult run_learning_loop(const LoopRequest& request);

}  // namespace feedplan::trial
