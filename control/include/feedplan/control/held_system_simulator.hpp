#pragma once
// A ContinuousSystem driven through a β-FROH (fractional_order_hold.hpp) and stepped one sampling period at
// a time, with its output between the samples: seed 004 judges its controllers by the continuous-time force
// (its performance index, Eq. 10, and the cost of §VI integrate it over each period), not by the samples.
//
// Each period is cut into m equal substeps; the hold's output is linear on each, so the state moves exactly
// (linear_input_transition() over T/m) and the output is exact at the m + 1 substep instants — what lies
// between them is left to whoever integrates (tracking_index.hpp: the trapezoid rule).

#include <array>
#include <vector>

#include "feedplan/control/continuous_system.hpp"
#include "feedplan/control/fractional_order_hold.hpp"

namespace feedplan::control {

//! The system's state, stepped period by period.
class HeldSystemSimulator {
 public:
  //! Starts at rest (x = 0). Needs a finite period > 0 and m ≥ 1 substeps (asserted).
  HeldSystemSimulator(const ContinuousSystem& system, double period_s, int substeps_per_period);

  //! Changes the system from the next step on; the state is kept (a new depth of cut, same feed and force).
  void set_system(const ContinuousSystem& system);

  //! Holds the samples (`command`, the one before `previous_command`) over one period through the β-FROH
  //! and returns the output at the period's end. Inputs finite, β in [−1, 1] (asserted).
  double step(double command, double previous_command, double beta);

  //! The output at the m + 1 substep instants of the last step, its start and end included (one value, the
  //! output now, before the first step).
  const std::vector<double>& period_outputs() const { return period_outputs_; }
  double output() const;                                    //!< y = C x now
  const std::array<double, 2>& state() const { return x_; }  //!< x now
  void set_state(const std::array<double, 2>& x);           //!< puts the state at x (finite, asserted)
  const ContinuousSystem& system() const { return system_; }  //!< the system in effect
  double period_s() const { return period_s_; }               //!< T, s
  int substeps_per_period() const { return substeps_; }       //!< m

 private:
  ContinuousSystem system_;
  double period_s_ = 0.0;
  int substeps_ = 1;
  LinearInputTransition substep_;
  std::array<double, 2> x_{0.0, 0.0};
  std::vector<double> period_outputs_;
};

}  // namespace feedplan::control
