#include "feedplan/control/beta_switching.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "feedplan/control/fractional_order_hold.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"

namespace feedplan::control {

std::vector<double> seed_004_beta_bank() {
  std::vector<double> bank;
  for (int i = 1; i <= 15; ++i) bank.push_back(1.0 - (i - 1) / 10.0);
  return bank;
}

std::size_t fixed_set_choice(std::span<const double> indices, std::size_t active) {
  assert(!indices.empty());
  std::size_t best = active < indices.size() && !std::isnan(indices[active]) ? active : indices.size();
  for (std::size_t i = 0; i < indices.size(); ++i) {
    if (std::isnan(indices[i])) continue;
    if (best == indices.size() || indices[i] < indices[best]) best = i;
  }
  return best == indices.size() ? std::min(active, indices.size() - 1) : best;
}

std::vector<InputProblem> validate(const NeighbourSearchParameters& parameters, const std::string& field_prefix) {
  ProblemList problems(field_prefix);
  problems.add_all(validate_beta(parameters.initial_beta, field_prefix + "initial_beta"));
  if (!(std::isfinite(parameters.initial_step) && parameters.initial_step > 0.0 && parameters.initial_step <= 2.0)) {
    problems.add_value("initial_step", shortest_number_text(parameters.initial_step),
                       "must be finite and in (0, 2], the width of the hold's range");
  }
  if (!(std::isfinite(parameters.step_divisor) && parameters.step_divisor > 1.0)) {
    problems.add_value("step_divisor", shortest_number_text(parameters.step_divisor), "must be finite and > 1");
  }
  return problems.take();
}

NeighbourBetaSearch::NeighbourBetaSearch(const NeighbourSearchParameters& parameters)
    : beta_(parameters.initial_beta), step_(parameters.initial_step), divisor_(parameters.step_divisor) {
  assert(validate(parameters).empty());
}

std::array<double, 3> NeighbourBetaSearch::candidates() const {
  return {std::max(beta_ - step_, -1.0), beta_, std::min(beta_ + step_, 1.0)};
}

bool NeighbourBetaSearch::update(const std::array<double, 3>& indices) {
  const std::size_t best = fixed_set_choice(indices, 1);
  const double chosen = candidates()[best];
  if (best == 1 || chosen == beta_) {
    step_ /= divisor_;
    return false;
  }
  beta_ = chosen;
  return true;
}

}  // namespace feedplan::control
