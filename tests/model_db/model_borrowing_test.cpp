// The model match (model_db/model_borrowing.hpp) against differences worked out by hand: which
// properties differ, both values, and the relative force difference of each.

#include <gtest/gtest.h>

#include "feedplan/model_db/model_borrowing.hpp"

namespace feedplan::model_db {
namespace {

ToolRecord tool(const char* name, double diameter_mm, int flutes, double helix_deg) {
  ToolRecord t;
  t.name = name;
  t.diameter_mm = diameter_mm;
  t.flutes = flutes;
  t.helix_deg = helix_deg;
  return t;
}

MaterialRecord material(const char* name, IsoGroup group, double hardness, const char* scale = "HB") {
  MaterialRecord m;
  m.name = name;
  m.iso_group = group;
  m.hardness_value = hardness;
  m.hardness_scale = scale;
  return m;
}

TEST(ModelBorrowing, TheSameGeometryAndMaterialIsExactWhateverTheToolIsCalled) {
  const ModelBorrowing b = model_borrowing(tool("mine", 10, 4, 30), material("S50C", IsoGroup::kP, 200),
                                           tool("SC EM D10 Z4", 10, 4, 30), material("S50C", IsoGroup::kP, 200));
  EXPECT_EQ(b.status, ModelMatchStatus::kExact);
  EXPECT_TRUE(b.differences.empty());
  EXPECT_EQ(b.borrowed_fraction, 0.0);
  EXPECT_EQ(describe(b), "exact");
}

// Ø8 3-flute 35° asked, Ø10 4-flute 30° used: 2/8 = 0.25, 1/3, 0.05 × 5/30.
TEST(ModelBorrowing, ToolDifferencesAreRelativeToTheSmallerValue) {
  const ModelBorrowing b = model_borrowing(tool("D8", 8, 3, 35), material("S50C", IsoGroup::kP, 200),
                                           tool("D10", 10, 4, 30), material("S50C", IsoGroup::kP, 200));
  ASSERT_EQ(b.status, ModelMatchStatus::kBorrowed);
  ASSERT_EQ(b.differences.size(), 3u);
  EXPECT_EQ(b.differences[0].property, "diameter");
  EXPECT_EQ(b.differences[0].wanted, "8 mm");
  EXPECT_EQ(b.differences[0].used, "10 mm");
  EXPECT_DOUBLE_EQ(b.differences[0].relative, 0.25);
  EXPECT_DOUBLE_EQ(b.differences[1].relative, 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(b.differences[2].relative, 0.05 * 5.0 / 30.0);
  EXPECT_DOUBLE_EQ(b.borrowed_fraction, 0.25 + 1.0 / 3.0 + 0.05 * 5.0 / 30.0);
  EXPECT_EQ(describe(b).rfind("borrowed: diameter 10 mm for 8 mm (25 %), flutes 4 for 3 (33 %)", 0), 0u) << describe(b);
}

// 300 HB asked, 200 HB used: 100 / 200 = 0.5; an alloy of equal hardness still counts 0.1; another
// scale 0.5; another ISO group 1.
TEST(ModelBorrowing, MaterialDifferencesFollowHardnessAndGroup) {
  const ToolRecord d10 = tool("D10", 10, 4, 30);
  const MaterialRecord s50c = material("S50C", IsoGroup::kP, 200);
  EXPECT_DOUBLE_EQ(model_borrowing(d10, material("S55C", IsoGroup::kP, 300), d10, s50c).borrowed_fraction, 0.5);
  EXPECT_DOUBLE_EQ(model_borrowing(d10, material("C45", IsoGroup::kP, 200), d10, s50c).borrowed_fraction, 0.1);
  EXPECT_DOUBLE_EQ(model_borrowing(d10, material("X", IsoGroup::kP, 30, "HRC"), d10, s50c).borrowed_fraction, 0.5);
  const ModelBorrowing ti = model_borrowing(d10, material("Ti6Al4V", IsoGroup::kS, 330), d10, s50c);
  EXPECT_DOUBLE_EQ(ti.borrowed_fraction, 1.0);
  EXPECT_EQ(ti.differences.back().property, "ISO group");
  const ModelBorrowing unknown = model_borrowing(d10, UnknownMaterial{"Mystery"}, d10, s50c);
  EXPECT_EQ(unknown.status, ModelMatchStatus::kBorrowed);
  EXPECT_DOUBLE_EQ(unknown.borrowed_fraction, 0.5);
}

}  // namespace
}  // namespace feedplan::model_db
