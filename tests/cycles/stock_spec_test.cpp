// Reading a workpiece on its own (feedplan simulate --stock): a stock document or a cycle spec.

#include <gtest/gtest.h>

#include <string>

#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"

namespace feedplan::cycles {
namespace {

const std::string kStock =
    "stock:\n"
    "  z_bottom_mm: -20\n"
    "  z_top_mm: 0\n"
    "  regions:\n"
    "    - outer: {polygon: [[0, -40], [60, -40], [60, 40], [0, 40]]}\n"
    "      holes: [{circle: {center: [30, 0], radius_mm: 8}}]\n";

TEST(StockSpec, ReadsAStockDocument) {
  const geometry::Stock stock = read_stock_spec(kStock, "stock.yaml");
  EXPECT_EQ(stock.z_bottom_mm, -20.0);
  EXPECT_EQ(stock.z_top_mm, 0.0);
  ASSERT_EQ(stock.regions.size(), 1u);
  ASSERT_EQ(stock.regions[0].outer.vertices.size(), 4u);
  EXPECT_EQ(stock.regions[0].outer.vertices[1].x_mm, 60.0);
  ASSERT_EQ(stock.regions[0].holes.size(), 1u);
  EXPECT_EQ(stock.regions[0].holes[0].radius_mm, 8.0);
  EXPECT_TRUE(stock.removed.empty());
}

TEST(StockSpec, ACycleSpecGivesTheStockItsCycleImplies) {
  const std::string spec =
      "cycle: spiral\n"
      "tool: {diameter_mm: 10, flutes: 4}\n"
      "axial_depth_mm: 10\n"
      "spiral: {center: [0, 0], initial_radius_mm: 8, final_radius_mm: 16, pitch_mm: 1}\n";
  const geometry::Stock stock = read_stock_spec(spec, "spiral.yaml");
  const geometry::Stock expected = generate(read_cycle_spec(spec, "spiral.yaml")).stock;
  ASSERT_EQ(stock.regions.size(), expected.regions.size());
  ASSERT_EQ(stock.regions[0].holes.size(), 1u);
  EXPECT_EQ(stock.regions[0].holes[0].radius_mm, 8.0);  // the pre-drilled bore of the spiral
  EXPECT_EQ(stock.z_top_mm, expected.z_top_mm);
}

void expect_problem(const std::string& yaml, const std::string& field_start, const std::string& fragment) {
  try {
    read_stock_spec(yaml, "bad.yaml");
    FAIL() << "no InputError for:\n" << yaml;
  } catch (const InputError& e) {
    bool found = false;
    for (const auto& p : e.problems()) {
      const std::string text = to_string(p);
      if (text.rfind(field_start, 0) == 0 && text.find(fragment) != std::string::npos) found = true;
    }
    EXPECT_TRUE(found) << "expected a problem starting '" << field_start << "' containing '" << fragment << "', got:\n"
                       << e.what();
  }
}

TEST(StockSpec, BadStocksNameTheFieldAndLine) {
  expect_problem("", "bad.yaml", "is empty");
  expect_problem("stock: [1, 2]\n", "stock", "");
  expect_problem("stok: {z_bottom_mm: -1, z_top_mm: 0}\n", "stok (line 1)", "did you mean stock");
  expect_problem("stock:\n  z_bottom_mm: -20\n  z_top_mm: 0\n", "stock", "regions");
  expect_problem("stock:\n  z_bottom_mm: 0\n  z_top_mm: -20\n  regions:\n    - outer: {circle: {center: [0, 0], radius_mm: 5}}\n",
                 "stock", "z_top");
  expect_problem("stock:\n  z_bottom_mm: -20\n  z_top_mm: 0\n  regions:\n    - outer: {circle: {center: [0, 0], radius_mm: -5}}\n",
                 "stock.regions[0].outer.circle.radius_mm (line 5)", "-5");
  expect_problem("stock:\n  z_bottom_mm: -20\n  z_top_mm: 0\n  regions:\n"
                 "    - outer: {polygon: [[0, 0], [10, 10], [10, 0], [0, 10]]}\n",
                 "stock.regions[0].outer.polygon (line 5)", "not simple");
  expect_problem("stock:\n  z_bottom_mm: .nan\n  z_top_mm: 0\n  regions:\n    - outer: {circle: {center: [0, 0], radius_mm: 5}}\n",
                 "stock.z_bottom_mm (line 2)", "nan");
  expect_problem("stock: {z_bottom_mm: -1, z_top_mm: 0, regions: [{outer: {circle: {center: [0, 0], radius_mm: 5}}}]\n",
                 "bad.yaml", "not valid YAML");
}

}  // namespace
}  // namespace feedplan::cycles
