#pragma once
// Seed 004's milling force controller (Rubio & De la Sen 2007, "Discrete-time model reference control
// schemes of milling forces using fractional order holds", IECON 2007): model-following control of the
// peak force on a known milling plant (milling_plant.hpp), sampled once per spindle revolution behind a
// fractional-order hold whose gain β a supervisor chooses among several discrete models.
//
// Two levels (§IV):
//   basic control — for each β considered, the plant and the reference model (reference_model.hpp) are
//     discretised behind the β-FROH (froh_discretisation.hpp) and the model-following law R, S, T designed
//     (model_reference_design.hpp);
//   choice of β — each β's tracking index (Eq. 10, tracking_index.hpp) over the last M + 1 periods ranks
//     them, and scheme 1 or 2 (beta_switching.hpp) picks the active one, at most once per residence time.
//
// How a model's index is computed. Seed 004 says the control "at the previous time instant is applied to
// the above scheme by calculating the output of all the continuous time models" and compares those outputs
// with the reference. Read here as: for each period j of the window and each candidate β, the candidate's
// own law (Eq. 9) computes the command from the forces and commands actually seen up to jT, and the known
// continuous plant, started from its state at jT, is driven over the period by the candidate's β-FROH; the
// period's term is ∫ |F_m − F_p,β| dt, F_m being the continuous reference model's answer to the reference
// force (a step at the first sample, the plant starting at rest). The plant being known (seed 004: "the
// milling system model is perfectly characterized"), its state is that of a copy of the continuous model
// driven by the commands applied; the depth of cut is told to the controller when it changes
// (set_depth_of_cut_mm, "varied in a known way") and every model is redesigned for it.
//
// The active model's law gives f_c,k from F_p,k; the feed is commanded as an override of the programmed
// feed, within the override range (which the paper does not have: keep it wide enough not to bind, or the
// loop is no longer the designed one). The β-FROH then ramps the feed over the period: the machine applies
//   f(kT + τ) = f_c,k + β (f_c,k − f_c,k−1) τ/T,
// what held_feed_mm_per_s() gives; step() returns the ratio at the sample.

#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "feedplan/control/beta_switching.hpp"
#include "feedplan/control/held_system_simulator.hpp"
#include "feedplan/control/milling_plant.hpp"
#include "feedplan/control/model_reference_design.hpp"
#include "feedplan/control/override_range.hpp"
#include "feedplan/control/reference_model.hpp"
#include "feedplan/core/input_error.hpp"

namespace feedplan::control {

//! Settings of the controller.
struct FrohModelReferenceParameters {
  MillingPlantParameters plant;  //!< Eq. 3's numbers (the plant is known)
  //! b at the start, mm (> 0). Seed 004's work-piece (Fig. 1) is lost with its figures; 3 mm is a choice.
  double initial_depth_mm = 3.0;
  ReferenceModelParameters reference_model;  //!< Eq. 6
  double reference_force_n = 1200.0;  //!< F_r, N (> 0); seed 004 §V: 1.2 kN
  SwitchingScheme scheme = SwitchingScheme::kFixedSet;  //!< §III.E or §III.F
  //! Scheme 1's bank (at least one β, each in [−1, 1]); the first is active until the first comparison.
  //! A bank of the single β = 0 is the basic ZOH model-reference controller of §III.D.
  std::vector<double> betas = seed_004_beta_bank();
  NeighbourSearchParameters neighbour_search;  //!< scheme 2's settings
  double forgetting_factor = 1.0;  //!< λ of Eq. 10, in (0, 1]; seed 004 §V: 1
  int index_window_periods = 1;    //!< M of Eq. 10, ≥ 1; seed 004 §V: 1
  int residence_periods = 1;       //!< fewest periods between two switches of β, ≥ 1; seed 004 §V: one period
  //! Zeros of the discrete plant inside this radius are cancelled, in (0, 1]; seed 004: 1, every stable zero.
  double zero_cancellation_radius = 1.0;
  //! Substeps per period on which the continuous outputs are integrated (≥ 1). Seed 004 gives none; 32 is a
  //! choice (the trapezoid rule's relative error is then about (1/32)² / 12 ≈ 1e-4 on a smooth period).
  int substeps_per_period = 32;
  double programmed_feed_mm_per_min = 1000.0;  //!< the feed an override ratio of 1 means, mm/min (> 0)
  //! What the override can express. Seed 004 has no limit; 0–400 % (a choice) does not bind in its §VI run.
  OverrideRange override_range{4.0, 0.0};
};

//! Every problem with the parameters, each named "<field_prefix><field>" with its value and the rule
//! ("froh_mrc.betas[2] = 1.5: must be finite and in [−1, 1], …", "froh_mrc.betas = []: must hold at least
//! one β"). Empty when usable.
std::vector<InputProblem> validate(const FrohModelReferenceParameters& parameters,
                                   const std::string& field_prefix = "froh_mrc.");

//! The controller's state, stepped once per spindle revolution.
class FrohModelReferenceController {
 public:
  //! Designs the starting models at initial_depth_mm and the spindle period. Throws InputError with
  //! validate()'s problems, and "froh_mrc.betas[i]" (or "froh_mrc.neighbour_search.initial_beta") when that
  //! β's model admits no design (the design's message).
  explicit FrohModelReferenceController(const FrohModelReferenceParameters& parameters);

  //! Takes over a cut already under way instead of starting from rest (seed 004's case): before the first
  //! step (asserted), puts every past sample at a steady state — the forces at `force_n`, the commands at the
  //! override `ratio` of the programmed feed, the references and the reference model at reference_force_n —
  //! and the plant copy at that feed and force. Without it, the first step sees the reference and the force
  //! jump from 0 and the law follows the reference model's rise from 0: on a machine that is already
  //! cutting, a cut of the feed towards 0. Both finite, ratio ≥ 0 (asserted).
  void start_in_steady_state(double force_n, double ratio);

  //! The depth of cut from the current sample on (finite, > 0; asserted): the plant copy and every model
  //! follow it.
  void set_depth_of_cut_mm(double depth_mm);

  //! Takes the force F_p,k measured at the sample (finite) and the time since the previous sample (finite,
  //! > 0; both asserted) — every model is redesigned when it differs from the period in use by more than
  //! 1e-9 of it — chooses β as the file comment says and returns the override ratio f_c,k / programmed feed.
  double step(double measured_force_n, double dt_s);

  double active_beta() const { return active_beta_; }  //!< β of the hold over the coming period
  double commanded_feed_mm_per_s() const { return commands_[0]; }  //!< f_c,k, mm/s (after the override range)
  double previous_commanded_feed_mm_per_s() const { return commands_[1]; }  //!< f_c,k−1, mm/s
  //! The β-FROH's feed a fraction `fraction_of_period` (in [0, 1]) into the coming period, mm/s.
  double held_feed_mm_per_s(double fraction_of_period) const;
  int switches() const { return switches_; }  //!< times β changed
  int failed_designs() const { return failed_designs_; }  //!< samples whose active model had no design (command held)
  //! The index of each candidate at the last comparison, in the order of the candidates (scheme 1: the bank;
  //! scheme 2: β − Δβ, β, β + Δβ before the update).
  const std::vector<double>& last_indices() const { return last_indices_; }

 private:
  //! What the index needs to replay one past period for any β.
  struct PeriodRecord {
    HeldSystemSimulator plant;               // the plant copy at the period's start, with its system
    double depth_mm = 0.0;                   // the depth over the period
    std::vector<double> reference_outputs;   // F_m over the period, at the substep instants
    std::array<double, 3> reference_n{};     // F_r,j, F_r,j−1, F_r,j−2
    std::array<double, 3> force_n{};         // F_p,j, F_p,j−1, F_p,j−2
    std::array<double, 2> commands{};        // f_c,j−1, f_c,j−2
  };

  const ModelReferenceDesign& design_for(double depth_mm, double beta);
  double applied_command(double command_mm_per_s) const;
  double candidate_index(double beta);
  void choose_beta();
  void reset_period(double period_s);

  FrohModelReferenceParameters parameters_;
  double period_s_ = 0.0;
  double depth_mm_ = 0.0;
  HeldSystemSimulator plant_copy_;
  HeldSystemSimulator reference_copy_;
  std::map<std::pair<double, double>, ModelReferenceDesign> designs_;  // by (depth, β)
  std::vector<PeriodRecord> records_;  // newest first, at most M + 1
  NeighbourBetaSearch search_;
  std::array<double, 3> reference_n_{0.0, 0.0, 0.0};  // F_r,k, F_r,k−1, F_r,k−2
  std::array<double, 3> force_n_{0.0, 0.0, 0.0};      // F_p,k, F_p,k−1, F_p,k−2
  std::array<double, 2> commands_{0.0, 0.0};          // after a step: f_c,k, f_c,k−1
  double active_beta_ = 0.0;
  std::size_t active_position_ = 0;  // scheme 1: β's place in the bank
  long long samples_ = 0;
  long long last_switch_sample_ = 0;
  int switches_ = 0;
  int failed_designs_ = 0;
  std::vector<double> last_indices_;
};

}  // namespace feedplan::control
