#pragma once
// The feed override channel of the virtual machine: what an external feedback controller (seed 002,
// docs/method.md §6.3) commands, and the override ratio the machine actually applies.
//
// The controller commands a ratio r_cmd ∈ [0, max_ratio] (0–150 % by default, the range seed 001's
// controller used; commands outside are clamped, as an override knob stops at its ends). The machine
// sees it through a first-order lag with dead time, G(s) = e^(−T_d s) / (τ s + 1); seed 002 identified
// 14 e^(−0.08 s)/(s + 14), i.e. τ = 1/14 s (71 ms) and T_d = 0.08 s.
//
// Discretised exactly for a command held constant over each step Δt (zero-order hold), for any
// T_d = N Δt + δ with 0 ≤ δ < Δt (the modified z-transform): with α = e^(−Δt/τ),
//   y_{k+1} = α y_k + e^(−(Δt−δ)/τ) (1 − e^(−δ/τ)) u_{k−N−1} + (1 − e^(−(Δt−δ)/τ)) u_{k−N},
// where u_k is the command held over [kΔt, (k+1)Δt) and y_k the actual ratio at kΔt. The delayed
// commands u_{k−N−1}, u_{k−N} come from a delay line. τ = 0 is a pure dead time.

#include <cstddef>
#include <vector>

#include "feedplan/core/input_error.hpp"

namespace feedplan::sim {

//! Dynamics and range of the override channel.
struct FeedOverrideOptions {
  double time_constant_s = 1.0 / 14.0;  //!< τ of the first-order lag (seed 002: 1/14 s), ≥ 0, s
  double dead_time_s = 0.08;            //!< dead time T_d (seed 002: 0.08 s), ≥ 0, s
  double max_ratio = 1.5;               //!< largest ratio a command may ask for (1.5 = 150 %), > 0
  //! Ratio in effect before the first command, in steady state (commanded and actual), in [0, max_ratio].
  double initial_ratio = 1.0;
};

//! Checks the options and the time step: time constant and dead time finite and ≥ 0, max_ratio
//! finite and > 0, initial_ratio in [0, max_ratio], step_s finite and > 0. Fields are named
//! "feed_override.<field>" and "feed_override.step_s". Returns every problem; empty when valid.
std::vector<InputProblem> validate(const FeedOverrideOptions& options, double step_s);

//! The override channel stepped at a fixed time step.
class FeedOverride {
 public:
  //! Starts in steady state at options.initial_ratio, at time 0. Throws InputError with validate's
  //! problems when the options or `step_s` are invalid.
  FeedOverride(const FeedOverrideOptions& options, double step_s);

  //! Sets the commanded ratio held from now on, clamped to [0, max_ratio]. Must not be NaN (asserted).
  void command(double ratio);

  //! Advances time by one step (the command held over it) and returns the actual ratio at the new time.
  double step();

  //! The ratio the machine applies now.
  double actual() const { return actual_; }

  //! The ratio commanded now (after clamping).
  double commanded() const { return commanded_; }

  //! Time since the start: the number of steps taken times step_s(), s.
  double time_s() const { return static_cast<double>(steps_) * step_s_; }

  //! The time step, s.
  double step_s() const { return step_s_; }

 private:
  double max_ratio_ = 0.0;
  double step_s_ = 0.0;
  double alpha_ = 0.0;         // weight of y_k
  double gain_older_ = 0.0;    // weight of u_{k−N−1}
  double gain_newer_ = 0.0;    // weight of u_{k−N}
  std::vector<double> delay_;  // ring buffer of the last N + 2 held commands
  std::size_t head_ = 0;       // slot of the command held over the current step, u_k
  std::size_t delay_steps_ = 0;  // N
  double commanded_ = 0.0;
  double actual_ = 0.0;
  long long steps_ = 0;
};

}  // namespace feedplan::sim
