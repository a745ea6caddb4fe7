#include "feedplan/sim/material.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <system_error>

#include "feedplan/core/bounded_read.hpp"
#include "feedplan/core/did_you_mean.hpp"
#include "feedplan/core/joined_text.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/core/yaml_fields.hpp"
#include "feedplan/core/yaml_text.hpp"

namespace feedplan::sim {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// One coefficient field of the YAML `coefficients:` mapping and where it goes in CuttingCoefficients.
struct CoefficientField {
  const char* key;
  double CuttingCoefficients::*member;
  const char* unit;
  const char* meaning;
  bool must_be_positive;  // ktc: a material without a tangential cutting force cuts nothing
};

const std::array<CoefficientField, 6> kCoefficientFields = {{
    {"ktc_n_per_mm2", &CuttingCoefficients::ktc_n_per_mm2, "N/mm²", "tangential cutting coefficient Ktc", true},
    {"krc_n_per_mm2", &CuttingCoefficients::krc_n_per_mm2, "N/mm²", "radial cutting coefficient Krc", false},
    {"kac_n_per_mm2", &CuttingCoefficients::kac_n_per_mm2, "N/mm²", "axial cutting coefficient Kac", false},
    {"kte_n_per_mm", &CuttingCoefficients::kte_n_per_mm, "N/mm", "tangential edge coefficient Kte", false},
    {"kre_n_per_mm", &CuttingCoefficients::kre_n_per_mm, "N/mm", "radial edge coefficient Kre", false},
    {"kae_n_per_mm", &CuttingCoefficients::kae_n_per_mm, "N/mm", "axial edge coefficient Kae", false},
}};

const std::vector<std::string> kMaterialFields = {"name",        "aliases",     "description", "source",
                                                  "coefficients", "size_effect", "sources"};
const std::vector<std::string> kSizeEffectFields = {"exponent", "reference_chip_mm", "min_chip_mm"};

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  const auto last = text.find_last_not_of(" \t\r\n");
  return text.substr(first, last - first + 1);
}

std::string child(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

// Collects structural and value problems while walking the YAML tree. The field rules are core's
// YamlFieldReader.
class Reader : public YamlFieldReader<YAML::Node> {
 public:
  Reader() : YamlFieldReader(YamlSectionWording::kPath) {}

  // Checks that `node` (the value of `path`) is a mapping with known keys only.
  bool mapping(const YAML::Node& node, const std::string& path, const std::vector<std::string>& allowed,
               const std::string& what) {
    return check_mapping(node, path, allowed, "must be a mapping — " + what + " with fields " + joined_text(allowed, ", "));
  }

  // A number at map[key]; nullopt (and a problem) when missing or not a number. ".nan" and ".inf" are
  // numbers here: the range checks report them with the allowed range.
  std::optional<double> number(const YAML::Node& map, const std::string& path, const std::string& key,
                               const std::string& meaning) {
    return YamlFieldReader::number(map, path, key, true, meaning);
  }

  // Appends `<field> = <value>: must be ≥ 0 N/mm² — ...` unless the value is finite and in range.
  void check_range(const std::string& field, int line, double value, double low, bool low_closed,
                   const std::string& unit, const std::string& why) {
    if (std::isfinite(value) && (low_closed ? value >= low : value > low)) return;
    const std::string range = (low_closed ? "≥ " : "> ") + shortest_number_text(low) + (unit.empty() ? "" : " " + unit);
    add(field, line,
        "= " + shortest_number_text(value) + ": must be " + (std::isfinite(value) ? "" : "a finite number ") + range +
            " — " + why);
  }
};

// Where a name or alias was first used, to report duplicates.
struct NameUse {
  std::string field;
  std::string material;
};

// The material's canonical name, trimmed; "" (with a problem) when missing, not text or empty.
std::string read_name(Reader& in, const YAML::Node& node, const std::string& path) {
  const std::string name = trim(in.text(node, path, "name", true, "the material's canonical name, e.g. S50C"));
  if (node["name"] && node["name"].IsScalar() && name.empty()) {
    in.add(child(path, "name"), yaml_line(node["name"]), "= \"\": must not be empty — the material's canonical name");
  }
  return name;
}

// The optional list of aliases, each trimmed; items that are not names or empty are problems.
std::vector<std::string> read_aliases(Reader& in, const YAML::Node& node, const std::string& path,
                                      const std::string& who) {
  std::vector<std::string> result;
  const YAML::Node aliases = node["aliases"];
  if (!aliases) return result;
  const std::string field = child(path, "aliases");
  if (!aliases.IsSequence()) {
    in.type_problem(field, aliases, "must be a list of names, e.g. [\"1045\", C45]");
    return result;
  }
  for (std::size_t i = 0; i < aliases.size(); ++i) {
    const std::string item_field = field + "[" + std::to_string(i) + "]";
    if (!aliases[i].IsScalar()) {
      in.type_problem(item_field, aliases[i], "must be a name (text)");
      continue;
    }
    const std::string alias = trim(aliases[i].Scalar());
    if (alias.empty()) {
      in.add(item_field, yaml_line(aliases[i]), "= \"\": must not be empty — an alias of " + who);
      continue;
    }
    result.push_back(alias);
  }
  return result;
}

// Where the coefficients come from, trimmed; required and not empty.
std::string read_source(Reader& in, const YAML::Node& node, const std::string& path, const std::string& who) {
  const std::string source = trim(in.text(node, path, "source", true,
                                          "where the coefficients come from (a book, a vendor table, a cutting test, "
                                          "or \"estimate\")"));
  if (node["source"] && node["source"].IsScalar() && source.empty()) {
    in.add(child(path, "source"), yaml_line(node["source"]),
           "= \"\": must say where the coefficients of " + who + " come from (write \"estimate\" if nothing stands "
           "behind them)");
  }
  return source;
}

// The six cutting coefficients, each required and in range; a bad one is NaN.
void read_coefficients(Reader& in, const YAML::Node& node, const std::string& path, const std::string& who,
                       CuttingCoefficients& c) {
  const std::string coefficients_path = child(path, "coefficients");
  const YAML::Node coefficients = node["coefficients"];
  if (!coefficients) {
    in.missing(node, path, "coefficients",
               "the cutting coefficients {ktc_n_per_mm2, krc_n_per_mm2, kac_n_per_mm2, kte_n_per_mm, kre_n_per_mm, "
               "kae_n_per_mm}");
    return;
  }
  std::vector<std::string> keys;
  for (const auto& f : kCoefficientFields) keys.emplace_back(f.key);
  if (!in.mapping(coefficients, coefficients_path, keys, "the mechanistic cutting coefficients")) return;
  for (const auto& f : kCoefficientFields) {
    const std::string meaning = std::string(f.meaning) + " in " + f.unit;
    const std::optional<double> value = in.number(coefficients, coefficients_path, f.key, meaning);
    c.*(f.member) = value.value_or(kNaN);
    if (value) {
      in.check_range(child(coefficients_path, f.key), yaml_line(coefficients[f.key]), *value, 0.0,
                     !f.must_be_positive, f.unit, std::string(f.meaning) + " of " + who);
    }
  }
}

// The size-effect values as read: nullopt where absent or not a number.
struct SizeEffectFields {
  std::optional<double> exponent;
  std::optional<double> reference_chip_mm;
  std::optional<double> min_chip_mm;
};

// Problems with the size-effect values: exponent in [0, 1), reference chip > 0, min chip in
// (0, reference chip].
void check_size_effect(Reader& in, const YAML::Node& size, const std::string& size_path, const std::string& who,
                       const SizeEffectFields& read) {
  const std::optional<double>& exponent = read.exponent;
  const std::optional<double>& reference = read.reference_chip_mm;
  const std::optional<double>& min_chip = read.min_chip_mm;
  if (exponent && !(std::isfinite(*exponent) && *exponent >= 0.0 && *exponent < 1.0)) {
    in.add(child(size_path, "exponent"), yaml_line(size["exponent"]),
           "= " + shortest_number_text(*exponent) + ": must be in [0, 1) — size-effect exponent m_c of " + who +
               " (0 turns it off)");
  }
  if (reference) {
    in.check_range(child(size_path, "reference_chip_mm"), yaml_line(size["reference_chip_mm"]), *reference, 0.0,
                   false, "mm", "reference chip thickness of " + who);
  }
  if (min_chip) {
    const bool reference_ok = reference && std::isfinite(*reference) && *reference > 0.0;
    const bool ok = std::isfinite(*min_chip) && *min_chip > 0.0 && (!reference_ok || *min_chip <= *reference);
    if (!ok) {
      in.add(child(size_path, "min_chip_mm"), yaml_line(size["min_chip_mm"]),
             "= " + shortest_number_text(*min_chip) + ": must be in (0, " +
                 (reference_ok ? shortest_number_text(*reference) : std::string("reference_chip_mm")) +
                 "] mm — smallest chip thickness the size effect of " + who + " is evaluated at");
    }
  }
}

// The optional size effect k_c ∝ (h / reference_chip_mm)^(−exponent) into `c`.
void read_size_effect(Reader& in, const YAML::Node& node, const std::string& path, const std::string& who,
                      CuttingCoefficients& c) {
  const YAML::Node size = node["size_effect"];
  if (!size) return;
  const std::string size_path = child(path, "size_effect");
  if (!in.mapping(size, size_path, kSizeEffectFields, "the size effect k_c ∝ (h / reference_chip_mm)^(−exponent)")) {
    return;
  }
  SizeEffectFields read;
  read.exponent = in.number(size, size_path, "exponent", "size-effect exponent m_c (docs/method.md §6.2: ≈ 0.13 steel, 0 = off)");
  read.reference_chip_mm =
      in.number(size, size_path, "reference_chip_mm", "chip thickness in mm at which the K*c values hold");
  if (size["min_chip_mm"]) {
    read.min_chip_mm =
        in.number(size, size_path, "min_chip_mm", "smallest chip thickness in mm the size effect is evaluated at");
  }
  c.size_exponent = read.exponent.value_or(kNaN);
  c.size_reference_chip_mm = read.reference_chip_mm.value_or(kNaN);
  if (read.min_chip_mm) c.size_min_chip_mm = *read.min_chip_mm;
  check_size_effect(in, size, size_path, who, read);
}

// The optional sources of single coefficients (and of the size effect), each non-empty text.
void read_coefficient_sources(Reader& in, const YAML::Node& node, const std::string& path,
                              std::map<std::string, std::string>& coefficient_sources) {
  const YAML::Node sources = node["sources"];
  if (!sources) return;
  const std::string sources_path = child(path, "sources");
  std::vector<std::string> keys;
  for (const auto& f : kCoefficientFields) keys.emplace_back(f.key);
  keys.emplace_back("size_effect");
  if (!in.mapping(sources, sources_path, keys, "where single coefficients come from")) return;
  for (const auto& item : sources) {
    const std::string key = yaml_key_text(item.first);
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) continue;  // reported by mapping()
    if (!item.second.IsScalar() || trim(item.second.Scalar()).empty()) {
      in.type_problem(child(sources_path, key), item.second, "must be text saying where " + key + " comes from");
      continue;
    }
    coefficient_sources[key] = trim(item.second.Scalar());
  }
}

Material read_material(Reader& in, const YAML::Node& node, const std::string& path) {
  Material m;
  if (!in.mapping(node, path, kMaterialFields, "one material")) return m;
  m.name = read_name(in, node, path);
  const std::string who = m.name.empty() ? path : m.name;
  m.aliases = read_aliases(in, node, path, who);
  m.description = in.text(node, path, "description", false, "what the material is");
  m.source = read_source(in, node, path, who);
  read_coefficients(in, node, path, who, m.coefficients);
  read_size_effect(in, node, path, who, m.coefficients);
  read_coefficient_sources(in, node, path, m.coefficient_sources);
  return m;
}

std::string material_names(const Material& m) {
  if (m.aliases.empty()) return m.name;
  return m.name + " (" + joined_text(m.aliases, ", ") + ")";
}

}  // namespace

const Material* MaterialLibrary::find(const std::string& name) const {
  const std::string wanted = lower(trim(name));
  if (wanted.empty()) return nullptr;
  for (const auto& m : materials) {
    if (lower(m.name) == wanted) return &m;
    for (const auto& alias : m.aliases) {
      if (lower(alias) == wanted) return &m;
    }
  }
  return nullptr;
}

const Material& MaterialLibrary::get(const std::string& name, const std::string& field) const {
  if (const Material* m = find(name)) return *m;
  throw InputError({unknown_material_problem(*this, name, field)});
}

InputProblem unknown_material_problem(const MaterialLibrary& library, const std::string& name,
                                      const std::string& field) {
  std::vector<std::string> known;
  std::vector<std::string> all_names;
  for (const auto& m : library.materials) {
    known.push_back(material_names(m));
    all_names.push_back(m.name);
    all_names.insert(all_names.end(), m.aliases.begin(), m.aliases.end());
  }
  std::string message = "= \"" + name + "\": unknown material; known";
  if (!library.source_name.empty()) message += " in " + library.source_name;
  message += ": " + (known.empty() ? std::string("none") : joined_text(known, ", "));
  std::string best = closest_name(trim(name), all_names, LetterCase::kIgnored);
  if (best.empty() && !trim(name).empty()) {
    // "s50" → "S50C": a prefix is as good a hint as a typo.
    for (const auto& candidate : all_names) {
      if (lower(candidate).rfind(lower(trim(name)), 0) == 0) {
        best = candidate;
        break;
      }
    }
  }
  if (!best.empty()) {
    const Material* m = library.find(best);
    message += " (did you mean " + best + (m != nullptr && m->name != best ? " = " + m->name : "") + "?)";
  }
  return {field, message};
}

// Nodes a material library may expand to (1 000 materials of about 30 nodes, with room to spare).
constexpr std::size_t kMaxMaterialYamlNodes = 100000;
// Bytes a material library file may hold (1 000 materials are about 300 KiB).
constexpr std::size_t kMaxMaterialFileBytes = std::size_t{4} << 20;

MaterialLibrary read_materials(const std::string& yaml_text, const std::string& source_name) {
  const YAML::Node loaded = load_bounded_yaml<YAML::Exception>(
      [](const std::string& text) { return YAML::Load(text); }, yaml_text, source_name, kMaxMaterialYamlNodes,
      "a material library has about 30 per material");
  // Const access only: a non-const operator[] may add the key it looks up.
  const YAML::Node& root = loaded;
  const std::string expected = "expected a material library: materials: [{name, aliases, description, source, "
                               "coefficients: {ktc_n_per_mm2, ...}}, ...] (see data/materials.yaml)";
  if (!root || root.IsNull()) throw InputError(source_name, "is empty: " + expected);
  if (!root.IsMap()) {
    throw InputError(source_name, "is not a YAML mapping (it is " +
                                      std::string(root.IsSequence() ? "a list" : "a single value") + "): " + expected);
  }

  Reader in;
  MaterialLibrary library;
  library.source_name = source_name;
  in.mapping(root, "", {"materials"}, "a material library");
  const YAML::Node list = root["materials"];
  if (!list) {
    in.missing(root, "", "materials", "the list of materials");
  } else if (!list.IsSequence() || list.size() == 0) {
    in.type_problem("materials", list, "must be a non-empty list of materials, each {name, source, coefficients, ...}");
  } else {
    std::map<std::string, NameUse> used;  // lower-case name or alias → first use
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string path = "materials[" + std::to_string(i) + "]";
      Material m = read_material(in, list[i], path);
      if (!list[i].IsMap()) continue;
      // Names and aliases share one namespace: find() must never be ambiguous.
      auto claim = [&](const std::string& name, const std::string& field, const YAML::Node& node) {
        if (name.empty()) return;
        const auto [it, inserted] = used.emplace(lower(name), NameUse{with_yaml_line(field, yaml_line(node)), m.name});
        if (inserted) return;
        in.add(field, yaml_line(node),
               "= \"" + name + "\": already used by " + it->second.field +
                   (it->second.material.empty() || it->second.material == m.name ? "" : " (" + it->second.material + ")") +
                   " — names and aliases must be unique, ignoring case");
      };
      if (list[i]["name"]) claim(m.name, child(path, "name"), list[i]["name"]);
      const YAML::Node aliases = list[i]["aliases"];
      if (aliases && aliases.IsSequence()) {
        for (std::size_t a = 0; a < aliases.size(); ++a) {
          if (aliases[a].IsScalar()) {
            claim(trim(aliases[a].Scalar()), child(path, "aliases") + "[" + std::to_string(a) + "]", aliases[a]);
          }
        }
      }
      library.materials.push_back(std::move(m));
    }
  }
  if (!in.problems.empty()) throw InputError(std::move(in.problems));
  return library;
}

MaterialLibrary load_materials(const std::string& path) {
  const std::string text =
      read_input_file(path, {"a material library", kMaxMaterialFileBytes, "a library of 1 000 materials is about 300 KiB"});
  return read_materials(text, path);
}

}  // namespace feedplan::sim
