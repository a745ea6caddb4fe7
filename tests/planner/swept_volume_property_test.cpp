// Seeded random property test of the WRITTEN programs (PlanResult::program) against a truth the planner
// does not produce: the brute-force material oracle of tests/geometry/brute_force_oracle.hpp, which
// samples the tool circle and asks of every point whether it lies in the initial stock and outside every
// earlier sweep at or below the height (it shares no code with geometry::compute_engagement). Random
// corner roundings, trochoids, spirals and helical borings (random_cases.hpp) are planned on random stocks
// (the cycle's own, with a random pre-drilled hole, or a random block that covers only part of the path)
// with random tools (a plunge feed per tooth of their own or the default); then, every 0.5 mm along every
// program move:
//   1. where the oracle finds material within the tool's reach — engaged on the tool circle on the lowest
//      layer above the tip (every higher layer's engaged set lies inside it, so no height between the tip
//      and the stock top has material the lowest layer lacks), or, under a rapid or a descending move,
//      on the tool's bottom face (points of the disc that were material before the move began) — the
//      move is a feed move, never a rapid;
//   2. there the block's F is at most the feed the oracle's engagement allows: its engaged angle α, chip
//      factor k (closed form over the engaged arcs), contact length r·α and height of material in contact
//      above the tip (bisection over heights) turned into a feed by the planner's public rule
//      planner::sample_feed_limit (feed_limit.hpp) with the linear axial-depth transfer only (load ratio 0:
//      the planner also applies the chip-load transfer, which can only lower its feed, so the oracle's
//      feed is an upper bound of the planner's), at least the machine's minimum feed;
//      in particular a place with material is never run at the air feed;
//   3. a feed move that descends into material runs at most at
//      tool.plunge_feed_per_tooth_mm() · flutes · rpm · length / descent;
//   4. a plan whose status is not unsafe has no violation of planner::check_safety; a plan reported unsafe
//      names its first violation (describe()) in its first message; and every program move where the
//      oracle finds a violation is one the check reports.
//
// Tolerances, and why:
//   - depth: material counts where some point of the tool circle lies at least δ = 1 µm inside it — δ
//     inside the stock's boundary and δ beyond every earlier sweep — and the material above the tip is at
//     least δ high. Where the tool runs tangent to material (a retract where the last feed move ended, a
//     loop on the circle of an earlier one, a pass along a stock face), the exact engagement can be a wide
//     arc of zero depth, which touches and does not cut; rounding in either computation turns such
//     contacts into slivers. 1 µm is below the 0.001 mm the programs are written with. The circle is
//     sampled at 0.5° steps, which finds arcs about that wide (an arc 1 µm deep is 0.8° on D20).
//     Forces are computed from the exact engagement, not the δ-deep part.
//   - sample spacing: the planner evaluates the engagement at its own samples, ds apart, and a block's F is
//     at most the limit at every sample inside it; between two samples the engagement may exceed both
//     (a corner of material grazed between them). A point is a violation only when F is above the feed
//     the oracle allows at the point AND at the planner's two samples around it.
//   - feeds: 1 % (the safety check's own relative tolerance); F is rounded down to the feed resolution.
//
// Reproduce a run with FEEDPLAN_TEST_SEED and FEEDPLAN_TEST_COUNT (printed at the start).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "brute_force_oracle.hpp"
#include "feedplan/core/angle.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/planner/feed_limit.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/planner/safety_check.hpp"
#include "random_cases.hpp"

namespace feedplan::planner {
namespace {

constexpr double kPointSpacingMm = 0.5;     // oracle points along every program move
constexpr int kCircleSamples = 720;         // oracle samples of the tool circle (0.5°)
constexpr double kDepthToleranceMm = 1e-3;  // δ: less material than this is not material (file comment)
constexpr double kFeedTolerance = 0.01;     // relative, as the safety check's
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// What the oracle finds at one place of the program, and the feeds it allows there.
struct Place {
  geometry::Point3 position;
  double engagement_rad = 0.0;
  double chip_factor = 0.0;
  double material_height_mm = 0.0;
  bool bottom_in_material = false;  // the bottom face meets material (rapids and descending moves)
  bool circle_in_material = false;  // the tool circle meets material, beyond the depth tolerance
  bool material = false;            // either: material within reach
  double force_feed_mm_per_min = kInfinity;   // property 2
  double plunge_feed_mm_per_min = kInfinity;  // property 3
  double allowed_mm_per_min() const { return std::min(force_feed_mm_per_min, plunge_feed_mm_per_min); }
};

// XY travel direction at fraction f of a move, rad (NaN for a pure z move).
double travel_direction_rad(const geometry::Move& move, double f) {
  if (move.kind == geometry::MoveKind::kArc) {
    const geometry::Point3 p = geometry::point_at(move, f);
    const double radial = std::atan2(p.y_mm - move.center.y_mm, p.x_mm - move.center.x_mm);
    return radial + (move.ccw ? 0.5 : -0.5) * kPi;
  }
  const double dx = move.end.x_mm - move.start.x_mm;
  const double dy = move.end.y_mm - move.start.y_mm;
  return dx == 0.0 && dy == 0.0 ? std::numeric_limits<double>::quiet_NaN() : std::atan2(dy, dx);
}

bool descends(const geometry::Move& move) { return move.end.z_mm < move.start.z_mm; }

// The oracle on one program, with the settings that turn its engagement into feeds.
class ProgramOracle {
 public:
  ProgramOracle(const geometry::Program& program, const geometry::Stock& stock, const geometry::Tool& tool,
                const PlanSettings& settings)
      : program_(program), stock_(stock), tool_(tool), settings_(settings),
        truth_(program.path, stock, tool.radius_mm()) {}

  Place at(std::size_t move_index, double f) {
    const geometry::Move& move = program_.path.moves[move_index];
    Place place;
    place.position = geometry::point_at(move, f);
    const std::vector<geometry::oracle::Arc> arcs = truth_.engaged_arcs(move_index, f, kCircleSamples);
    for (const auto& a : arcs) place.engagement_rad += a.end_rad - a.begin_rad;
    const double direction = travel_direction_rad(move, f);
    place.chip_factor = std::isnan(direction) ? 0.0 : geometry::oracle::chip_factor(arcs, direction);
    place.material_height_mm = truth_.material_height_mm(arcs, deg_to_rad(2.0), 1e-3);
    if (move.kind == geometry::MoveKind::kRapid || descends(move)) place.bottom_in_material = bottom_in_material();
    place.circle_in_material = place.material_height_mm >= kDepthToleranceMm && deep_material_on_circle(arcs);
    place.material = place.circle_in_material || place.bottom_in_material;
    if (!place.material || move.kind == geometry::MoveKind::kRapid) return place;
    place.force_feed_mm_per_min = force_feed(move, place);
    if (descends(move)) {
      place.plunge_feed_mm_per_min = tool_.plunge_feed_per_tooth_mm() * tool_.flutes * settings_.spindle_rpm *
                                     geometry::length_mm(move) / (move.start.z_mm - move.end.z_mm);
    }
    return place;
  }

 private:
  // Some point of the engaged arcs (every 0.5° inside them) has material at least δ deep, δ above the tip.
  bool deep_material_on_circle(const std::vector<geometry::oracle::Arc>& arcs) {
    const double height = truth_.tip_z_mm() + kDepthToleranceMm;
    if (height > stock_.z_top_mm) return false;
    truth_.set_height(height);
    const double step = 2.0 * kPi / kCircleSamples;
    for (const auto& a : arcs) {
      const double width = a.end_rad - a.begin_rad;
      const int n = std::max(1, static_cast<int>(std::ceil(width / step)));
      for (int j = 0; j < n; ++j) {
        if (truth_.engaged_deeper_than(a.begin_rad + width * (j + 0.5) / n, kDepthToleranceMm)) return true;
      }
    }
    return false;
  }

  // Points of the tool's disc (rings at 0, 0.3, 0.6 and 0.9 r), δ above the tip, that were material
  // before the move began.
  bool bottom_in_material() {
    const double height = truth_.tip_z_mm() + kDepthToleranceMm;
    if (height > stock_.z_top_mm) return false;
    truth_.set_height(height);
    const geometry::oracle::XY c = truth_.centre();
    bool found = truth_.material_before_move(c);
    for (int ring = 1; ring <= 3 && !found; ++ring) {
      for (int k = 0; k < 12 && !found; ++k) {
        const double rho = 0.3 * ring * tool_.radius_mm();
        const double phi = 2.0 * kPi * (k + 0.5 * ring) / 12.0;
        found = truth_.material_before_move({c.x + rho * std::cos(phi), c.y + rho * std::sin(phi)});
      }
    }
    return found;
  }

  // The planner's public rule applied to the oracle's engagement (file comment, property 2).
  double force_feed(const geometry::Move& move, const Place& place) const {
    geometry::EngagementSample sample;
    sample.cutting = true;
    sample.engagement_rad = place.engagement_rad;
    sample.chip_factor = place.chip_factor;
    sample.contact_length_mm = tool_.radius_mm() * place.engagement_rad;
    sample.xy_speed_ratio = geometry::xy_length_mm(move) / geometry::length_mm(move);
    sample.axial_depth_mm = place.material_height_mm;
    sample.material_height_mm = place.material_height_mm;
    const SampleFeedLimit limit = sample_feed_limit(settings_.model, sample, 0.0, settings_.target_force_n,
                                                    tool_.flutes, settings_.spindle_rpm, kInfinity);
    const double min_feed = settings_.machine.min_feed_mm_per_min;
    return limit.target_below_model ? min_feed : std::max(limit.feed_mm_per_min, min_feed);
  }

  const geometry::Program& program_;
  const geometry::Stock& stock_;
  const geometry::Tool& tool_;
  const PlanSettings& settings_;
  geometry::oracle::EngagementOracle truth_;
};

// --- Random stocks and tools ------------------------------------------------------------------------

// XY box of the path's feed moves.
struct Box {
  double x0 = kInfinity, y0 = kInfinity, x1 = -kInfinity, y1 = -kInfinity;
};

Box feed_box(const geometry::ToolPath& path) {
  Box box;
  for (const geometry::Move& move : path.moves) {
    if (move.kind == geometry::MoveKind::kRapid) continue;
    for (int i = 0; i <= 32; ++i) {
      const geometry::Point3 p = geometry::point_at(move, i / 32.0);
      box.x0 = std::min(box.x0, p.x_mm), box.y0 = std::min(box.y0, p.y_mm);
      box.x1 = std::max(box.x1, p.x_mm), box.y1 = std::max(box.y1, p.y_mm);
    }
  }
  return box;
}

// The cycle's own stock, the same with a random pre-drilled hole, or a random block over part of the
// path (same heights, earlier cuts kept). A draw that geometry::validate refuses keeps the cycle's stock.
geometry::Stock random_stock(std::mt19937_64& rng, const geometry::Stock& own, const geometry::ToolPath& path,
                             double diameter_mm, std::string& description) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int kind = static_cast<int>(3 * u(rng)) % 3;
  const Box box = feed_box(path);
  geometry::Stock stock = own;
  if (kind == 1) {
    const double radius = diameter_mm * (0.15 + 0.85 * u(rng));
    const geometry::Point2 centre{box.x0 + u(rng) * (box.x1 - box.x0), box.y0 + u(rng) * (box.y1 - box.y0)};
    for (auto& region : stock.regions) region.holes.push_back(geometry::Contour::circle(centre, radius));
    description = ", stock with a hole r " + std::to_string(radius);
  } else if (kind == 2) {
    const double w = box.x1 - box.x0 + 2 * diameter_mm;
    const double h = box.y1 - box.y0 + 2 * diameter_mm;
    const double x0 = box.x0 - diameter_mm + 0.6 * w * u(rng);
    const double y0 = box.y0 - diameter_mm + 0.6 * h * u(rng);
    const geometry::Point2 low{x0, y0};
    const geometry::Point2 high{x0 + w * (0.2 + 0.8 * u(rng)), y0 + h * (0.2 + 0.8 * u(rng))};
    stock.regions = {geometry::StockRegion{geometry::Contour::rectangle(low, high), {}}};
    description = ", block over part of the path";
  }
  if (kind != 0 && !geometry::validate(stock).empty()) {
    description = ", own stock (the draw was invalid)";
    return own;
  }
  if (kind == 0) description = ", own stock";
  return stock;
}

// --- The properties ----------------------------------------------------------------------------------

enum class Broken { kRapidInMaterial, kAboveForceFeed, kAbovePlungeFeed };

std::string to_text(Broken broken) {
  switch (broken) {
    case Broken::kRapidInMaterial: return "rapid where the oracle finds material (property 1)";
    case Broken::kAboveForceFeed: return "F above the feed the oracle's engagement allows (property 2)";
    case Broken::kAbovePlungeFeed: return "F above the plunge feed while descending into material (property 3)";
  }
  return "?";
}

// The worst place of one program move that breaks property 1, 2 or 3.
struct Violation {
  Broken broken = Broken::kAboveForceFeed;
  std::size_t move_index = 0;
  double s_mm = 0.0;
  Place place;
  double feed_mm_per_min = 0.0;     // the block's F (the rapid rate on rapids)
  double allowed_mm_per_min = 0.0;  // the most the oracle allows at the point and the samples around it
  double ratio() const { return allowed_mm_per_min > 0.0 ? feed_mm_per_min / allowed_mm_per_min : kInfinity; }
};

struct Tally {
  long long cases = 0, plans_by_status[4] = {0, 0, 0, 0}, moves = 0, points = 0, material_points = 0;
  long long descending_material_points = 0, rapid_points = 0, bracket_places = 0;
  long long violations[3] = {0, 0, 0}, air_feed_in_material = 0, missed_by_check = 0, check_disagrees = 0;
  long long end_face_only = 0;  // violations where only the tool's end face meets material (not its circle)
  long long refused_unavoidable = 0;  // violations no F could avoid, in plans refused as unsafe (accepted)
  long long refused_without_violation = 0;  // unsafe plans in which the oracle finds no violation at all
};

// One planned case: everything the properties look at.
struct PlannedCase {
  std::string where;  // seed, case number and description, for messages
  geometry::Stock stock;
  geometry::Tool tool;
  PlanSettings settings;
  PlanResult result;
};

// The program moves' start s, mm (one more entry: the end).
std::vector<double> move_starts(const geometry::ToolPath& path) {
  std::vector<double> start{0.0};
  for (const geometry::Move& move : path.moves) start.push_back(start.back() + geometry::length_mm(move));
  return start;
}

// The most the oracle allows at the planner's own samples around s on move m (or at the point itself).
class Bracket {
 public:
  Bracket(ProgramOracle& oracle, const PlanResult& result, const std::vector<double>& starts, Tally& tally)
      : oracle_(oracle), result_(result), starts_(starts), tally_(tally) {}

  double allowed(std::size_t m, double s_mm, double at_point) {
    const auto& samples = result_.samples;
    const auto after = std::lower_bound(samples.begin(), samples.end(), s_mm,
                                        [](const PlannedSample& p, double s) { return p.s_mm < s; });
    const auto k = static_cast<std::size_t>(after - samples.begin());
    double most = at_point;
    for (const std::size_t i : {k == 0 ? k : k - 1, std::min(k, samples.size() - 1)}) most = std::max(most, at(m, i));
    return most;
  }

 private:
  double at(std::size_t m, std::size_t i) {
    const auto key = std::make_pair(m, i);
    if (const auto found = cache_.find(key); found != cache_.end()) return found->second;
    ++tally_.bracket_places;
    const double length = starts_[m + 1] - starts_[m];
    const double f = length > 0.0 ? std::clamp((result_.samples[i].s_mm - starts_[m]) / length, 0.0, 1.0) : 0.0;
    return cache_[key] = oracle_.at(m, f).allowed_mm_per_min();
  }

  ProgramOracle& oracle_;
  const PlanResult& result_;
  const std::vector<double>& starts_;
  Tally& tally_;
  std::map<std::pair<std::size_t, std::size_t>, double> cache_;
};

// Properties 1–3 at every point of one program move; the move's worst violation, if any.
std::optional<Violation> check_move(const PlannedCase& c, ProgramOracle& oracle, Bracket& bracket,
                                    const std::vector<double>& starts, std::size_t m, Tally& tally) {
  const geometry::Move& move = c.result.program.path.moves[m];
  const bool rapid = move.kind == geometry::MoveKind::kRapid;
  const double feed = rapid ? c.settings.machine.rapid_feed_mm_per_min : c.result.program.blocks[m].feed_mm_per_min;
  const double length = starts[m + 1] - starts[m];
  const int n = std::max(1, static_cast<int>(std::ceil(length / kPointSpacingMm)));
  std::optional<Violation> worst;
  for (int j = 0; j < n; ++j) {
    const double f = (j + 0.5) / n;
    const Place place = oracle.at(m, f);
    ++tally.points;
    tally.rapid_points += rapid;
    if (!place.material) continue;
    ++tally.material_points;
    tally.descending_material_points += descends(move) && !rapid;
    Violation v{Broken::kRapidInMaterial, m, starts[m] + f * length, place, feed, 0.0};
    if (!rapid) {
      if (!(feed > place.allowed_mm_per_min() * (1.0 + kFeedTolerance))) continue;
      v.broken = place.plunge_feed_mm_per_min < place.force_feed_mm_per_min ? Broken::kAbovePlungeFeed
                                                                            : Broken::kAboveForceFeed;
      v.allowed_mm_per_min = bracket.allowed(m, v.s_mm, place.allowed_mm_per_min());
      if (!(feed > v.allowed_mm_per_min * (1.0 + kFeedTolerance))) continue;
    }
    if (!worst || v.ratio() > worst->ratio()) worst = v;
  }
  return worst;
}

std::string describe(const Violation& v, const PlannedCase& c, bool reported_by_check) {
  std::ostringstream text;
  const geometry::Point3& p = v.place.position;
  text << c.where << ": program move " << v.move_index << " at s = " << v.s_mm << " mm (x " << p.x_mm << ", y "
       << p.y_mm << ", z " << p.z_mm << "): " << to_text(v.broken) << "; F " << v.feed_mm_per_min
       << " mm/min, allowed " << v.allowed_mm_per_min << " mm/min (engaged " << rad_to_deg(v.place.engagement_rad)
       << " deg, chip factor " << v.place.chip_factor << ", " << v.place.material_height_mm
       << " mm of material above the tip; material on the circle " << v.place.circle_in_material
       << ", under the end face " << v.place.bottom_in_material
       << "); plan status " << to_string(c.result.status) << ", the safety check "
       << (reported_by_check ? "reports" : "does NOT report") << " this move";
  return text.str();
}

// Property 4. Returns the program moves the safety check reports.
std::vector<int> check_status_and_messages(const PlannedCase& c, double ds_mm, Tally& tally) {
  SafetyCheckInput input;
  input.stock = &c.stock;
  input.tool = &c.tool;
  input.settings = &c.settings;
  for (const PlannedSample& sample : c.result.samples) input.correction_s_mm.push_back(sample.s_mm);
  input.ds_mm = ds_mm;
  const std::vector<SafetyViolation> violations = check_safety(c.result.program, input).violations;
  std::vector<int> moves;
  for (const SafetyViolation& v : violations) moves.push_back(v.move_index);
  const bool unsafe = c.result.status == PlanStatus::kUnsafe;
  if (unsafe != !violations.empty()) {
    ++tally.check_disagrees;
    ADD_FAILURE() << c.where << ": status " << to_string(c.result.status) << " but check_safety finds "
                  << violations.size() << " violations" << (violations.empty() ? "" : ", first: " + describe(violations[0]));
  } else if (unsafe && (c.result.messages.empty() ||
                        c.result.messages.front().find(describe(violations.front())) == std::string::npos)) {
    ++tally.check_disagrees;
    ADD_FAILURE() << c.where << ": an unsafe plan whose first message does not name the place \""
                  << describe(violations.front()) << "\"; messages: " << ::testing::PrintToString(c.result.messages);
  }
  return moves;
}

// Whether the planner could not have avoided the violation: a rapid (the cycle's, which no F changes) or
// a place where the feed allowed is below the machine's minimum feed and F is that minimum. A plan that
// holds one may only be refused: reported unsafe, naming the move.
bool unavoidable(const Violation& v, const PlanSettings& settings) {
  const double min_feed = settings.machine.min_feed_mm_per_min;
  return v.broken == Broken::kRapidInMaterial ||
         (v.allowed_mm_per_min < min_feed && v.feed_mm_per_min <= min_feed * (1.0 + kFeedTolerance));
}

// Properties 1–3 on the whole program; failures are reported (the first `report_budget` in full).
// Returns the number of program moves with a violation (refused ones included).
int check_program(const PlannedCase& c, const std::vector<int>& check_moves, Tally& tally, int& report_budget) {
  const geometry::Program& program = c.result.program;
  const std::vector<double> starts = move_starts(program.path);
  ProgramOracle oracle(program, c.stock, c.tool, c.settings);
  Bracket bracket(oracle, c.result, starts, tally);
  const double air_feed = c.settings.options.air_feed_mm_per_min > 0.0 ? c.settings.options.air_feed_mm_per_min
                                                                       : c.settings.machine.max_feed_mm_per_min;
  int found = 0;
  for (std::size_t m = 0; m < program.path.moves.size(); ++m) {
    ++tally.moves;
    const std::optional<Violation> v = check_move(c, oracle, bracket, starts, m, tally);
    if (!v) continue;
    ++found;
    const bool reported = std::find(check_moves.begin(), check_moves.end(), static_cast<int>(m)) != check_moves.end();
    if (c.result.status == PlanStatus::kUnsafe && reported && unavoidable(*v, c.settings)) {
      ++tally.refused_unavoidable;
      continue;
    }
    if (!v->place.circle_in_material) {
      ++tally.end_face_only;
    } else {
      ++tally.violations[static_cast<int>(v->broken)];
    }
    tally.air_feed_in_material += v->broken != Broken::kRapidInMaterial && v->feed_mm_per_min >= air_feed;
    tally.missed_by_check += !reported;
    if (report_budget-- > 0) ADD_FAILURE() << describe(*v, c, reported);
  }
  return found;
}

// The case's tool: the spec's, with a plunge feed per tooth of its own half of the time.
geometry::Tool random_tool(std::mt19937_64& rng, const geometry::Tool& tool, std::string& description) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  geometry::Tool drawn = tool;
  if (u(rng) < 0.5) {
    drawn.max_plunge_feed_per_tooth_mm = tool.diameter_mm * (0.0005 + 0.0095 * u(rng));
    description += ", plunge f_z " + std::to_string(drawn.max_plunge_feed_per_tooth_mm) + " mm";
  }
  return drawn;
}

TEST(SweptVolumeProperty, WrittenProgramsAgreeWithTheBruteForceMaterialOracle) {
  const unsigned seed = testing::env_or("FEEDPLAN_TEST_SEED", 20261207u);
  const unsigned count = testing::env_or("FEEDPLAN_TEST_COUNT", 500u);
  std::cout << "swept volume: FEEDPLAN_TEST_SEED=" << seed << " FEEDPLAN_TEST_COUNT=" << count << "\n";
  std::mt19937_64 rng(seed);
  std::mt19937_64 stock_rng(seed ^ 0x5eed5eedULL);  // stocks and tools: the cases stay those of the seed
  Tally tally;
  int report_budget = 20;
  for (unsigned n = 0; n < count; ++n) {
    testing::RandomCase random = testing::random_case(rng);
    cycles::Cycle cycle;
    try {
      cycle = cycles::generate(random.spec);
    } catch (const InputError&) {
      continue;  // a random combination the generator refuses (validated elsewhere)
    }
    PlannedCase c;
    std::string drawn;
    c.stock = random_stock(stock_rng, cycle.stock, cycle.path, random.spec.tool.diameter_mm, drawn);
    c.tool = random_tool(stock_rng, random.spec.tool, drawn);
    c.where = "seed " + std::to_string(seed) + " case " + std::to_string(n) + " (" + random.description + drawn + ")";
    const double ds_mm = 0.02 * c.tool.diameter_mm;
    c.settings = random.settings;
    c.settings.options.ds_mm = ds_mm;
    const PlanGeometry geometry = analyse(cycle.path, c.stock, c.tool, ds_mm);
    c.result = plan(geometry, c.settings);
    ++tally.cases;
    ++tally.plans_by_status[static_cast<int>(c.result.status)];
    const std::vector<int> check_moves = check_status_and_messages(c, ds_mm, tally);
    const int found = check_program(c, check_moves, tally, report_budget);
    if (c.result.status == PlanStatus::kUnsafe && found == 0 && ++tally.refused_without_violation <= 3) {
      std::cout << "swept volume: refused, but the oracle finds no violation: " << c.where << ": "
                << c.result.messages.front() << "\n";
    }
  }
  const long long violations = tally.violations[0] + tally.violations[1] + tally.violations[2];
  std::cout << "swept volume: " << tally.cases << " cases (status ok " << tally.plans_by_status[0] << ", extrapolated "
            << tally.plans_by_status[1] << ", target not met " << tally.plans_by_status[2] << ", unsafe "
            << tally.plans_by_status[3] << "), " << tally.moves << " program moves, " << tally.points
            << " points checked (" << tally.material_points << " with material, " << tally.descending_material_points
            << " of them on descending feed moves; " << tally.rapid_points << " on rapids), " << tally.bracket_places
            << " places at the planner's samples\n"
            << "swept volume: program moves violating: rapid in material " << tally.violations[0]
            << ", above the force feed " << tally.violations[1] << ", above the plunge feed " << tally.violations[2]
            << ", above the plunge feed with material under the end face only " << tally.end_face_only
            << "; at the air feed " << tally.air_feed_in_material << "; not reported by the safety check "
            << tally.missed_by_check << "; status and check disagree " << tally.check_disagrees << "\n"
            << "swept volume: refused as unsafe where no feed could help (a rapid, or an allowed feed below the "
            << "machine's minimum): " << tally.refused_unavoidable << " program moves; unsafe plans in which the "
            << "oracle finds no violation: " << tally.refused_without_violation << "\n";
  EXPECT_EQ(violations, 0) << "program moves where the written program breaks properties 1-3 (listed above)";
  // The engagement (geometry::compute_engagement, the planner and the safety check alike) looks at the tool
  // circle only: a descending move whose end face comes down on material the circle does not touch (a block
  // or boss smaller than the tool's footprint) is taken for air and runs above the plunge feed.
  EXPECT_EQ(tally.end_face_only, 0)
      << "program moves descending onto material under the tool's end face, away from its circle, above the "
         "plunge feed (listed above): the planner takes that material for air";
  EXPECT_GT(tally.material_points, 100LL * tally.cases);
  EXPECT_GT(tally.descending_material_points, 0);
}

}  // namespace
}  // namespace feedplan::planner
