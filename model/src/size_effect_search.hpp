#pragma once
// The size-effect exponent of cutting tests (mechanistic identification with identify_size_effect,
// private to the model module). With m fixed the force is linear in the coefficients again, so m is found
// by a one-dimensional search of the residual of the coefficients' least-squares fit over m (variable
// projection), with the runout, helix, phases and sensor found before held.

#include <functional>
#include <vector>

#include "feedplan/model/mechanistic_identification.hpp"

namespace feedplan::model::detail {

//! Largest size-effect exponent searched: k_c = k_1·h^(−m) with m up to about 0.5 is what the literature
//! reports for steels and aluminium (Kienzle's 1 − m_c lies between 0.6 and 0.9); beyond, the fit is
//! trading the exponent against the edge coefficients.
inline constexpr double kMaxSizeExponent = 0.6;

//! The reference chip the identified coefficients hold at: the geometric mean of the tests' f_z, mm, so
//! that the cutting coefficients and the exponent are least correlated.
double size_reference_chip_mm(const std::vector<MechanisticCuttingTest>& tests);

//! The search's result.
struct SizeEffectSearch {
  double exponent = 0.0;       //!< the m with the smallest residual, in [0, kMaxSizeExponent]
  double residual_n2 = 0.0;    //!< sum of squared residuals there, N²
  double residual_without_n2 = 0.0;  //!< the same at m = 0, N²
  bool at_upper_bound = false;  //!< the smallest residual is at kMaxSizeExponent: the search was cut short
};

//! Brent's minimisation of `residual_n2(m)` over [0, kMaxSizeExponent] (boost::math), with m = 0 compared too
//! (the residual may fall all the way to the bound).
SizeEffectSearch search_size_exponent(const std::function<double(double)>& residual_n2);

}  // namespace feedplan::model::detail
