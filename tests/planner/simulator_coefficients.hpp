#pragma once
// The virtual machine's cutting coefficients of a material as a mechanistic model (known, not fitted):
// what the planner tests that check the mechanistic kind against the simulator start from.

#include "feedplan/model/mechanistic_model.hpp"
#include "feedplan/sim/material.hpp"

namespace feedplan::planner::testing {

inline model::MechanisticModel mechanistic(const sim::CuttingCoefficients& k) {
  model::MechanisticModel m;
  m.ktc_n_per_mm2 = k.ktc_n_per_mm2;
  m.krc_n_per_mm2 = k.krc_n_per_mm2;
  m.kac_n_per_mm2 = k.kac_n_per_mm2;
  m.kte_n_per_mm = k.kte_n_per_mm;
  m.kre_n_per_mm = k.kre_n_per_mm;
  m.kae_n_per_mm = k.kae_n_per_mm;
  m.size_exponent = k.size_exponent;
  m.size_reference_chip_mm = k.size_reference_chip_mm;
  m.size_min_chip_mm = k.size_min_chip_mm;
  return m;
}

}  // namespace feedplan::planner::testing
