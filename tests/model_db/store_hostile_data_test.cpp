// Model databases and records no feedplan wrote: what a probe of the store found (a schema version
// set by hand, numbers no tool has, text in a number column, names that are not UTF-8). Each is
// refused with an InputError naming the file or the field, and the database is left as it was,
// where the store used to crash, store nonsense or read a number as 0.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "feedplan/model_db/model_exchange.hpp"
#include "feedplan/model_db/store.hpp"
#include "store_fixtures.hpp"

namespace feedplan::model_db {
namespace {

using fixtures::input_error_of;
using fixtures::ScratchDir;
using ::testing::HasSubstr;

// PRAGMA user_version = -1 and then any write: prepare_schema migrated from migrations[-1] (SIGBUS).
TEST(StoreHostileData, NegativeSchemaVersionIsRefusedAndTheFileIsUntouched) {
  ScratchDir dir;
  const auto path = dir / "negative.db";
  {
    Store store = Store::open(path, OpenMode::kCreate);
    fixtures::populate(store);
  }
  fixtures::raw_sql(path, "PRAGMA user_version = -1");
  const std::string before = fixtures::file_bytes(path);
  const std::string expected = path.string() +
                               " has model database schema version -1, which feedplan never writes (it writes 1 to 5): "
                               "the file was changed outside feedplan; restore it from a backup or an export";
  EXPECT_EQ(input_error_of([&] { Store::open(path, OpenMode::kCreate); }), expected);
  EXPECT_EQ(input_error_of([&] { Store::open(path, OpenMode::kExisting); }), expected);
  EXPECT_EQ(input_error_of([&] { Store::open(path, OpenMode::kReadOnly); }), expected);
  EXPECT_EQ(fixtures::file_bytes(path), before);
  EXPECT_EQ(fixtures::raw_sql(path, "PRAGMA user_version"), "-1");
}

// A 1e308 mm end mill was stored; so were hardness values no material has.
TEST(StoreHostileData, ToolAndMaterialNumbersMustBePhysical) {
  ScratchDir dir;
  Store store = Store::open(dir / "models.db", OpenMode::kCreate);
  EXPECT_EQ(input_error_of([&] { store.add_tool(fixtures::tool("huge", 1e308, 4, 30)); }),
            "tools.diameter_mm = 1e+308: must be in (0, 1000] mm");
  EXPECT_EQ(input_error_of([&] { store.add_tool(fixtures::tool("many", 10, 1000, 30)); }),
            "tools.flutes = 1000: must be in [1, 100]");
  EXPECT_EQ(input_error_of([&] { store.add_material(fixtures::material("hard", IsoGroup::kH, 85, "HRC")); }),
            "materials.hardness_value = 85: must be in (0, 70] on the HRC scale");
  EXPECT_EQ(input_error_of([&] { store.add_material(fixtures::material("diamond", IsoGroup::kH, 1e300, "HV")); }),
            "materials.hardness_value = 1e+300: must be in (0, 2500] on the HV scale");
  EXPECT_TRUE(store.tools().empty());
  EXPECT_TRUE(store.materials().empty());
  store.add_tool(fixtures::tool("face mill", 160, 12, 0));
  store.add_material(fixtures::material("hardened", IsoGroup::kH, 62, "HRC"));
  EXPECT_EQ(store.tools().size(), 1u);
}

// Cutting conditions beyond any machine were stored too.
TEST(StoreHostileData, CuttingConditionsMustBePhysical) {
  ScratchDir dir;
  Store store = Store::open(dir / "models.db", OpenMode::kCreate);
  fixtures::populate(store);
  CuttingTestRecord test = fixtures::cutting_test("SC EM D10 Z4", "S50C", 9);
  test.conditions.spindle_rpm = 1e12;
  test.conditions.axial_depth_mm = 1e9;
  EXPECT_EQ(input_error_of([&] { store.add_cutting_test(test); }),
            "cutting_tests.spindle_rpm = 1e+12: must be in (0, 200000] rev/min\n"
            "cutting_tests.axial_depth_mm = 1e+09: must be in (0, 1000] mm");
}

// A tool name in Latin-1 was stored, and then `db list --json` and `db export` failed on it.
TEST(StoreHostileData, TextThatIsNotUtf8IsRefusedWhereItEnters) {
  ScratchDir dir;
  Store store = Store::open(dir / "models.db", OpenMode::kCreate);
  EXPECT_EQ(input_error_of([&] { store.add_tool(fixtures::tool("Fr\xe4ser D10", 10, 4, 30)); }),
            "tools.name = 'Fr?ser D10': is not UTF-8 text (byte 3 is 0xE4)");
  ToolRecord coated = fixtures::tool("D10", 10, 4, 30);
  coated.coating = "TiAlN \xff";
  EXPECT_EQ(input_error_of([&] { store.add_tool(coated); }),
            "tools.coating = 'TiAlN ?': is not UTF-8 text (byte 7 is 0xFF)");
  MaterialRecord material = fixtures::material("S50C", IsoGroup::kP, 200);
  material.notes = "\xc0\xaf";  // an overlong '/'
  EXPECT_THAT(input_error_of([&] { store.add_material(material); }), HasSubstr("materials.notes = '?" "?': is not UTF-8"));
  EXPECT_TRUE(store.tools().empty());
  store.add_tool(fixtures::tool("Fräser D10 ünïcode", 10, 4, 30));
  EXPECT_EQ(store.tools().at(0).name, "Fräser D10 ünïcode");
}

// Text in a number column (written behind the store's back; SQLite's CHECK (diameter_mm > 0) lets
// text through) was read as 0.
TEST(StoreHostileData, TextInANumberColumnIsRefusedNamingTableColumnAndRow) {
  ScratchDir dir;
  const auto path = dir / "models.db";
  {
    Store store = Store::open(path, OpenMode::kCreate);
    fixtures::populate(store);
  }
  fixtures::raw_sql(path, "UPDATE tools SET diameter_mm = 'ten' WHERE name = 'SC EM D6 Z3'");
  const std::string id = fixtures::raw_sql(path, "SELECT id FROM tools WHERE name = 'SC EM D6 Z3'");
  Store store = Store::open(path, OpenMode::kReadOnly);
  const std::string expected = path.string() + " table tools, column diameter_mm, row id " + id +
                               " = 'ten': must be a number; the file was changed outside feedplan";
  EXPECT_THAT(input_error_of([&] { store.tools(); }), HasSubstr(expected));
  EXPECT_THAT(input_error_of([&] { store.find_tool("SC EM D6 Z3"); }), HasSubstr(expected));
  EXPECT_THAT(input_error_of([&] { export_json(store); }), HasSubstr(expected));
}

// A whole number column holding 4.5 was read as 4.
TEST(StoreHostileData, FractionInAnIntegerColumnIsRefused) {
  ScratchDir dir;
  const auto path = dir / "models.db";
  {
    Store store = Store::open(path, OpenMode::kCreate);
    fixtures::populate(store);
  }
  fixtures::raw_sql(path, "UPDATE tools SET flutes = 4.5 WHERE name = 'SC EM D10 Z4'");
  Store store = Store::open(path, OpenMode::kReadOnly);
  EXPECT_THAT(input_error_of([&] { store.tools(); }),
              HasSubstr("table tools, column flutes, row id 1 = 4.5: must be a whole number"));
}

// Names that are not UTF-8, written behind the store's back, are named when read (JSON cannot hold them).
TEST(StoreHostileData, StoredTextThatIsNotUtf8IsRefusedWhenRead) {
  ScratchDir dir;
  const auto path = dir / "models.db";
  {
    Store store = Store::open(path, OpenMode::kCreate);
    fixtures::populate(store);
  }
  fixtures::raw_sql(path, "UPDATE materials SET notes = CAST(X'4142FE' AS TEXT) WHERE name = 'S50C'");
  Store store = Store::open(path, OpenMode::kReadOnly);
  EXPECT_THAT(input_error_of([&] { store.materials(); }),
              HasSubstr("table materials, column notes, row id 1 = 'AB?': is not UTF-8 text (byte 3 is 0xFE)"));
}

// A model export nested 100 000 levels deep overflowed the stack as a plan report did.
TEST(StoreHostileData, DeeplyNestedExportIsRefusedByItsDepth) {
  ScratchDir dir;
  Store store = Store::open(dir / "models.db", OpenMode::kCreate);
  const std::string nested = std::string(100000, '[') + std::string(100000, ']');
  EXPECT_THAT(input_error_of([&] { import_json(store, nested, {}, "export.json"); }),
              HasSubstr("export.json line 1: nests arrays and objects deeper than 64 levels"));
}

}  // namespace
}  // namespace feedplan::model_db
