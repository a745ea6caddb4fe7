#pragma once
// Internal: the median the cutting-test import takes of per-revolution values (steady-state rule of
// cutting_test_import.hpp) and of the log's time steps.

#include <vector>

namespace feedplan::model_db::detail {

//! Median of the finite values (the mean of the middle two for an even count); NaN when there are none.
double median(std::vector<double> values);

}  // namespace feedplan::model_db::detail
