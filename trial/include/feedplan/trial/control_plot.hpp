#pragma once
// The plot of a controlled run (`feedplan control --plot`), as self-contained SVG: above, the force
// against time — the force the controller sensed per revolution, the true per-revolution peak of |F_xy|
// and the target; below, the feed override the controller commanded and the one the machine applied
// (after the override channel's lag and dead time), in percent.

#include <string>
#include <vector>

#include "feedplan/sim/milling_simulation.hpp"  // force_log::RevolutionPeak, the simulation's true peaks
#include "feedplan/trial/override_control.hpp"

namespace feedplan::trial {

//! What to draw besides the data.
struct ControlPlotOptions {
  std::string title = "Feedback control on the virtual machine";  //!< text above the plot
  std::string sensed_label = "sensed per revolution";             //!< legend of the sensed force
  double width_px = 1200.0;   //!< SVG width, px (≥ 400)
  double height_px = 700.0;   //!< SVG height, px (≥ 400)
};

//! The SVG text for `trace` (the controller's revolutions and steps), the true per-revolution peaks
//! `revolutions` and `target_force_n` (> 0). Sizes must be valid (asserted); an empty run gives the axes
//! and a "no data" note.
std::string control_plot_svg(const ControlTrace& trace, const std::vector<force_log::RevolutionPeak>& revolutions,
                             double target_force_n, const ControlPlotOptions& options = {});

}  // namespace feedplan::trial
