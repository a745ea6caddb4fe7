#include "compare_command.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <system_error>

#include "comparison_report.hpp"
#include "data_path.hpp"
#include "html_report_pages.hpp"
#include "database_path.hpp"
#include "model_choice.hpp"
#include "number_flag.hpp"
#include "output_files.hpp"
#include "output_path.hpp"
#include "plan_outcome.hpp"
#include "progress_bar.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/gcode/reader.hpp"
#include "feedplan/gcode/writer.hpp"
#include "feedplan/sim/machine_file.hpp"
#include "feedplan/sim/material.hpp"
#include "feedplan/trial/comparison_plot.hpp"
#include "feedplan/trial/strategy_comparison.hpp"

namespace feedplan::cli {

namespace fs = std::filesystem;

void add_compare_command(CLI::App& app, CompareOptions& options) {
  auto* cmd = app.add_subcommand(
      "compare",
      "Run every strategy on one cycle on one virtual machine and judge them the same way: constant feed, the\n"
      "feed-forward plan, the plan after N cycles of learning, each feedback controller alone, and the robust\n"
      "servo trimming the plan; writes compare.md, compare.json and compare.svg and prints the table");
  cmd->add_option("spec", options.spec_path, "Cycle spec (YAML)")->required();
  add_integer_flag(cmd, "--cycles", options.cycles, "The learned row is cycle N of the learning loop (2–20, default 3)");
  add_number_flag(cmd, "--machine-scale", options.machine_scale,
                  "The virtual machine's cutting coefficients × this: its forces ≈ this × the model's (default 1.4)");
  cmd->add_option("--machine", options.machine_path,
                  "Machine file (data/machines/*.yaml) to cut on instead of the spec's material × --machine-scale");
  add_number_flag(cmd, "--target-force", options.target_force_n, "Per-revolution peak force to hold, N (default: the spec's)");
  add_number_flag(cmd, "--constant-feed", options.constant_feed_mm_per_min,
                  "Feed of the constant-feed rows, mm/min (default: the spec's feed_mm_per_min, else the constant\n"
                  "feed the model predicts to peak where the plan does)");
  cmd->add_option("--db", options.db_path, "Model database (default: $FEEDPLAN_DB, else the bundled sample database)");
  cmd->add_option("--materials", options.materials_path, "Materials file of the virtual machine (default: the bundled one)");
  cmd->add_option("--out", options.out_dir,
                  "Directory to write compare.md, compare.json and compare.svg into, created if missing (its parent\n"
                  "must exist; default: compare-<spec name> in the current directory)");
  cmd->add_option("--html", options.html_path, "Write the comparison as one self-contained HTML file (feedplan report)");
  cmd->add_flag("--json", options.json, "Print compare.json's content instead of the table");
}

namespace {

// The virtual machine's forces over the material's without --machine.
double machine_scale(const CompareOptions& o) { return o.machine_scale.value_or(1.4); }

// The spec, the target and where the outputs go, every flag checked.
struct CompareInputs {
  cycles::CycleSpec spec;
  double target_force_n = 0.0;
  std::string materials_path;
  std::string out_dir;
  std::string markdown_path, json_path, plot_path;
};

// --out: a directory, existing or to be made in an existing one; none of the files inside a directory or an
// input.
void check_out_dir(const CompareOptions& o, CompareInputs& in, std::vector<InputProblem>& problems) {
  std::error_code ec;
  const fs::path dir(in.out_dir);
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec)) {
      problems.push_back({"--out", "= '" + in.out_dir + "': exists and is not a directory; expected a directory to write "
                                   "compare.md, compare.json and compare.svg into"});
      return;
    }
  } else {
    const fs::path parent = dir.has_parent_path() ? dir.parent_path() : fs::path(".");
    if (!fs::is_directory(parent, ec)) {
      problems.push_back({"--out", "= '" + in.out_dir + "': directory '" + parent.string() +
                                   "' does not exist (--out is created, its parents are not)"});
      return;
    }
  }
  const std::vector<NamedPath> inputs = {{"SPEC", o.spec_path},
                                         {"--db", database_path(o.db_path)},
                                         {"--machine", o.machine_path},
                                         {"--materials", in.materials_path}};
  for (const std::string& path : {in.markdown_path, in.json_path, in.plot_path}) {
    if (fs::is_directory(path, ec)) {
      problems.push_back({"--out", "= '" + in.out_dir + "': " + path + " is a directory, expected a file name"});
      continue;
    }
    for (const NamedPath& input : inputs) {
      if (!input.path.empty() && same_file(path, input.path)) {
        problems.push_back({"--out", "= '" + in.out_dir + "': " + path + " is the same file as " + input.flag + " ('" +
                                         input.path + "'): writing it would destroy that input"});
      }
    }
  }
}

CompareInputs read_compare_inputs(const CompareOptions& o) {
  CompareInputs in;
  in.spec = cycles::load_cycle_spec(o.spec_path);
  const cycles::CycleSpec& spec = in.spec;
  std::vector<InputProblem> problems;
  if (!(o.cycles >= 2 && o.cycles <= 20)) {
    problems.push_back({"--cycles", "= " + std::to_string(o.cycles) +
                                        ": must be in [2, 20] (cycle 1 is the model's plan; the learned row is cycle N)"});
  }
  if (o.machine_scale && !o.machine_path.empty()) {
    problems.push_back({"--machine-scale", "conflicts with --machine " + o.machine_path +
                                               ", which sets the machine's physics; give one of them"});
  }
  check_flag(problems, "--machine-scale", o.machine_scale, {0.1, false, 10.0, false},
             "the virtual machine's forces over the material's");
  check_flag(problems, "--target-force", o.target_force_n, {0.0, false}, "the per-revolution peak force to hold, N");
  check_flag(problems, "--constant-feed", o.constant_feed_mm_per_min,
             {spec.machine.min_feed_mm_per_min, true, spec.machine.max_feed_mm_per_min, true},
             "the machine's feed range, mm/min");
  in.target_force_n = o.target_force_n.value_or(spec.target_force_n);
  if (!o.target_force_n && !(spec.target_force_n > 0.0)) {
    problems.push_back({"target_force_n", "is not in the spec: a target force > 0 N is required (in the spec or with "
                                          "--target-force)"});
  }
  if (!(spec.spindle_rpm > 0.0)) problems.push_back({"spindle_rpm", "is required (rev/min > 0)"});
  in.materials_path = o.materials_path.empty() ? bundled_materials_path() : o.materials_path;
  in.out_dir = o.out_dir.empty() ? "compare-" + fs::path(o.spec_path).stem().string() : o.out_dir;
  in.markdown_path = (fs::path(in.out_dir) / kCompareMarkdownName).string();
  in.json_path = (fs::path(in.out_dir) / kCompareJsonName).string();
  in.plot_path = (fs::path(in.out_dir) / kComparePlotName).string();
  check_out_dir(o, in, problems);
  check_outputs({{"SPEC", o.spec_path}, {"--db", database_path(o.db_path)}, {"--machine", o.machine_path},
                 {"--materials", in.materials_path}},
                {{"--html", o.html_path}}, problems);
  for (const std::string& path : {in.markdown_path, in.json_path, in.plot_path}) {
    if (!o.html_path.empty() && same_file(o.html_path, path)) {
      problems.push_back({"--html", "= '" + o.html_path + "': is " + path + ", which compare writes too"});
    }
  }
  if (!problems.empty()) throw InputError(std::move(problems));
  return in;
}

// The machine every row runs on: the spec's tool, stock, limits and spindle speed, and the physics of
// --machine or of the material × --machine-scale; its description in words.
trial::VirtualMachine comparison_machine(const CompareOptions& o, const CompareInputs& in, const PlannedCycle& planned,
                                         std::string& description) {
  const cycles::CycleSpec& spec = in.spec;
  const sim::MaterialLibrary materials = sim::load_materials(in.materials_path);
  trial::VirtualMachine machine;
  machine.tool = spec.tool;
  if (o.machine_path.empty()) {
    const double scale = machine_scale(o);
    const sim::Material& material = materials.get(spec.material, "material");
    machine.coefficients = sim::scaled(material.coefficients, scale);
    description = material.name + " × " + shortest_number_text(scale);
  } else {
    trial::use_machine_file(machine, sim::load_machine_file(o.machine_path, materials), spec.tool);
    description = o.machine_path;
  }
  machine.stock = planned.cycle.stock;
  machine.machine = spec.machine;
  machine.spindle_rpm = spec.spindle_rpm;
  return machine;
}

// The constant-feed rows' feed and where it comes from.
double constant_feed(const CompareOptions& o, const CompareInputs& in, const PlannedCycle& planned, std::string& source) {
  if (o.constant_feed_mm_per_min) {
    source = "F" + shortest_number_text(*o.constant_feed_mm_per_min) + " (--constant-feed)";
    return *o.constant_feed_mm_per_min;
  }
  if (in.spec.feed_mm_per_min) {
    source = "F" + shortest_number_text(*in.spec.feed_mm_per_min) + ", the spec's feed_mm_per_min";
    return *in.spec.feed_mm_per_min;
  }
  const planner::ConstantFeedBaseline& baseline = planned.result.summary.baseline;
  source = "F" + shortest_number_text(baseline.feed_mm_per_min) +
           " — the spec has no feed_mm_per_min: the constant feed the model predicts to peak at " +
           fixed_number_text(baseline.peak_force_n, 1) + " N, where the plan does";
  return baseline.feed_mm_per_min;
}

// The model in words: id, version, kind and how it matches the spec.
std::string model_text(const PlanModel& model) {
  const model_db::ModelRecord& record = model.mechanistic ? *model.mechanistic : model.chosen.record;
  std::string text = "id " + std::to_string(record.id) + " v" + std::to_string(record.version);
  text += model.mechanistic ? " (mechanistic), " : " (response surface), ";
  text += model_db::describe(model.chosen.borrowing);
  return text;
}

trial::ComparisonRequest comparison_request(const CompareInputs& in, const PlanAsWritten& plan, double feed_mm_per_min,
                                            const CompareOptions& o, ComparisonContext& context) {
  trial::ComparisonRequest request;
  request.geometry = plan.planned.geometry;
  request.settings = plan.planned.settings;
  request.machine = comparison_machine(o, in, plan.planned, context.machine);
  request.constant_feed_mm_per_min = feed_mm_per_min;
  // Every program as the machine receives it: written as `plan` writes it and read back, as `plan
  // --simulate` and `simulate` read it.
  const gcode::WriterOptions writer = plan.writer;
  request.as_received = [writer](const geometry::Program& program) {
    return gcode::read_program(gcode::write_gcode(program, writer), "planned program");
  };
  request.learning_cycles = o.cycles;
  request.first_cut_uncertainty = plan.model.relative_uncertainty;
  request.sigmas = kBorrowedModelSigmas;
  request.start_fit_covariance = plan.model.chosen.record.fit.covariance;
  if (request.settings.mechanistic) {
    planner::PlanSettings learning = request.settings;
    learning.mechanistic.reset();
    learning.options.max_chip_thickness_mm = 0.0;
    request.learning_settings = learning;
    context.notes.push_back("the feed-forward plan is of the mechanistic kind; the learning loop starts from the "
                            "response surface, as `feedplan loop` does");
  }
  if (plan.planned.result.status == planner::PlanStatus::kTargetNotMet ||
      plan.planned.result.status == planner::PlanStatus::kUnsafe) {
    context.notes.push_back("the cycle-1 plan's status is " + planner::to_string(plan.planned.result.status) +
                            ": `feedplan plan` would not write its program; it is run here all the same");
  }
  return request;
}

// compare.md, compare.json and compare.svg, staged and put in place together; --out made first when missing.
// Returns the first error, or "".
std::string write_outputs(const CompareOptions& o, const CompareInputs& in, const std::string& markdown,
                          const std::string& json, const std::string& svg, const std::string& html) {
  std::error_code ec;
  if (!fs::exists(in.out_dir, ec)) {
    fs::create_directory(in.out_dir, ec);
    if (ec) return "cannot create directory " + in.out_dir + ": " + ec.message();
  }
  OutputFiles files;
  files.add(in.markdown_path, markdown);
  files.add(in.json_path, json);
  files.add(in.plot_path, svg);
  if (!o.html_path.empty()) files.add(o.html_path, html);
  return files.commit();
}

}  // namespace

int run_compare_command(const CompareOptions& o) {
  const CompareInputs in = read_compare_inputs(o);
  const std::optional<PlanAsWritten> plan = plan_as_written(o.spec_path, in.spec, in.target_force_n, database_path(o.db_path));
  if (!plan) return 1;
  ComparisonContext context;
  context.spec_path = o.spec_path;
  context.cycle = in.spec.cycle;
  context.model = model_text(plan->model);
  const double feed_mm_per_min = constant_feed(o, in, plan->planned, context.constant_feed_source);
  trial::ComparisonRequest request = comparison_request(in, *plan, feed_mm_per_min, o, context);
  trial::StrategyComparison comparison;
  {
    ProgressBar progress("compare: " + std::to_string(5 + request.controllers.size()) +
                         " strategies on the virtual machine, " + std::to_string(o.cycles - 1) +
                         (o.cycles == 2 ? " learning cycle" : " learning cycles") + " first");
    request.progress = [&progress](double fraction) { progress(fraction); };
    comparison = trial::compare_strategies(request);
  }
  const std::string markdown = comparison_markdown(context, comparison);
  const nlohmann::json document = comparison_json(context, comparison);
  const std::string json = document.dump(2) + "\n";
  const std::string html = o.html_path.empty() ? "" : comparison_page_html(document, in.json_path);
  trial::ComparisonPlotOptions plot;
  plot.title = o.spec_path + " (" + in.spec.cycle + "): true per-revolution peaks on the virtual machine " +
               context.machine + ", target " + shortest_number_text(in.target_force_n) + " N";
  if (const std::string error = write_outputs(o, in, markdown, json, trial::comparison_plot_svg(comparison, plot), html);
      !error.empty()) {
    std::cerr << "feedplan: failed: " << error << "\n";
    return 1;
  }
  if (o.json) {
    std::cout << json;
  } else {
    std::cout << markdown << "\nwritten: " << in.markdown_path << ", " << in.json_path << ", " << in.plot_path
              << (o.html_path.empty() ? "" : ", ") << o.html_path << "\n";
  }
  for (const trial::StrategyRow& row : comparison.rows) {
    for (const std::string& warning : row.warnings) std::cerr << "feedplan: warning: " << row.name << ": " << warning << "\n";
  }
  return 0;
}

}  // namespace feedplan::cli
