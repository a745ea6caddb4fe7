#pragma once
// The revolution-to-revolution spread of the peak XY force at fixed cutting conditions, as cutting tests
// show it: the relative standard deviation of each test's per-revolution peaks about that test's own
// mean, pooled over the tests (docs/method.md §5.8). It is the spread part of a prediction interval
// (prediction_interval.hpp): what a model of the mean peak cannot predict, revolution by revolution.

#include <vector>

#include "feedplan/core/input_error.hpp"

namespace feedplan::model {

//! The pooled relative standard deviation of per-revolution peaks, dimensionless:
//!   s_rel² = Σ_t Σ_k (P_tk / P̄_t − 1)² / Σ_t (n_t − 1),
//! with P_tk the k-th peak of test t, P̄_t the test's mean and n_t its count (each test's deviations taken
//! about its own mean, so the tests' different levels do not count as spread; a test with one peak adds
//! nothing). `peaks_per_test_n[t]` holds test t's per-revolution peaks, N (e.g. the steady peaks of a
//! cutting test, force_log::revolution_peaks). Throws feedplan::InputError listing every problem: no test
//! with at least two peaks ("peaks_per_test_n"), a peak that is not finite or < 0
//! ("peaks_per_test_n[t][k]"), a test whose mean is not > 0 ("peaks_per_test_n[t]", tests with two peaks or more).
double pooled_revolution_spread_rel(const std::vector<std::vector<double>>& peaks_per_test_n);

}  // namespace feedplan::model
