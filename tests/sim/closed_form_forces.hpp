#pragma once
// Test oracle: the closed-form mean forces of a straight cut (Altintas, Manufacturing Automation
// ch. 2; docs/method.md §6.1), written here independently of the code under test, and the Al7075
// coefficients the checks use. Shared by milling_forces_test.cpp and milling_simulation_test.cpp.

#include <cmath>
#include <numbers>

#include "feedplan/sim/cutting_coefficients.hpp"

namespace feedplan::sim {

//! Mean force over one revolution in the feed frame (x along the feed).
struct MeanForce {
  double fx_n = 0.0;  //!< mean force along the feed, N
  double fy_n = 0.0;  //!< mean force normal to the feed, N
};

//! F̄x, F̄y of docs/method.md §6.1 for `n` teeth, axial depth `a_mm`, feed per tooth `c_mm`, every tooth
//! engaged from `phi_st` to `phi_ex` (rad), feed along +x.
inline MeanForce closed_form_mean(int n, double a_mm, double c_mm, double phi_st, double phi_ex,
                                  const CuttingCoefficients& k) {
  constexpr double kPi = std::numbers::pi;
  auto fx = [&](double p) {
    return n * a_mm * c_mm / (8 * kPi) * (k.ktc_n_per_mm2 * std::cos(2 * p) - k.krc_n_per_mm2 * (2 * p - std::sin(2 * p))) +
           n * a_mm / (2 * kPi) * (-k.kte_n_per_mm * std::sin(p) + k.kre_n_per_mm * std::cos(p));
  };
  auto fy = [&](double p) {
    return n * a_mm * c_mm / (8 * kPi) * (k.ktc_n_per_mm2 * (2 * p - std::sin(2 * p)) + k.krc_n_per_mm2 * std::cos(2 * p)) -
           n * a_mm / (2 * kPi) * (k.kte_n_per_mm * std::cos(p) + k.kre_n_per_mm * std::sin(p));
  };
  return {fx(phi_ex) - fx(phi_st), fy(phi_ex) - fy(phi_st)};
}

//! Al7075 cutting coefficients of docs/method.md §6.2 (Altintas), no size effect.
inline CuttingCoefficients al7075() {
  CuttingCoefficients k;
  k.ktc_n_per_mm2 = 796;
  k.krc_n_per_mm2 = 169;
  k.kac_n_per_mm2 = 222;
  k.kte_n_per_mm = 27.7;
  k.kre_n_per_mm = 30.8;
  k.kae_n_per_mm = 1.4;
  return k;
}

}  // namespace feedplan::sim
