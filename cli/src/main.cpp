// feedplan — feedforward feedrate planning for canned milling cycles. The CLI is thin: it parses,
// calls the libraries, prints, and exits 0 (done), 1 (failed) or 2 (bad input).

#include <CLI/CLI.hpp>

#include <cerrno>
#include <cstdio>
#include <exception>
#include <iostream>
#include <system_error>

#include "cycle_command.hpp"
#include "db_command.hpp"
#include "calibration_command.hpp"
#include "compare_command.hpp"
#include "control_command.hpp"
#include "learn_command.hpp"
#include "loop_command.hpp"
#include "plan_command.hpp"
#include "report_command.hpp"
#include "simulate_command.hpp"
#include "optimize_command.hpp"
#include "feedplan/core/input_error.hpp"

namespace {

constexpr int kExitFailed = 1;
constexpr int kExitBadInput = 2;

int bad_input(const feedplan::InputError& e) {
  std::cerr << "feedplan: bad input:\n";
  for (const auto& problem : e.problems()) std::cerr << "  " << feedplan::to_string(problem) << "\n";
  return kExitBadInput;
}

// Parses and runs one command; its exit code.
int run_command_line(int argc, char** argv) {
  CLI::App app{"feedplan " FEEDPLAN_VERSION
               " — feedforward feedrate planning for canned milling cycles (corner rounding, trochoid,\n"
               "spiral, helical boring, pocket): tool path, cutter engagement, and feeds that hold the\n"
               "cutting force at a target."};
  app.set_version_flag("--version", "feedplan " FEEDPLAN_VERSION);
  app.require_subcommand(1);

  feedplan::cli::CycleOptions cycle_options;
  feedplan::cli::add_cycle_command(app, cycle_options);
  feedplan::cli::SimulateOptions simulate_options;
  feedplan::cli::add_simulate_command(app, simulate_options);
  feedplan::cli::OptimizeOptions optimize_options;
  feedplan::cli::add_optimize_command(app, optimize_options);
  feedplan::cli::PlanCommandOptions plan_options;
  feedplan::cli::add_plan_command(app, plan_options);
  feedplan::cli::CalibrationOptions calibration_options;
  feedplan::cli::add_calibration_command(app, calibration_options);
  feedplan::cli::LearnOptions learn_options;
  feedplan::cli::add_learn_command(app, learn_options);
  feedplan::cli::LoopOptions loop_options;
  feedplan::cli::add_loop_command(app, loop_options);
  feedplan::cli::ControlOptions control_options;
  feedplan::cli::add_control_command(app, control_options);
  feedplan::cli::CompareOptions compare_options;
  feedplan::cli::add_compare_command(app, compare_options);
  feedplan::cli::ReportOptions report_options;
  feedplan::cli::add_report_command(app, report_options);
  feedplan::cli::DbOptions db_options;
  feedplan::cli::add_db_command(app, db_options);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitBadInput;
  } catch (const feedplan::InputError& e) {  // a numeric flag that is not a number (number_flag.hpp)
    return bad_input(e);
  }

  try {
    if (app.got_subcommand("cycle")) return feedplan::cli::run_cycle_command(cycle_options);
    if (app.got_subcommand("simulate")) return feedplan::cli::run_simulate_command(simulate_options);
    if (app.got_subcommand("plan")) return feedplan::cli::run_plan_command(plan_options);
    if (app.got_subcommand("optimize")) return feedplan::cli::run_optimize_command(optimize_options);
    if (app.got_subcommand("calibrate-currents")) return feedplan::cli::run_calibration_command(calibration_options);
    if (app.got_subcommand("learn")) return feedplan::cli::run_learn_command(learn_options);
    if (app.got_subcommand("loop")) return feedplan::cli::run_loop_command(loop_options);
    if (app.got_subcommand("control")) return feedplan::cli::run_control_command(control_options);
    if (app.got_subcommand("compare")) return feedplan::cli::run_compare_command(compare_options);
    if (app.got_subcommand("report")) return feedplan::cli::run_report_command(report_options);
    if (app.got_subcommand("db")) return feedplan::cli::run_db_command(app, db_options);
  } catch (const feedplan::InputError& e) {
    return bad_input(e);
  } catch (const std::exception& e) {
    std::cerr << "feedplan: failed: " << e.what() << "\n";
    return kExitFailed;
  }
  return kExitFailed;
}

// Standard output is an output too: a summary that could not be written (a full disk, a closed pipe) is a
// failure, not a silent success. Exit 0 when everything printed reached it, else 1 with the reason.
int standard_output_written() {
  std::cout.flush();
  errno = 0;
  if (std::fflush(stdout) == 0 && !std::ferror(stdout) && std::cout.good()) return 0;
  const int error = errno;  // 0 when an earlier write failed and the reason is gone
  std::cerr << "feedplan: failed: cannot write to standard output: "
            << (error != 0 ? std::generic_category().message(error) : "a write failed") << "\n";
  return kExitFailed;
}

}  // namespace

int main(int argc, char** argv) {
  const int exit_code = run_command_line(argc, argv);
  return exit_code == 0 ? standard_output_written() : exit_code;
}
