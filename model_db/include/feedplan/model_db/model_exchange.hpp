#pragma once
// Moving a model database's content between files: export to one JSON document, import that document
// into another store in one transaction.
//
// The document ("format": "feedplan-model-db", "format_version": 2) holds, in this order and sorted so
// that equal content gives equal text:
//   tools            by name: name, diameter_mm, flutes, helix_deg, tool_material, coating, notes
//   materials        by name: name, iso_group, hardness_value, hardness_scale, notes
//   models           by tool, material, version: tool, material, version, parent_version (null when
//                    the parent is not in the document), active, source, created_at, note,
//                    kind ("response_surface" or "mechanistic"; absent in format 1: response surface),
//                    model {beta[6], centres, scales, range, axial_depth_mm, spindle_rpm, quantity},
//                    mechanistic (kind mechanistic) {the six coefficients, size effect, runout_mm[], helix_deg
//                    (null: the tool's),
//                    covariance[16] of Ktc, Krc, Kte, Kre, signal_rms_residual_n, condition_number,
//                    identified, unidentifiable[]},
//                    fit {n, rmse_n, r_squared, covariance[36], standard_errors[6], loo_rmse_n, engagement_cv_rmse_n (optional, 0 when absent)}
//   cutting_tests    by tool, material, created_at: conditions, derived values, peak statistics,
//                    steady_peaks_n[], synchronous_fx_n[], synchronous_fy_n[] (optional: the force over a
//                    revolution averaged over the steady ones, force_log/synchronous_average.hpp),
//                    source, notes[], created_at
//   learning_history by created_at: model_before / model_after as {tool, material, version}, …, and
//                    samples[] {chip_mm, contact_length_mm, force_n, weight, s_mm} (optional: the
//                    per-revolution samples the step learned from, absent when it stored none)
// Row ids never appear (references are by name and version); versions, created_at and the active flags
// are kept, so export → import into an empty store → export gives byte-identical text. Not exported:
// the activation audit trail (the import records its own activations, reason "imported").
//
// Import rules:
// - Tools and materials are matched by name. Same content: skipped. Different content: InputError
//   ("tools.name = 'X' already exists with different content: diameter_mm 12 vs 10") unless
//   ImportOptions::on_name_clash renames the incoming one ("X (imported)", "X (imported 2)", …) or
//   replaces the stored one's fields with the incoming ones.
// - Model versions are matched by tool, material and version number. Same content: skipped. A version
//   number not yet used is imported with its number. A clash (same number, different content) is an
//   InputError with kFail; otherwise the incoming version is appended as the next free version (history
//   is never rewritten) and the renumbering reported. The document's active version of each kind becomes
//   the active one of that kind, except with kRename when the pair already had an active version of the
//   kind (then that one stays).
// - Cutting tests and learning entries identical to stored ones (every field, created_at included) are
//   skipped, so importing a document twice changes nothing.
// - The whole document is checked first (every problem reported at once, with its place, e.g.
//   "models[3].model.beta[2] = null: must be a finite number"); then everything is written in one
//   transaction, and any error leaves the store as it was.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "feedplan/model_db/store.hpp"

namespace feedplan::model_db {

//! The document format written by export_json and read by import_json (2: model versions carry their
//! "kind" and a mechanistic version its "mechanistic" coefficients; 1, response surfaces only, is read too).
inline constexpr int kExchangeFormatVersion = 2;

//! What to export.
struct ExportOptions {
  bool active_models_only = false;       //!< only the active version of each tool and material
  bool include_cutting_tests = true;     //!< the cutting tests too
  bool include_learning_history = true;  //!< the learning history too (entries whose models are exported)
};

//! The whole content of `store` (as `options` selects) as a JSON document, 2-space indented, ending in
//! a newline. Deterministic: equal content gives equal text.
std::string export_json(const Store& store, const ExportOptions& options = {});

//! export_json written to `path` atomically (temporary file, then rename). Throws InputError naming the
//! path when it cannot be written.
void export_to_file(const Store& store, const std::filesystem::path& path, const ExportOptions& options = {});

//! What to do when an incoming tool or material has the name of a stored one with other content.
enum class NameClash {
  kFail,     //!< InputError (the default)
  kRename,   //!< import it under "<name> (imported)" (or "(imported 2)", …)
  kReplace,  //!< overwrite the stored one's fields with the incoming ones (its models stay)
};

//! How to import.
struct ImportOptions {
  NameClash on_name_clash = NameClash::kFail;  //!< see NameClash
};

//! What an import did.
struct ImportSummary {
  int tools_added = 0;              //!< new tools
  int tools_skipped = 0;            //!< identical to a stored one
  int tools_renamed = 0;            //!< imported under a new name (kRename)
  int tools_replaced = 0;           //!< stored one overwritten (kReplace)
  int materials_added = 0;          //!< new materials
  int materials_skipped = 0;        //!< identical to a stored one
  int materials_renamed = 0;        //!< imported under a new name (kRename)
  int materials_replaced = 0;       //!< stored one overwritten (kReplace)
  int models_added = 0;             //!< versions written (renumbered ones included)
  int models_renumbered = 0;        //!< of those, appended under a new version number
  int models_skipped = 0;           //!< identical to a stored version
  int cutting_tests_added = 0;      //!< cutting tests written
  int cutting_tests_skipped = 0;    //!< identical to a stored one
  int learning_entries_added = 0;   //!< learning entries written
  int learning_entries_skipped = 0; //!< identical to a stored one
  std::vector<std::string> messages;  //!< renames, replacements and renumberings, one line each
};

//! Imports the document `json_text` into `store` by the rules above, in one transaction. `source_name`
//! (a file name) prefixes messages about the text itself. Throws InputError for a document that is not
//! valid JSON or not this format, has a newer format_version ("… upgrade feedplan"), fails any check,
//! or clashes with the store under NameClash::kFail; the store is then unchanged.
ImportSummary import_json(Store& store, std::string_view json_text, const ImportOptions& options = {},
                          const std::string& source_name = "import");

//! import_json of the file at `path`. Throws InputError naming the path when it cannot be read.
ImportSummary import_from_file(Store& store, const std::filesystem::path& path, const ImportOptions& options = {});

}  // namespace feedplan::model_db
