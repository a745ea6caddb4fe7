// Model versions of two kinds in one store (store.hpp, schema 4): a response surface and a mechanistic
// model of the same tool and material each have their own active version and parent, share the version
// numbers, roll back within their kind, and survive export → import → export byte for byte; the planner's
// closest-model choice never hands a mechanistic version out as a response surface.

#include <gtest/gtest.h>

#include <string>

#include "feedplan/model_db/closest_model.hpp"
#include "feedplan/model_db/model_exchange.hpp"
#include "store_fixtures.hpp"

namespace feedplan::model_db {
namespace {

using fixtures::ScratchDir;

ModelRecord mechanistic(double ktc_n_per_mm2) {
  ModelRecord r = fixtures::model("SC EM D10 Z4", "S50C");
  r.kind = ModelKind::kMechanistic;
  r.model.beta = {};
  MechanisticFit fit;
  fit.model.ktc_n_per_mm2 = ktc_n_per_mm2;
  fit.model.krc_n_per_mm2 = 550.0;
  fit.model.kte_n_per_mm = 24.5;
  fit.model.kre_n_per_mm = 17.25;
  fit.model.runout_mm = {0.0, 0.0035, 0.007, 0.0034};
  fit.model.helix_deg = 25.9;
  for (int i = 0; i < 4; ++i) fit.covariance[i][i] = 1.0 + i;
  fit.covariance[0][1] = fit.covariance[1][0] = 0.25;
  fit.signal_rms_residual_n = 5.7;
  fit.condition_number = 3.8;
  fit.unidentifiable = {"K_ac, K_ae: only Fx and Fy"};
  r.mechanistic = fit;
  return r;
}

class ModelKindStore : public ::testing::Test {
 protected:
  void SetUp() override {
    store_.add_tool(fixtures::tool("SC EM D10 Z4", 10, 4, 30));
    store_.add_material(fixtures::material("S50C", IsoGroup::kP, 200));
  }
  ScratchDir dir_;
  Store store_ = Store::open(dir_ / "kinds.db", OpenMode::kCreate);
};

TEST_F(ModelKindStore, EachKindHasItsOwnActiveVersionAndParent) {
  const ModelRecord surface = store_.add_model(fixtures::model("SC EM D10 Z4", "S50C"));
  const ModelRecord first = store_.add_model(mechanistic(1600));
  const ModelRecord second = store_.add_model(mechanistic(1650));
  EXPECT_EQ(surface.version, 1);
  EXPECT_EQ(first.version, 2);
  EXPECT_FALSE(first.parent_version.has_value());  // the response surface is not its parent
  EXPECT_EQ(second.version, 3);
  EXPECT_EQ(second.parent_version, 2);

  const auto active_surface = store_.active_model("SC EM D10 Z4", "S50C");
  ASSERT_TRUE(active_surface);
  EXPECT_EQ(active_surface->version, 1);
  EXPECT_EQ(active_surface->kind, ModelKind::kResponseSurface);
  const auto active_mechanistic = store_.active_model("SC EM D10 Z4", "S50C", ModelKind::kMechanistic);
  ASSERT_TRUE(active_mechanistic && active_mechanistic->mechanistic);
  EXPECT_EQ(active_mechanistic->version, 3);
  EXPECT_DOUBLE_EQ(active_mechanistic->mechanistic->model.ktc_n_per_mm2, 1650);
  EXPECT_EQ(active_mechanistic->mechanistic->model.runout_mm, mechanistic(0).mechanistic->model.runout_mm);
  EXPECT_EQ(active_mechanistic->mechanistic->model.helix_deg, 25.9);
  EXPECT_DOUBLE_EQ(active_mechanistic->mechanistic->covariance[1][0], 0.25);

  // Rolling the mechanistic kind back leaves the response surface active as it was.
  store_.rollback("SC EM D10 Z4", "S50C", 2);
  EXPECT_EQ(store_.active_model("SC EM D10 Z4", "S50C", ModelKind::kMechanistic)->version, 2);
  EXPECT_EQ(store_.active_model("SC EM D10 Z4", "S50C")->version, 1);
  EXPECT_EQ(store_.active_models().size(), 1u);
  EXPECT_EQ(store_.active_models(ModelKind::kMechanistic).size(), 1u);
}

TEST_F(ModelKindStore, TheClosestModelIsNeverAMechanisticVersion) {
  store_.add_model(mechanistic(1600));
  const ClosestModel none = closest_model(store_, "SC EM D10 Z4", "S50C");
  EXPECT_NE(none.status, ClosestModelStatus::kFound);
  store_.add_model(fixtures::model("SC EM D10 Z4", "S50C"));
  const ClosestModel found = closest_model(store_, "SC EM D10 Z4", "S50C");
  ASSERT_EQ(found.status, ClosestModelStatus::kFound);
  EXPECT_EQ(found.model->kind, ModelKind::kResponseSurface);
}

TEST_F(ModelKindStore, VersionsOfBothKindsSurviveExportAndImport) {
  store_.add_model(fixtures::model("SC EM D10 Z4", "S50C"));
  store_.add_model(mechanistic(1600));
  ModelRecord no_helix = mechanistic(1700);
  no_helix.mechanistic->model.helix_deg.reset();
  store_.add_model(no_helix);
  ExportOptions all;
  all.active_models_only = false;
  const std::string text = export_json(store_, all);
  EXPECT_NE(text.find("\"kind\": \"mechanistic\""), std::string::npos);
  EXPECT_NE(text.find("\"helix_deg\": null"), std::string::npos);

  Store other = Store::open(dir_ / "other.db", OpenMode::kCreate);
  import_json(other, text);
  EXPECT_EQ(export_json(other, all), text);
  const auto active = other.active_model("SC EM D10 Z4", "S50C", ModelKind::kMechanistic);
  ASSERT_TRUE(active && active->mechanistic);
  EXPECT_EQ(active->version, 3);
  EXPECT_EQ(active->parent_version, 2);
  EXPECT_FALSE(active->mechanistic->model.helix_deg.has_value());
}

TEST_F(ModelKindStore, AMechanisticVersionWithoutItsCoefficientsIsRefused) {
  ModelRecord bare = mechanistic(1600);
  bare.mechanistic.reset();
  EXPECT_THROW(store_.add_model(bare), InputError);
  ModelRecord bad = mechanistic(1600);
  bad.mechanistic->model.helix_deg = 95.0;
  try {
    store_.add_model(bad);
    FAIL() << "a helix of 95° was stored";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("models.mechanistic.helix_deg = 95: must be in (−90, 90)"), std::string::npos)
        << error.what();
  }
  EXPECT_TRUE(store_.models_for("SC EM D10 Z4", "S50C").empty());
}

}  // namespace
}  // namespace feedplan::model_db
