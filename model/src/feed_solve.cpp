#include "feedplan/model/feed_solve.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/model/model_prediction.hpp"

namespace feedplan::model {
namespace {

//! The numbers solve_feed() relies on are usable; cheap, so the full validate() (which builds strings)
//! runs only when this fails.
bool usable(const ResponseSurfaceModel& model) {
  for (double b : model.beta) {
    if (!std::isfinite(b)) return false;
  }
  const FittedRange& r = model.range;
  return std::isfinite(model.chip_center_mm) && std::isfinite(model.contact_length_center_mm) &&
         std::isfinite(model.chip_scale_mm) && model.chip_scale_mm > 0.0 &&
         std::isfinite(model.contact_length_scale_mm) && model.contact_length_scale_mm > 0.0 &&
         std::isfinite(r.chip_min_mm) && std::isfinite(r.chip_max_mm) && r.chip_min_mm >= 0.0 &&
         r.chip_min_mm <= r.chip_max_mm && std::isfinite(r.contact_length_min_mm) &&
         std::isfinite(r.contact_length_max_mm) && r.contact_length_min_mm >= 0.0 &&
         r.contact_length_min_mm <= r.contact_length_max_mm;
}

void check_arguments(const ResponseSurfaceModel& model, double chip_factor, double contact_length_mm,
                     double target_force_n) {
  const bool factor_ok = std::isfinite(chip_factor) && chip_factor > 0.0 && chip_factor <= 1.0;
  const bool length_ok = std::isfinite(contact_length_mm) && contact_length_mm >= 0.0;
  const bool target_ok = std::isfinite(target_force_n) && target_force_n > 0.0;
  if (factor_ok && length_ok && target_ok && usable(model)) return;
  std::vector<InputProblem> problems;
  if (!factor_ok) {
    problems.push_back({"chip_factor", "= " + shortest_number_text(chip_factor) +
                                           ": must be in (0, 1] — t_m / f_z = sin(min(α_en, π/2)) of a cutting sample"});
  }
  if (!length_ok) {
    problems.push_back({"contact_length_mm", "= " + shortest_number_text(contact_length_mm) + ": must be finite and ≥ 0"});
  }
  if (!target_ok) {
    problems.push_back({"target_force_n", "= " + shortest_number_text(target_force_n) + ": must be finite and > 0"});
  }
  for (InputProblem& problem : validate(model)) problems.push_back(std::move(problem));
  throw InputError(std::move(problems));
}

//! F̂ as the quadratic A + B X1 + C X1² in X1 at a fixed L (file comment of feed_solve.hpp).
struct QuadraticInChip {
  double a = 0.0;
  double b = 0.0;
  double c = 0.0;
  double at(double x1) const { return a + x1 * (b + x1 * c); }
};

//! One solve: the arguments, and F̂ as a quadratic in X1 at their L.
struct FeedRequest {
  const ResponseSurfaceModel& model;
  double chip_factor = 0.0;
  double contact_length_mm = 0.0;
  double target_force_n = 0.0;
  QuadraticInChip f_hat;

  double x1_of(double chip_mm) const { return (chip_mm - model.chip_center_mm) / model.chip_scale_mm; }
  double chip_of(double x1) const { return model.chip_center_mm + model.chip_scale_mm * x1; }
};

//! A, B and C of F̂ at contact length L (file comment of feed_solve.hpp).
QuadraticInChip quadratic_in_chip(const ResponseSurfaceModel& model, double contact_length_mm) {
  const auto& beta = model.beta;
  const double x2 = (contact_length_mm - model.contact_length_center_mm) / model.contact_length_scale_mm;
  return {beta[kBeta0] + x2 * (beta[kBeta2] + x2 * beta[kBeta22]), beta[kBeta1] + beta[kBeta12] * x2, beta[kBeta11]};
}

//! The one root X1 on the rising branch, where dF̂/dX1 = +√D (file comment of feed_solve.hpp); none when
//! D < 0 or F̂ does not rise.
std::optional<double> rising_root_x1(const QuadraticInChip& f_hat, double target_force_n) {
  std::optional<double> rising_x1;
  const double a0 = f_hat.a - target_force_n;
  const double discriminant = f_hat.b * f_hat.b - 4.0 * f_hat.c * a0;
  if (discriminant >= 0.0) {
    const double root_d = std::sqrt(discriminant);
    if (f_hat.b >= 0.0) {
      const double denominator = f_hat.b + root_d;
      if (denominator > 0.0) {
        rising_x1 = -2.0 * a0 / denominator;
      } else if (f_hat.c != 0.0) {
        rising_x1 = 0.0;  // B = 0 and D = 0: a double root at the vertex
      }
    } else if (f_hat.c != 0.0) {
      rising_x1 = (-f_hat.b + root_d) / (2.0 * f_hat.c);
    }
  }
  return rising_x1;
}

//! t_m of the rising-branch root when it lies at a positive feed, mm.
std::optional<double> rising_root_chip_mm(const FeedRequest& request) {
  const std::optional<double> rising_x1 = rising_root_x1(request.f_hat, request.target_force_n);
  std::optional<double> root_chip_mm;
  if (rising_x1 && std::isfinite(*rising_x1) && request.chip_of(*rising_x1) > 0.0) {
    root_chip_mm = request.chip_of(*rising_x1);
  }
  return root_chip_mm;
}

//! t_m where F̂ is largest over [t_min, t_max]: the vertex of a concave F̂ when inside, else the better edge
//! (on a tie the smaller feed), mm.
double largest_force_chip_mm(const FeedRequest& request) {
  const QuadraticInChip& f_hat = request.f_hat;
  const double chip_min_mm = request.model.range.chip_min_mm;
  const double chip_max_mm = request.model.range.chip_max_mm;
  const double x_min = request.x1_of(chip_min_mm);
  const double x_max = request.x1_of(chip_max_mm);
  double best_x = x_min;
  if (f_hat.at(x_max) > f_hat.at(x_min)) best_x = x_max;
  if (f_hat.c < 0.0) {
    const double vertex = -f_hat.b / (2.0 * f_hat.c);
    if (vertex > x_min && vertex < x_max && f_hat.at(vertex) > f_hat.at(best_x)) best_x = vertex;
  }
  return best_x == x_min ? chip_min_mm : best_x == x_max ? chip_max_mm : request.chip_of(best_x);
}

//! The status, root feed and t_m of `solution` by the rule table of feed_solve.hpp; returns that t_m, mm.
double choose_chip_mm(const FeedRequest& request, const std::optional<double>& root_chip_mm,
                      FeedSolution& solution) {
  const FittedRange& range = request.model.range;
  if (root_chip_mm) {
    solution.root_feed_per_tooth_mm = *root_chip_mm / request.chip_factor;
    if (!chip_outside(range, *root_chip_mm)) {
      solution.status = FeedSolveStatus::kOk;
      return *root_chip_mm;
    }
    solution.status = FeedSolveStatus::kClampedToRange;
    return *root_chip_mm > range.chip_max_mm ? range.chip_max_mm : range.chip_min_mm;
  }
  if (request.f_hat.at(request.x1_of(0.0)) >= request.target_force_n) {
    solution.status = FeedSolveStatus::kTargetBelowModel;
    return range.chip_min_mm;
  }
  solution.status = FeedSolveStatus::kUnreachable;
  return largest_force_chip_mm(request);
}

//! The feed, t_m and predicted force of `solution` at `chip_mm`, and whether L lies outside the fitted range.
void evaluate_at_chip(const FeedRequest& request, double chip_mm, FeedSolution& solution) {
  solution.chip_mm = chip_mm;
  solution.feed_per_tooth_mm = chip_mm / request.chip_factor;
  solution.predicted_force_n = request.f_hat.at(request.x1_of(chip_mm));
  solution.contact_length_outside = contact_length_outside(request.model.range, request.contact_length_mm);
}

//! The sentence saying why the feed does not meet the target, for any status but kOk.
std::string off_target_message(const FeedRequest& request, const std::optional<double>& root_chip_mm,
                               const FeedSolution& solution) {
  const double chip_min_mm = request.model.range.chip_min_mm;
  const double chip_max_mm = request.model.range.chip_max_mm;
  const double chip_mm = solution.chip_mm;
  const std::string target = six_digit_number_text(request.target_force_n) + " N";
  const std::string range_text = "the fitted t_m range " + six_digit_number_text(chip_min_mm) + "–" +
                                 six_digit_number_text(chip_max_mm) + " mm";
  const std::string here = "f_z = " + six_digit_number_text(solution.feed_per_tooth_mm) +
                           " mm (t_m = " + six_digit_number_text(chip_mm) + " mm), where the model predicts " +
                           six_digit_number_text(solution.predicted_force_n) + " N";
  if (solution.status == FeedSolveStatus::kClampedToRange) {
    return "the target " + target + " needs t_m = " + six_digit_number_text(*root_chip_mm) + " mm (f_z = " +
           six_digit_number_text(*solution.root_feed_per_tooth_mm) + " mm), " +
           (*root_chip_mm > chip_max_mm ? "above " : "below ") + range_text + ": clamped to " + here;
  }
  if (solution.status == FeedSolveStatus::kTargetBelowModel) {
    return "the model predicts " + six_digit_number_text(request.f_hat.at(request.x1_of(0.0))) +
           " N as f_z → 0, already above the target " + target + ": using the smallest feed in " + range_text +
           ", " + here;
  }
  return "the model never reaches the target " + target +
         " on its rising branch: using the feed of its largest value in " + range_text + ", " + here;
}

//! The clause saying that L lies outside the fitted L range.
std::string contact_length_outside_message(const FeedRequest& request) {
  const FittedRange& range = request.model.range;
  return "L = " + six_digit_number_text(request.contact_length_mm) + " mm lies outside the fitted L range " +
         six_digit_number_text(range.contact_length_min_mm) + "–" + six_digit_number_text(range.contact_length_max_mm) +
         " mm: the model extrapolates";
}

}  // namespace

std::string to_string(FeedSolveStatus status) {
  switch (status) {
    case FeedSolveStatus::kOk: return "ok";
    case FeedSolveStatus::kClampedToRange: return "clamped to range";
    case FeedSolveStatus::kTargetBelowModel: return "target below model";
    case FeedSolveStatus::kUnreachable: return "unreachable";
  }
  return "?";
}

FeedSolution solve_feed(const ResponseSurfaceModel& model, double chip_factor, double contact_length_mm,
                        double target_force_n) {
  check_arguments(model, chip_factor, contact_length_mm, target_force_n);
  const FeedRequest request{model, chip_factor, contact_length_mm, target_force_n,
                            quadratic_in_chip(model, contact_length_mm)};
  const std::optional<double> root_chip_mm = rising_root_chip_mm(request);
  FeedSolution solution;
  const double chip_mm = choose_chip_mm(request, root_chip_mm, solution);
  evaluate_at_chip(request, chip_mm, solution);
  if (solution.status != FeedSolveStatus::kOk) {  // messages only off the common path: the planner calls this per sample
    solution.message = off_target_message(request, root_chip_mm, solution);
  }
  if (solution.contact_length_outside) {
    if (!solution.message.empty()) solution.message += "; ";
    solution.message += contact_length_outside_message(request);
  }
  return solution;
}

}  // namespace feedplan::model
