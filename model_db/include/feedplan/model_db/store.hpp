#pragma once
// The model database: one SQLite file — or one database on a PostgreSQL server, opened by its URL
// (database_url.hpp) — holding tools, workpiece materials, the versions of the force models of each tool
// in each material (response surfaces and mechanistic models; exactly one version of
// each kind active), the cutting tests
// they were fitted on, the audit trail of which version was active when, and the learning history.
//
// Guarantees:
// - Every write is one transaction (BEGIN IMMEDIATE … COMMIT). It is checked before anything is
//   written; on any error, exception or crash in the middle the database is as it was before.
// - Nothing is deleted: a new model version becomes active and the old one stays; rollback() makes an
//   older version active again and records that it did.
// - WAL journal: readers (the planner) keep working while one process writes; a writer waits up to
//   the busy timeout for another writer.
// - The schema carries a version (PRAGMA user_version; PRAGMA application_id marks the file as a
//   feedplan database). Opening a file of an older version migrates it in one transaction; a newer
//   one is refused with a message asking to upgrade feedplan.
//
// On a PostgreSQL server the same holds, with the server's means: a write transaction takes one advisory
// lock (the server's single writer; readers are never blocked) and waits up to the busy timeout for it; a
// client killed mid-write is rolled back by the server; the schema version is kept in the table
// feedplan_schema, with the same versions and migrations as a file.
//
// A Store is one connection: use it from one thread at a time (open one Store per thread or process).
//
// Errors: bad input (unknown names, duplicate names, non-finite numbers, a file that is not a model
// database, a schema newer than this code) throws feedplan::InputError naming the field or the path and
// the value. SQLite failures that are not the user's (disk full, I/O error) throw std::runtime_error.

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "feedplan/model_db/cutting_test.hpp"
#include "feedplan/model_db/store_records.hpp"

namespace feedplan::model_db {

//! The schema version this code writes and reads (PRAGMA user_version).
inline constexpr int kStoreSchemaVersion = 5;

//! How Store::open treats the file.
enum class OpenMode {
  kCreate,    //!< open read-write; create the file and schema if missing, migrate an older schema
  kExisting,  //!< open read-write; the file must exist; migrate an older schema
  kReadOnly,  //!< open read-only; the file must exist and have the current schema
};

//! Options of Store::open, with their defaults.
struct StoreOptions {
  int busy_timeout_ms = 5000;  //!< how long a write waits for another process's write, ms
  bool quick_check_on_open = true;  //!< run PRAGMA quick_check on open; a damaged file is refused
  //! Page cache of the connection, KiB (SQLite's default). A write larger than this spills pages to
  //! the WAL file before it commits; the crash tests set it small to make sure they do.
  int cache_size_kib = 2000;
};

//! Result of Store::integrity_check().
struct IntegrityReport {
  bool ok = false;                    //!< SQLite's integrity_check said "ok"
  std::vector<std::string> messages;  //!< its rows ("ok", or one line per problem found)
};

//! Called by a write inside its open transaction after each step (`step` names it, e.g.
//! "models.insert"). For tests: a hook that throws makes the write roll back; one that kills the
//! process leaves a transaction for SQLite to roll back on the next open.
using WriteHook = std::function<void(std::string_view step)>;

class Store {
 public:
  //! Opens (or with kCreate creates) the database at `path`: a file, or with a postgresql:// (postgres://)
  //! URL an existing database on a PostgreSQL server (kCreate makes the schema in an empty one; the server
  //! must answer: InputError naming the URL, the host and port and what may help otherwise). Throws
  //! InputError naming the path when
  //! the file is missing (kExisting, kReadOnly), is not a SQLite database or not a feedplan one, is
  //! damaged (quick_check), has a schema newer than kStoreSchemaVersion ("… upgrade feedplan"), or
  //! (kReadOnly) an older one that needs migrating.
  static Store open(const std::filesystem::path& path, OpenMode mode = OpenMode::kExisting,
                    const StoreOptions& options = {});

  Store(Store&&) noexcept;
  Store& operator=(Store&&) noexcept;
  ~Store();

  //! The file this store was opened from, or the server's URL without its password.
  const std::filesystem::path& path() const;

  //! The schema version of the open file (kStoreSchemaVersion after open).
  int schema_version() const;

  //! Runs PRAGMA integrity_check over the whole file.
  IntegrityReport integrity_check() const;

  // ---- tools and materials ----

  //! Adds a tool. Throws InputError for every validate() problem, or "tools.name = 'X' already
  //! exists". Returns the stored record (with its id).
  ToolRecord add_tool(const ToolRecord& tool);

  //! The tool called `name` (exact match), or nothing.
  std::optional<ToolRecord> find_tool(std::string_view name) const;

  //! Every tool, ordered by name.
  std::vector<ToolRecord> tools() const;

  //! Adds a material; like add_tool ("materials.name = 'X' already exists").
  MaterialRecord add_material(const MaterialRecord& material);

  //! The material called `name` (exact match), or nothing.
  std::optional<MaterialRecord> find_material(std::string_view name) const;

  //! Every material, ordered by name.
  std::vector<MaterialRecord> materials() const;

  // ---- models ----

  //! Adds a new version of the model of model.tool_name in model.material_name: version = the
  //! highest so far + 1 (over both kinds), parent = the version of the same kind active until now (none
  //! for the first), created_at = now; it becomes the active version of its kind and the change is recorded. Ignores the fields marked "set by
  //! the store". Throws InputError for unknown tool or material names ("models.tool_name = 'X':
  //! unknown tool; known: …") and every validate() problem. Returns the stored version.
  ModelRecord add_model(const ModelRecord& model);

  //! add_model for each of `models` in turn, in one transaction: all are stored or none (e.g. the response
  //! surface and the mechanistic model fitted from the same tests). Returns the stored versions in order.
  std::vector<ModelRecord> add_models(const std::vector<ModelRecord>& models);

  //! A learned version, the learning entry that explains it and the per-revolution samples it was learned
  //! from, in one transaction: add_model(model), then add_learning_entry(entry) with model_id_after = the
  //! new version's id, then the samples. All are stored or none (the database is unchanged on any error).
  //! The version the step was fitted from (entry.model_id_before) must still be the active version of the
  //! pair when the write transaction holds the lock, so that it is the new version's true parent; when
  //! another learning step or a rollback changed the active version since, throws StaleModelError
  //! (stale_model_error.hpp) and stores nothing — two learners racing on one database never both land on
  //! the same parent. Throws as add_model and add_learning_entry do, and InputError naming
  //! "learning_samples[i].<field>" for a sample with a non-finite number or a weight ≤ 0.
  std::pair<ModelRecord, LearningEntry> add_learned_model(const ModelRecord& model, const LearningEntry& entry,
                                                          const std::vector<LearnedSample>& samples = {});

  //! Every stored learning sample whose learning step produced a version of the pair's model, oldest
  //! first. Throws InputError for an unknown tool or material.
  std::vector<LearnedSample> learned_samples(std::string_view tool_name, std::string_view material_name) const;

  //! Every version of the model of `tool_name` in `material_name`, oldest first (empty if none).
  //! Throws InputError for an unknown tool or material.
  std::vector<ModelRecord> models_for(std::string_view tool_name, std::string_view material_name) const;

  //! The active version of `kind` for the pair (each kind has its own active version; the response
  //! surface unless asked), or nothing when it has no model of that kind. Throws InputError for an
  //! unknown tool or material.
  std::optional<ModelRecord> active_model(std::string_view tool_name, std::string_view material_name,
                                          ModelKind kind = ModelKind::kResponseSurface) const;

  //! Every active version of `kind` in the store (one per tool and material that has a model of it), ordered by
  //! tool name and material name.
  std::vector<ModelRecord> active_models(ModelKind kind = ModelKind::kResponseSurface) const;

  //! Every model version in the store, ordered by tool name, material name and version.
  std::vector<ModelRecord> all_models() const;

  //! The model version with row id `id`, or nothing.
  std::optional<ModelRecord> model_by_id(RowId id) const;

  //! Makes `version` the active one again (nothing is deleted) and records the change. Throws
  //! InputError for an unknown tool, material or version ("rollback.version = 7: no such version of
  //! SC EM D10 Z4 in S50C; versions 1–3"). Making the active version active again changes nothing.
  //! Returns the now active version.
  ModelRecord rollback(std::string_view tool_name, std::string_view material_name, int version);

  //! Every change of the active version of the pair, oldest first.
  std::vector<ActivationEvent> activation_history(std::string_view tool_name,
                                                  std::string_view material_name) const;

  // ---- cutting tests ----

  //! Stores a cutting test (conditions name the tool and material). Throws InputError for unknown
  //! names and every validate() problem. Returns it with its id and time stamp.
  StoredCuttingTest add_cutting_test(const CuttingTestRecord& test);

  //! The cutting tests of the pair, oldest first. Throws InputError for an unknown tool or material.
  std::vector<StoredCuttingTest> cutting_tests(std::string_view tool_name, std::string_view material_name) const;

  //! Every cutting test, ordered by tool name, material name, time and id.
  std::vector<StoredCuttingTest> all_cutting_tests() const;

  // ---- learning history ----

  //! Appends a learning entry. Throws InputError when a model id does not exist or validate() finds
  //! a problem. Returns it with its id and time stamp.
  LearningEntry add_learning_entry(const LearningEntry& entry);

  //! The learning entries whose model before or after belongs to the pair, oldest first. Throws
  //! InputError for an unknown tool or material.
  std::vector<LearningEntry> learning_history(std::string_view tool_name, std::string_view material_name) const;

  //! Every learning entry, oldest first.
  std::vector<LearningEntry> all_learning_entries() const;

  // ---- for tests ----

  //! Installs (or with an empty function removes) the write hook: see WriteHook.
  void set_write_hook(WriteHook hook);

  class Impl;
  //! The implementation, for the module's own sources (import runs its rows in one transaction).
  Impl& impl() { return *impl_; }
  const Impl& impl() const { return *impl_; }

 private:
  explicit Store(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace feedplan::model_db
