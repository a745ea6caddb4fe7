// Re-feeding a long CAM program: what `feedplan optimize` does once its inputs are read — read the
// G-code, cut its moves out of the stock and compute the engagement, plan (controller-friendly blocks), and
// write the same text with the new F words. The program is an adaptive-clearing style spiral of 20 000
// short G1 lines (FreeCAD's adaptive writes its helices and clearing as such segments): a Ø6 3-flute end
// mill 4 mm deep in a 110 × 110 mm block of aluminium, stepping over 1.5 mm per turn.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "feedplan/gcode/reader.hpp"
#include "feedplan/gcode/refeed.hpp"
#include "feedplan/planner/feed_plan.hpp"

namespace {

using namespace feedplan;

constexpr int kLines = 20000;

std::string spiral_program() {
  std::string text = "(adaptive-style spiral, 20000 segments)\nG21 G17 G90\nM3 S12000\nG0 Z5\nG0 X3 Y0\nG1 Z-4 F300\n";
  const double step_over_mm = 1.5, r0_mm = 3.0, r1_mm = 50.0;
  const double turns = (r1_mm - r0_mm) / step_over_mm;
  char line[96];
  for (int k = 1; k <= kLines; ++k) {
    const double t = turns * k / kLines;  // turns so far
    const double r = r0_mm + step_over_mm * t, a = 2.0 * 3.14159265358979323846 * t;
    std::snprintf(line, sizeof line, "G1 X%.3f Y%.3f F1500\n", r * std::cos(a), r * std::sin(a));
    text += line;
  }
  text += "G0 Z5\nM5\nM2\n";
  return text;
}

void BM_OptimizeTwentyThousandLines(benchmark::State& state) {
  const std::string text = spiral_program();
  geometry::Tool tool;
  tool.diameter_mm = 6.0;
  tool.flutes = 3;
  tool.helix_deg = 35.0;
  geometry::Stock stock;
  stock.regions.push_back({geometry::Contour::rectangle({-55.0, -55.0}, {55.0, 55.0}), {}});
  stock.z_bottom_mm = -10.0;
  stock.z_top_mm = 0.0;
  planner::PlanSettings settings;  // the sample database's magnitude for aluminium with a Ø6 end mill
  settings.model.beta = {120.0, 90.0, 20.0, -4.0, -2.0, 6.0};
  settings.model.chip_center_mm = 0.04;
  settings.model.chip_scale_mm = 0.03;
  settings.model.contact_length_center_mm = 2.0;
  settings.model.contact_length_scale_mm = 1.0;
  settings.model.range = {0.005, 0.12, 0.0, 4.7};
  settings.model.axial_depth_mm = 6.0;
  settings.target_force_n = 150.0;
  settings.spindle_rpm = 12000.0;
  settings.options.feed_step = 0.02;
  settings.options.min_block_duration_s = 0.02;
  std::size_t out_lines = 0;
  for (auto _ : state) {
    std::vector<gcode::WrittenMove> written;
    const geometry::Program program = gcode::read_program(text, "spiral", {}, written);
    const planner::PlanGeometry geometry = planner::analyse(program.path, stock, tool);
    const planner::PlanResult result = planner::plan(geometry, settings);
    std::vector<gcode::FeedPiece> pieces;
    for (std::size_t k = 0; k < result.blocks.size(); ++k) {
      if (result.blocks[k].feed_mm_per_min > 0.0) {
        pieces.push_back({result.blocks[k].move_index, result.program.path.moves[k], result.blocks[k].feed_mm_per_min});
      }
    }
    const gcode::RefeedResult refed = gcode::refeed_text(text, program, written, pieces);
    out_lines = static_cast<std::size_t>(std::count(refed.text.begin(), refed.text.end(), '\n'));
    benchmark::DoNotOptimize(refed);
  }
  state.counters["input_lines"] = static_cast<double>(std::count(text.begin(), text.end(), '\n'));
  state.counters["output_lines"] = static_cast<double>(out_lines);
}

BENCHMARK(BM_OptimizeTwentyThousandLines)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
