#include "feedplan/model/mechanistic_model.hpp"

#include <cmath>
#include <string>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"

namespace feedplan::model {

std::vector<InputProblem> validate(const MechanisticModel& model, const std::string& field_prefix) {
  ProblemList problems(field_prefix);
  problems.finite("ktc_n_per_mm2", model.ktc_n_per_mm2);
  problems.finite("krc_n_per_mm2", model.krc_n_per_mm2);
  problems.finite("kac_n_per_mm2", model.kac_n_per_mm2);
  problems.finite("kte_n_per_mm", model.kte_n_per_mm);
  problems.finite("kre_n_per_mm", model.kre_n_per_mm);
  problems.finite("kae_n_per_mm", model.kae_n_per_mm);
  if (!(model.size_exponent >= 0.0 && model.size_exponent < 1.0)) {
    problems.add_value("size_exponent", shortest_number_text(model.size_exponent), "must be in [0, 1)");
  }
  problems.positive("size_reference_chip_mm", model.size_reference_chip_mm);
  problems.positive("size_min_chip_mm", model.size_min_chip_mm);
  for (std::size_t j = 0; j < model.runout_mm.size(); ++j) {
    problems.finite("runout_mm[" + std::to_string(j) + "]", model.runout_mm[j]);
  }
  if (model.helix_deg && !(std::abs(*model.helix_deg) < 90.0)) {
    problems.add_value("helix_deg", shortest_number_text(*model.helix_deg), "must be in (−90, 90)");
  }
  return problems.take();
}

}  // namespace feedplan::model
