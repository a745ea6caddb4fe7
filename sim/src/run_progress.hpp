#pragma once
// Internal to the virtual machine (milling_simulation.cpp): how much of a run is done, for
// SimulationRequest::progress. A run has two parts whose share of the time depends on the program —
// the stock's engagement (path length sampled over all layer bands) and the internal steps (each
// summing the force over the layers the flutes reach) — so each part's work is weighted by a rough
// cost per unit (run_progress.cpp), and the fraction reported is the weighted work done over the
// weighted work in all: a remaining-time estimate from it holds across the switch from one part to
// the other, instead of jumping there.

#include <functional>

namespace feedplan::sim::detail {

//! The fraction of one run done, reported at least every 1 % and at the end.
class RunProgress {
 public:
  //! `report` may be empty (then nothing is computed). `total_steps`: the planned steps; `layers`:
  //! the stock layers the flutes may reach; `ds_mm`: the engagement sample spacing.
  RunProgress(const std::function<void(double)>& report, long long total_steps, int layers, double ds_mm);

  //! The engagement so far: path length sampled and to sample over all bands, mm.
  void engagement(double done_mm, double total_mm);
  //! The fraction of the planned motion's time run so far (0..1).
  void motion(double fraction);
  //! The run is over.
  void finish();

 private:
  void update();

  const std::function<void(double)>& report_;
  double step_work_ = 0.0;        // weighted work of all steps
  double ds_mm_ = 0.0;
  double engagement_done_ = 0.0;  // weighted work done / in all
  double engagement_total_ = 0.0;
  double motion_fraction_ = 0.0;
  double next_report_ = 0.0;
};

}  // namespace feedplan::sim::detail
