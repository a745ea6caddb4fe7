#include "feedplan/cycles/spec_reader.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <system_error>
#include <vector>

#include "common_checks.hpp"
#include "feedplan/core/bounded_read.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/core/joined_text.hpp"
#include "feedplan/core/yaml_fields.hpp"
#include "feedplan/core/yaml_text.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "problems.hpp"

namespace feedplan::cycles {

using geometry::Point2;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The most YAML nodes a spec may expand to (each alias counted where it is used): a spec has a few
// dozen, a stock polygon of 10 000 vertices 30 000. Beyond it every walk over the document (its
// checks, the values shown in problems) costs time and memory without bound: 800 bytes of nested
// aliases expand to 10⁹ nodes.
constexpr std::size_t kMaxSpecYamlNodes = 100000;

// The largest spec or stock file read: /dev/zero or an endless pipe would otherwise be read until
// memory runs out.
constexpr std::size_t kMaxSpecFileBytes = std::size_t{4} << 20;

const std::vector<std::string> kCycleNames = {"corner", "trochoid", "spiral", "helical_boring", "pocket"};

// Reads one document into a CycleSpec, collecting structural problems (types, unknown and missing
// fields) and the YAML line of every field it visits. The field rules are core's YamlFieldReader.
class SpecReader : public YamlFieldReader<YAML::Node> {
 public:
  SpecReader() : YamlFieldReader(YamlSectionWording::kSection) {}

  // Checks that `node` (the value of `path`) is a mapping with known keys only; records key lines.
  bool mapping(const YAML::Node& node, const std::string& path, const std::vector<std::string>& allowed) {
    return check_mapping(node, path, allowed, "must be a mapping of fields (" + joined_text(allowed, ", ") + ")");
  }

  // A number; absent: `fallback` (or, when required, a problem and NaN).
  double number(const YAML::Node& map, const std::string& path, const std::string& key, bool required,
                double fallback, const std::string& meaning) {
    if (!required && !map[key]) return fallback;
    return YamlFieldReader::number(map, path, key, required, meaning).value_or(kNaN);
  }

  std::optional<double> optional_number(const YAML::Node& map, const std::string& path, const std::string& key,
                                        const std::string& meaning) {
    if (!map[key]) return std::nullopt;
    return number(map, path, key, false, kNaN, meaning);
  }

  // A number that may be left out (0), but when given must lie in `range` (0 is "not given" in the struct).
  double in_range_if_given(const YAML::Node& map, const std::string& path, const std::string& key,
                           const detail::Range& range, const std::string& meaning) {
    if (!map[key]) return 0.0;
    const double value = number(map, path, key, false, 0.0, meaning);
    detail_check(child(path, key), value, range, meaning);
    return value;
  }

  // A number that may be left out, but when given must be > 0 (0 means "not given" in the struct).
  double positive_if_given(const YAML::Node& map, const std::string& path, const std::string& key,
                           const std::string& meaning) {
    if (!map[key]) return 0.0;
    const double value = number(map, path, key, false, 0.0, meaning);
    const std::string field = child(path, key);
    if (reported.count(field) == 0 && !detail::check(problems, with_yaml_line(field, lines[field]), value,
                                                     detail::above(0), meaning + "; leave it out when unknown")) {
      reported.insert(field);
    }
    return value;
  }

  int integer(const YAML::Node& map, const std::string& path, const std::string& key, bool required, int fallback,
              const std::string& meaning) {
    return YamlFieldReader::integer(map, path, key, required, meaning).value_or(fallback);
  }

  Point2 point(const YAML::Node& map, const std::string& path, const std::string& key, bool required,
               const std::string& meaning) {
    const YAML::Node node = map[key];
    if (!node) {
      if (required) missing(map, path, key, meaning);
      return required ? Point2{kNaN, kNaN} : Point2{};
    }
    Point2 p{kNaN, kNaN};
    if (!node.IsSequence() || node.size() != 2 || !coordinate(node[0], p.x_mm) || !coordinate(node[1], p.y_mm)) {
      type_problem(child(path, key), node, "must be [x, y], two numbers in mm — " + meaning);
      return {kNaN, kNaN};
    }
    return p;
  }

  Direction direction(const YAML::Node& map, const std::string& path) {
    const YAML::Node node = map["direction"];
    if (!node) return Direction::kCcw;
    if (node.IsScalar() && node.Scalar() == "ccw") return Direction::kCcw;
    if (node.IsScalar() && node.Scalar() == "cw") return Direction::kCw;
    type_problem(child(path, "direction"), node,
                 "must be ccw or cw — ccw is climb milling with an M3 spindle, cw its mirror image");
    return Direction::kCcw;
  }

  geometry::Contour contour(const YAML::Node& node, const std::string& path) {
    geometry::Contour result = geometry::Contour::circle({kNaN, kNaN}, kNaN);
    if (!mapping(node, path, {"polygon", "circle"})) return result;
    const bool has_polygon = static_cast<bool>(node["polygon"]);
    const bool has_circle = static_cast<bool>(node["circle"]);
    if (has_polygon == has_circle) {
      add(path, yaml_line(node), has_polygon ? "has both polygon and circle: give exactly one"
                                           : "is empty: give polygon: [[x, y], ...] or circle: {center: [x, y], "
                                             "radius_mm: R}");
      return result;
    }
    if (has_circle) {
      const YAML::Node circle = node["circle"];
      const std::string circle_path = child(path, "circle");
      if (!mapping(circle, circle_path, {"center", "radius_mm"})) return result;
      result.center = point(circle, circle_path, "center", true, "circle centre");
      result.radius_mm = number(circle, circle_path, "radius_mm", true, kNaN, "circle radius in mm");
      detail_check(circle_path + ".radius_mm", result.radius_mm, detail::above(0), "a circle's radius");
      return result;
    }
    const YAML::Node polygon = node["polygon"];
    const std::string polygon_path = child(path, "polygon");
    if (!polygon.IsSequence()) {
      type_problem(polygon_path, polygon, "must be a list of vertices [[x, y], ...] in mm");
      return result;
    }
    result = geometry::Contour::polygon({});
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      const std::string vertex_path = polygon_path + "[" + std::to_string(i) + "]";
      lines[vertex_path] = yaml_line(polygon[i]);
      Point2 p{kNaN, kNaN};
      if (!polygon[i].IsSequence() || polygon[i].size() != 2 || !coordinate(polygon[i][0], p.x_mm) ||
          !coordinate(polygon[i][1], p.y_mm)) {
        type_problem(vertex_path, polygon[i], "must be [x, y], two numbers in mm");
      } else if (!std::isfinite(p.x_mm) || !std::isfinite(p.y_mm)) {
        add(vertex_path, yaml_line(polygon[i]),
            "= " + yaml_value_text(polygon[i]) + ": coordinates must be finite numbers");
      }
      result.vertices.push_back(p);
    }
    if (polygon.size() < 3) {
      add(polygon_path, yaml_line(polygon),
          "has " + std::to_string(polygon.size()) + " vertices: a polygon needs at least 3");
    }
    return result;
  }

  geometry::Stock stock(const YAML::Node& node, const std::string& path) {
    geometry::Stock result;
    if (!mapping(node, path, {"z_bottom_mm", "z_top_mm", "regions"})) return result;
    result.z_bottom_mm = number(node, path, "z_bottom_mm", true, kNaN, "bottom of the material in mm");
    result.z_top_mm = number(node, path, "z_top_mm", true, kNaN, "top face of the material in mm");
    detail_check(path + ".z_bottom_mm", result.z_bottom_mm, {}, "");
    detail_check(path + ".z_top_mm", result.z_top_mm, {}, "");
    const YAML::Node regions = node["regions"];
    const std::string regions_path = child(path, "regions");
    if (!regions) {
      missing(node, path, "regions", "list of {outer: contour, holes: [contour, ...]}");
      return result;
    }
    if (!regions.IsSequence() || regions.size() == 0) {
      type_problem(regions_path, regions, "must be a non-empty list of {outer: contour, holes: [contour, ...]}");
      return result;
    }
    for (std::size_t i = 0; i < regions.size(); ++i) {
      const std::string region_path = regions_path + "[" + std::to_string(i) + "]";
      lines[region_path] = yaml_line(regions[i]);
      geometry::StockRegion region;
      if (!mapping(regions[i], region_path, {"outer", "holes"})) continue;
      if (!regions[i]["outer"]) {
        missing(regions[i], region_path, "outer", "the region's outer contour");
      } else {
        region.outer = contour(regions[i]["outer"], child(region_path, "outer"));
      }
      if (const YAML::Node holes = regions[i]["holes"]) {
        const std::string holes_path = child(region_path, "holes");
        if (!holes.IsSequence()) {
          type_problem(holes_path, holes, "must be a list of contours");
        } else {
          for (std::size_t h = 0; h < holes.size(); ++h) {
            const std::string hole_path = holes_path + "[" + std::to_string(h) + "]";
            lines[hole_path] = yaml_line(holes[h]);
            region.holes.push_back(contour(holes[h], hole_path));
          }
        }
      }
      result.regions.push_back(region);
    }
    return result;
  }

 private:
  bool coordinate(const YAML::Node& node, double& value) { return decode_yaml_number(node, value); }

  // A value-range problem found while reading (stock contours), attributed like a structural one.
  void detail_check(const std::string& field, double value, const detail::Range& range, const std::string& why) {
    if (reported.count(field) != 0) return;
    std::vector<InputProblem> found;
    if (!detail::check(found, field, value, range, why)) add(field, lines.count(field) ? lines[field] : 0, found.front().message);
  }

};

CycleGeometry read_corner(SpecReader& in, const YAML::Node& node) {
  CornerSpec g;
  const std::string p = "corner";
  if (!in.mapping(node, p, {"corner_point", "entry_heading_deg", "corner_angle_deg", "corner_radius_mm",
                            "radial_depth_mm", "wall_length_mm", "lead_mm", "direction"})) {
    return g;
  }
  g.corner_point = in.point(node, p, "corner_point", false, "intersection of the two finished wall lines");
  g.entry_heading_deg = in.number(node, p, "entry_heading_deg", false, 0.0, "direction of travel along wall 1 in deg");
  g.corner_angle_deg = in.number(node, p, "corner_angle_deg", false, 90.0, "interior angle between the walls in deg");
  g.corner_radius_mm = in.number(node, p, "corner_radius_mm", true, 0, "radius of the finished wall at the corner in mm");
  g.radial_depth_mm = in.number(node, p, "radial_depth_mm", true, 0, "radial depth of cut R_d in mm");
  g.wall_length_mm = in.number(node, p, "wall_length_mm", false, 30.0, "length of each straight wall in mm");
  g.lead_mm = in.optional_number(node, p, "lead_mm", "air approach and departure beyond the stock in mm");
  g.direction = in.direction(node, p);
  return g;
}

CycleGeometry read_trochoid(SpecReader& in, const YAML::Node& node) {
  TrochoidSpec g;
  const std::string p = "trochoid";
  if (!in.mapping(node, p, {"start", "end", "loop_radius_mm", "pitch_mm", "direction"})) return g;
  g.start = in.point(node, p, "start", true, "centre of the first loop");
  g.end = in.point(node, p, "end", true, "centre of the last loop");
  g.loop_radius_mm = in.number(node, p, "loop_radius_mm", true, 0, "radius of the tool-centre circles in mm");
  g.pitch_mm = in.number(node, p, "pitch_mm", true, 0, "advance of the loop centre per loop in mm");
  g.direction = in.direction(node, p);
  return g;
}

CycleGeometry read_spiral(SpecReader& in, const YAML::Node& node) {
  SpiralSpec g;
  const std::string p = "spiral";
  if (!in.mapping(node, p, {"center", "initial_radius_mm", "final_radius_mm", "pitch_mm", "direction"})) return g;
  g.center = in.point(node, p, "center", false, "bore axis");
  g.initial_radius_mm = in.number(node, p, "initial_radius_mm", true, 0, "radius of the pre-drilled bore in mm");
  g.final_radius_mm = in.number(node, p, "final_radius_mm", true, 0, "radius of the finished bore in mm");
  g.pitch_mm = in.number(node, p, "pitch_mm", true, 0, "increase of the radius per turn in mm");
  g.direction = in.direction(node, p);
  return g;
}

CycleGeometry read_helical_boring(SpecReader& in, const YAML::Node& node) {
  HelicalBoringSpec g;
  const std::string p = "helical_boring";
  if (!in.mapping(node, p, {"center", "hole_diameter_mm", "pitch_mm", "depth_mm", "direction"})) return g;
  g.center = in.point(node, p, "center", false, "hole axis");
  g.hole_diameter_mm = in.number(node, p, "hole_diameter_mm", true, 0, "finished hole diameter in mm");
  g.pitch_mm = in.number(node, p, "pitch_mm", true, 0, "depth per helix turn in mm");
  g.depth_mm = in.number(node, p, "depth_mm", true, 0, "hole depth below the stock top in mm");
  g.direction = in.direction(node, p);
  return g;
}

CycleGeometry read_pocket(SpecReader& in, const YAML::Node& node) {
  PocketSpec g;
  const std::string p = "pocket";
  if (!in.mapping(node, p, {"center", "width_mm", "height_mm", "depth_mm", "corner_radius_mm", "finish_allowance_mm",
                            "helix_pitch_mm", "spiral_pitch_mm", "trochoid_pitch_mm", "direction"})) {
    return g;
  }
  g.center = in.point(node, p, "center", false, "pocket centre");
  g.width_mm = in.number(node, p, "width_mm", true, 0, "pocket size along X in mm");
  g.height_mm = in.number(node, p, "height_mm", true, 0, "pocket size along Y in mm");
  g.depth_mm = in.number(node, p, "depth_mm", true, 0, "pocket depth below the stock top in mm");
  g.corner_radius_mm = in.number(node, p, "corner_radius_mm", true, 0, "finished corner radius in mm");
  g.finish_allowance_mm = in.optional_number(node, p, "finish_allowance_mm", "wall stock for the finishing pass in mm");
  g.helix_pitch_mm = in.optional_number(node, p, "helix_pitch_mm", "pitch of the centre bore's helix in mm");
  g.spiral_pitch_mm = in.optional_number(node, p, "spiral_pitch_mm", "radius increase per spiral turn in mm");
  g.trochoid_pitch_mm = in.optional_number(node, p, "trochoid_pitch_mm", "loop advance of the slots in mm");
  g.direction = in.direction(node, p);
  return g;
}

// A cycle spec document must be a mapping; anything else says what was expected.
void require_spec_mapping(const YAML::Node& root, const std::string& source_name) {
  if (!root || root.IsNull()) {
    throw InputError(source_name, "is empty: expected a cycle spec, a YAML mapping with cycle, tool, axial_depth_mm "
                                  "and the cycle's section (see samples/*.yaml)");
  }
  if (!root.IsMap()) {
    throw InputError(source_name, "is not a YAML mapping (it is " + std::string(root.IsSequence() ? "a list" : "a single value") +
                                      "): expected fields such as cycle: trochoid, tool: {diameter_mm: 10, flutes: 4}");
  }
}

std::vector<std::string> top_level_fields() {
  std::vector<std::string> top_fields = {"cycle", "tool", "material", "spindle_rpm", "axial_depth_mm",
                                         "target_force_n", "feed_mm_per_min", "machine", "clearance_z_mm", "stock"};
  top_fields.insert(top_fields.end(), kCycleNames.begin(), kCycleNames.end());
  return top_fields;
}

// spec.cycle; true when it names a known cycle (an unknown name is a problem).
bool read_cycle_name(SpecReader& in, const YAML::Node& root, CycleSpec& spec) {
  spec.cycle = in.text(root, "", "cycle", true, "one of " + joined_text(kCycleNames, ", "));
  const bool cycle_known = std::find(kCycleNames.begin(), kCycleNames.end(), spec.cycle) != kCycleNames.end();
  if (!cycle_known && in.reported.count("cycle") == 0) {
    in.add("cycle", yaml_line(root["cycle"]),
           "= " + yaml_value_text(root["cycle"]) + ": unknown cycle; expected one of " + joined_text(kCycleNames, ", "));
  }
  return cycle_known;
}

// A tool section (`tool` of a spec, or an entry of a tool library) at `path`; a malformed one leaves the
// diameter NaN.
void read_tool_section(SpecReader& in, const YAML::Node& tool, const std::string& path, geometry::Tool& tool_spec) {
  if (in.mapping(tool, path, {"diameter_mm", "flutes", "helix_deg", "max_plunge_feed_per_tooth_mm", "name"})) {
    tool_spec.diameter_mm = in.number(tool, path, "diameter_mm", true, kNaN, "cutting diameter of the end mill in mm");
    tool_spec.flutes = in.integer(tool, path, "flutes", true, 4, "number of teeth");
    tool_spec.helix_deg = in.number(tool, path, "helix_deg", false, 30.0, "helix angle in deg");
    // Absent: 0, the default of geometry::Tool. Given, it is checked here, where a given 0 is still
    // told apart from an absent field.
    tool_spec.max_plunge_feed_per_tooth_mm =
        in.in_range_if_given(tool, path, "max_plunge_feed_per_tooth_mm",
                             detail::plunge_feed_per_tooth_range(tool_spec), detail::kPlungeFeedPerToothMeaning);
    tool_spec.name = in.text(tool, path, "name", false, "free text shown in reports");
  } else {
    tool_spec.diameter_mm = kNaN;
  }
}

// The tool section; a missing or malformed one leaves the diameter NaN.
void read_tool(SpecReader& in, const YAML::Node& root, geometry::Tool& tool_spec) {
  if (const YAML::Node tool = root["tool"]) {
    read_tool_section(in, tool, "tool", tool_spec);
  } else {
    in.text(root, "", "tool", true, "the end mill: {diameter_mm, flutes, helix_deg, max_plunge_feed_per_tooth_mm, name}");
    tool_spec.diameter_mm = kNaN;
  }
}

// Material, spindle speed, target force, clearance and axial depth (required for layered cycles).
void read_cutting_conditions(SpecReader& in, const YAML::Node& root, CycleSpec& spec) {
  spec.material = in.text(root, "", "material", false, "workpiece material name");
  spec.spindle_rpm = in.positive_if_given(root, "", "spindle_rpm", "spindle speed in rev/min");
  spec.target_force_n = in.positive_if_given(root, "", "target_force_n", "cutting force to hold in N");
  spec.feed_mm_per_min = in.optional_number(root, "", "feed_mm_per_min", "the constant feed you would program, mm/min");
  spec.clearance_z_mm = in.number(root, "", "clearance_z_mm", false, 5.0, "rapid height above the stock top in mm");
  const bool layered = spec.cycle == "corner" || spec.cycle == "trochoid" || spec.cycle == "spiral";
  spec.axial_depth_mm = in.number(root, "", "axial_depth_mm", layered, 0.0, "axial depth of cut A_d in mm");
}

// The optional machine section over the defaults in spec.machine.
void read_machine(SpecReader& in, const YAML::Node& root, CycleSpec& spec) {
  const YAML::Node machine = root["machine"];
  if (!machine) return;
  const std::string p = "machine";
  if (!in.mapping(machine, p, {"max_feed_mm_per_min", "min_feed_mm_per_min", "max_accel_mm_per_s2",
                              "rapid_feed_mm_per_min", "block_time_min_s"})) {
    return;
  }
  geometry::MachineLimits& m = spec.machine;
  m.max_feed_mm_per_min = in.number(machine, p, "max_feed_mm_per_min", false, m.max_feed_mm_per_min, "mm/min");
  m.min_feed_mm_per_min = in.number(machine, p, "min_feed_mm_per_min", false, m.min_feed_mm_per_min, "mm/min");
  m.max_accel_mm_per_s2 = in.number(machine, p, "max_accel_mm_per_s2", false, m.max_accel_mm_per_s2, "mm/s²");
  m.rapid_feed_mm_per_min = in.number(machine, p, "rapid_feed_mm_per_min", false, m.rapid_feed_mm_per_min, "mm/min");
  m.block_time_min_s = in.number(machine, p, "block_time_min_s", false, m.block_time_min_s, "s");
}

// A section for a cycle other than `cycle` is a problem: it would be silently ignored.
void report_sections_of_other_cycles(SpecReader& in, const YAML::Node& root, const std::string& cycle) {
  for (const auto& name : kCycleNames) {
    if (name == cycle || !root[name]) continue;
    in.add(name, yaml_line(root[name]),
           "is a section for cycle " + name + ", but cycle is " + (cycle.empty() ? "not given" : cycle) +
               ": remove it or change cycle");
  }
}

// The known cycle's section into spec.geometry; true when it was a mapping (otherwise the reader
// reported it and the values are placeholders).
bool read_geometry(SpecReader& in, const YAML::Node& root, CycleSpec& spec) {
  const YAML::Node section = root[spec.cycle];
  if (!section) {
    in.text(root, "", spec.cycle, true, "the " + spec.cycle + " cycle's parameters");
    return false;
  }
  if (spec.cycle == "corner") {
    spec.geometry = read_corner(in, section);
  } else if (spec.cycle == "trochoid") {
    spec.geometry = read_trochoid(in, section);
  } else if (spec.cycle == "spiral") {
    spec.geometry = read_spiral(in, section);
  } else if (spec.cycle == "helical_boring") {
    spec.geometry = read_helical_boring(in, section);
  } else {
    spec.geometry = read_pocket(in, section);
  }
  return section.IsMap();
}

// The value problems of `spec`: all of them when its cycle section was read as a mapping; without
// geometry to check, still those of the tool and the rest.
std::vector<InputProblem> validate_read_spec(const CycleSpec& spec, bool have_geometry) {
  if (have_geometry) return validate(spec);
  std::vector<InputProblem> semantic = validate_tool(spec.tool);
  for (auto& problem : detail::validate_common(spec)) semantic.push_back(std::move(problem));
  return semantic;
}

// The line of `field` or, failing that, of its nearest recorded ancestor ("a.b[2].c" → "a.b[2]" → "a.b").
int line_for(const std::map<std::string, int>& lines, std::string field) {
  while (!field.empty()) {
    if (const auto it = lines.find(field); it != lines.end()) return it->second;
    const std::size_t cut = field.find_last_of(".[");
    if (cut == std::string::npos) break;
    field.resize(cut);
  }
  return 0;
}

// The stock element a field belongs to: its contour ("stock.regions[0].outer",
// "stock.regions[0].holes[1]") or, above contours, the field itself.
std::string stock_part_of(const std::string& field) {
  if (const std::size_t outer = field.find(".outer"); outer != std::string::npos) return field.substr(0, outer + 6);
  if (const std::size_t holes = field.find(".holes["); holes != std::string::npos) {
    const std::size_t close = field.find(']', holes);
    if (close != std::string::npos) return field.substr(0, close + 1);
  }
  return field;
}

// True when `field` is `part` or lies inside it ("part.x", "part[2]").
bool is_within(const std::string& field, const std::string& part) {
  if (field.rfind(part, 0) != 0) return false;
  return field.size() == part.size() || field[part.size()] == '.' || field[part.size()] == '[';
}

// Contours (or z fields, or the region list) of the stock that had structural problems hold
// placeholders: geometry::validate's findings about them would only repeat those problems.
std::vector<std::string> bad_stock_parts(const std::set<std::string>& reported) {
  std::vector<std::string> parts;
  for (const auto& field : reported) {
    if (field.rfind("stock", 0) == 0) parts.push_back(stock_part_of(field));
  }
  return parts;
}

// Drops the problems about fields within any of `parts`.
void drop_problems_within(std::vector<InputProblem>& problems, const std::vector<std::string>& parts) {
  std::erase_if(problems, [&](const InputProblem& p) {
    return std::any_of(parts.begin(), parts.end(), [&](const std::string& part) { return is_within(p.field, part); });
  });
}

// The reader's structural problems, then the value problems of fields it did not report, each
// field with its line.
std::vector<InputProblem> structural_then_semantic(SpecReader& in, std::vector<InputProblem> semantic) {
  std::vector<InputProblem> problems = std::move(in.problems);
  for (auto& problem : semantic) {
    if (in.reported.count(problem.field) != 0) continue;
    problem.field = with_yaml_line(problem.field, line_for(in.lines, problem.field));
    problems.push_back(std::move(problem));
  }
  return problems;
}

// Parses YAML text; malformed YAML is an InputError naming the source, line and column, and so is a
// document that expands beyond kMaxSpecYamlNodes through its aliases.
YAML::Node load_yaml(const std::string& yaml_text, const std::string& source_name) {
  return load_bounded_yaml<YAML::Exception>([](const std::string& text) { return YAML::Load(text); }, yaml_text,
                                            source_name, kMaxSpecYamlNodes,
                                            "a cycle spec has a few dozen (a stock polygon one per vertex)");
}

std::string read_text_file(const std::filesystem::path& path, const std::string& what) {
  return read_input_file(path, {what, kMaxSpecFileBytes, "a spec is a few hundred bytes, a stock of 10 000 vertices some 300 KiB"});
}

}  // namespace

CycleSpec read_cycle_spec(const std::string& yaml_text, const std::string& source_name) {
  const YAML::Node loaded = load_yaml(yaml_text, source_name);
  // Const access only: a non-const operator[] may add the key it looks up.
  const YAML::Node& root = loaded;
  require_spec_mapping(root, source_name);

  SpecReader in;
  in.mapping(root, "", top_level_fields());
  CycleSpec spec;
  const bool cycle_known = read_cycle_name(in, root, spec);
  read_tool(in, root, spec.tool);
  read_cutting_conditions(in, root, spec);
  read_machine(in, root, spec);
  if (const YAML::Node stock = root["stock"]) spec.stock = in.stock(stock, "stock");
  report_sections_of_other_cycles(in, root, spec.cycle);
  const bool have_geometry = cycle_known && read_geometry(in, root, spec);

  std::vector<InputProblem> semantic = validate_read_spec(spec, have_geometry);
  drop_problems_within(semantic, bad_stock_parts(in.reported));
  std::vector<InputProblem> problems = structural_then_semantic(in, std::move(semantic));
  if (!problems.empty()) throw InputError(std::move(problems));
  return spec;
}

CycleSpec load_cycle_spec(const std::filesystem::path& path) {
  return read_cycle_spec(read_text_file(path, "a cycle spec"), path.string());
}

geometry::Stock read_stock_spec(const std::string& yaml_text, const std::string& source_name) {
  const YAML::Node loaded = load_yaml(yaml_text, source_name);
  const YAML::Node& root = loaded;
  if (!root || root.IsNull()) {
    throw InputError(source_name, "is empty: expected a stock (stock: {z_bottom_mm, z_top_mm, regions}) or a cycle spec");
  }
  if (root.IsMap() && root["cycle"]) return generate(read_cycle_spec(yaml_text, source_name)).stock;
  if (!root.IsMap()) {
    throw InputError(source_name, "is not a YAML mapping: expected stock: {z_bottom_mm, z_top_mm, regions: [...]}");
  }
  SpecReader in;
  in.mapping(root, "", {"stock"});
  geometry::Stock stock;
  if (const YAML::Node node = root["stock"]) {
    stock = in.stock(node, "stock");
  } else {
    in.text(root, "", "stock", true, "the workpiece: {z_bottom_mm, z_top_mm, regions: [{outer: contour, holes: [...]}]}");
  }
  const std::vector<std::string> bad_parts = bad_stock_parts(in.reported);
  std::vector<InputProblem> problems = std::move(in.problems);
  if (root["stock"]) {
    for (auto& problem : geometry::validate(stock, "stock")) {
      const bool repeats = std::any_of(bad_parts.begin(), bad_parts.end(),
                                       [&](const std::string& part) { return is_within(problem.field, part); });
      if (repeats || in.reported.count(problem.field) != 0) continue;
      problem.field = with_yaml_line(problem.field, line_for(in.lines, problem.field));
      problems.push_back(std::move(problem));
    }
  }
  if (!problems.empty()) throw InputError(std::move(problems));
  return stock;
}

geometry::Stock load_stock_spec(const std::filesystem::path& path) {
  return read_stock_spec(read_text_file(path, "a stock spec"), path.string());
}

std::map<int, geometry::Tool> read_tool_library(const std::string& yaml_text, const std::string& source_name) {
  const YAML::Node loaded = load_yaml(yaml_text, source_name);
  const YAML::Node& root = loaded;
  if (!root || !root.IsMap()) {
    throw InputError(source_name, "is not a YAML mapping: expected tools: {<T number>: {diameter_mm, flutes, "
                                  "helix_deg, name}, ...}");
  }
  SpecReader in;
  in.mapping(root, "", {"tools"});
  std::map<int, geometry::Tool> tools;
  const YAML::Node list = root["tools"];
  if (!list) {
    in.text(root, "", "tools", true, "the end mills by T number: {2: {diameter_mm: 6.35, flutes: 2}, ...}");
  } else if (!list.IsMap() || list.size() == 0) {
    in.add("tools", yaml_line(list), "= " + yaml_value_text(list) +
                                         ": must be a mapping of T numbers to tools, e.g. {2: {diameter_mm: 6.35, flutes: 2}}");
  } else {
    for (const auto& entry : list) {
      const std::string key = yaml_key_text(entry.first);
      const std::string path = "tools." + key;
      char* end = nullptr;
      const long number = std::strtol(key.c_str(), &end, 10);
      if (key.empty() || *end != '\0' || number < 0 || number > 1000000) {
        in.add(path, yaml_line(entry.first), "is not a T number: the keys of tools are whole numbers ≥ 0");
        continue;
      }
      geometry::Tool tool;
      read_tool_section(in, entry.second, path, tool);
      if (std::isfinite(tool.diameter_mm)) {
        for (InputProblem problem : validate_tool(tool, path)) {
          problem.field = with_yaml_line(problem.field, yaml_line(entry.second));
          in.problems.push_back(std::move(problem));
        }
      }
      if (tool.name.empty()) tool.name = "T" + key;
      tools[static_cast<int>(number)] = tool;
    }
  }
  if (!in.problems.empty()) throw InputError(std::move(in.problems));
  return tools;
}

std::map<int, geometry::Tool> load_tool_library(const std::filesystem::path& path) {
  return read_tool_library(read_text_file(path, "a tool library"), path.string());
}

}  // namespace feedplan::cycles
