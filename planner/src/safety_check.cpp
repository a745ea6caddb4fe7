#include "feedplan/planner/sample_force_model.hpp"
#include "feedplan/planner/safety_check.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "feedplan/core/angle.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/geometry/engagement.hpp"
#include "feedplan/planner/feed_limit.hpp"

namespace feedplan::planner {

namespace {

// The force correction at arc length s: the larger of the two plan samples around it (1 without one).
double correction_at(const SafetyCheckInput& input, double s_mm) {
  const auto& values = input.settings->force_correction;
  const auto& at = input.correction_s_mm;
  if (values.empty() || at.size() != values.size()) return 1.0;
  const auto upper = std::lower_bound(at.begin(), at.end(), s_mm);
  const auto k = static_cast<std::size_t>(upper - at.begin());
  if (k == 0) return values.front();
  if (k >= values.size()) return values.back();
  return std::max(values[k - 1], values[k]);
}

// Engagements closer than this (rad, mm) are the same input to the chip load.
constexpr double kSameEngagement = 1e-9;

bool near(double a, double b) { return std::abs(a - b) <= kSameEngagement; }

// True when sample `a` of `pa` and `b` of `pb` hold the same engaged layers and sets relative to the tip.
bool same_engagement(const geometry::EngagementProfile& pa, const geometry::EngagementSample& a,
                     const geometry::EngagementProfile& pb, const geometry::EngagementSample& b) {
  if (a.layer_count != b.layer_count || !near(a.chip_factor, b.chip_factor) ||
      !near(a.contact_length_mm, b.contact_length_mm) || !near(a.material_height_mm, b.material_height_mm)) {
    return false;
  }
  for (int k = 0; k < a.layer_count; ++k) {
    const geometry::EngagementLayer& la = pa.layers[static_cast<std::size_t>(a.layer_begin + k)];
    const geometry::EngagementLayer& lb = pb.layers[static_cast<std::size_t>(b.layer_begin + k)];
    if (la.interval_count != lb.interval_count || !near(la.bottom_z_mm - a.position.z_mm, lb.bottom_z_mm - b.position.z_mm) ||
        !near(la.top_z_mm - a.position.z_mm, lb.top_z_mm - b.position.z_mm)) {
      return false;
    }
    for (int i = 0; i < la.interval_count; ++i) {
      const geometry::EngagedInterval& ia = pa.intervals[static_cast<std::size_t>(la.interval_begin + i)];
      const geometry::EngagedInterval& ib = pb.intervals[static_cast<std::size_t>(lb.interval_begin + i)];
      if (!near(ia.entry_rad, ib.entry_rad) || !near(ia.exit_rad, ib.exit_rad)) return false;
    }
  }
  return true;
}

// The chip-load ratio at the check's sample: the planner's where its sample at the same place has the same
// engagement, else computed.
double load_ratio_at(const SafetyCheckInput& input, const SampleForceModel& forces,
                     const geometry::EngagementProfile& profile, const geometry::EngagementSample& sample) {
  const auto* planned = input.planned_engagement;
  const auto* ratios = input.planned_load_ratio;
  if (planned && ratios && ratios->size() == planned->samples.size()) {
    const auto& samples = planned->samples;
    const auto at = std::lower_bound(samples.begin(), samples.end(), sample.s_mm - kSameEngagement,
                                     [](const geometry::EngagementSample& p, double s) { return p.s_mm < s; });
    if (at != samples.end() && near(at->s_mm, sample.s_mm) && same_engagement(*planned, *at, profile, sample)) {
      return (*ratios)[static_cast<std::size_t>(at - samples.begin())];
    }
  }
  return forces.load_ratio(sample);
}

// The largest feed the force model allows at the sample (the machine's minimum where none meets the target).
double force_limit_mm_per_min(const SafetyCheckInput& input, const geometry::EngagementProfile& profile,
                              const geometry::EngagementSample& sample) {
  const PlanSettings& settings = *input.settings;
  const double correction = correction_at(input, sample.s_mm);
  const ForceUncertainty* uncertainty = settings.uncertainty ? &*settings.uncertainty : nullptr;
  geometry::EngagementSample bound_sample = sample;
  if (uncertainty && uncertainty->off_straight_cut) {
    bound_sample.chip_area_ratio = std::max(sample.chip_area_ratio / correction, 1.0);
  }
  const SampleForceModel forces(settings.model, settings.mechanistic ? &*settings.mechanistic : nullptr, profile,
                                *input.tool);
  const double load_ratio = load_ratio_at(input, forces, profile, sample);
  const SampleFeedLimit limit =
      forces.feed_limit(bound_sample, load_ratio, settings.target_force_n / correction, input.tool->flutes,
                        settings.spindle_rpm, std::numeric_limits<double>::infinity(), uncertainty);
  if (limit.target_below_model) return settings.machine.min_feed_mm_per_min;
  return std::max(limit.feed_mm_per_min, settings.machine.min_feed_mm_per_min);
}

// Least depth below which a rapid's contact with material counts as grazing, mm.
constexpr double kGrazingDepthMm = 0.001;

// The feed allowed at one sample and the invariant that sets it.
struct SampleAllowance {
  double mm_per_min = std::numeric_limits<double>::infinity();
  SafetyProblem problem = SafetyProblem::kAboveForceLimit;
};

// True when `move` goes straight up: the tool body (a cylinder above the tip) already occupies the
// space it passes through, so it removes nothing — a retract from the end of a cut that still touches
// the wall it just cut is not a collision.
bool rises_straight_up(const geometry::Move& move) {
  return move.end.z_mm > move.start.z_mm && geometry::xy_length_mm(move) < 1e-9;
}

// True when the tool circle only grazes the material at `sample`: the material it meets reaches into the
// circle less deep than the program's coordinates resolve (at least 1 µm), r·(1 − cos(α/2)) for an engaged
// angle α against a wall — a rapid retracing a cut it made along the wall it left, where the stock's
// polygons and the path's rounding leave slivers of a micrometre. Its end face meets nothing.
bool grazes(const geometry::EngagementSample& sample, double tool_radius_mm, double resolution_mm) {
  if (sample.end_face_in_material) return false;
  const double depth_mm = tool_radius_mm * (1.0 - std::cos(0.5 * sample.engagement_rad));
  return depth_mm <= std::max(resolution_mm, kGrazingDepthMm);
}

SampleAllowance allowance(const SafetyCheckInput& input, const geometry::EngagementProfile& profile,
                          const geometry::EngagementSample& sample, const geometry::Move& move) {
  if (!std::isfinite(sample.engagement_rad) || !std::isfinite(sample.chip_factor) ||
      !std::isfinite(sample.material_height_mm)) {
    return {0.0, SafetyProblem::kEngagementUnknown};
  }
  if (!meets_material(sample) || rises_straight_up(move)) return {};
  if (move.kind == geometry::MoveKind::kRapid) {
    if (grazes(sample, profile.tool_radius_mm, input.settings->options.coordinate_resolution_mm)) return {};
    return {0.0, SafetyProblem::kRapidInMaterial};
  }
  const double plunge = plunge_feed_limit_mm_per_min(move, *input.tool, input.settings->spindle_rpm,
                                                     input.settings->options.coordinate_resolution_mm);
  const double force =
      is_engaged(sample) ? force_limit_mm_per_min(input, profile, sample) : std::numeric_limits<double>::infinity();
  if (plunge < force) return {plunge, SafetyProblem::kAbovePlungeLimit};
  return {force, SafetyProblem::kAboveForceLimit};
}

// How bad a violation is, for keeping a move's worst one.
double severity(const SafetyViolation& v) {
  return v.allowed_mm_per_min > 0.0 ? v.feed_mm_per_min / v.allowed_mm_per_min : std::numeric_limits<double>::infinity();
}

}  // namespace

std::string to_string(SafetyProblem problem) {
  switch (problem) {
    case SafetyProblem::kRapidInMaterial: return "rapid through material";
    case SafetyProblem::kAboveForceLimit: return "above the force limit";
    case SafetyProblem::kAbovePlungeLimit: return "above the plunge limit";
    case SafetyProblem::kEngagementUnknown: return "engagement unknown";
  }
  return "?";
}

SafetyCheck check_safety(const geometry::Program& program, const SafetyCheckInput& input) {
  assert(input.stock && input.tool && input.settings && input.ds_mm > 0.0);
  assert(program.blocks.size() == program.path.moves.size());
  geometry::EngagementOptions options;
  options.ds_mm = input.ds_mm;
  const geometry::EngagementProfile profile =
      geometry::compute_engagement(program.path, *input.stock, input.tool->radius_mm(), options);
  SafetyCheck check;
  std::vector<SafetyViolation>& violations = check.violations;
  check.allowed.reserve(profile.samples.size());
  const double slack = 1.0 + input.relative_tolerance;
  int last_move = -1;
  for (const geometry::EngagementSample& sample : profile.samples) {
    const auto m = static_cast<std::size_t>(sample.move_index);
    const geometry::Move& move = program.path.moves[m];
    const double feed = move.kind == geometry::MoveKind::kRapid ? input.settings->machine.rapid_feed_mm_per_min
                                                                : program.blocks[m].feed_mm_per_min;
    const SampleAllowance allowed = allowance(input, profile, sample, move);
    check.allowed.push_back({sample.s_mm, sample.move_index, allowed.mm_per_min});
    if (!(feed > allowed.mm_per_min * slack)) continue;
    const SafetyViolation found{allowed.problem, sample.move_index,     program.blocks[m].source_line,
                                sample.s_mm,     sample.position,       feed,
                                allowed.mm_per_min, sample.engagement_rad, sample.material_height_mm};
    if (sample.move_index != last_move) {
      violations.push_back(found);
      last_move = sample.move_index;
    } else if (severity(found) > severity(violations.back())) {
      violations.back() = found;
    }
  }
  return check;
}

std::string describe(const SafetyViolation& v) {
  std::string text = "program move " + std::to_string(v.move_index);
  if (v.source_line > 0) text += " (line " + std::to_string(v.source_line) + ")";
  text += " at s = " + fixed_number_text(v.s_mm, 2) + " mm (x " + fixed_number_text(v.position.x_mm, 3) + ", y " +
          fixed_number_text(v.position.y_mm, 3) + ", z " + fixed_number_text(v.position.z_mm, 3) + "): " +
          to_string(v.problem);
  if (v.problem == SafetyProblem::kRapidInMaterial) {
    return text + " — a G0 meets material (engaged " + fixed_number_text(rad_to_deg(v.engagement_rad), 1) +
           " deg, " + fixed_number_text(v.material_height_mm, 3) + " mm of material above the tip)";
  }
  if (v.problem == SafetyProblem::kEngagementUnknown) return text + " — it is not taken for air";
  return text + ", F " + fixed_number_text(v.feed_mm_per_min, 0) + " mm/min where the engagement allows " +
         fixed_number_text(v.allowed_mm_per_min, 0) + " mm/min (engaged " +
         fixed_number_text(rad_to_deg(v.engagement_rad), 1) + " deg on " +
         fixed_number_text(v.material_height_mm, 3) + " mm of material)";
}

}  // namespace feedplan::planner
