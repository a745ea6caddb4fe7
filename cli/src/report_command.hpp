#pragma once
// `feedplan report`: one self-contained HTML file (report/html_page.hpp) from a plan report (plan or learn
// --report: the plan, and the learning history when it carries one) or a comparison (compare.json).

#include <CLI/CLI.hpp>

#include <string>

namespace feedplan::cli {

//! The flags of `feedplan report`.
struct ReportOptions {
  std::string input_path;   //!< REPORT: a plan report (JSON) or compare.json
  std::string output_path;  //!< -o: the HTML file to write
  std::string db_path;      //!< --db: the model database (default: the report's, else $FEEDPLAN_DB, else the sample)
};

//! Adds the `report` subcommand to `app`, its flags into `options`.
void add_report_command(CLI::App& app, ReportOptions& options);

//! Writes the HTML report. Returns 0, or 1 when the file cannot be written; throws InputError (exit 2)
//! for a file that is not a plan report or a comparison, naming the file, the field and what was expected.
int run_report_command(const ReportOptions& options);

}  // namespace feedplan::cli
