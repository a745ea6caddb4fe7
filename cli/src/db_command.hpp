#pragma once
// `feedplan db …`: offline maintenance of the model database — tools, materials, cutting tests,
// fitted response-surface models, versions, export/import, and syncing a local file with a shared server.

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace feedplan::cli {

struct DbOptions {
  std::string db_path;          //!< --db; empty: $FEEDPLAN_DB, else the bundled sample database
  bool json = false;            //!< --json
  std::string name;             //!< add-tool / add-material: the new name
  double diameter_mm = 0.0;     //!< add-tool
  int flutes = 0;               //!< add-tool
  double helix_deg = 30.0;      //!< add-tool
  std::string tool_material;    //!< add-tool
  std::string coating;          //!< add-tool
  std::string notes;            //!< add-tool / add-material
  std::string iso_group;        //!< add-material
  std::string hardness;         //!< add-material, e.g. "200 HB"
  std::string tool;             //!< --tool
  std::string material;         //!< --material
  std::string log_path;         //!< import-test
  double spindle_rpm = 0.0;     //!< import-test
  double feed_mm_per_min = 0.0; //!< import-test
  double radial_depth_mm = 0.0; //!< import-test / predict
  double axial_depth_mm = 0.0;  //!< import-test
  std::string mode = "down";    //!< import-test: down | up | slot
  bool no_store = false;        //!< import-test: only measure
  std::string loss = "huber";   //!< fit
  std::string note;             //!< fit
  bool per_revolution = false;  //!< fit: every steady per-revolution peak is a sample (else one per test)
  std::string kind = "both";    //!< fit: mechanistic, response-surface or both
  bool no_peak_matching = false;  //!< fit: the force over a revolution alone, not the tests' mean peaks too (mechanistic)
  bool no_runout = false;       //!< fit: do not identify the per-tooth runout (mechanistic)
  bool no_helix = false;        //!< fit: keep the tool record's helix (mechanistic)
  bool no_size_effect = false;  //!< fit: no size-effect exponent (mechanistic)
  bool sensor = false;          //!< fit: identify the dynamometer's modes too (mechanistic)
  double feed_per_tooth_mm = 0.0;  //!< predict
  std::string file;             //!< export / import
  bool all_versions = false;    //!< export
  std::optional<int> version;   //!< show (unset: the active version) / rollback (required)
  std::string sync_from;        //!< sync: the database copied from (a file or a postgresql:// URL)
  std::string sync_to;          //!< sync: the database copied into (created when missing)
};

//! Registers `db` and its subcommands.
void add_db_command(CLI::App& app, DbOptions& options);

//! Runs the subcommand that was given. Returns the exit code (0 ok, 1 failed); throws InputError on
//! bad input (the database is then unchanged: every write is one transaction).
int run_db_command(const CLI::App& app, const DbOptions& options);

}  // namespace feedplan::cli
