#pragma once
// A mechanistic model version from the cutting tests a store holds (docs/method.md §5.7): each stored test
// with its revolution-synchronous force becomes a model::MechanisticCuttingTest (the tool record's radius,
// flutes and catalogue helix; the straight cut's engaged arc from the mode and radial depth), the
// coefficients — and, where the tests allow, the per-tooth runout — are identified from them together
// (model::identify_mechanistic), and the version's statistics are those of a response surface's, over the
// same quantity: each test's mean steady per-revolution peak, predicted by the kernel on the test's arc.
// The leave-one-out error refits without each test in turn (same phases and runout search), so it says how
// well the model predicts a cut it was not fitted on — the figure `plan` compares the kinds by.

#include <string>
#include <vector>

#include "feedplan/model/mechanistic_identification.hpp"
#include "feedplan/model/prediction_interval.hpp"
#include "feedplan/model_db/store_records.hpp"

namespace feedplan::model_db {

//! How to identify.
struct MechanisticFitOptions {
  //! Identify the per-tooth runout too (needs ≥ 2 flutes; tests that cannot show it leave it near 0).
  bool identify_runout = true;
  //! With the runout, identify the flutes' helix too (model::MechanisticIdentificationOptions::identify_helix).
  bool identify_helix = true;
  //! Identify the size-effect exponent (model::MechanisticIdentificationOptions::identify_size_effect); tests
  //! at one feed leave it at 0 and say so.
  bool identify_size_effect = true;
  //! Identify the dynamometer's modes too (model::MechanisticIdentificationOptions::identify_sensor) and fit the
  //! coefficients of the force on the tool through them: for tests read by a sensor that rings at the tooth
  //! pulses. The leave-one-out error is then not computed (its refit does not model the sensor).
  bool identify_sensor = false;
  //! Fit the coefficients to the tests' mean per-revolution peaks as well as to their force over a revolution
  //! (model::MechanisticIdentificationOptions::match_peaks).
  bool match_peaks = true;
  //! Compute the leave-one-out error (one identification per test); false leaves fit.loo_rmse_n at 0.
  bool leave_one_out = true;
};

//! The identified version, ready for Store::add_model, and what the user should know about it.
struct MechanisticFitResult {
  ModelRecord record;              //!< kind kMechanistic, source kCuttingTests, fit statistics filled
  int tests_used = 0;              //!< tests with a synchronous force, identified from
  int tests_without_signal = 0;    //!< tests stored without their synchronous force (skipped)
  //! Predicted peak of each test used, N, in the order of the tests given (those with a signal).
  std::vector<double> predicted_peaks_n;
  std::vector<double> measured_peaks_n;   //!< their measured mean steady peaks, N, same order
  //! Sentences for the user: skipped tests, what the tests could not identify, runout convergence.
  std::vector<std::string> notes;
};

//! Identifies a mechanistic version of `tool` in `material_name` from `tests` (the pair's stored tests).
//! Throws InputError ("cutting_tests = …: …") when fewer than 2 tests hold a synchronous force, naming
//! what to do (import the tests' logs again with a feedplan that keeps the force over a revolution), and
//! with model::validate's problems for tests that are not usable.
MechanisticFitResult fit_mechanistic(const ToolRecord& tool, const std::string& material_name,
                                     const std::vector<StoredCuttingTest>& tests,
                                     const MechanisticFitOptions& options = {});

//! Stored test number `index` of `tool` as identification takes it: the tool record's radius, flutes and
//! catalogue helix, the straight cut's engaged arc, a_p, f_z, the synchronous force and the steady peaks.
model::MechanisticCuttingTest identification_test(const ToolRecord& tool, const StoredCuttingTest& stored, int index);

//! The straight cut of `test` as the mechanistic kernel sees it: the predicted mean steady peak of `model`
//! for the test's conditions with `tool`'s cutter, N.
double predicted_test_peak_n(const model::MechanisticModel& model, const ToolRecord& tool, const CuttingTestRecord& test);

//! The prediction interval (model/prediction_interval.hpp) of that peak: the version's coefficient
//! covariance and the tests' revolution-to-revolution spread `revolution_spread_rel`.
model::PredictionInterval predicted_test_interval(const MechanisticFit& fit, const ToolRecord& tool,
                                                  const CuttingTestRecord& test, double revolution_spread_rel);

}  // namespace feedplan::model_db
