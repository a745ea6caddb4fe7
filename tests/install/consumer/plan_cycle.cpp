// Plans one cycle spec with the closest model of an exchange file, through the installed libraries:
//   plan_cycle SPEC.yaml MODELS.json WORK_DIR
// and prints the plan's status, block count and cycle time as `feedplan plan` reports them.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>

#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/model_db/closest_model.hpp"
#include "feedplan/model_db/model_exchange.hpp"
#include "feedplan/model_db/store.hpp"
#include "feedplan/planner/feed_plan.hpp"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: plan_cycle SPEC.yaml MODELS.json WORK_DIR\n";
    return 2;
  }
  try {
    using namespace feedplan;
    const cycles::CycleSpec spec = cycles::load_cycle_spec(argv[1]);
    model_db::Store store =
        model_db::Store::open(std::filesystem::path(argv[3]) / "models.db", model_db::OpenMode::kCreate);
    model_db::import_from_file(store, argv[2]);
    const model_db::ClosestModel chosen = model_db::closest_model(store, spec.tool.name, spec.material);
    if (!chosen.model) {
      std::cerr << chosen.explanation << "\n";
      return 1;
    }
    const cycles::Cycle cycle = cycles::generate(spec);
    planner::PlanSettings settings;
    settings.model = chosen.model->model;
    settings.target_force_n = spec.target_force_n;
    settings.spindle_rpm = spec.spindle_rpm;
    settings.machine = spec.machine;
    const planner::PlanGeometry geometry =
        planner::analyse(cycle.path, cycle.stock, spec.tool, settings.options.ds_mm);
    const planner::PlanResult result = planner::plan(geometry, settings);
    std::printf("status: %s\nblocks: %zu\ncycle time: %.2f s\n", planner::to_string(result.status).c_str(),
                result.blocks.size(), result.summary.cycle_time_s);
    return 0;
  } catch (const feedplan::InputError& error) {
    std::cerr << error.what() << "\n";
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "failed: " << error.what() << "\n";
    return 1;
  }
}
