#include "size_effect_search.hpp"

#include <boost/math/tools/minima.hpp>

#include <cmath>
#include <cstdint>

namespace feedplan::model::detail {
namespace {

//! Bits of precision of Brent's search: 2^−12 of the interval, 0.00015 in m, far below its uncertainty.
constexpr int kBits = 12;
constexpr std::uintmax_t kMaxEvaluations = 30;

}  // namespace

double size_reference_chip_mm(const std::vector<MechanisticCuttingTest>& tests) {
  double log_sum = 0.0;
  for (const auto& t : tests) log_sum += std::log(t.feed_per_tooth_mm);
  return std::exp(log_sum / static_cast<double>(tests.size()));
}

SizeEffectSearch search_size_exponent(const std::function<double(double)>& residual_n2) {
  SizeEffectSearch result;
  result.residual_without_n2 = residual_n2(0.0);
  std::uintmax_t evaluations = kMaxEvaluations;
  const auto [m, r] = boost::math::tools::brent_find_minima(residual_n2, 0.0, kMaxSizeExponent, kBits, evaluations);
  if (r < result.residual_without_n2) {
    result.exponent = m;
    result.residual_n2 = r;
  } else {
    result.residual_n2 = result.residual_without_n2;
  }
  result.at_upper_bound = result.exponent > kMaxSizeExponent * (1.0 - 1e-3);
  return result;
}

}  // namespace feedplan::model::detail
