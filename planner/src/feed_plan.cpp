#include "feedplan/planner/engaged_sections.hpp"
#include "feedplan/model/mechanistic_force.hpp"
#include "feedplan/planner/sample_force_model.hpp"
#include "feedplan/planner/feed_plan.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <sstream>

#include "block_split.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/geometry/chip_load.hpp"
#include "feedplan/model/model_prediction.hpp"
#include "feedplan/planner/controller_model.hpp"
#include "feedplan/planner/feed_limit.hpp"
#include "feedplan/planner/safety_check.hpp"
#include "feedplan/planner/speed_profile.hpp"

namespace feedplan::planner {
namespace {

std::string num(double value) { return shortest_number_text(value); }
std::string fixed(double value, int digits) { return fixed_number_text(value, digits); }

bool finite_positive(double value) { return std::isfinite(value) && value > 0.0; }

std::string where(const geometry::EngagementSample& sample) {
  return "s = " + fixed(sample.s_mm, 2) + " mm (x " + fixed(sample.position.x_mm, 3) + ", y " +
         fixed(sample.position.y_mm, 3) + ")";
}

// First sample of every move, and the last sample at the end (see detail::split_blocks).
std::vector<int> first_samples(const geometry::ToolPath& path, const geometry::EngagementProfile& engagement) {
  std::vector<int> first(path.moves.size() + 1, static_cast<int>(engagement.samples.size()) - 1);
  for (std::size_t i = engagement.samples.size(); i-- > 0;) {
    first[static_cast<std::size_t>(engagement.samples[i].move_index)] = static_cast<int>(i);
  }
  // Moves without samples (none today: every move has at least one step) take the next move's first.
  for (std::size_t m = path.moves.size(); m-- > 0;) first[m] = std::min(first[m], first[m + 1]);
  return first;
}

// Interval caps for the controller: block F (or the rapid rate), never above the centripetal cap.
std::vector<double> block_caps(const std::vector<PlannedBlock>& blocks, std::size_t intervals,
                               const std::vector<double>& centripetal, const geometry::ToolPath& path,
                               double rapid_mm_per_s) {
  std::vector<double> caps(intervals, rapid_mm_per_s);
  for (const PlannedBlock& block : blocks) {
    const bool rapid = path.moves[static_cast<std::size_t>(block.move_index)].kind == geometry::MoveKind::kRapid;
    for (int j = block.first_sample; j < block.last_sample; ++j) {
      const auto k = static_cast<std::size_t>(j);
      caps[k] = rapid ? rapid_mm_per_s : std::min(block.feed_mm_per_min / 60.0, centripetal[k]);
    }
  }
  return caps;
}

// The sub-move of `move` between fractions j0/n and j1/n of its length.
geometry::Move sub_move(const geometry::Move& move, int j0, int j1, int n) {
  geometry::Move part = move;
  if (j0 == 0 && j1 == n) return part;
  const double f0 = static_cast<double>(j0) / n;
  const double f1 = static_cast<double>(j1) / n;
  part.start = j0 == 0 ? move.start : geometry::point_at(move, f0);
  part.end = j1 == n ? move.end : geometry::point_at(move, f1);
  if (move.kind == geometry::MoveKind::kArc) part.sweep_rad = move.sweep_rad * (f1 - f0);
  return part;
}

}  // namespace

std::string to_string(PlanMode mode) { return mode == PlanMode::kSafe ? "safe" : "regulate"; }

std::string to_string(PlanStatus status) {
  switch (status) {
    case PlanStatus::kOk: return "ok";
    case PlanStatus::kExtrapolated: return "extrapolated";
    case PlanStatus::kTargetNotMet: return "target not met";
    case PlanStatus::kUnsafe: return "unsafe";
  }
  return "?";
}

std::string to_string(FeedLimitReason reason) {
  switch (reason) {
    case FeedLimitReason::kForce: return "force";
    case FeedLimitReason::kModelRange: return "model range";
    case FeedLimitReason::kMaxFeed: return "max feed";
    case FeedLimitReason::kCentripetal: return "centripetal";
    case FeedLimitReason::kAirFeed: return "air";
    case FeedLimitReason::kMinFeed: return "min feed";
    case FeedLimitReason::kRapid: return "rapid";
    case FeedLimitReason::kPlunge: return "plunge";
  }
  return "?";
}

PlanGeometry analyse(const geometry::ToolPath& path, const geometry::Stock& stock, const geometry::Tool& tool,
                     double ds_mm) {
  std::vector<InputProblem> problems;
  if (!(std::isfinite(ds_mm) && ds_mm > 0.0 && ds_mm <= 5.0)) {
    problems.push_back({"options.ds_mm", "= " + num(ds_mm) + ": must be in (0, 5] mm"});
  }
  if (!finite_positive(tool.diameter_mm)) {
    problems.push_back({"tool.diameter_mm", "= " + num(tool.diameter_mm) + ": must be a finite number > 0"});
  }
  if (path.moves.empty()) problems.push_back({"path", "has no moves: nothing to plan"});
  for (const std::string& defect : geometry::consistency_defects(path)) problems.push_back({"path", defect});
  if (!problems.empty()) throw InputError(std::move(problems));
  PlanGeometry result;
  result.path = path;
  result.stock = stock;
  result.tool = tool;
  geometry::EngagementOptions options;
  options.ds_mm = ds_mm;
  result.engagement = geometry::compute_engagement(path, stock, tool.radius_mm(), options);
  result.straight_cuts = std::make_shared<geometry::StraightCutLoads>(tool);
  result.peak_chip_load_mm.reserve(result.engagement.samples.size());
  for (const auto& sample : result.engagement.samples) {
    result.peak_chip_load_mm.push_back(is_engaged(sample) ? geometry::peak_chip_load_mm(result.engagement, sample, tool) : 0.0);
  }
  return result;
}

std::vector<InputProblem> validate(const PlanSettings& settings, const geometry::Tool& tool) {
  std::vector<InputProblem> problems = model::validate(settings.model);
  if (!finite_positive(settings.target_force_n)) {
    problems.push_back({"target_force_n", "= " + num(settings.target_force_n) + ": must be a finite force > 0 N"});
  }
  if (!finite_positive(settings.spindle_rpm)) {
    problems.push_back({"spindle_rpm", "= " + num(settings.spindle_rpm) + ": must be a finite speed > 0 rev/min"});
  }
  if (tool.flutes < 1) problems.push_back({"tool.flutes", "= " + std::to_string(tool.flutes) + ": must be ≥ 1"});
  if (settings.mechanistic) {
    for (InputProblem& p : model::validate(*settings.mechanistic, cutter_geometry(tool), "mechanistic.")) {
      problems.push_back(std::move(p));
    }
  }
  const geometry::MachineLimits& m = settings.machine;
  for (InputProblem& p : geometry::validate(m)) problems.push_back(std::move(p));
  if (settings.uncertainty) {
    const ForceUncertainty& u = *settings.uncertainty;
    if (!(std::isfinite(u.sigmas) && u.sigmas >= 0.0)) {
      problems.push_back({"uncertainty.sigmas", "= " + num(u.sigmas) + ": must be a finite number ≥ 0"});
    }
    if (!(std::isfinite(u.relative) && u.relative >= 0.0)) {
      problems.push_back({"uncertainty.relative", "= " + num(u.relative) + ": must be a finite number ≥ 0"});
    }
    for (std::size_t k = 0; k < 36; ++k) {
      if (!std::isfinite(u.covariance.entries()[k]) || (k % 7 == 0 && u.covariance.entries()[k] < 0.0)) {
        problems.push_back({"uncertainty.covariance[" + std::to_string(k) + "]",
                            "= " + num(u.covariance.entries()[k]) + ": must be finite (and ≥ 0 on the diagonal)"});
      }
    }
  }
  for (std::size_t i = 0; i < settings.force_correction.size(); ++i) {
    const double c = settings.force_correction[i];
    if (!(std::isfinite(c) && c >= kMinForceCorrection && c <= kMaxForceCorrection)) {
      problems.push_back({"force_correction[" + std::to_string(i) + "]", "= " + num(c) + ": must be in [" +
                                                                             num(kMinForceCorrection) + ", " +
                                                                             num(kMaxForceCorrection) + "]"});
      break;
    }
  }
  const PlanOptions& o = settings.options;
  if (!(std::isfinite(o.air_feed_mm_per_min) && o.air_feed_mm_per_min >= 0.0)) {
    problems.push_back({"options.air_feed_mm_per_min", "= " + num(o.air_feed_mm_per_min) +
                                                           ": must be ≥ 0 mm/min (0: the machine's maximum feed)"});
  } else if (o.air_feed_mm_per_min > 0.0 && finite_positive(m.max_feed_mm_per_min) &&
             (o.air_feed_mm_per_min > m.max_feed_mm_per_min || o.air_feed_mm_per_min < m.min_feed_mm_per_min)) {
    problems.push_back({"options.air_feed_mm_per_min", "= " + num(o.air_feed_mm_per_min) +
                                                           ": must lie in the machine's feed range [" +
                                                           num(m.min_feed_mm_per_min) + ", " +
                                                           num(m.max_feed_mm_per_min) + "] mm/min"});
  }
  if (!(std::isfinite(o.merge_tolerance) && o.merge_tolerance >= 0.0 && o.merge_tolerance <= 0.5)) {
    problems.push_back({"options.merge_tolerance", "= " + num(o.merge_tolerance) + ": must be in [0, 0.5]"});
  }
  if (!(std::isfinite(o.feed_step) && o.feed_step >= 0.0 && o.feed_step <= 0.5)) {
    problems.push_back({"options.feed_step", "= " + num(o.feed_step) + ": must be in [0, 0.5] (0: blocks follow the "
                                             "command profile)"});
  }
  if (!(std::isfinite(o.min_block_duration_s) && o.min_block_duration_s >= 0.0 && o.min_block_duration_s <= 10.0)) {
    problems.push_back({"options.min_block_duration_s", "= " + num(o.min_block_duration_s) + ": must be in [0, 10] s"});
  }
  if (!(std::isfinite(o.feed_resolution_mm_per_min) && o.feed_resolution_mm_per_min > 0.0 &&
        o.feed_resolution_mm_per_min <= 100.0)) {
    problems.push_back({"options.feed_resolution_mm_per_min",
                        "= " + num(o.feed_resolution_mm_per_min) + ": must be in (0, 100] mm/min"});
  }
  if (!(std::isfinite(o.max_chip_thickness_mm) && o.max_chip_thickness_mm >= 0.0)) {
    problems.push_back({"options.max_chip_thickness_mm",
                        "= " + num(o.max_chip_thickness_mm) + ": must be a finite number ≥ 0 mm (0: no limit)"});
  }
  if (!(std::isfinite(o.coordinate_resolution_mm) && o.coordinate_resolution_mm >= 0.0 &&
        o.coordinate_resolution_mm <= 0.1)) {
    problems.push_back({"options.coordinate_resolution_mm",
                        "= " + num(o.coordinate_resolution_mm) + ": must be in [0, 0.1] mm (10^-decimals of the program)"});
  }
  if (!(std::isfinite(o.jerk_limit_mm_per_s3) && o.jerk_limit_mm_per_s3 >= 0.0)) {
    problems.push_back({"options.jerk_limit_mm_per_s3", "= " + num(o.jerk_limit_mm_per_s3) + ": must be ≥ 0 (0: none)"});
  }
  return problems;
}

namespace {

// Plans of the program before one the safety check refuses is reported unsafe.
constexpr int kSafetyPasses = 4;

// True when analyse's chip loads in `geometry` belong to its tool (not changed since).
bool made_for_tool(const PlanGeometry& geometry) {
  if (!geometry.straight_cuts) return false;
  const geometry::Tool& made = geometry.straight_cuts->tool();
  return made.diameter_mm == geometry.tool.diameter_mm && made.flutes == geometry.tool.flutes &&
         made.helix_deg == geometry.tool.helix_deg;
}

// What every step of plan() reads: the inputs, and the values derived from them once.
struct PlanContext {
  PlanContext(const PlanGeometry& geometry, const PlanSettings& settings);
  double correction(std::size_t i) const {
    return settings.force_correction.empty() ? 1.0 : settings.force_correction[i];
  }
  const geometry::EngagementSample& bound_sample(std::size_t i) const {
    return corrected_bound_samples.empty() ? samples[i] : corrected_bound_samples[i];
  }

  const PlanSettings& settings;
  const geometry::ToolPath& path;
  const geometry::EngagementProfile& engagement;
  const std::vector<geometry::EngagementSample>& samples;
  const std::size_t n;
  const int flutes;
  const double rpm;
  const double air_feed;                      // mm/min
  const ForceUncertainty* const uncertainty;  // null: the plain model
  const geometry::Tool& tool;
  const double stock_top_z_mm;                // the top of the stock the path cuts
  std::vector<double> s;                      // s_mm of every sample
  std::vector<int> move_first;                // first_samples(path, engagement)
  SampleForceModel forces;                    // the force model of either kind at the samples
  std::vector<double> load_ratio;             // chip_load_ratio of every sample (feed_limit.hpp)
  // The sample the bound is evaluated on: with a correction c measured along the path, the entry factor
  // is max(ρ, c) in all (force_bound.hpp), so its chip-area ratio becomes max(ρ / c, 1).
  // Copies only when both apply (ρ ≥ 1 already without a correction).
  std::vector<geometry::EngagementSample> corrected_bound_samples;
};

PlanContext::PlanContext(const PlanGeometry& geometry, const PlanSettings& settings)
    : settings(settings),
      path(geometry.path),
      engagement(geometry.engagement),
      samples(geometry.engagement.samples),
      n(samples.size()),
      flutes(geometry.tool.flutes),
      rpm(settings.spindle_rpm),
      air_feed(settings.options.air_feed_mm_per_min > 0.0 ? settings.options.air_feed_mm_per_min
                                                          : settings.machine.max_feed_mm_per_min),
      uncertainty(settings.uncertainty ? &*settings.uncertainty : nullptr),
      tool(geometry.tool),
      stock_top_z_mm(geometry.stock.z_top_mm),
      s(n),
      move_first(first_samples(path, engagement)),
      forces(settings.model, settings.mechanistic ? &*settings.mechanistic : nullptr, geometry.engagement, geometry.tool,
             made_for_tool(geometry) ? geometry.straight_cuts : nullptr),
      load_ratio(n) {
  assert(!samples.empty());
  if (uncertainty && uncertainty->off_straight_cut && !settings.force_correction.empty()) {
    corrected_bound_samples = samples;
    for (std::size_t i = 0; i < n; ++i) {
      corrected_bound_samples[i].chip_area_ratio = std::max(samples[i].chip_area_ratio / correction(i), 1.0);
    }
  }
  const bool loads_known = made_for_tool(geometry) && geometry.peak_chip_load_mm.size() == n;
  for (std::size_t i = 0; i < n; ++i) {
    s[i] = samples[i].s_mm;
    load_ratio[i] = loads_known ? forces.load_ratio(samples[i], geometry.peak_chip_load_mm[i]) : forces.load_ratio(samples[i]);
  }
}

// Throws InputError with every problem validate() finds, and a force correction of another path.
void check_plan_input(const PlanGeometry& geometry, const PlanSettings& settings) {
  std::vector<InputProblem> problems = validate(settings, geometry.tool);
  const std::size_t n_samples = geometry.engagement.samples.size();
  if (!settings.force_correction.empty() && settings.force_correction.size() != n_samples) {
    problems.push_back({"force_correction", "has " + std::to_string(settings.force_correction.size()) +
                                                " values for " + std::to_string(n_samples) +
                                                " engagement samples: it belongs to another path or sampling"});
  }
  if (!problems.empty()) throw InputError(std::move(problems));
}

// Step 1's result.
struct FeedLimits {
  std::vector<double> centripetal;  // cap per interval at the machine's acceleration, mm/s
  std::vector<double> mm_per_min;   // feed limit per sample, mm/min
  int target_below_model = 0;       // samples where the model predicts more than the target at any feed
};

// A sample of the plan with the engagement it was planned for.
PlannedSample planned_engagement(const geometry::EngagementSample& sample) {
  PlannedSample planned;
  planned.s_mm = sample.s_mm;
  planned.position = sample.position;
  planned.move_index = sample.move_index;
  planned.engaged = is_engaged(sample);
  planned.engagement_rad = sample.engagement_rad;
  planned.chip_factor = sample.chip_factor;
  planned.contact_length_mm = sample.contact_length_mm;
  planned.axial_depth_mm = sample.axial_depth_mm;
  return planned;
}

// Step 1 at sample i: the model's feed for the (corrected) target, clamped to the machine's feed range,
// capped by the centripetal cap of the interval after it and, at a move's first sample, of the one before
// it; rapids at the rapid rate.
double feed_limit_at(const PlanContext& c, const std::vector<double>& centripetal, std::size_t i,
                     PlannedSample& planned, int& target_below_model) {
  const auto& samples = c.samples;
  const std::size_t n = c.n;
  const auto& machine = c.settings.machine;
  const geometry::EngagementSample& sample = samples[i];
  const geometry::Move& move = c.path.moves[static_cast<std::size_t>(sample.move_index)];
  if (move.kind == geometry::MoveKind::kRapid) {
    planned.limit_reason = FeedLimitReason::kRapid;
    planned.feed_limit_mm_per_min = machine.rapid_feed_mm_per_min;
    return machine.rapid_feed_mm_per_min;
  }
  const SampleFeedLimit limit = c.forces.feed_limit(c.bound_sample(i), c.load_ratio[i],
                                                    c.settings.target_force_n / c.correction(i), c.flutes, c.rpm,
                                                    c.air_feed, c.uncertainty);
  double feed = limit.feed_mm_per_min;
  FeedLimitReason reason = limit.reason;
  if (const double max_chip_mm = c.settings.options.max_chip_thickness_mm; max_chip_mm > 0.0 && is_engaged(sample)) {
    const double chip_mm = chip_thickness_mm(sample, feed, c.flutes, c.rpm);
    if (chip_mm > max_chip_mm) {
      feed *= max_chip_mm / chip_mm;
      reason = FeedLimitReason::kModelRange;
    }
  }
  // A descent meeting material, or below the stock's top (a plunge beside the part, where a stock a little
  // larger than modelled would be met), runs at the tool's plunge feed, as a CAM post writes it.
  if (meets_material(sample) || (move.end.z_mm < move.start.z_mm && sample.position.z_mm < c.stock_top_z_mm)) {
    const double plunge =
        plunge_feed_limit_mm_per_min(move, c.tool, c.rpm, c.settings.options.coordinate_resolution_mm);
    if (plunge < feed) {
      feed = plunge;
      reason = FeedLimitReason::kPlunge;
    }
  }
  if (feed > machine.max_feed_mm_per_min) {
    feed = machine.max_feed_mm_per_min;
    if (reason != FeedLimitReason::kAirFeed) reason = FeedLimitReason::kMaxFeed;
  }
  auto apply_centripetal = [&](std::size_t interval) {
    const double cap = centripetal[interval] * 60.0;
    if (cap < feed) {
      feed = cap;
      reason = FeedLimitReason::kCentripetal;
    }
  };
  if (i + 1 < n) apply_centripetal(i);
  if (i > 0 && samples[i - 1].move_index != sample.move_index) apply_centripetal(i - 1);
  if (feed < machine.min_feed_mm_per_min) {
    feed = machine.min_feed_mm_per_min;
    reason = FeedLimitReason::kMinFeed;
  }
  if (limit.target_below_model) ++target_below_model;
  planned.limit_reason = reason;
  planned.extrapolated = limit.extrapolated && (reason == FeedLimitReason::kForce || reason == FeedLimitReason::kMinFeed);
  planned.feed_limit_mm_per_min = feed;
  return feed;
}

// The sample at a move boundary belongs to the next move; the previous move's end is the same point,
// and its limit must hold there too (the rapid/feed distinction is the next move's).
void hold_feed_limit_before_rapids(const PlanContext& c, std::vector<double>& limit_mm_per_min) {
  const geometry::ToolPath& path = c.path;
  for (std::size_t m = 1; m < path.moves.size(); ++m) {
    const auto i = static_cast<std::size_t>(c.move_first[m]);
    if (i >= c.n || i == 0) continue;
    const bool rapid_before = path.moves[m - 1].kind == geometry::MoveKind::kRapid;
    const bool rapid_after = path.moves[m].kind == geometry::MoveKind::kRapid;
    if (rapid_before == rapid_after) continue;
    // A feed move beside a rapid: the boundary node keeps the feed side's limit.
    if (rapid_after) limit_mm_per_min[i] = limit_mm_per_min[i - 1];
  }
}

// The chip a tooth takes is the distance the tool centre travelled since the previous tooth passed, not the
// current speed times the tooth period: while the machine slows down into an engagement, the last tooth
// period ran faster than the speed at the place. So each engaged sample's force limit also holds over the
// tool travel of one tooth period before it (its limit feed per tooth, F / (Z·n)): the chip there is then
// at most the one the limit allows. The mechanistic kind only, for now: its feed limit is the kernel's peak
// at exactly that chip (an entry decelerating from the air feed ran +27 % without this); the response
// surface's transfers already err on the cautious side at entries.
void hold_force_limit_over_the_last_tooth(const PlanContext& c, std::vector<double>& limit_mm_per_min) {
  if (!c.forces.mechanistic()) return;
  const std::vector<double> own = limit_mm_per_min;
  for (std::size_t i = 1; i < c.n; ++i) {
    if (!is_engaged(c.samples[i])) continue;
    const double tooth_travel_mm = own[i] / (c.flutes * c.rpm);
    for (std::size_t j = i; j-- > 0 && c.s[i] - c.s[j] <= tooth_travel_mm;) {
      if (c.path.moves[static_cast<std::size_t>(c.samples[j].move_index)].kind == geometry::MoveKind::kRapid) break;
      limit_mm_per_min[j] = std::min(limit_mm_per_min[j], own[i]);
    }
  }
}

// Step 1. Feed limits per sample; the limit of a node shared by two moves is the smaller of both sides.
FeedLimits limit_feeds(const PlanContext& c, PlanResult& result) {
  FeedLimits limits;
  limits.centripetal = centripetal_caps_mm_per_s(c.path, c.engagement, c.settings.machine.max_accel_mm_per_s2);
  limits.mm_per_min.resize(c.n);
  result.samples.resize(c.n);
  for (std::size_t i = 0; i < c.n; ++i) {
    result.samples[i] = planned_engagement(c.samples[i]);
    result.samples[i].load_ratio = c.load_ratio[i];
    limits.mm_per_min[i] = feed_limit_at(c, limits.centripetal, i, result.samples[i], limits.target_below_model);
  }
  hold_feed_limit_before_rapids(c, limits.mm_per_min);
  hold_force_limit_over_the_last_tooth(c, limits.mm_per_min);
  return limits;
}

// Step 2's result.
struct CommandProfile {
  double accel_mm_per_s2 = 0.0;    // acceleration the passes use (a, or a_eff with a jerk limit)
  std::vector<double> mm_per_min;  // command feed per sample
};

// The greatest profile under the limits at acceleration a, mm/s.
std::vector<double> greatest_command(const PlanContext& c, const std::vector<double>& limit_mm_per_min, double a) {
  std::vector<double> cap(c.n);
  for (std::size_t i = 0; i < c.n; ++i) cap[i] = limit_mm_per_min[i] / 60.0;
  return greatest_speeds(c.s, cap, a);
}

// Step 2. Command profile: the greatest profile under the limits and the acceleration (no stops).
CommandProfile plan_command_profile(const PlanContext& c, const FeedLimits& limits, PlanResult& result) {
  const auto& machine = c.settings.machine;
  const PlanOptions& options = c.settings.options;
  // Acceleration the passes use (with the jerk heuristic of PlanOptions::jerk_limit_mm_per_s3).
  double accel = machine.max_accel_mm_per_s2;
  std::vector<double> command = greatest_command(c, limits.mm_per_min, accel);
  if (options.jerk_limit_mm_per_s3 > 0.0) {
    // Heuristic: an S-curve with acceleration limit a and jerk limit J covers a speed change Δv in
    // Δv/a + a/J, i.e. at the mean acceleration a_eff = a·Δv / (Δv + a²/J). Taken for the largest
    // change of the profile between a local minimum and the next maximum (approximated by the largest
    // difference anywhere in a feed stretch), it bounds that change; smaller changes need little distance.
    const auto [lowest, highest] = std::minmax_element(command.begin(), command.end());
    const double largest_change = *highest - *lowest;
    if (largest_change > 0.0) {
      const double a = machine.max_accel_mm_per_s2;
      accel = a * largest_change / (largest_change + a * a / options.jerk_limit_mm_per_s3);
      command = greatest_command(c, limits.mm_per_min, accel);
    }
  }
  result.summary.accel_used_mm_per_s2 = accel;
  CommandProfile profile;
  profile.accel_mm_per_s2 = accel;
  profile.mm_per_min.resize(c.n);
  for (std::size_t i = 0; i < c.n; ++i) {
    profile.mm_per_min[i] = command[i] * 60.0;
    result.samples[i].command_feed_mm_per_min = profile.mm_per_min[i];
  }
  return profile;
}

// Step 3. Blocks.
void split_into_blocks(const PlanContext& c, const CommandProfile& command, const FeedLimits& limits,
                       PlanResult& result) {
  const PlanOptions& options = c.settings.options;
  const auto& machine = c.settings.machine;
  detail::BlockSplitSettings split;
  split.mode = options.mode;
  split.merge_tolerance = options.merge_tolerance;
  split.feed_resolution_mm_per_min = options.feed_resolution_mm_per_min;
  split.block_time_min_s = machine.block_time_min_s;
  split.short_block_s = machine.block_time_min_s;
  split.min_feed_mm_per_min = machine.min_feed_mm_per_min;
  split.accel_mm_per_s2 = command.accel_mm_per_s2;
  if (options.feed_step > 0.0) {
    // Controller-friendly: least-time blocks under the limits, each lasting at least the shortest duration,
    // their F rounded down onto the levels (block_split.hpp).
    split.least_time = true;
    split.level_step = options.feed_step;
    split.level_top_mm_per_min = machine.max_feed_mm_per_min;
    split.block_time_min_s = std::max(machine.block_time_min_s, options.min_block_duration_s);
    result.blocks =
        detail::split_blocks(c.path, c.s, limits.mm_per_min, c.move_first, split, result.summary.short_blocks);
    return;
  }
  result.blocks =
      detail::split_blocks(c.path, c.s, command.mm_per_min, c.move_first, split, result.summary.short_blocks);
}

// The controller model (controller_model.hpp) set up for this path: runs a list of its blocks.
struct BlockRunner {
  BlockRunner(const PlanContext& c, const FeedLimits& limits, double accel);
  ControllerRun run(const std::vector<PlannedBlock>& blocks) const {
    return run_controller(c.s, block_caps(blocks, c.n - 1, centripetal, c.path, rapid_mm_per_s), stops,
                          interval_cutting, accel);
  }

  const PlanContext& c;
  const std::vector<double>& centripetal;  // mm/s per interval
  const double accel;                      // mm/s²
  const double rapid_mm_per_s;
  std::vector<bool> stops;
  std::vector<bool> interval_cutting;
};

BlockRunner::BlockRunner(const PlanContext& c, const FeedLimits& limits, double accel)
    : c(c),
      centripetal(limits.centripetal),
      accel(accel),
      rapid_mm_per_s(c.settings.machine.rapid_feed_mm_per_min / 60.0),
      stops(controller_stops(c.path, c.engagement)),
      interval_cutting(c.n - 1) {
  for (std::size_t j = 0; j + 1 < c.n; ++j) interval_cutting[j] = c.samples[j].cutting;
}

// Every block's smallest limit and predicted duration; every sample's block and block F.
void time_blocks(const ControllerRun& run, const std::vector<double>& limit_mm_per_min, PlanResult& result) {
  for (std::size_t b = 0; b < result.blocks.size(); ++b) {
    PlannedBlock& block = result.blocks[b];
    block.min_limit_mm_per_min = std::numeric_limits<double>::infinity();
    for (int i = block.first_sample; i <= block.last_sample; ++i) {
      auto k = static_cast<std::size_t>(i);
      block.min_limit_mm_per_min = std::min(block.min_limit_mm_per_min, limit_mm_per_min[k]);
      if (i < block.last_sample || b + 1 == result.blocks.size()) {
        result.samples[k].block_index = static_cast<int>(b);
        result.samples[k].block_feed_mm_per_min = block.feed_mm_per_min;
      }
    }
    block.duration_s = run.time_s[static_cast<std::size_t>(block.last_sample)] -
                       run.time_s[static_cast<std::size_t>(block.first_sample)];
  }
}

// The first samples the status messages name (null: none).
struct FirstProblems {
  const geometry::EngagementSample* over = nullptr;          // predicted above the target
  const geometry::EngagementSample* extrapolated = nullptr;  // the model extrapolates and sets the feed
  double max_upper_force_n = 0.0;                            // largest cautious bound (PlannedSample::upper_force_n)
};

// Every sample's speed, time, chip and forces as the machine runs the blocks; the summary's counts.
FirstProblems predict_samples(const PlanContext& c, const ControllerRun& run, PlanResult& result) {
  const auto& samples = c.samples;
  const PlanSettings& settings = c.settings;
  PlanSummary& summary = result.summary;
  FirstProblems first;
  for (std::size_t i = 0; i < c.n; ++i) {
    PlannedSample& planned = result.samples[i];
    planned.feed_mm_per_min = run.speed_mm_per_s[i] * 60.0;
    planned.time_s = run.time_s[i];
    planned.chip_thickness_mm =
        planned.engaged ? chip_thickness_mm(samples[i], planned.feed_mm_per_min, c.flutes, c.rpm) : 0.0;
    planned.predicted_force_n =
        c.correction(i) *
        c.forces.predicted_force_n(samples[i], c.load_ratio[i], planned.feed_mm_per_min, c.flutes, c.rpm);
    planned.transfer_factor =
        c.forces.transfer_factor(samples[i], c.load_ratio[i], planned.feed_mm_per_min, c.flutes, c.rpm);
    planned.upper_force_n = c.uncertainty ? c.correction(i) * c.forces.upper_force_n(c.bound_sample(i), c.load_ratio[i],
                                                                                     planned.feed_mm_per_min, c.flutes,
                                                                                     c.rpm, c.uncertainty)
                                          : planned.predicted_force_n;
    planned.within_model_range = planned.engaged && !model::chip_outside(settings.model.range, planned.chip_thickness_mm) &&
                                 !model::contact_length_outside(settings.model.range, planned.contact_length_mm);
    summary.max_predicted_force_n = std::max(summary.max_predicted_force_n, planned.predicted_force_n);
    first.max_upper_force_n = std::max(first.max_upper_force_n, planned.upper_force_n);
    if (planned.engaged) ++summary.engaged_samples;
    if (planned.limit_reason == FeedLimitReason::kForce) ++summary.force_limited_samples;
    if (planned.extrapolated) {
      ++summary.extrapolated_samples;
      if (!first.extrapolated) first.extrapolated = &samples[i];
    }
    if (planned.engaged && planned.upper_force_n > settings.target_force_n * (1.0 + 1e-9)) {
      ++summary.over_target_samples;
      if (!first.over) first.over = &samples[i];
    }
  }
  return first;
}

// The summary's times and block feed range.
void summarise_run(const ControllerRun& run, PlanResult& result) {
  PlanSummary& summary = result.summary;
  summary.cycle_time_s = run.cycle_time_s;
  summary.cutting_time_s = run.cutting_time_s;
  summary.air_time_s = run.air_time_s;
  summary.min_feed_mm_per_min = std::numeric_limits<double>::infinity();
  for (const PlannedBlock& block : result.blocks) {
    if (block.feed_mm_per_min <= 0.0) continue;
    summary.min_feed_mm_per_min = std::min(summary.min_feed_mm_per_min, block.feed_mm_per_min);
    summary.max_feed_mm_per_min = std::max(summary.max_feed_mm_per_min, block.feed_mm_per_min);
  }
  if (!std::isfinite(summary.min_feed_mm_per_min)) summary.min_feed_mm_per_min = 0.0;
}

// Step 4. Prediction: the controller runs the blocks.
FirstProblems predict(const PlanContext& c, const FeedLimits& limits, const BlockRunner& runner, PlanResult& result) {
  const ControllerRun run = runner.run(result.blocks);
  time_blocks(run, limits.mm_per_min, result);
  const FirstProblems first = predict_samples(c, run, result);
  summarise_run(run, result);
  return first;
}

// The one feed whose predicted peak equals the plan's, on every feed move.
double baseline_feed_mm_per_min(const PlanContext& c, const PlanResult& result) {
  const auto& machine = c.settings.machine;
  const PlanSummary& summary = result.summary;
  if (summary.max_predicted_force_n > 0.0) {
    double feed = machine.max_feed_mm_per_min;
    for (std::size_t i = 0; i < c.n; ++i) {
      if (!result.samples[i].engaged) continue;
      const SampleFeedLimit limit = c.forces.feed_limit(c.samples[i], c.load_ratio[i],
                                                        summary.max_predicted_force_n / c.correction(i), c.flutes,
                                                        c.rpm, c.air_feed, nullptr);
      if (limit.reason == FeedLimitReason::kAirFeed) continue;
      feed = std::min(feed, limit.target_below_model ? machine.min_feed_mm_per_min : limit.feed_mm_per_min);
    }
    const double r = c.settings.options.feed_resolution_mm_per_min;
    return std::max(machine.min_feed_mm_per_min, std::floor(feed / r + 1e-9) * r);
  }
  return c.air_feed;
}

// One block per move, all at `feed_mm_per_min`.
std::vector<PlannedBlock> constant_feed_blocks(const PlanContext& c, double feed_mm_per_min) {
  std::vector<PlannedBlock> constant;
  for (std::size_t m = 0; m < c.path.moves.size(); ++m) {
    PlannedBlock block;
    block.move_index = static_cast<int>(m);
    block.first_sample = c.move_first[m];
    block.last_sample = c.move_first[m + 1];
    block.feed_mm_per_min = feed_mm_per_min;
    constant.push_back(block);
  }
  return constant;
}

// Step 5. Baseline: the one feed whose predicted peak equals the plan's, on every feed move; the time saved.
void plan_baseline(const PlanContext& c, const BlockRunner& runner, PlanResult& result) {
  PlanSummary& summary = result.summary;
  ConstantFeedBaseline& baseline = summary.baseline;
  baseline.feed_mm_per_min = baseline_feed_mm_per_min(c, result);
  const ControllerRun base_run = runner.run(constant_feed_blocks(c, baseline.feed_mm_per_min));
  baseline.cycle_time_s = base_run.cycle_time_s;
  baseline.cutting_time_s = base_run.cutting_time_s;
  for (std::size_t i = 0; i < c.n; ++i) {
    baseline.peak_force_n =
        std::max(baseline.peak_force_n, c.correction(i) * c.forces.predicted_force_n(c.samples[i], c.load_ratio[i],
                                                                                      base_run.speed_mm_per_s[i] * 60.0,
                                                                                      c.flutes, c.rpm));
  }
  summary.time_saved_percent =
      baseline.cycle_time_s > 0.0 ? 100.0 * (baseline.cycle_time_s - summary.cycle_time_s) / baseline.cycle_time_s : 0.0;
}

// Program: one move per block, M3 at the settings' speed.
void write_program(const PlanContext& c, PlanResult& result) {
  const geometry::ToolPath& path = c.path;
  const std::vector<int>& move_first = c.move_first;
  for (const PlannedBlock& block : result.blocks) {
    const geometry::Move& move = path.moves[static_cast<std::size_t>(block.move_index)];
    const int first = move_first[static_cast<std::size_t>(block.move_index)];
    const int steps = move_first[static_cast<std::size_t>(block.move_index) + 1] - first;
    result.program.path.moves.push_back(sub_move(move, block.first_sample - first, block.last_sample - first, steps));
    geometry::BlockCommand command_block;
    command_block.feed_mm_per_min = block.feed_mm_per_min;
    command_block.spindle_rpm = c.rpm;
    command_block.spindle = geometry::SpindleDirection::kClockwise;
    result.program.blocks.push_back(command_block);
  }
  result.program.path.part_names = path.part_names;
}

std::string target_not_met_message(const PlanContext& c, const FeedLimits& limits, const FirstProblems& first,
                                   const PlanSummary& summary) {
  const PlanSettings& settings = c.settings;
  return "target " + num(settings.target_force_n) + " N not met at " + std::to_string(summary.over_target_samples) +
         " samples, first at " + where(*first.over) + ": " +
         (limits.target_below_model > 0 ? "the model predicts more than the target even as the feed goes to 0"
                                        : "the target needs less than the machine's minimum feed " +
                                              num(settings.machine.min_feed_mm_per_min) + " mm/min") +
         "; planned at the minimum feed, predicted up to " + fixed(summary.max_predicted_force_n, 1) + " N" +
         (c.uncertainty && first.max_upper_force_n > summary.max_predicted_force_n
              ? " (" + fixed(first.max_upper_force_n, 1) + " N with the cautious bound held at the target)"
              : "");
}

std::string extrapolation_message(const PlanContext& c, const FirstProblems& first, const PlanSummary& summary) {
  const PlanSettings& settings = c.settings;
  const geometry::EngagementSample& e = *first.extrapolated;
  const auto& range = settings.model.range;
  return "the model extrapolates where it sets the feed at " + std::to_string(summary.extrapolated_samples) +
         " samples, first at " + where(e) + " (L = " + fixed(e.contact_length_mm, 3) + " mm, fitted " +
         fixed(range.contact_length_min_mm, 3) + "–" + fixed(range.contact_length_max_mm, 3) + " mm; t_m fitted " +
         fixed(range.chip_min_mm, 4) + "–" + fixed(range.chip_max_mm, 4) + " mm; a_p " + fixed(e.axial_depth_mm, 3) +
         " mm, fitted at " + num(settings.model.axial_depth_mm) + " mm)";
}

// Status and messages.
void report_outcome(const PlanContext& c, const FeedLimits& limits, const FirstProblems& first, PlanResult& result) {
  const PlanSettings& settings = c.settings;
  const PlanSummary& summary = result.summary;
  if (summary.over_target_samples > 0) {
    result.status = PlanStatus::kTargetNotMet;
    result.messages.push_back(target_not_met_message(c, limits, first, summary));
  } else if (summary.extrapolated_samples > 0) {
    result.status = PlanStatus::kExtrapolated;
  }
  if (summary.extrapolated_samples > 0) result.messages.push_back(extrapolation_message(c, first, summary));
  int range_limited = 0;
  for (const PlannedSample& planned : result.samples) range_limited += planned.limit_reason == FeedLimitReason::kModelRange;
  if (range_limited > 0) {
    const double max_chip_mm = settings.options.max_chip_thickness_mm;
    result.messages.push_back(
        (max_chip_mm > 0.0 ? "the largest chip the cutting tests saw (t_m ≤ " + fixed(max_chip_mm, 4) + " mm for this cutter)"
                           : "the model's fitted chip range (t_m ≤ " + fixed(settings.model.range.chip_max_mm, 4) + " mm)") +
        " limits the feed at " + std::to_string(range_limited) +
        " samples: the force there stays below the target rather than extrapolate");
  }
  if (summary.short_blocks > 0) {
    result.messages.push_back(std::to_string(summary.short_blocks) +
                              " blocks last less than the block time " + num(settings.machine.block_time_min_s) +
                              " s (whole moves that short; the controller may slow down there)");
  }
  for (const std::string& warning : c.engagement.warnings) result.messages.push_back(warning);
}

// The safety check (safety_check.hpp) on the written program.
SafetyCheck check_program(const PlanContext& c, const PlanGeometry& geometry, const PlanResult& result) {
  SafetyCheckInput input;
  input.stock = &geometry.stock;
  input.tool = &geometry.tool;
  input.settings = &c.settings;
  input.correction_s_mm = c.s;
  input.ds_mm = c.engagement.ds_mm;  // the spacing the plan was analysed at
  input.planned_engagement = &c.engagement;
  input.planned_load_ratio = &c.load_ratio;
  // --mode regulate promises F within the merge tolerance of the limit (feed_plan.hpp), not below it.
  if (c.settings.options.mode == PlanMode::kRegulate) {
    input.relative_tolerance = std::max(input.relative_tolerance, c.settings.options.merge_tolerance);
  }
  return check_safety(result.program, input);
}

// The check samples between two planner samples where the limit is lower than at both: every check sample
// of a program move that breaks an invariant lowers the limits of the two planner samples around it to
// the feed the check allows there (on feed moves; a rapid in material or an unknown engagement is not
// mended by a feed). True when a limit was lowered.
bool hold_check_allowances(const PlanContext& c, const SafetyCheck& check, FeedLimits& limits, PlanResult& result) {
  std::vector<bool> violating(result.program.path.moves.size(), false);
  for (const SafetyViolation& v : check.violations) violating[static_cast<std::size_t>(v.move_index)] = true;
  bool lowered = false;
  for (const AllowedFeed& allowed : check.allowed) {
    if (!violating[static_cast<std::size_t>(allowed.move_index)]) continue;
    if (!(allowed.mm_per_min > 0.0) || !std::isfinite(allowed.mm_per_min)) continue;
    const auto after = std::upper_bound(c.s.begin(), c.s.end(), allowed.s_mm);
    const std::size_t i = after == c.s.begin() ? 0 : static_cast<std::size_t>(after - c.s.begin()) - 1;
    for (std::size_t j = i; j <= std::min(i + 1, c.n - 1); ++j) {
      const auto& move = c.path.moves[static_cast<std::size_t>(c.samples[j].move_index)];
      if (move.kind == geometry::MoveKind::kRapid || !(limits.mm_per_min[j] > allowed.mm_per_min * (1.0 + 1e-9))) {
        continue;
      }
      limits.mm_per_min[j] = allowed.mm_per_min;
      result.samples[j].feed_limit_mm_per_min = allowed.mm_per_min;
      result.samples[j].limit_reason = FeedLimitReason::kForce;
      lowered = true;
    }
  }
  return lowered;
}

// Steps 2 and 3 and the program under the current limits; the check on it.
SafetyCheck plan_checked_program(const PlanContext& c, const PlanGeometry& geometry, const FeedLimits& limits,
                                 CommandProfile& command, PlanResult& result) {
  command = plan_command_profile(c, limits, result);
  split_into_blocks(c, command, limits, result);
  result.program = {};
  write_program(c, result);
  return check_program(c, geometry, result);
}

// A plan the check still refuses is unsafe, named at its first places.
void report_unsafe(const SafetyCheck& check, PlanResult& result) {
  const std::vector<SafetyViolation>& violations = check.violations;
  if (violations.empty()) return;
  result.status = PlanStatus::kUnsafe;
  constexpr std::size_t kNamed = 3;
  std::string text = "unsafe: " + std::to_string(violations.size()) +
                     " program moves run faster than their engagement allows (or rapid through material): ";
  for (std::size_t k = 0; k < std::min(kNamed, violations.size()); ++k) {
    text += (k > 0 ? "; " : "") + describe(violations[k]);
  }
  if (violations.size() > kNamed) text += "; …";
  result.messages.insert(result.messages.begin(), text);
}

}  // namespace

// The steps of the method in feed_plan.hpp, in order; steps 2 and 3 again (at most kSafetyPasses times in
// all) while the safety check finds places between the planner's samples that need a lower feed.
PlanResult plan(const PlanGeometry& geometry, const PlanSettings& settings) {
  check_plan_input(geometry, settings);
  const PlanContext context(geometry, settings);
  PlanResult result;
  FeedLimits limits = limit_feeds(context, result);
  CommandProfile command;
  SafetyCheck check = plan_checked_program(context, geometry, limits, command, result);
  for (int pass = 1; pass < kSafetyPasses && !check.violations.empty(); ++pass) {
    if (!hold_check_allowances(context, check, limits, result)) break;
    check = plan_checked_program(context, geometry, limits, command, result);
  }
  const BlockRunner runner(context, limits, command.accel_mm_per_s2);
  const FirstProblems first = predict(context, limits, runner, result);
  plan_baseline(context, runner, result);
  report_outcome(context, limits, first, result);
  report_unsafe(check, result);
  return result;
}

std::vector<double> sample_feeds_mm_per_min(const PlanResult& result) {
  std::vector<double> feeds;
  feeds.reserve(result.samples.size());
  for (const PlannedSample& sample : result.samples) feeds.push_back(sample.feed_mm_per_min);
  return feeds;
}

}  // namespace feedplan::planner
