#pragma once
// The feed planner (seed 003 §2, docs/method.md §5.3, §5.5): the engagement along a path + a force model +
// a target force + the machine's limits → a program whose F words hold the predicted force at the
// target, with a prediction of what the machine will do and the constant-feed baseline.
//
// The method, step by step (each step's rule is in the file named):
//   1. Feed limit per sample (feed_limit.hpp): the feed at which the model predicts the target, capped by
//      the machine's feed range and the centripetal limit on arcs; air at the air feed.
//   2. Command profile: the greatest profile under those limits and the path acceleration limit
//      (speed_profile.hpp; no stops — the controller makes those itself).
//   3. Blocks (block_split.hpp): each feed move cut into stretches of constant F, F ≤ the profile's
//      smallest value inside (default mode), merged while the profile stays within the merge tolerance
//      (but a block ends where a new minimum would cost it more time than one block lasts, so a long
//      plateau keeps its own F when a descent follows), lasting at least the controller's block time
//      (whole moves may be shorter); F rounded DOWN to the feed resolution; then a pass
//      over the blocks so that every change of F between neighbours can be made inside the faster of the
//      two at the acceleration limit (the controller model below).
//   4. Prediction (controller_model.hpp): how a look-ahead controller runs the blocks, the force the
//      model predicts at the feed actually run, and the cycle time.
//   5. Baseline (PlanSummary::baseline; the program itself: constant_feed.hpp): the one feed with the
//      same predicted peak force, its cycle time and the time saved.
//
// Controller model (what "the machine runs" means in every prediction and test):
//   - each feed block runs at most at its F (and at most at √(a·R) on arcs of radius R), rapids at the
//     rapid rate;
//   - the path speed changes at most at the acceleration limit a, with look-ahead over all blocks, so the
//     machine has slowed down before a slower block starts — the greatest profile under these caps;
//   - the machine stops (exact stop) at the start and end, where rapids and feed moves meet, and at
//     junctions whose tangent turns by more than kTangentJunctionToleranceRad (the virtual machine's
//     junction-deviation rule rounds such corners at a small speed; stopping is the conservative bound);
//   - a controller without look-ahead still meets the force target with these programs: step 3 makes
//     every F change feasible within the faster block (it decelerates at the end of a fast block and
//     accelerates at the start of the next fast one).

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/geometry/machine_limits.hpp"
#include "feedplan/geometry/engagement.hpp"
#include "feedplan/geometry/straight_cut_loads.hpp"
#include "feedplan/geometry/program.hpp"
#include "feedplan/geometry/stock.hpp"
#include "feedplan/geometry/tool.hpp"
#include "feedplan/geometry/tool_path.hpp"
#include "feedplan/model/mechanistic_model.hpp"
#include "feedplan/model/response_surface_model.hpp"
#include "feedplan/planner/force_bound.hpp"

namespace feedplan::planner {

//! Junctions whose tangents turn by at most this angle are tangent-continuous (no stop), rad.
inline constexpr double kTangentJunctionToleranceRad = 1e-6;

//! How block F values are chosen from the command profile.
enum class PlanMode {
  //! F is at most the smallest limit inside the block: the predicted force never exceeds the target.
  kSafe,
  //! F is the length-weighted mean of the command profile over the block: the predicted force tracks
  //! the target more closely and may exceed it by what a feed change of the merge tolerance causes
  //! (≤ 2 % in feed by default, so ≤ about 2 % in force).
  kRegulate,
};

//! "safe", "regulate".
std::string to_string(PlanMode mode);

//! Planner settings beyond the machine limits.
struct PlanOptions {
  PlanMode mode = PlanMode::kSafe;      //!< how block F values are chosen
  //! Feed for feed moves through air and for cutting moves where no tooth engages, mm/min; 0: the
  //! machine's maximum feed (seed 003 shortened the air cuts the same way).
  double air_feed_mm_per_min = 0.0;
  double merge_tolerance = 0.02;        //!< relative spread of the command profile merged into one block, in [0, 0.5]
  double feed_resolution_mm_per_min = 1.0;  //!< F is rounded down to a multiple of this, mm/min, in (0, 100]
  //! Controller-friendly blocks, in [0, 0.5]; 0: off. Above 0, step 3 cuts the blocks from the feed limits
  //! of step 1 instead of the command profile — the acceleration ramps are the controller's look-ahead's
  //! to make, not F words — with every F rounded DOWN onto the geometric grid max_feed·(1 + feed_step)^−k
  //! (a few levels, so small changes of the limit change no F), and each block lasting at least
  //! min_block_duration_s (whole moves may be shorter): fewer, longer blocks, every F still at most the
  //! smallest limit inside its block.
  double feed_step = 0.0;
  //! Shortest block of the controller-friendly rule, s (at most 1 / this many F changes per second); the
  //! machine's block time when larger. In [0, 10].
  double min_block_duration_s = 0.1;
  //! Path jerk limit, mm/s³; 0: none. Heuristic (documented in feed_plan.cpp): the passes use the
  //! acceleration a_eff = a·Δv/(Δv + a²/J) that an S-curve reaches over a speed change Δv, taken for the
  //! largest speed change of the plan — conservative for that change, approximate for smaller ones.
  double jerk_limit_mm_per_s3 = 0.0;
  //! Engagement sample spacing the geometry was analysed at, mm: plan() works on the samples it is given;
  //! the report records this so a re-plan (learning) analyses the path at the same spacing.
  double ds_mm = 0.05;
  //! Resolution the program's coordinates are written with, mm (10^−decimals): rounding each end of a
  //! move can steepen a short descent by up to this much, so the plunge limit is held for the descent
  //! plus it (feed_limit.hpp); 0: the program is run as planned, unrounded. In [0, 0.1].
  double coordinate_resolution_mm = 0.001;
  //! Largest chip thickness t_m a feed may cut, mm; 0: none. A model predicts forces, not whether an edge
  //! chips or a flute packs: beyond the chips its cutting tests saw the planner does not go, whatever the
  //! force. Held like the response surface's fitted chip range (FeedLimitReason::kModelRange); callers
  //! planning with the mechanistic kind set it (the response surface holds its own range).
  double max_chip_thickness_mm = 0.0;
};

//! The controller-friendly blocks `feedplan plan` and `feedplan optimize` write by default (PlanOptions::
//! feed_step and min_block_duration_s): F levels 2 % apart and blocks of at least 6 ms — at most 167 F
//! changes a second. On the bundled samples they cost 0.1–1.0 % of cycle time against blocks that write
//! every acceleration ramp out, with a third fewer lines and a fifth of the distinct F values.
inline constexpr double kControllerFriendlyFeedStep = 0.02;
inline constexpr double kControllerFriendlyMinBlockS = 0.006;  //!< see kControllerFriendlyFeedStep

//! Everything about the path that does not depend on the feed: computed once, planned many times.
struct PlanGeometry {
  geometry::ToolPath path;                  //!< the tool-centre path (moves, parts)
  geometry::Stock stock;                    //!< the material before the path (what the safety check cuts)
  geometry::Tool tool;                      //!< the end mill
  geometry::EngagementProfile engagement;   //!< engagement along the path (docs/method.md §5.1–5.2)
  //! geometry::peak_chip_load_mm of every engagement sample (0 where it has no layers): geometric, so
  //! computed once for all plans of the path. plan() computes it again when it is empty or
  //! `straight_cuts` is not for `tool`; clear both when changing `engagement`.
  std::vector<double> peak_chip_load_mm;
  //! The straight cuts' peak chip loads for `tool` the plans of this path asked for (made by analyse;
  //! null: each plan finds its own).
  std::shared_ptr<geometry::StraightCutLoads> straight_cuts;
};

//! Computes the engagement of `tool` along `path` on `stock` at `ds_mm` (geometry::compute_engagement).
//! Throws InputError when ds_mm is not in (0, 5] or the path is inconsistent.
PlanGeometry analyse(const geometry::ToolPath& path, const geometry::Stock& stock, const geometry::Tool& tool,
                     double ds_mm = 0.05);

//! What the plan is asked to do.
struct PlanSettings {
  //! The response surface F̂(t_m, L) (seed 003 Eq. 1): the force model unless `mechanistic` is set, when
  //! only its fitted range (the tests') is read.
  model::ResponseSurfaceModel model;
  //! The mechanistic model (cutting and edge coefficients, runout, helix): when set, the planner predicts
  //! the force with the kernel on every sample's engaged arcs instead (sample_force_model.hpp).
  std::optional<model::MechanisticModel> mechanistic;
  double target_force_n = 0.0;           //!< per-revolution peak XY force to hold, N (> 0)
  double spindle_rpm = 0.0;              //!< spindle speed, rev/min (> 0)
  geometry::MachineLimits machine;         //!< feed range, acceleration, rapid rate, block time
  PlanOptions options;                   //!< mode, air feed, merging, resolution, jerk
  //! When set, the cautious plan: the upper bound F̂ + z·σ is held at the target (force_bound.hpp).
  std::optional<ForceUncertainty> uncertainty;
  //! Iterative learning along this very path: per engagement sample, the measured / model force ratio
  //! earlier cycles of the same program showed there (learning/path_correction.hpp); the planner uses
  //! F̂ · c. Empty: 1 everywhere. Where the geometry leaves the straight-cut data a response surface is
  //! fitted on (entries into material), the model alone cannot be right; repeated parts can.
  std::vector<double> force_correction;
};

//! The range of PlanSettings::force_correction values (outside, more likely a bad measurement than physics).
inline constexpr double kMinForceCorrection = 0.2;
inline constexpr double kMaxForceCorrection = 5.0;  //!< see kMinForceCorrection

//! Every problem with the settings (model via model::validate as "model.…", "target_force_n",
//! "spindle_rpm", "machine.…", "options.…"), with the value and the allowed range; empty when valid.
//! Also checks them against the geometry's tool (flutes ≥ 1).
std::vector<InputProblem> validate(const PlanSettings& settings, const geometry::Tool& tool);

//! Overall outcome of a plan (the worst that happened anywhere).
enum class PlanStatus {
  kOk,             //!< the target is held wherever the model binds, inside the model's fitted range
  kExtrapolated,   //!< somewhere the feed comes from the model outside its fitted range (t_m, L or axial depth)
  kTargetNotMet,   //!< somewhere even the minimum feed is predicted above the target: planned at the minimum feed
  //! the safety check (safety_check.hpp) found a feed move of the program running above the feed its
  //! engagement allows, or a rapid through material: no program may be written
  kUnsafe,
};

//! "ok", "extrapolated", "target not met", "unsafe".
std::string to_string(PlanStatus status);

//! What limits the feed at a sample.
enum class FeedLimitReason {
  kForce,        //!< the force target (the model)
  kModelRange,   //!< the model's fitted t_m range (the target needs a larger chip than the model has seen)
  kMaxFeed,      //!< the machine's maximum feed
  kCentripetal,  //!< v² ≤ a·R on an arc
  kAirFeed,      //!< no engagement: the air feed
  kMinFeed,      //!< the target would need less than the machine's minimum feed: the minimum feed
  kRapid,        //!< a rapid move (G0)
  kPlunge,       //!< the tool's plunge feed per tooth while descending into material
};

//! "force", "model range", "max feed", "centripetal", "air", "min feed", "rapid", "plunge".
std::string to_string(FeedLimitReason reason);

//! One engagement sample with its plan.
struct PlannedSample {
  double s_mm = 0.0;                    //!< arc length from the start of the path, mm
  geometry::Point3 position;            //!< tool tip, mm
  int move_index = 0;                   //!< move of the input path
  int block_index = -1;                 //!< block (PlanResult::blocks) the sample starts or lies in
  bool engaged = false;                 //!< a cutting move with some tooth in the material
  double engagement_rad = 0.0;          //!< α_en, rad
  double chip_factor = 0.0;             //!< k = t_m / f_z (XY feed per tooth), in [0, 1]
  double contact_length_mm = 0.0;       //!< L = r α_en, mm
  double axial_depth_mm = 0.0;          //!< axial depth of cut, mm
  double load_ratio = 0.0;              //!< C / C_ref of the chip-load transfer (feed_limit.hpp), 0: none
  //! force_transfer_factor at the speed run here (feed_limit.hpp): predicted force over the straight-cut
  //! model's own F̂(t_m, max(L, L_min)), before the force correction (1 where not engaged)
  double transfer_factor = 1.0;
  double feed_limit_mm_per_min = 0.0;   //!< the feed limit of step 1, mm/min
  FeedLimitReason limit_reason = FeedLimitReason::kAirFeed;  //!< what sets feed_limit_mm_per_min
  bool extrapolated = false;            //!< the force model is used outside its fitted range here
  double command_feed_mm_per_min = 0.0; //!< the command profile of step 2, mm/min
  double block_feed_mm_per_min = 0.0;   //!< F of the block the sample lies in (0 on rapids), mm/min
  double feed_mm_per_min = 0.0;         //!< predicted path speed the machine runs here, mm/min
  double chip_thickness_mm = 0.0;       //!< t_m at that speed, mm
  double predicted_force_n = 0.0;       //!< F̂ at that speed, N (0 where not engaged)
  double upper_force_n = 0.0;           //!< F̂ + z·σ at that speed with PlanSettings::uncertainty, else F̂, N
  //! t_m at that speed and L both inside the model's fitted range (false where not engaged): the
  //! prediction interpolates the cutting tests the model was fitted on.
  bool within_model_range = false;
  double time_s = 0.0;                  //!< predicted time from the program start, s
};

//! One block of the program: a stretch of one input move with one F.
struct PlannedBlock {
  int move_index = 0;                 //!< the input move it is part of
  int first_sample = 0;               //!< sample at its start
  int last_sample = 0;                //!< sample at its end
  double feed_mm_per_min = 0.0;       //!< programmed F, mm/min (0 for rapids)
  double length_mm = 0.0;             //!< length in space, mm
  double min_limit_mm_per_min = 0.0;  //!< smallest feed limit of step 1 inside it, mm/min
  double duration_s = 0.0;            //!< predicted time to run it, s
};

//! The constant-feed program a CAM programmer would otherwise run: the single F with the same
//! predicted peak force as the plan.
struct ConstantFeedBaseline {
  double feed_mm_per_min = 0.0;        //!< its F on every feed move, mm/min
  double peak_force_n = 0.0;           //!< largest predicted force at that feed, N
  double cycle_time_s = 0.0;           //!< predicted cycle time, s
  double cutting_time_s = 0.0;         //!< time on cutting moves, s
};

//! Totals of a plan.
struct PlanSummary {
  double cycle_time_s = 0.0;           //!< predicted program duration, s
  double cutting_time_s = 0.0;         //!< predicted time on cutting moves, s
  double air_time_s = 0.0;             //!< predicted time on rapids and air feed moves, s
  double max_predicted_force_n = 0.0;  //!< largest predicted force, N
  double min_feed_mm_per_min = 0.0;    //!< smallest block F, mm/min
  double max_feed_mm_per_min = 0.0;    //!< largest block F, mm/min
  ConstantFeedBaseline baseline;       //!< the constant-feed program with the same peak force
  double time_saved_percent = 0.0;     //!< (baseline − planned) / baseline × 100
  int engaged_samples = 0;             //!< samples with some tooth in the material
  int force_limited_samples = 0;       //!< samples whose limit is the force target
  int extrapolated_samples = 0;        //!< samples where the model extrapolates and sets the feed
  int over_target_samples = 0;         //!< samples predicted above the target (min feed reached)
  int short_blocks = 0;                //!< blocks shorter than the block time (whole short moves)
  double accel_used_mm_per_s2 = 0.0;   //!< acceleration the passes used (a, or a_eff with a jerk limit)
};

//! A plan.
struct PlanResult {
  PlanStatus status = PlanStatus::kOk;   //!< the worst outcome anywhere
  std::vector<std::string> messages;     //!< one sentence per thing a user must know (with s and x, y)
  geometry::Program program;             //!< the blocks as moves with F, spindle M3 at the settings' rpm
  std::vector<PlannedSample> samples;    //!< one per engagement sample
  std::vector<PlannedBlock> blocks;      //!< one per program move
  PlanSummary summary;                   //!< totals
};

//! Plans the feeds for `geometry` under `settings` (the method at the top of this file). Throws
//! InputError with every problem validate() finds. Every other outcome — target not met, model
//! extrapolating — is a status with messages in the result, never an exception. Deterministic; linear
//! in the number of samples.
PlanResult plan(const PlanGeometry& geometry, const PlanSettings& settings);

//! The predicted speed the machine runs at each sample of `result` (PlannedSample::feed_mm_per_min), mm/min.
std::vector<double> sample_feeds_mm_per_min(const PlanResult& result);

}  // namespace feedplan::planner
