// Material library: the shipped data file against docs/method.md §6.2, and every kind of bad input with
// the message it must produce (field path with line, value, allowed range).

#include "feedplan/sim/material.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "feedplan/core/input_error.hpp"
#include "has_problem.hpp"

namespace feedplan::sim {
namespace {

using test_support::has_problem;

const std::string kLibraryPath = std::string(FEEDPLAN_SOURCE_DIR) + "/data/materials.yaml";

// A valid two-material library; tests replace one line at a time. Line numbers matter: line 3 is
// the first material's name, lines 8-13 its coefficients.
const std::string kValid =
    "materials:\n"                              // 1
    "  - name: Steel-A\n"                       // 2
    "    aliases: [\"1045\", C45]\n"            // 3
    "    description: test steel\n"             // 4
    "    source: test\n"                        // 5
    "    coefficients:\n"                       // 6
    "      ktc_n_per_mm2: 2000\n"               // 7
    "      krc_n_per_mm2: 600\n"                // 8
    "      kac_n_per_mm2: 500\n"                // 9
    "      kte_n_per_mm: 20\n"                  // 10
    "      kre_n_per_mm: 20\n"                  // 11
    "      kae_n_per_mm: 2\n"                   // 12
    "  - name: Alu-B\n"                         // 13
    "    source: test\n"                        // 14
    "    coefficients: {ktc_n_per_mm2: 796, krc_n_per_mm2: 169, kac_n_per_mm2: 222,\n"  // 15
    "                   kte_n_per_mm: 27.7, kre_n_per_mm: 30.8, kae_n_per_mm: 1.4}\n";  // 16

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not in the text";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// The problems read_materials reports for `yaml`; fails the test when it does not throw.
std::vector<InputProblem> problems_of(const std::string& yaml) {
  try {
    read_materials(yaml, "test.yaml");
  } catch (const InputError& e) {
    return e.problems();
  }
  ADD_FAILURE() << "read_materials accepted:\n" << yaml;
  return {};
}

TEST(MaterialLibrary, ShippedFileHasDesignValuesForAl7075) {
  const MaterialLibrary library = load_materials(kLibraryPath);
  const Material* al = library.find("Al7075-T6");
  ASSERT_NE(al, nullptr);
  // docs/method.md §6.2 (Altintas).
  EXPECT_EQ(al->coefficients.ktc_n_per_mm2, 796.0);
  EXPECT_EQ(al->coefficients.krc_n_per_mm2, 169.0);
  EXPECT_EQ(al->coefficients.kac_n_per_mm2, 222.0);
  EXPECT_EQ(al->coefficients.kte_n_per_mm, 27.7);
  EXPECT_EQ(al->coefficients.kre_n_per_mm, 30.8);
  EXPECT_EQ(al->coefficients.kae_n_per_mm, 1.4);
  EXPECT_EQ(al->coefficients.size_exponent, 0.0);
  EXPECT_NE(al->source.find("Altintas"), std::string::npos);
}

TEST(MaterialLibrary, ShippedFileSteelMatchesDesignSanityCase) {
  const MaterialLibrary library = load_materials(kLibraryPath);
  const Material* steel = library.find("S50C");
  ASSERT_NE(steel, nullptr);
  // docs/method.md §6.2 sanity case: Ktc 2000, Krc = 0.3 Ktc.
  EXPECT_EQ(steel->coefficients.ktc_n_per_mm2, 2000.0);
  EXPECT_DOUBLE_EQ(steel->coefficients.krc_n_per_mm2, 0.3 * 2000.0);
  EXPECT_EQ(library.find("1045"), steel);
  EXPECT_EQ(library.find("c45"), steel);
  EXPECT_EQ(library.find("  s50c "), steel);
}

TEST(MaterialLibrary, ShippedFileEveryMaterialSourcedAndInDesignRanges) {
  const MaterialLibrary library = load_materials(kLibraryPath);
  ASSERT_GE(library.materials.size(), 4u);
  for (const auto& m : library.materials) {
    SCOPED_TRACE(m.name);
    EXPECT_FALSE(m.source.empty());
    EXPECT_FALSE(m.description.empty());
    EXPECT_GT(m.coefficients.ktc_n_per_mm2, 0.0);
    for (double k : {m.coefficients.krc_n_per_mm2, m.coefficients.kac_n_per_mm2, m.coefficients.kte_n_per_mm,
                     m.coefficients.kre_n_per_mm, m.coefficients.kae_n_per_mm}) {
      EXPECT_TRUE(std::isfinite(k) && k >= 0.0);
    }
  }
  const Material* ti = library.find("ti-6al-4v");
  ASSERT_NE(ti, nullptr);
  EXPECT_EQ(ti->name, "Ti6Al4V");
  // docs/method.md §6.2: Ktc ≈ 1600–1900, Krc ≈ 350–600 N/mm².
  EXPECT_GE(ti->coefficients.ktc_n_per_mm2, 1600.0);
  EXPECT_LE(ti->coefficients.ktc_n_per_mm2, 1900.0);
  EXPECT_GE(ti->coefficients.krc_n_per_mm2, 350.0);
  EXPECT_LE(ti->coefficients.krc_n_per_mm2, 600.0);
  const Material* stainless = library.find("AISI 304");
  ASSERT_NE(stainless, nullptr);
  EXPECT_NE(stainless->source.find("estimate"), std::string::npos) << "unmeasured numbers must say so";
}

TEST(MaterialLibrary, ReadsFieldsAliasesAndPerNumberSources) {
  const std::string yaml = kValid +
                           "    size_effect: {exponent: 0.13, reference_chip_mm: 0.1, min_chip_mm: 0.01}\n"
                           "    sources: {krc_n_per_mm2: from a test, size_effect: DESIGN 6.2}\n";
  const MaterialLibrary library = read_materials(yaml, "test.yaml");
  ASSERT_EQ(library.materials.size(), 2u);
  const Material& steel = library.materials[0];
  EXPECT_EQ(steel.name, "Steel-A");
  EXPECT_EQ(steel.aliases, (std::vector<std::string>{"1045", "C45"}));
  EXPECT_EQ(steel.description, "test steel");
  EXPECT_EQ(steel.coefficients.kae_n_per_mm, 2.0);
  EXPECT_EQ(steel.coefficients.size_exponent, 0.0) << "no size_effect given: off";
  const Material& alu = library.materials[1];
  EXPECT_EQ(alu.coefficients.kte_n_per_mm, 27.7);
  EXPECT_EQ(alu.coefficients.size_exponent, 0.13);
  EXPECT_EQ(alu.coefficients.size_reference_chip_mm, 0.1);
  EXPECT_EQ(alu.coefficients.size_min_chip_mm, 0.01);
  EXPECT_EQ(alu.coefficient_sources.at("krc_n_per_mm2"), "from a test");
  EXPECT_EQ(alu.coefficient_sources.at("size_effect"), "DESIGN 6.2");
  EXPECT_EQ(library.find("alu-b"), &library.materials[1]);
  EXPECT_EQ(library.find("nothing"), nullptr);
  EXPECT_EQ(library.find(""), nullptr);
}

TEST(MaterialLibrary, UnknownNameListsKnownOnesAndSuggests) {
  const MaterialLibrary library = load_materials(kLibraryPath);
  try {
    library.get("S55C", "spec.material (line 3)");
    FAIL() << "no error for S55C";
  } catch (const InputError& e) {
    ASSERT_EQ(e.problems().size(), 1u);
    EXPECT_EQ(e.problems()[0].field, "spec.material (line 3)");
    const std::string& m = e.problems()[0].message;
    EXPECT_NE(m.find("= \"S55C\": unknown material"), std::string::npos) << m;
    EXPECT_NE(m.find("Al7075-T6"), std::string::npos) << m;
    EXPECT_NE(m.find("Ti6Al4V"), std::string::npos) << m;
    EXPECT_NE(m.find("(did you mean S50C?)"), std::string::npos) << m;
  }
  // An alias suggestion names the material it belongs to.
  const std::string alias_hint = unknown_material_problem(library, "C46").message;
  EXPECT_NE(alias_hint.find("did you mean C45 = S50C?"), std::string::npos) << alias_hint;
  // A prefix is a hint too; nothing close gives no suggestion.
  const std::string prefix_hint = unknown_material_problem(library, "x5crni").message;
  EXPECT_NE(prefix_hint.find("did you mean X5CrNi18-10 = SUS304?"), std::string::npos) << prefix_hint;
  EXPECT_EQ(unknown_material_problem(library, "brass alloy").message.find("did you mean"), std::string::npos);
}

TEST(MaterialLibraryErrors, NegativeCoefficientNamesFieldLineValueAndRange) {
  const auto problems = problems_of(replace(kValid, "krc_n_per_mm2: 600", "krc_n_per_mm2: -5"));
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_TRUE(has_problem(problems, "materials[0].coefficients.krc_n_per_mm2 (line 8)",
                          "= -5: must be ≥ 0 N/mm² — radial cutting coefficient Krc of Steel-A"));
}

TEST(MaterialLibraryErrors, ZeroOrNonFiniteKtc) {
  EXPECT_TRUE(has_problem(problems_of(replace(kValid, "ktc_n_per_mm2: 2000", "ktc_n_per_mm2: 0")),
                          "materials[0].coefficients.ktc_n_per_mm2 (line 7)", "= 0: must be > 0 N/mm²"));
  EXPECT_TRUE(has_problem(problems_of(replace(kValid, "kte_n_per_mm: 27.7", "kte_n_per_mm: .inf")),
                          "materials[1].coefficients.kte_n_per_mm (line 16)",
                          "= inf: must be a finite number ≥ 0 N/mm"));
  EXPECT_TRUE(has_problem(problems_of(replace(kValid, "ktc_n_per_mm2: 2000", "ktc_n_per_mm2: .nan")),
                          "materials[0].coefficients.ktc_n_per_mm2 (line 7)", "= nan: must be a finite number > 0"));
}

TEST(MaterialLibraryErrors, UnknownFieldsSuggestTheClosest) {
  const auto in_material = problems_of(replace(kValid, "    aliases:", "    alias:"));
  EXPECT_TRUE(has_problem(in_material, "materials[0].alias (line 3)", "is not a known field; expected one of name, "
                                                                      "aliases"));
  EXPECT_TRUE(has_problem(in_material, "materials[0].alias (line 3)", "(did you mean aliases?)"));

  const auto in_coefficients = problems_of(replace(kValid, "kte_n_per_mm: 20", "kte_n_per_mm2: 20"));
  EXPECT_TRUE(has_problem(in_coefficients, "materials[0].coefficients.kte_n_per_mm2 (line 10)",
                          "(did you mean kte_n_per_mm?)"));
  // ... and the real field is then missing.
  EXPECT_TRUE(has_problem(in_coefficients, "materials[0].coefficients.kte_n_per_mm",
                          "is missing from materials[0].coefficients (line 7): required — tangential edge"));

  const auto at_top = problems_of("material:\n" + kValid.substr(std::string("materials:\n").size()));
  EXPECT_TRUE(has_problem(at_top, "material (line 1)", "(did you mean materials?)"));
}

TEST(MaterialLibraryErrors, WrongTypes) {
  EXPECT_TRUE(has_problem(problems_of(replace(kValid, "ktc_n_per_mm2: 2000", "ktc_n_per_mm2: lots")),
                          "materials[0].coefficients.ktc_n_per_mm2 (line 7)",
                          "= lots: must be a number — tangential cutting coefficient Ktc in N/mm²"));
  EXPECT_TRUE(has_problem(problems_of(replace(kValid, "ktc_n_per_mm2: 2000", "ktc_n_per_mm2: \"2000\"")),
                          "materials[0].coefficients.ktc_n_per_mm2 (line 7)", "= \"2000\": must be a number"));
  EXPECT_TRUE(has_problem(problems_of(replace(kValid, "aliases: [\"1045\", C45]", "aliases: C45")),
                          "materials[0].aliases (line 3)", "= C45: must be a list of names"));
  EXPECT_TRUE(has_problem(problems_of(replace(kValid, "name: Alu-B", "name: [Alu, B]")),
                          "materials[1].name (line 13)", "= [Alu, B]: must be text"));
  EXPECT_TRUE(has_problem(problems_of(kValid.substr(0, kValid.find("    coefficients: {")) + "    coefficients: 5\n"),
                          "materials[1].coefficients (line 15)", "= 5: must be a mapping"));
  EXPECT_TRUE(has_problem(problems_of("materials: {a: 1}\n"), "materials (line 1)", "must be a non-empty list"));
}

TEST(MaterialLibraryErrors, DuplicateNamesAndAliasesIgnoringCase) {
  const auto same_name = problems_of(replace(kValid, "name: Alu-B", "name: steel-a"));
  EXPECT_TRUE(has_problem(same_name, "materials[1].name (line 13)",
                          "= \"steel-a\": already used by materials[0].name (line 2) (Steel-A) — names and aliases "
                          "must be unique, ignoring case"));
  const auto alias_clash = problems_of(replace(kValid, "  - name: Alu-B\n", "  - name: Alu-B\n    aliases: [c45]\n"));
  EXPECT_TRUE(has_problem(alias_clash, "materials[1].aliases[0] (line 14)",
                          "already used by materials[0].aliases[1] (line 3) (Steel-A)"));
  const auto own_name = problems_of(replace(kValid, "aliases: [\"1045\", C45]", "aliases: [STEEL-A]"));
  EXPECT_TRUE(has_problem(own_name, "materials[0].aliases[0] (line 3)", "already used by materials[0].name (line 2)"));
}

TEST(MaterialLibraryErrors, MissingFields) {
  const auto no_source = problems_of(replace(kValid, "    source: test\n    coefficients:\n", "    coefficients:\n"));
  EXPECT_TRUE(has_problem(no_source, "materials[0].source", "is missing from materials[0] (line 2): required — where "
                                                            "the coefficients come from"));
  const auto no_coefficients = problems_of(kValid.substr(0, kValid.find("    coefficients: {")));
  EXPECT_TRUE(has_problem(no_coefficients, "materials[1].coefficients", "is missing from materials[1] (line 13)"));
  const auto no_ktc = problems_of(replace(kValid, "      ktc_n_per_mm2: 2000\n", ""));
  EXPECT_TRUE(has_problem(no_ktc, "materials[0].coefficients.ktc_n_per_mm2", "is missing"));
  const auto no_name = problems_of(replace(kValid, "  - name: Alu-B\n    source", "  - source"));
  EXPECT_TRUE(has_problem(no_name, "materials[1].name", "is missing"));
  const auto empty_source = problems_of(replace(kValid, "    source: test\n    coefficients:\n",
                                                "    source: \"\"\n    coefficients:\n"));
  EXPECT_TRUE(has_problem(empty_source, "materials[0].source (line 5)", "write \"estimate\""));
  EXPECT_TRUE(has_problem(problems_of("materials: []\n"), "materials (line 1)", "must be a non-empty list"));
  EXPECT_TRUE(has_problem(problems_of("other: 1\n"), "materials", "is missing: required — the list of materials"));
}

TEST(MaterialLibraryErrors, SizeEffectRanges) {
  const std::string base = kValid + "    size_effect: {exponent: 1.2, reference_chip_mm: 0.1, min_chip_mm: 0.2}\n";
  const auto problems = problems_of(base);
  EXPECT_TRUE(has_problem(problems, "materials[1].size_effect.exponent (line 17)", "= 1.2: must be in [0, 1)"));
  EXPECT_TRUE(has_problem(problems, "materials[1].size_effect.min_chip_mm (line 17)", "= 0.2: must be in (0, 0.1] mm"));
  const auto no_reference = problems_of(kValid + "    size_effect: {exponent: 0.1, reference_chip_mm: 0}\n");
  EXPECT_TRUE(has_problem(no_reference, "materials[1].size_effect.reference_chip_mm (line 17)", "= 0: must be > 0 mm"));
  const auto bad_source_key = problems_of(kValid + "    sources: {ktc: x}\n");
  EXPECT_TRUE(has_problem(bad_source_key, "materials[1].sources.ktc (line 17)", "is not a known field"));
}

TEST(MaterialLibraryErrors, EveryProblemReportedAtOnce) {
  std::string yaml = replace(kValid, "krc_n_per_mm2: 600", "krc_n_per_mm2: -1");
  yaml = replace(yaml, "kae_n_per_mm: 1.4", "kae_n_per_mm: -2");
  yaml = replace(yaml, "    description: test steel\n", "    descripton: test steel\n");
  const auto problems = problems_of(yaml);
  EXPECT_EQ(problems.size(), 3u);
  EXPECT_TRUE(has_problem(problems, "materials[0].descripton (line 4)", "did you mean description?"));
  EXPECT_TRUE(has_problem(problems, "materials[1].coefficients.kae_n_per_mm (line 16)", "= -2: must be ≥ 0 N/mm"));
}

TEST(MaterialLibraryErrors, MalformedEmptyAndWrongShapeDocuments) {
  const auto malformed = problems_of("materials:\n  - name: [unclosed\n");
  ASSERT_EQ(malformed.size(), 1u);
  EXPECT_EQ(malformed[0].field, "test.yaml");
  EXPECT_NE(malformed[0].message.find("is not valid YAML at line"), std::string::npos) << malformed[0].message;

  for (const std::string empty : {"", "\n# only a comment\n"}) {
    const auto problems = problems_of(empty);
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].field, "test.yaml");
    EXPECT_NE(problems[0].message.find("is empty: expected a material library"), std::string::npos);
  }
  const auto list = problems_of("- a\n- b\n");
  ASSERT_EQ(list.size(), 1u);
  EXPECT_NE(list[0].message.find("is not a YAML mapping (it is a list)"), std::string::npos);
}

TEST(MaterialLibraryErrors, FileProblemsNameThePath) {
  try {
    load_materials("/nonexistent/materials.yaml");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/materials.yaml cannot be read: no such file (expected a material "
                                     "library)");
  }
}

// Six levels of ten aliases: 10⁶ nodes from 300 bytes. Refused after counting 100 000, with the way out.
TEST(MaterialLibraryErrors, AnAliasBombIsRefusedBeforeItExpands) {
  const std::string bomb =
      "a: &a [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]\n"
      "b: &b [*a, *a, *a, *a, *a, *a, *a, *a, *a, *a]\n"
      "c: &c [*b, *b, *b, *b, *b, *b, *b, *b, *b, *b]\n"
      "d: &d [*c, *c, *c, *c, *c, *c, *c, *c, *c, *c]\n"
      "e: &e [*d, *d, *d, *d, *d, *d, *d, *d, *d, *d]\n"
      "f: &f [*e, *e, *e, *e, *e, *e, *e, *e, *e, *e]\n"
      "materials: *f\n";
  try {
    read_materials(bomb, "bomb.yaml");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "bomb.yaml expands to more than 100000 YAML nodes through its aliases (*name), counting each use: a "
              "material library has about 30 per material; write it without the aliases");
  }
}

}  // namespace
}  // namespace feedplan::sim
