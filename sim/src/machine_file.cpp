#include "feedplan/sim/machine_file.hpp"

#include <yaml-cpp/yaml.h>

#include <array>
#include <cmath>
#include <optional>

#include "feedplan/core/bounded_read.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/core/yaml_fields.hpp"
#include "feedplan/core/yaml_text.hpp"

namespace feedplan::sim {

namespace {

// One coefficient override and where it goes in CuttingCoefficients.
struct CoefficientField {
  const char* key;
  double CuttingCoefficients::*member;
  const char* unit;
  bool must_be_positive;  // ktc: a material without a tangential cutting force cuts nothing
};

const std::array<CoefficientField, 6> kCoefficientFields = {{
    {"ktc_n_per_mm2", &CuttingCoefficients::ktc_n_per_mm2, "N/mm²", true},
    {"krc_n_per_mm2", &CuttingCoefficients::krc_n_per_mm2, "N/mm²", false},
    {"kac_n_per_mm2", &CuttingCoefficients::kac_n_per_mm2, "N/mm²", false},
    {"kte_n_per_mm", &CuttingCoefficients::kte_n_per_mm, "N/mm", false},
    {"kre_n_per_mm", &CuttingCoefficients::kre_n_per_mm, "N/mm", false},
    {"kae_n_per_mm", &CuttingCoefficients::kae_n_per_mm, "N/mm", false},
}};

const std::vector<std::string> kMachineFields = {"name",      "description",      "material",   "coefficients",
                                                 "size_effect", "runout_mm", "helix_offset_deg", "dynamometer"};
const std::vector<std::string> kSizeEffectFields = {"exponent", "reference_chip_mm", "min_chip_mm"};
const std::vector<std::string> kDynamometerFields = {"bandwidth_hz", "damping_ratio", "noise_n"};

constexpr double kMaxRunoutMm = 0.05;       // more is a broken holder, not runout
constexpr std::size_t kMaxTeeth = 16;
constexpr double kMaxHelixOffsetDeg = 15.0;  // beyond it the catalogue names another tool

class Reader : public YamlFieldReader<YAML::Node> {
 public:
  Reader() : YamlFieldReader(YamlSectionWording::kPath) {}

  // Adds "<field> = <value>: must be <range> — <why>" unless `ok`.
  void check(bool ok, const YAML::Node& map, const std::string& path, const std::string& key, double value,
             const std::string& range, const std::string& why) {
    if (ok) return;
    add(child(path, key), yaml_line(map[key]), "= " + shortest_number_text(value) + ": must be " + range + " — " + why);
  }
};

// The material named in the file, or nullptr (with a problem) when missing or unknown.
const Material* read_material(Reader& in, const YAML::Node& root, const MaterialLibrary& materials) {
  const std::string name = in.text(root, "", "material", true,
                                   "the material of the library the machine cuts, e.g. S50C");
  if (name.empty()) return nullptr;
  const Material* material = materials.find(name);
  if (material == nullptr) {
    InputProblem problem = unknown_material_problem(materials, name, with_yaml_line("material", yaml_line(root["material"])));
    in.problems.push_back(problem);
  }
  return material;
}

// The optional overrides of single coefficients.
void read_coefficients(Reader& in, const YAML::Node& root, CuttingCoefficients& c) {
  const YAML::Node node = root["coefficients"];
  if (!node) return;
  std::vector<std::string> keys;
  for (const auto& f : kCoefficientFields) keys.emplace_back(f.key);
  if (!in.check_mapping(node, "coefficients", keys, "must be a mapping of coefficient overrides, fields " + Reader::joined(keys))) {
    return;
  }
  for (const auto& f : kCoefficientFields) {
    const std::optional<double> value = in.number(node, "coefficients", f.key, false, std::string("a coefficient in ") + f.unit);
    if (!value) continue;
    const bool ok = std::isfinite(*value) && (f.must_be_positive ? *value > 0.0 : *value >= 0.0);
    in.check(ok, node, "coefficients", f.key, *value, std::string(f.must_be_positive ? "> 0 " : "≥ 0 ") + f.unit,
             "replaces the material's value");
    c.*(f.member) = *value;
  }
}

// The optional size effect k_c ∝ (h / reference_chip_mm)^(−exponent), replacing the material's.
void read_size_effect(Reader& in, const YAML::Node& root, CuttingCoefficients& c) {
  const YAML::Node node = root["size_effect"];
  if (!node) return;
  const std::string path = "size_effect";
  if (!in.check_mapping(node, path, kSizeEffectFields, "must be a mapping {exponent, reference_chip_mm, min_chip_mm}")) return;
  const auto exponent = in.number(node, path, "exponent", true, "size-effect exponent m_c, in [0, 1)");
  const auto reference = in.number(node, path, "reference_chip_mm", true, "chip thickness at which the K*c values hold, mm");
  const auto min_chip = in.number(node, path, "min_chip_mm", false, "smallest chip the size effect is evaluated at, mm");
  if (exponent) {
    in.check(std::isfinite(*exponent) && *exponent >= 0.0 && *exponent < 1.0, node, path, "exponent", *exponent,
             "in [0, 1)", "size-effect exponent m_c (0 turns it off)");
    c.size_exponent = *exponent;
  }
  const bool reference_ok = reference && std::isfinite(*reference) && *reference > 0.0;
  if (reference) {
    in.check(reference_ok, node, path, "reference_chip_mm", *reference, "> 0 mm", "chip thickness at which the K*c values hold");
    c.size_reference_chip_mm = *reference;
  }
  if (min_chip) {
    const double high = reference_ok ? *reference : 0.0;
    in.check(std::isfinite(*min_chip) && *min_chip > 0.0 && (!reference_ok || *min_chip <= high), node, path,
             "min_chip_mm", *min_chip,
             "in (0, " + (reference_ok ? shortest_number_text(high) : std::string("reference_chip_mm")) + "] mm",
             "smallest chip thickness the size effect is evaluated at");
    c.size_min_chip_mm = *min_chip;
  }
}

// The runout per tooth: a list of 1 to 16 numbers within ±kMaxRunoutMm.
std::vector<double> read_runout(Reader& in, const YAML::Node& root) {
  std::vector<double> runout;
  const YAML::Node node = root["runout_mm"];
  const std::string expected = "must be a list of 1 to 16 radial runouts per tooth in mm, one per flute, e.g. [0.005, 0, -0.003, 0]";
  if (!node) {
    in.missing(root, "", "runout_mm", "radial runout per tooth in mm, one per flute (e.g. [0.005, 0, -0.003, 0]; all 0: none)");
    return runout;
  }
  if (!node.IsSequence() || node.size() == 0 || node.size() > kMaxTeeth) {
    in.type_problem("runout_mm", node, expected);
    return runout;
  }
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string field = "runout_mm[" + std::to_string(i) + "]";
    double value = 0.0;
    if (!decode_yaml_number(node[i], value)) {
      in.type_problem(field, node[i], "must be a number — runout of tooth " + std::to_string(i + 1) + " in mm");
      continue;
    }
    if (!(std::isfinite(value) && std::abs(value) <= kMaxRunoutMm)) {
      in.add(field, yaml_line(node[i]),
             "= " + shortest_number_text(value) + ": must be in [-0.05, 0.05] mm — runout of tooth " +
                 std::to_string(i + 1) + " (runout is a few µm; 50 µm is a broken holder)");
    }
    runout.push_back(value);
  }
  return runout;
}

// The dynamometer's bandwidth, damping and noise.
void read_dynamometer(Reader& in, const YAML::Node& root, DynamometerOptions& d) {
  const YAML::Node node = root["dynamometer"];
  if (!node) {
    in.missing(root, "", "dynamometer", "the table dynamometer {bandwidth_hz, noise_n, damping_ratio (optional)}");
    return;
  }
  const std::string path = "dynamometer";
  if (!in.check_mapping(node, path, kDynamometerFields, "must be a mapping {bandwidth_hz, damping_ratio, noise_n}")) return;
  if (const auto v = in.number(node, path, "bandwidth_hz", true, "−3 dB frequency of the dynamometer, Hz")) {
    in.check(std::isfinite(*v) && *v > 0.0, node, path, "bandwidth_hz", *v, "> 0 Hz", "−3 dB frequency of the dynamometer");
    d.bandwidth_hz = *v;
  }
  if (const auto v = in.number(node, path, "damping_ratio", false, "damping ratio ζ of its low pass, in (0, 2]")) {
    in.check(std::isfinite(*v) && *v > 0.0 && *v <= 2.0, node, path, "damping_ratio", *v, "in (0, 2]",
             "damping ratio ζ of the dynamometer's low pass (0.707: flat; small: a resonance)");
    d.damping_ratio = *v;
  }
  if (const auto v = in.number(node, path, "noise_n", true, "RMS noise on each axis, N")) {
    in.check(std::isfinite(*v) && *v >= 0.0, node, path, "noise_n", *v, "≥ 0 N", "RMS noise on each axis");
    d.noise_n = *v;
  }
}

// The helix offset, in [−15, 15] deg.
double read_helix_offset(Reader& in, const YAML::Node& root) {
  const auto v = in.number(root, "", "helix_offset_deg", true, "true helix − catalogue helix of the tool, deg");
  if (!v) return 0.0;
  in.check(std::isfinite(*v) && std::abs(*v) <= kMaxHelixOffsetDeg, root, "", "helix_offset_deg", *v,
           "in [-15, 15] deg", "true helix − catalogue helix of the tool");
  return *v;
}

}  // namespace

// Nodes and bytes a machine file may hold: it has about 30 nodes and 2 KiB.
constexpr std::size_t kMaxMachineYamlNodes = 10000;
constexpr std::size_t kMaxMachineFileBytes = std::size_t{1} << 20;

MachineFile read_machine_file(const std::string& yaml_text, const std::string& source_name,
                              const MaterialLibrary& materials) {
  const YAML::Node loaded = load_bounded_yaml<YAML::Exception>(
      [](const std::string& text) { return YAML::Load(text); }, yaml_text, source_name, kMaxMachineYamlNodes,
      "a machine file has about 30");
  const YAML::Node& root = loaded;
  const std::string expected = "expected a machine file: {name, material, runout_mm, helix_offset_deg, dynamometer, ...} "
                               "(see data/machines/)";
  if (!root || root.IsNull()) throw InputError(source_name, "is empty: " + expected);
  if (!root.IsMap()) throw InputError(source_name, "is not a YAML mapping: " + expected);
  Reader in;
  MachineFile machine;
  machine.source_name = source_name;
  in.check_mapping(root, "", kMachineFields, "a machine file");
  machine.name = in.text(root, "", "name", true, "the machine's name");
  machine.description = in.text(root, "", "description", false, "what is special about the machine");
  if (const Material* material = read_material(in, root, materials)) {
    machine.material = material->name;
    machine.coefficients = material->coefficients;
  }
  read_coefficients(in, root, machine.coefficients);
  read_size_effect(in, root, machine.coefficients);
  machine.runout_mm = read_runout(in, root);
  machine.helix_offset_deg = read_helix_offset(in, root);
  read_dynamometer(in, root, machine.dynamometer);
  if (!in.problems.empty()) {
    for (InputProblem& p : in.problems) p.field = source_name + ": " + p.field;
    throw InputError(std::move(in.problems));
  }
  return machine;
}

MachineFile load_machine_file(const std::string& path, const MaterialLibrary& materials) {
  const std::string text = read_input_file(path, {"a machine file", kMaxMachineFileBytes, "a machine file is about 2 KiB"});
  return read_machine_file(text, path, materials);
}

std::vector<InputProblem> apply_machine(const MachineFile& machine, SimulationRequest& request) {
  std::vector<InputProblem> problems;
  const int flutes = request.tool.flutes;
  if (static_cast<int>(machine.runout_mm.size()) != flutes) {
    problems.push_back({machine.source_name + ": runout_mm",
                        "has " + std::to_string(machine.runout_mm.size()) + " values: must have one per flute, and the tool " +
                            request.tool.name + " has " + std::to_string(flutes)});
  }
  const double helix_deg = request.tool.helix_deg + machine.helix_offset_deg;
  if (!(helix_deg >= 0.0 && helix_deg < 70.0)) {
    problems.push_back({machine.source_name + ": helix_offset_deg",
                        "= " + shortest_number_text(machine.helix_offset_deg) + ": makes the true helix " +
                            shortest_number_text(helix_deg) + " deg (catalogue " +
                            shortest_number_text(request.tool.helix_deg) + " deg): must stay in [0, 70) deg"});
  }
  if (!problems.empty()) return problems;
  request.coefficients = machine.coefficients;
  request.options.runout_mm = machine.runout_mm;
  request.tool.helix_deg = helix_deg;
  request.sensors.dynamometer = machine.dynamometer;
  return problems;
}

}  // namespace feedplan::sim
