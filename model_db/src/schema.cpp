#include "schema.hpp"

#include <cstdio>
#include <string>

#include "feedplan/core/input_error.hpp"

namespace feedplan::model_db::detail {
namespace {

// Version 1: everything. Column names carry units (docs/method.md §3). The CHECK constraints repeat the
// validate() rules as a last line of defence for files written by other programs.
const char* const kVersion1 = R"sql(
CREATE TABLE tools (
  id INTEGER PRIMARY KEY,
  name TEXT NOT NULL UNIQUE CHECK (length(name) > 0),
  diameter_mm REAL NOT NULL CHECK (diameter_mm > 0),
  flutes INTEGER NOT NULL CHECK (flutes >= 1),
  helix_deg REAL NOT NULL CHECK (helix_deg >= 0 AND helix_deg < 90),
  tool_material TEXT NOT NULL DEFAULT '',
  coating TEXT NOT NULL DEFAULT '',
  notes TEXT NOT NULL DEFAULT ''
);
CREATE TABLE materials (
  id INTEGER PRIMARY KEY,
  name TEXT NOT NULL UNIQUE CHECK (length(name) > 0),
  iso_group TEXT NOT NULL CHECK (iso_group IN ('P', 'M', 'K', 'N', 'S', 'H')),
  hardness_value REAL NOT NULL CHECK (hardness_value > 0),
  hardness_scale TEXT NOT NULL CHECK (hardness_scale IN ('HB', 'HV', 'HRC', 'HRB')),
  notes TEXT NOT NULL DEFAULT ''
);
CREATE TABLE models (
  id INTEGER PRIMARY KEY,
  tool_id INTEGER NOT NULL REFERENCES tools(id),
  material_id INTEGER NOT NULL REFERENCES materials(id),
  version INTEGER NOT NULL CHECK (version >= 1),
  parent_id INTEGER REFERENCES models(id),
  beta0 REAL NOT NULL,
  beta1 REAL NOT NULL,
  beta2 REAL NOT NULL,
  beta11 REAL NOT NULL,
  beta22 REAL NOT NULL,
  beta12 REAL NOT NULL,
  chip_center_mm REAL NOT NULL,
  chip_scale_mm REAL NOT NULL CHECK (chip_scale_mm > 0),
  contact_length_center_mm REAL NOT NULL,
  contact_length_scale_mm REAL NOT NULL CHECK (contact_length_scale_mm > 0),
  chip_min_mm REAL NOT NULL,
  chip_max_mm REAL NOT NULL,
  contact_length_min_mm REAL NOT NULL,
  contact_length_max_mm REAL NOT NULL,
  axial_depth_mm REAL NOT NULL,
  spindle_rpm REAL NOT NULL,
  quantity TEXT NOT NULL,
  fit_n INTEGER NOT NULL CHECK (fit_n >= 0),
  rmse_n REAL NOT NULL,
  r_squared REAL NOT NULL,
  covariance_json TEXT NOT NULL,       -- 6×6 covariance of β, row-major JSON array of 36 numbers, N²
  standard_errors_json TEXT NOT NULL,  -- JSON array of 6 standard errors, N
  loo_rmse_n REAL NOT NULL,
  source TEXT NOT NULL CHECK (source IN ('cutting_tests', 'learned', 'imported')),
  created_at TEXT NOT NULL,
  note TEXT NOT NULL DEFAULT '',
  active INTEGER NOT NULL CHECK (active IN (0, 1)),
  UNIQUE (tool_id, material_id, version)
);
-- At most one active version per tool and material (the code keeps it exactly one).
CREATE UNIQUE INDEX models_one_active ON models (tool_id, material_id) WHERE active = 1;
CREATE TRIGGER models_never_deleted BEFORE DELETE ON models
  BEGIN SELECT RAISE(ABORT, 'models are never deleted; roll back to another version instead'); END;
CREATE TABLE model_activations (
  id INTEGER PRIMARY KEY,
  tool_id INTEGER NOT NULL REFERENCES tools(id),
  material_id INTEGER NOT NULL REFERENCES materials(id),
  model_id INTEGER NOT NULL REFERENCES models(id),
  previous_model_id INTEGER REFERENCES models(id),
  reason TEXT NOT NULL CHECK (reason IN ('added', 'rollback', 'imported')),
  created_at TEXT NOT NULL
);
CREATE TRIGGER model_activations_append_only_update BEFORE UPDATE ON model_activations
  BEGIN SELECT RAISE(ABORT, 'model_activations is append-only'); END;
CREATE TRIGGER model_activations_append_only_delete BEFORE DELETE ON model_activations
  BEGIN SELECT RAISE(ABORT, 'model_activations is append-only'); END;
CREATE TABLE cutting_tests (
  id INTEGER PRIMARY KEY,
  tool_id INTEGER NOT NULL REFERENCES tools(id),
  material_id INTEGER NOT NULL REFERENCES materials(id),
  spindle_rpm REAL NOT NULL CHECK (spindle_rpm > 0),
  feed_mm_per_min REAL NOT NULL CHECK (feed_mm_per_min > 0),
  radial_depth_mm REAL NOT NULL CHECK (radial_depth_mm > 0),
  axial_depth_mm REAL NOT NULL CHECK (axial_depth_mm > 0),
  mode TEXT NOT NULL CHECK (mode IN ('down', 'up', 'slot')),
  feed_per_tooth_mm REAL NOT NULL,
  chip_mm REAL NOT NULL,
  contact_length_mm REAL NOT NULL,
  peak_mean_n REAL NOT NULL,
  peak_std_n REAL NOT NULL,
  peak_min_n REAL NOT NULL,
  peak_max_n REAL NOT NULL,
  revolutions_total INTEGER NOT NULL,
  revolutions_used INTEGER NOT NULL,
  source_file TEXT NOT NULL DEFAULT '',
  notes_json TEXT NOT NULL DEFAULT '[]',  -- JSON array of strings
  created_at TEXT NOT NULL
);
CREATE INDEX cutting_tests_by_pair ON cutting_tests (tool_id, material_id, created_at);
-- The steady per-revolution peaks of each cutting test, in time order.
CREATE TABLE cutting_test_peaks (
  cutting_test_id INTEGER NOT NULL REFERENCES cutting_tests(id),
  revolution_index INTEGER NOT NULL,
  peak_n REAL NOT NULL,
  PRIMARY KEY (cutting_test_id, revolution_index)
) WITHOUT ROWID;
CREATE TABLE learning_history (
  id INTEGER PRIMARY KEY,
  model_id_before INTEGER NOT NULL REFERENCES models(id),
  model_id_after INTEGER REFERENCES models(id),
  part_name TEXT NOT NULL,
  n_samples INTEGER NOT NULL CHECK (n_samples >= 0),
  error_before_n REAL NOT NULL,
  error_after_n REAL NOT NULL,
  created_at TEXT NOT NULL,
  note TEXT NOT NULL DEFAULT ''
);
CREATE TRIGGER learning_history_append_only_update BEFORE UPDATE ON learning_history
  BEGIN SELECT RAISE(ABORT, 'learning_history is append-only'); END;
CREATE TRIGGER learning_history_append_only_delete BEFORE DELETE ON learning_history
  BEGIN SELECT RAISE(ABORT, 'learning_history is append-only'); END;
)sql";

// Version 2: the per-revolution samples each learning step learned from, so that a later batch refit
// spans every logged cycle of the tool and material.
constexpr const char* kVersion2 = R"sql(
CREATE TABLE learning_samples (
  learning_entry_id INTEGER NOT NULL REFERENCES learning_history(id),
  sample_index INTEGER NOT NULL CHECK (sample_index >= 0),
  chip_mm REAL NOT NULL,
  contact_length_mm REAL NOT NULL,
  force_n REAL NOT NULL,
  weight REAL NOT NULL CHECK (weight > 0),
  s_mm REAL NOT NULL,
  PRIMARY KEY (learning_entry_id, sample_index)
) WITHOUT ROWID;
CREATE TRIGGER learning_samples_append_only_update BEFORE UPDATE ON learning_samples
  BEGIN SELECT RAISE(ABORT, 'learning_samples is append-only'); END;
CREATE TRIGGER learning_samples_append_only_delete BEFORE DELETE ON learning_samples
  BEGIN SELECT RAISE(ABORT, 'learning_samples is append-only'); END;
)sql";

// Version 3: the revolution-synchronous average force of each cutting test (Fx and Fy per spindle-angle
// bin, JSON arrays of equal length), what identifying cutting coefficients and runout needs.
constexpr const char* kVersion3 = R"sql(
CREATE TABLE cutting_test_signals (
  cutting_test_id INTEGER PRIMARY KEY REFERENCES cutting_tests(id),
  fx_json TEXT NOT NULL,
  fy_json TEXT NOT NULL
);
)sql";

// Version 4: model versions of two kinds. A version is a response surface (seed 003 Eq. 1) or a mechanistic
// model (cutting and edge coefficients, size effect, per-tooth runout) with its identification; each kind
// has its own active version per tool and material. A mechanistic version keeps the range and conditions
// of its tests in the models row (β = 0) and its coefficients in mechanistic_models.
constexpr const char* kVersion4 = R"sql(
ALTER TABLE models ADD COLUMN kind TEXT NOT NULL DEFAULT 'response_surface'
  CHECK (kind IN ('response_surface', 'mechanistic'));
DROP INDEX models_one_active;
CREATE UNIQUE INDEX models_one_active ON models (tool_id, material_id, kind) WHERE active = 1;
CREATE TABLE mechanistic_models (
  model_id INTEGER PRIMARY KEY REFERENCES models(id),
  ktc_n_per_mm2 REAL NOT NULL,
  krc_n_per_mm2 REAL NOT NULL,
  kac_n_per_mm2 REAL NOT NULL,
  kte_n_per_mm REAL NOT NULL,
  kre_n_per_mm REAL NOT NULL,
  kae_n_per_mm REAL NOT NULL,
  size_exponent REAL NOT NULL CHECK (size_exponent >= 0 AND size_exponent < 1),
  size_reference_chip_mm REAL NOT NULL CHECK (size_reference_chip_mm > 0),
  size_min_chip_mm REAL NOT NULL CHECK (size_min_chip_mm > 0),
  runout_json TEXT NOT NULL,           -- JSON array of the runout per tooth, mm (empty: none)
  helix_deg REAL CHECK (helix_deg IS NULL OR (helix_deg > -90 AND helix_deg < 90)),  -- identified; NULL: the tool's
  covariance_json TEXT NOT NULL,       -- 4×4 covariance of (Ktc, Krc, Kte, Kre), row-major JSON array of 16
  signal_rms_residual_n REAL NOT NULL,
  condition_number REAL NOT NULL,
  identified INTEGER NOT NULL CHECK (identified IN (0, 1)),
  unidentifiable_json TEXT NOT NULL    -- JSON array of strings
);
CREATE TRIGGER mechanistic_models_never_changed BEFORE UPDATE ON mechanistic_models
  BEGIN SELECT RAISE(ABORT, 'mechanistic models are never changed; add a version instead'); END;
CREATE TRIGGER mechanistic_models_never_deleted BEFORE DELETE ON mechanistic_models
  BEGIN SELECT RAISE(ABORT, 'models are never deleted; roll back to another version instead'); END;
)sql";

int pragma_int(Connection& connection, const char* pragma) {
  Statement statement(connection, std::string("PRAGMA ") + pragma);
  return statement.step() ? statement.column_int(0) : 0;
}

int user_table_count(Connection& connection) {
  Statement statement(connection, "SELECT count(*) FROM sqlite_schema WHERE name NOT LIKE 'sqlite_%'");
  return statement.step() ? statement.column_int(0) : 0;
}

std::string hex(int value) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%08x", static_cast<unsigned>(value));
  return text;
}

void run_quick_check(Connection& connection) {
  Statement statement(connection, "PRAGMA quick_check(5)");
  std::string problems;
  while (statement.step()) {
    const std::string row = statement.column_text(0);
    if (row == "ok") continue;
    if (!problems.empty()) problems += "; ";
    problems += row;
  }
  if (!problems.empty()) {
    throw InputError(connection.path(), "is a damaged model database (quick_check: " + problems +
                                            "); restore it from a backup or an export");
  }
}

// Version 5: each version's leave-one-engagement-out error on its tests (model_db/engagement_groups.hpp), by
// which plan chooses the kind; 0 where it was not computed (versions fitted before, or on fewer engagements).
constexpr const char* kVersion5 = R"sql(
ALTER TABLE models ADD COLUMN engagement_cv_rmse_n REAL NOT NULL DEFAULT 0 CHECK (engagement_cv_rmse_n >= 0);
)sql";

}  // namespace

const std::vector<std::string>& schema_migrations() {
  static const std::vector<std::string> migrations{kVersion1, kVersion2, kVersion3, kVersion4, kVersion5};
  return migrations;
}

int prepare_schema(Connection& connection, OpenMode mode, bool quick_check) {
  static_assert(kStoreSchemaVersion == 5, "add the migration step to schema_migrations()");
  const auto& migrations = schema_migrations();
  // Reading the header is the first access to the file: a file that is not a database fails here.
  const int application_id = pragma_int(connection, "application_id");
  const int version = pragma_int(connection, "user_version");
  const bool empty = application_id == 0 && version == 0 && user_table_count(connection) == 0;
  if (empty && mode != OpenMode::kCreate) {
    throw InputError(connection.path(), "is empty (no tables), not a model database: check the path of the model "
                                        "database (--db, $FEEDPLAN_DB); `feedplan db init` would make this file a "
                                        "new database with no models");
  }
  if (!empty && application_id != kApplicationId) {
    throw InputError(connection.path(), "is a SQLite database but not a feedplan model database (application_id " +
                                            hex(application_id) + ", expected " + hex(kApplicationId) + ")");
  }
  if (version > kStoreSchemaVersion) {
    throw InputError(connection.path(), "has model database schema version " + std::to_string(version) +
                                            ", newer than this feedplan knows (" +
                                            std::to_string(kStoreSchemaVersion) + "): upgrade feedplan");
  }
  if (version < 0) {
    // migrations[version] below needs 0 ≤ version; feedplan writes 1 or more with its application_id.
    throw InputError(connection.path(), "has model database schema version " + std::to_string(version) +
                                            ", which feedplan never writes (it writes 1 to " +
                                            std::to_string(kStoreSchemaVersion) +
                                            "): the file was changed outside feedplan; restore it from a backup "
                                            "or an export");
  }
  if (quick_check && !empty) run_quick_check(connection);
  if (mode == OpenMode::kReadOnly) {
    if (version < kStoreSchemaVersion) {
      throw InputError(connection.path(), "has model database schema version " + std::to_string(version) +
                                              " and needs migrating to " + std::to_string(kStoreSchemaVersion) +
                                              ": run `feedplan db init --db " + connection.path() +
                                              "` once (it migrates the file and keeps everything in it)");
    }
    return version;
  }
  // WAL: readers go on while one process writes. journal_mode cannot change inside a transaction.
  connection.exec("PRAGMA journal_mode = WAL");
  if (version == kStoreSchemaVersion) return version;
  WriteTransaction transaction(connection);
  // Another process may have migrated between the read above and taking the write lock.
  const int locked_version = pragma_int(connection, "user_version");
  for (int step = locked_version; step < kStoreSchemaVersion; ++step) {
    connection.exec(migrations[static_cast<std::size_t>(step)]);
  }
  connection.exec("PRAGMA application_id = " + std::to_string(kApplicationId));
  connection.exec("PRAGMA user_version = " + std::to_string(kStoreSchemaVersion));
  transaction.commit();
  return kStoreSchemaVersion;
}

}  // namespace feedplan::model_db::detail
