#pragma once
// The rows of the model database (Store) as plain structs: tools, workpiece materials, model versions
// with their fit statistics, stored cutting tests and learning-history entries, and the checks each
// one passes before it is written. Field names are the column names; every dimensional value carries
// its unit in its name (docs/method.md §3).

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/model_db/cutting_test.hpp"
#include "feedplan/model/covariance.hpp"
#include "feedplan/model/mechanistic_model.hpp"
#include "feedplan/model/response_surface_model.hpp"

namespace feedplan::model_db {

//! A row id in the store; 0 means "not stored yet".
using RowId = std::int64_t;

//! An end mill as the store keeps it.
struct ToolRecord {
  RowId id = 0;                  //!< row id (ignored when adding)
  std::string name;              //!< unique name, e.g. "SC EM D10 Z4"
  double diameter_mm = 0.0;      //!< cutting diameter, mm (> 0)
  int flutes = 0;                //!< number of flutes (teeth), ≥ 1
  double helix_deg = 0.0;        //!< helix angle, degrees, in [0, 90)
  std::string tool_material;     //!< substrate, e.g. "solid carbide", "HSS" (may be empty)
  std::string coating;           //!< coating, e.g. "TiAlN" (may be empty)
  std::string notes;             //!< free text
};

//! ISO 513 workpiece material groups.
enum class IsoGroup {
  kP,  //!< steel
  kM,  //!< stainless steel
  kK,  //!< cast iron
  kN,  //!< non-ferrous (aluminium, copper)
  kS,  //!< heat-resistant super alloys and titanium
  kH,  //!< hardened steel
};

//! "P", "M", "K", "N", "S" or "H".
std::string to_string(IsoGroup group);

//! The group named by one letter (case-insensitive), or nothing for anything else.
std::optional<IsoGroup> parse_iso_group(std::string_view text);

//! A workpiece material as the store keeps it.
struct MaterialRecord {
  RowId id = 0;                      //!< row id (ignored when adding)
  std::string name;                  //!< unique name, e.g. "S50C"
  IsoGroup iso_group = IsoGroup::kP; //!< ISO 513 group
  double hardness_value = 0.0;       //!< hardness number, e.g. 200 (> 0)
  std::string hardness_scale = "HB"; //!< its scale: "HB", "HV", "HRC" or "HRB"
  std::string notes;                 //!< free text
};

//! How a model version came to be.
enum class ModelSource {
  kCuttingTests,  //!< fitted to cutting tests in this store
  kLearned,       //!< refitted from measured force logs of production cycles (learning)
  kImported,      //!< taken from outside (a model file, another shop's numbers)
};

//! "cutting_tests", "learned" or "imported".
std::string to_string(ModelSource source);

//! The source named by its text, or nothing.
std::optional<ModelSource> parse_model_source(std::string_view text);

//! How well a model fits the data it was fitted on. All zero when unknown (e.g. an imported model).
struct ModelFitStatistics {
  int n = 0;                                 //!< number of data points fitted
  double rmse_n = 0.0;                       //!< root-mean-square residual, N
  double r_squared = 0.0;                    //!< coefficient of determination
  model::Covariance covariance;              //!< covariance of β, N²
  std::array<double, 6> standard_errors{};   //!< standard error of each β, N
  double loo_rmse_n = 0.0;                   //!< leave-one-out RMS prediction error, N
  //! Leave-one-engagement-out RMS prediction error (engagement_groups.hpp), N; 0: not computed.
  double engagement_cv_rmse_n = 0.0;
};

//! Which force model a version holds.
enum class ModelKind {
  kResponseSurface,  //!< seed 003 Eq. 1: the per-revolution peak as a quadratic in (t_m, L)
  kMechanistic,      //!< cutting and edge coefficients on the engaged arcs (model/mechanistic_model.hpp)
};

//! "response_surface" or "mechanistic" (the store's and the exchange file's spelling).
std::string to_string(ModelKind kind);
//! The kind named "response_surface"/"response-surface" or "mechanistic", or nothing for anything else.
std::optional<ModelKind> parse_model_kind(std::string_view text);

//! What a mechanistic version holds beyond the fields every version has: the coefficients and what their
//! identification from the cutting tests said (model/mechanistic_identification.hpp).
struct MechanisticFit {
  model::MechanisticModel model;  //!< coefficients, size effect, per-tooth runout
  //! Covariance of (K_tc, K_rc, K_te, K_re) from the identification, N²/mm⁴, N²/mm³, N²/mm² (row-major)
  std::array<std::array<double, 4>, 4> covariance{};
  double signal_rms_residual_n = 0.0;  //!< RMS residual of the synchronous-average bins, N
  double condition_number = 0.0;       //!< of the column-scaled regressor matrix
  bool identified = true;              //!< false: the tests left a combination of coefficients poorly determined
  std::vector<std::string> unidentifiable;  //!< what the tests could not tell, in words
};

//! One version of the model of one tool in one material.
struct ModelRecord {
  RowId id = 0;                        //!< row id (set by the store)
  std::string tool_name;               //!< tool, by name
  std::string material_name;           //!< material, by name
  int version = 0;                     //!< 1, 2, … per tool and material (set by the store)
  std::optional<RowId> parent_id;      //!< the version this one was derived from (set by the store)
  std::optional<int> parent_version;   //!< that version's number, for people (set by the store)
  ModelKind kind = ModelKind::kResponseSurface;  //!< which force model the version holds
  //! The response surface: coefficients, centres, scales, fitted range, conditions. For a mechanistic
  //! version only the range and conditions of the cutting tests it was identified from (β = 0): never
  //! a force model.
  model::ResponseSurfaceModel model;
  //! The mechanistic model of a kMechanistic version (empty for a response surface).
  std::optional<MechanisticFit> mechanistic;
  //! Fit statistics. For a mechanistic version n, rmse_n, r_squared and loo_rmse_n are over the tests'
  //! mean per-revolution peaks predicted by the kernel (comparable with a response surface's), and the
  //! covariance and standard errors of β are 0.
  ModelFitStatistics fit;
  ModelSource source = ModelSource::kCuttingTests;  //!< how the version came to be
  std::string created_at;              //!< UTC ISO 8601, e.g. "2024-05-01T12:00:00.000Z" (set by the store)
  std::string note;                    //!< free text, e.g. "learned from pocket A, 3 logs"
  bool active = false;                 //!< the version the planner uses (set by the store)
};

//! A cutting test as stored: the record plus the store's id and time stamp.
struct StoredCuttingTest {
  RowId id = 0;                 //!< row id (set by the store)
  std::string created_at;       //!< UTC ISO 8601 (set by the store)
  CuttingTestRecord test;       //!< conditions, derived t_m / L, peak statistics, steady peaks
};

//! One learning step (appended by the learning module; never changed afterwards).
struct LearningEntry {
  RowId id = 0;                         //!< row id (set by the store)
  RowId model_id_before = 0;            //!< model version the cycle was planned with
  RowId model_id_after = 0;             //!< model version learned from it (0: none was stored)
  std::string part_name;                //!< part or cycle the logs came from
  int n_samples = 0;                    //!< aligned samples used
  double error_before_n = 0.0;          //!< RMS prediction error of the old model on them, N
  double error_after_n = 0.0;           //!< RMS prediction error of the new model on them, N
  std::string created_at;               //!< UTC ISO 8601 (set by the store)
  std::string note;                     //!< free text
};

//! One per-revolution sample a learning step learned from (the model's inputs where and at the feed it
//! was measured, and the measured peak), stored with its learning entry.
struct LearnedSample {
  double chip_mm = 0.0;            //!< t_m, mm
  double contact_length_mm = 0.0;  //!< L, mm
  double force_n = 0.0;            //!< measured peak XY force, on the model's axial-depth scale, N
  double weight = 1.0;             //!< relative precision (> 0)
  double s_mm = 0.0;               //!< where on the planned path, mm
};

//! Why a model version became the active one.
enum class ActivationReason {
  kAdded,     //!< a new version was added
  kRollback,  //!< rollback() made an older version active again
  kImported,  //!< an import made it active
};

//! One change of the active version of a tool in a material (the audit trail of add and rollback).
struct ActivationEvent {
  RowId id = 0;                          //!< row id
  std::string tool_name;                 //!< tool
  std::string material_name;             //!< material
  int version = 0;                       //!< the version made active
  std::optional<int> previous_version;   //!< the version active before (none for the first)
  ActivationReason reason = ActivationReason::kAdded;  //!< why
  std::string created_at;                //!< UTC ISO 8601
};

//! Every problem with `tool` before it is written: "tools.diameter_mm = -3: must be > 0", …
std::vector<InputProblem> validate(const ToolRecord& tool);

//! Every problem with `material`: empty name, hardness not finite and > 0, unknown scale.
std::vector<InputProblem> validate(const MaterialRecord& material);

//! Every problem with a model version's numbers: finite β ("models.beta[2] = nan: must be finite"),
//! finite centres, scales > 0, an ordered fitted range, finite statistics, n ≥ 0, covariance finite.
std::vector<InputProblem> validate(const ModelRecord& model);

//! Every problem with a cutting test's numbers: positive finite conditions, finite non-negative derived
//! values and peaks, revolutions_used ≤ revolutions_total, finite steady peaks.
std::vector<InputProblem> validate(const CuttingTestRecord& test);

//! Every problem with a learning entry: n_samples ≥ 0, finite non-negative errors, a model id given.
std::vector<InputProblem> validate(const LearningEntry& entry);

}  // namespace feedplan::model_db
