// Choosing the closest model (model_db/closest_model.hpp): each tier of the rule, the distances worked
// out by hand from the weights documented in the header, the explanation text, and the outcomes that
// are statuses rather than errors (no model at all, models only for other ISO groups).

#include <gtest/gtest.h>

#include <string>

#include "feedplan/core/input_error.hpp"
#include "feedplan/model_db/closest_model.hpp"
#include "feedplan/model_db/store.hpp"
#include "store_fixtures.hpp"

namespace feedplan::model_db {
namespace {

using fixtures::ScratchDir;

class ClosestModelTest : public ::testing::Test {
 protected:
  void SetUp() override {
    store_.add_tool(fixtures::tool("SC EM D10 Z4", 10, 4, 30));
    store_.add_tool(fixtures::tool("SC EM D8 Z3", 8, 3, 35));
    store_.add_tool(fixtures::tool("SC EM D6 Z3", 6, 3, 35));
    store_.add_tool(fixtures::tool("SC EM D12 Z4", 12, 4, 30));
    store_.add_material(fixtures::material("S50C", IsoGroup::kP, 200));
    store_.add_material(fixtures::material("S45C", IsoGroup::kP, 180));
    store_.add_material(fixtures::material("SCM440", IsoGroup::kP, 300));
    store_.add_material(fixtures::material("SKD11", IsoGroup::kP, 58, "HRC"));
    store_.add_material(fixtures::material("Al7075-T6", IsoGroup::kN, 150));
    store_.add_material(fixtures::material("Ti6Al4V", IsoGroup::kS, 36, "HRC"));
  }
  ModelRecord add(const std::string& tool, const std::string& material, double k = 1.0) {
    return store_.add_model(fixtures::model(tool, material, k));
  }
  ScratchDir dir_;
  Store store_ = Store::open(dir_ / "models.db", OpenMode::kCreate);
};

TEST_F(ClosestModelTest, ExactToolAndMaterial) {
  add("SC EM D10 Z4", "S50C");
  const auto v2 = add("SC EM D10 Z4", "S50C", 1.1);
  add("SC EM D8 Z3", "S50C");
  const ClosestModel found = closest_model(store_, "SC EM D10 Z4", "S50C");
  ASSERT_EQ(found.status, ClosestModelStatus::kFound);
  EXPECT_EQ(found.match, ModelMatch::kExact);
  EXPECT_EQ(found.model->id, v2.id);
  EXPECT_EQ(found.distance, 0.0);
  EXPECT_EQ(found.model_tool.name, "SC EM D10 Z4");
  EXPECT_EQ(found.model_material.name, "S50C");
  EXPECT_EQ(found.explanation, "using Ø10 4-flute (SC EM D10 Z4) in S50C v2 (exact match)");
}

TEST_F(ClosestModelTest, SameMaterialOtherToolWithTheExplanationOfTheIssue) {
  add("SC EM D10 Z4", "S50C");
  add("SC EM D10 Z4", "S45C");  // same tool in another material: a worse tier
  const ClosestModel found = closest_model(store_, "SC EM D8 Z3", "S50C");
  ASSERT_EQ(found.status, ClosestModelStatus::kFound);
  EXPECT_EQ(found.match, ModelMatch::kSameMaterialOtherTool);
  EXPECT_EQ(found.model_tool.name, "SC EM D10 Z4");
  EXPECT_EQ(found.model_material.name, "S50C");
  // |10 − 8| / 10 + 0.3 (flutes 4 vs 3) + 0.1 · 5° / 30°
  EXPECT_NEAR(found.distance, 0.2 + 0.3 + 0.1 * 5.0 / 30.0, 1e-12);
  EXPECT_EQ(found.explanation,
            "no model for Ø8 3-flute (SC EM D8 Z3) in S50C; using Ø10 4-flute (SC EM D10 Z4) in S50C v1 "
            "(same material, nearest diameter 10 vs 8 mm, flutes 4 vs 3, helix 30 vs 35°; distance 0.517)");
}

TEST_F(ClosestModelTest, TheSameFluteCountIsPreferredOverTheNearestDiameter) {
  add("SC EM D10 Z4", "S50C");  // 0.2 + 0.3 + 0.0167 = 0.517 from D8 Z3
  add("SC EM D6 Z3", "S50C");   // 0.25 from D8 Z3
  const ClosestModel found = closest_model(store_, "SC EM D8 Z3", "S50C");
  EXPECT_EQ(found.model_tool.name, "SC EM D6 Z3");
  EXPECT_NEAR(found.distance, 0.25, 1e-12);
  EXPECT_EQ(found.explanation,
            "no model for Ø8 3-flute (SC EM D8 Z3) in S50C; using Ø6 3-flute (SC EM D6 Z3) in S50C v1 "
            "(same material, nearest diameter 6 vs 8 mm, same flute count 3; distance 0.25)");
}

TEST_F(ClosestModelTest, SameMaterialBeatsTheExactToolInAnotherMaterialWhateverTheDistance) {
  add("SC EM D12 Z4", "S50C");  // from D6 Z3: 0.5 + 0.3 + 0.0167 = 0.817
  add("SC EM D6 Z3", "S45C");   // exact tool, hardness 0.1 away: a worse tier
  const ClosestModel found = closest_model(store_, "SC EM D6 Z3", "S50C");
  EXPECT_EQ(found.match, ModelMatch::kSameMaterialOtherTool);
  EXPECT_EQ(found.model_tool.name, "SC EM D12 Z4");
  EXPECT_NEAR(found.distance, 0.5 + 0.3 + 0.1 * 5.0 / 30.0, 1e-12);
}

TEST_F(ClosestModelTest, SameIsoGroupExactToolPicksTheNearestHardness) {
  add("SC EM D10 Z4", "SCM440");  // |300 − 200| / 300 = 0.333
  add("SC EM D10 Z4", "S45C");    // |180 − 200| / 200 = 0.1
  add("SC EM D8 Z3", "S45C");     // other tool and material: a worse tier
  const ClosestModel found = closest_model(store_, "SC EM D10 Z4", "S50C");
  ASSERT_EQ(found.status, ClosestModelStatus::kFound);
  EXPECT_EQ(found.match, ModelMatch::kSameIsoGroupExactTool);
  EXPECT_EQ(found.model_material.name, "S45C");
  EXPECT_NEAR(found.distance, 0.1, 1e-12);
  EXPECT_EQ(found.explanation,
            "no model for Ø10 4-flute (SC EM D10 Z4) in S50C; using Ø10 4-flute (SC EM D10 Z4) in S45C v1 "
            "(same tool, same ISO group P, hardness 180 HB vs 200 HB; distance 0.1)");
}

TEST_F(ClosestModelTest, SameIsoGroupOtherToolCombinesToolAndMaterialDistances) {
  add("SC EM D12 Z4", "S45C");   // 2/12 + 0 + 0 + 0.1  = 0.267
  add("SC EM D6 Z3", "SCM440");  // 4/10 + 0.3 + 0.0167 + 0.333 = 1.05
  add("SC EM D10 Z4", "Al7075-T6");  // other ISO group: never offered
  const ClosestModel found = closest_model(store_, "SC EM D10 Z4", "S50C");
  ASSERT_EQ(found.status, ClosestModelStatus::kFound);
  EXPECT_EQ(found.match, ModelMatch::kSameIsoGroupOtherTool);
  EXPECT_EQ(found.model_tool.name, "SC EM D12 Z4");
  EXPECT_NEAR(found.distance, 2.0 / 12.0 + 20.0 / 200.0, 1e-12);
  EXPECT_EQ(found.explanation,
            "no model for Ø10 4-flute (SC EM D10 Z4) in S50C; using Ø12 4-flute (SC EM D12 Z4) in S45C v1 "
            "(same ISO group P, hardness 180 HB vs 200 HB, nearest diameter 12 vs 10 mm, same flute count 4; "
            "distance 0.267)");
}

TEST_F(ClosestModelTest, HardnessOnAnotherScaleCountsAsHalfAwayNotAsComparable) {
  add("SC EM D10 Z4", "SKD11");   // 58 HRC vs 200 HB: 0.5
  add("SC EM D10 Z4", "SCM440");  // 0.333
  const ClosestModel found = closest_model(store_, "SC EM D10 Z4", "S50C");
  EXPECT_EQ(found.model_material.name, "SCM440");
  const MaterialRecord s50c = *store_.find_material("S50C");
  EXPECT_EQ(material_distance(s50c, *store_.find_material("SKD11")), 0.5);
  EXPECT_FALSE(material_distance(s50c, *store_.find_material("Al7075-T6")).has_value());
  EXPECT_EQ(material_distance(s50c, s50c), 0.0);
}

TEST_F(ClosestModelTest, OnlyTheActiveVersionIsUsed) {
  add("SC EM D10 Z4", "S50C", 1.0);
  add("SC EM D10 Z4", "S50C", 1.1);
  store_.rollback("SC EM D10 Z4", "S50C", 1);
  const ClosestModel found = closest_model(store_, "SC EM D10 Z4", "S50C");
  EXPECT_EQ(found.model->version, 1);
  EXPECT_EQ(found.model->model.beta[0], 480.0);
}

TEST_F(ClosestModelTest, NoModelAtAllIsAStatusNotAnError) {
  const ClosestModel found = closest_model(store_, "SC EM D10 Z4", "S50C");
  EXPECT_EQ(found.status, ClosestModelStatus::kNoModel);
  EXPECT_FALSE(found.model.has_value());
  EXPECT_EQ(found.explanation, "no model for Ø10 4-flute (SC EM D10 Z4) in S50C: the model database has no models yet");
}

TEST_F(ClosestModelTest, ModelsOnlyForOtherIsoGroupsAreNotOffered) {
  add("SC EM D10 Z4", "Al7075-T6");
  add("SC EM D6 Z3", "Al7075-T6");
  add("SC EM D10 Z4", "S50C");
  const ClosestModel found = closest_model(store_, "SC EM D10 Z4", "Ti6Al4V");
  EXPECT_EQ(found.status, ClosestModelStatus::kNoModel);
  EXPECT_EQ(found.explanation,
            "no model for Ø10 4-flute (SC EM D10 Z4) in Ti6Al4V nor for any material of ISO group S; models exist "
            "only for ISO groups N (2), P (1), and a model for another group would mislead the plan");
}

TEST_F(ClosestModelTest, ATiedDistanceIsBrokenByName) {
  add("SC EM D12 Z4", "S50C");  // from D10 Z4... both 4-flute at the same helix:
  add("SC EM D8 Z3", "S50C");
  // Ask for a tool not in the store, described by value: Ø9.6 4-flute 30° → D12: 2.4/12 = 0.2; D8 Z3:
  // 1.6/9.6 + 0.3 + 0.0167 = 0.483.
  const ClosestModel found =
      closest_model(store_, fixtures::tool("spec tool", 9.6, 4, 30), *store_.find_material("S50C"));
  EXPECT_EQ(found.model_tool.name, "SC EM D12 Z4");
  EXPECT_NEAR(found.distance, 0.2, 1e-12);
  // Two candidates at exactly the same distance (the same geometry under two names): the first by tool
  // name wins, whichever was added first.
  store_.add_tool(fixtures::tool("SC EM D10 Z4 spare", 10, 4, 30));
  add("SC EM D10 Z4 spare", "S45C");
  add("SC EM D10 Z4", "S45C");
  const ClosestModel tie = closest_model(store_, fixtures::tool("Ø11 spec", 11, 4, 30), *store_.find_material("S45C"));
  EXPECT_NEAR(tie.distance, 1.0 / 11.0, 1e-12);
  EXPECT_EQ(tie.model_tool.name, "SC EM D10 Z4");
}

TEST_F(ClosestModelTest, UnknownNamesAreInputErrors) {
  add("SC EM D10 Z4", "S50C");
  EXPECT_THROW(closest_model(store_, "SC EM D9 Z4", "S50C"), InputError);
  try {
    closest_model(store_, "SC EM D10 Z4", "S50CC");
    FAIL() << "no InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("material_name = 'S50CC': unknown material"), std::string::npos)
        << error.what();
    EXPECT_NE(std::string(error.what()).find("(did you mean S50C?)"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace feedplan::model_db
