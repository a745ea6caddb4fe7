// Machine files: the shipped ones read, every kind of bad input refused with the message it must
// produce (file, field with line, value, expectation), and a machine changing the simulation as it
// says — runout makes the teeth's peaks differ, a helix offset changes the force's shape.

#include "feedplan/sim/machine_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/sim/cutting_test.hpp"
#include "has_problem.hpp"

namespace feedplan::sim {
namespace {

using test_support::has_problem;

const std::string kSourceDir = FEEDPLAN_SOURCE_DIR;

const MaterialLibrary& library() {
  static const MaterialLibrary materials = load_materials(kSourceDir + "/data/materials.yaml");
  return materials;
}

// A valid machine; tests replace one line at a time. Line numbers matter.
const std::string kValid =
    "name: test machine\n"                                                    // 1
    "material: s50c\n"                                                        // 2
    "coefficients: {krc_n_per_mm2: 700}\n"                                    // 3
    "size_effect: {exponent: 0.2, reference_chip_mm: 0.05}\n"                 // 4
    "runout_mm: [0.005, 0, -0.005, 0]\n"                                      // 5
    "helix_offset_deg: -4\n"                                                  // 6
    "dynamometer: {bandwidth_hz: 800, noise_n: 8}\n";                         // 7

std::string with_line(int line, const std::string& replacement) {
  std::string text;
  std::size_t start = 0;
  for (int i = 1; start < kValid.size(); ++i) {
    const std::size_t end = kValid.find('\n', start);
    text += i == line ? replacement + "\n" : kValid.substr(start, end - start + 1);
    start = end + 1;
  }
  return text;
}

std::vector<InputProblem> problems_of(const std::string& text) {
  try {
    read_machine_file(text, "m.yaml", library());
  } catch (const InputError& e) {
    return e.problems();
  }
  ADD_FAILURE() << "no InputError for:\n" << text;
  return {};
}

TEST(MachineFile, ReadsAValidFileOverMaterialValues) {
  const MachineFile m = read_machine_file(kValid, "m.yaml", library());
  EXPECT_EQ(m.name, "test machine");
  EXPECT_EQ(m.material, "S50C");
  EXPECT_DOUBLE_EQ(m.coefficients.ktc_n_per_mm2, 2000.0);  // data/materials.yaml's S50C
  EXPECT_DOUBLE_EQ(m.coefficients.krc_n_per_mm2, 700.0);   // overridden
  EXPECT_DOUBLE_EQ(m.coefficients.size_exponent, 0.2);
  EXPECT_DOUBLE_EQ(m.coefficients.size_reference_chip_mm, 0.05);
  EXPECT_EQ(m.runout_mm, (std::vector<double>{0.005, 0.0, -0.005, 0.0}));
  EXPECT_DOUBLE_EQ(m.helix_offset_deg, -4.0);
  EXPECT_DOUBLE_EQ(m.dynamometer.bandwidth_hz, 800.0);
  EXPECT_DOUBLE_EQ(m.dynamometer.noise_n, 8.0);
  EXPECT_NEAR(m.dynamometer.damping_ratio, 0.7071, 1e-4);  // the default when not given
}

TEST(MachineFile, ShippedMachinesReadAndDifferFromEachOther) {
  std::vector<MachineFile> machines;
  for (const auto& entry : std::filesystem::directory_iterator(kSourceDir + "/data/machines")) {
    if (entry.path().extension() == ".yaml") machines.push_back(load_machine_file(entry.path().string(), library()));
  }
  ASSERT_GE(machines.size(), 3u);
  for (std::size_t i = 0; i < machines.size(); ++i) {
    const MachineFile& a = machines[i];
    EXPECT_GE(a.coefficients.size_exponent, 0.15) << a.name;
    EXPECT_LE(a.coefficients.size_exponent, 0.3) << a.name;
    EXPECT_LE(std::abs(a.helix_offset_deg), 5.0) << a.name;
    // One runout per flute: four for the steel machines (the samples' four-flute tool), two for aluminium.
    EXPECT_EQ(a.runout_mm.size(), a.material == "S50C" ? 4u : 2u) << a.name;
    for (std::size_t j = i + 1; j < machines.size(); ++j) {
      const MachineFile& b = machines[j];
      EXPECT_NE(a.coefficients.size_exponent, b.coefficients.size_exponent) << a.name << " vs " << b.name;
      EXPECT_NE(a.runout_mm, b.runout_mm) << a.name << " vs " << b.name;
      EXPECT_NE(a.helix_offset_deg, b.helix_offset_deg) << a.name << " vs " << b.name;
    }
  }
}

// The seeded family (data/machines/family, scripts/generate-machine-family.sh): at least 12 machines, each
// read by the machine-file reader, applicable to the samples' four-flute 30° tool, and within the generator's
// ranges — the shape differences the learning is to meet: size effect 0.1–0.3, edge coefficients half to twice
// the library's, 2–8 µm eccentric runout (±1 µm per tooth), helix within ±5°, a 500–3000 Hz dynamometer with
// 2–10 N noise. Between them they cover most of each range.
TEST(MachineFile, TheFamilySpansTheRangesItWasDrawnFrom) {
  std::vector<MachineFile> family;
  for (const auto& entry : std::filesystem::directory_iterator(kSourceDir + "/data/machines/family")) {
    if (entry.path().extension() == ".yaml") family.push_back(load_machine_file(entry.path().string(), library()));
  }
  ASSERT_GE(family.size(), 12u);
  double m_lo = 1, m_hi = 0, edge_lo = 1e9, edge_hi = 0, bw_lo = 1e9, bw_hi = 0;
  for (const MachineFile& m : family) {
    SCOPED_TRACE(m.name);
    EXPECT_GE(m.coefficients.size_exponent, 0.1);
    EXPECT_LE(m.coefficients.size_exponent, 0.3);
    for (double edge : {m.coefficients.kte_n_per_mm, m.coefficients.kre_n_per_mm}) {
      EXPECT_GE(edge, 0.5 * 20 - 0.05);
      EXPECT_LE(edge, 2.0 * 20 + 0.05);
      edge_lo = std::min(edge_lo, edge);
      edge_hi = std::max(edge_hi, edge);
    }
    ASSERT_EQ(m.runout_mm.size(), 4u);
    double largest = 0;
    for (double r : m.runout_mm) largest = std::max(largest, std::abs(r));
    EXPECT_LE(largest, 0.009 + 1e-9);
    EXPECT_LE(std::abs(m.helix_offset_deg), 5.0);
    EXPECT_GE(m.dynamometer.bandwidth_hz, 500.0 - 0.5);
    EXPECT_LE(m.dynamometer.bandwidth_hz, 3000.0 + 0.5);
    EXPECT_GE(m.dynamometer.noise_n, 2.0);
    EXPECT_LE(m.dynamometer.noise_n, 10.0);
    SimulationRequest request;
    request.tool = geometry::Tool{"SC EM D10 Z4", 10.0, 4, 30.0};
    EXPECT_TRUE(apply_machine(m, request).empty());
    m_lo = std::min(m_lo, m.coefficients.size_exponent);
    m_hi = std::max(m_hi, m.coefficients.size_exponent);
    bw_lo = std::min(bw_lo, m.dynamometer.bandwidth_hz);
    bw_hi = std::max(bw_hi, m.dynamometer.bandwidth_hz);
  }
  EXPECT_LT(m_lo, 0.13);
  EXPECT_GT(m_hi, 0.27);
  EXPECT_LT(edge_lo, 12.0);
  EXPECT_GT(edge_hi, 33.0);
  EXPECT_LT(bw_lo, 700.0);
  EXPECT_GT(bw_hi, 2000.0);
}

TEST(MachineFile, RefusesEachBadFieldWithItsMessage) {
  EXPECT_TRUE(has_problem(problems_of(with_line(2, "material: S55C")), "m.yaml: material (line 2)",
                          "= \"S55C\": unknown material; known"));
  EXPECT_TRUE(has_problem(problems_of(with_line(3, "coefficients: {ktc_n_per_mm2: 0}")),
                          "m.yaml: coefficients.ktc_n_per_mm2 (line 3)", "= 0: must be > 0 N/mm² — replaces the material's value"));
  EXPECT_TRUE(has_problem(problems_of(with_line(3, "coefficients: {kte_n_per_mm: -1}")),
                          "m.yaml: coefficients.kte_n_per_mm (line 3)", "= -1: must be ≥ 0 N/mm"));
  EXPECT_TRUE(has_problem(problems_of(with_line(4, "size_effect: {exponent: 1, reference_chip_mm: 0.05}")),
                          "m.yaml: size_effect.exponent (line 4)", "= 1: must be in [0, 1)"));
  EXPECT_TRUE(has_problem(problems_of(with_line(4, "size_effect: {exponent: 0.2, reference_chip_mm: 0.05, min_chip_mm: 0.1}")),
                          "m.yaml: size_effect.min_chip_mm (line 4)", "= 0.1: must be in (0, 0.05] mm"));
  EXPECT_TRUE(has_problem(problems_of(with_line(5, "runout_mm: [0.005, 0.06, 0, 0]")), "m.yaml: runout_mm[1] (line 5)",
                          "= 0.06: must be in [-0.05, 0.05] mm — runout of tooth 2"));
  EXPECT_TRUE(has_problem(problems_of(with_line(5, "runout_mm: []")), "m.yaml: runout_mm (line 5)",
                          "must be a list of 1 to 16 radial runouts per tooth in mm"));
  EXPECT_TRUE(has_problem(problems_of(with_line(6, "helix_offset_deg: 16")), "m.yaml: helix_offset_deg (line 6)",
                          "= 16: must be in [-15, 15] deg — true helix − catalogue helix of the tool"));
  EXPECT_TRUE(has_problem(problems_of(with_line(7, "dynamometer: {bandwidth_hz: 0, noise_n: 8}")),
                          "m.yaml: dynamometer.bandwidth_hz (line 7)", "= 0: must be > 0 Hz"));
  EXPECT_TRUE(has_problem(problems_of(with_line(7, "dynamometer: {bandwidth_hz: 800, noise_n: -2}")),
                          "m.yaml: dynamometer.noise_n (line 7)", "= -2: must be ≥ 0 N"));
  EXPECT_TRUE(has_problem(problems_of(with_line(7, "dynamometer: {bandwidth_hz: 800, noise_n: 8, damping_ratio: 3}")),
                          "m.yaml: dynamometer.damping_ratio (line 7)", "= 3: must be in (0, 2]"));
  EXPECT_TRUE(has_problem(problems_of(with_line(6, "helix_ofset_deg: 2")), "m.yaml: helix_ofset_deg (line 6)",
                          "is not a known field; expected one of name, description, material, coefficients, size_effect, "
                          "runout_mm, helix_offset_deg, dynamometer (did you mean helix_offset_deg?)"));
  EXPECT_TRUE(has_problem(problems_of(with_line(6, "helix_ofset_deg: 2")), "m.yaml: helix_offset_deg",
                          "is missing: required — true helix − catalogue helix of the tool, deg"));
  EXPECT_THROW(read_machine_file("", "m.yaml", library()), InputError);
  EXPECT_THROW(read_machine_file("- a\n", "m.yaml", library()), InputError);
}

TEST(MachineFile, ApplyNeedsOneRunoutPerFlute) {
  const MachineFile m = read_machine_file(kValid, "m.yaml", library());
  SimulationRequest request;
  request.tool = {"D6 Z3", 6.0, 3, 35.0};
  const std::vector<InputProblem> problems = apply_machine(m, request);
  EXPECT_TRUE(has_problem(problems, "m.yaml: runout_mm", "has 4 values: must have one per flute, and the tool D6 Z3 has 3"));
  EXPECT_DOUBLE_EQ(request.tool.helix_deg, 35.0);  // unchanged on failure
  EXPECT_TRUE(request.options.runout_mm.empty());
}

// A straight down-milling cut, a_e 2 mm, a_p 10 mm, 0.05 mm per tooth at 2800 rpm, on `machine_text`
// (with a noise-free dynamometer fast enough to show each tooth).
SimulationResult cut_on(const std::string& machine_text) {
  const geometry::Tool tool{"D10 Z4", 10.0, 4, 30.0};
  CuttingTest test;
  test.radial_depth_mm = 2.0;
  test.axial_depth_mm = 10.0;
  test.spindle_rpm = 2800.0;
  test.feed_mm_per_min = 0.05 * 4 * 2800.0;
  test.cut_length_mm = 30.0;
  CuttingTestSetup setup = make_cutting_test(test, tool);
  SimulationRequest request;
  request.program = setup.program;
  request.stock = setup.stock;
  request.tool = tool;
  request.machine.max_accel_mm_per_s2 = 2000;
  EXPECT_TRUE(apply_machine(read_machine_file(machine_text, "m.yaml", library()), request).empty());
  return simulate(request);
}

std::string machine_with(const std::string& runout, double helix_offset_deg) {
  return "name: t\nmaterial: S50C\nrunout_mm: " + runout + "\nhelix_offset_deg: " + std::to_string(helix_offset_deg) +
         "\ndynamometer: {bandwidth_hz: 3000, noise_n: 0}\n";
}

// Mean over the steady part of the cut (tool centre 7 mm past the block's start to 7 mm before its end)
// of each tooth's largest |F_xy|, tooth by tooth (tooth periods counted from t = 0).
std::vector<double> tooth_peaks_n(const SimulationResult& result) {
  std::vector<double> sum(4, 0.0);
  std::vector<int> count(4, 0);
  const double tooth_period_s = 60.0 / 2800.0 / 4.0;
  long long period = -1;
  double peak = 0.0;
  for (const auto& row : result.log.rows) {
    if (row.x_mm < 7.0 || row.x_mm > 23.0) continue;
    const auto p = static_cast<long long>(std::floor(row.t_s / tooth_period_s));
    if (p != period) {
      if (period >= 0) sum[period % 4] += peak, ++count[period % 4];
      period = p;
      peak = 0.0;
    }
    peak = std::max(peak, std::hypot(row.fx_n, row.fy_n));
  }
  for (int j = 0; j < 4; ++j) sum[j] /= std::max(count[j], 1);
  return sum;
}

double spread(const std::vector<double>& values) {
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  return (*high - *low) / *high;
}

TEST(MachineFile, RunoutMakesTheTeethsPeaksDiffer) {
  const std::vector<double> even = tooth_peaks_n(cut_on(machine_with("[0, 0, 0, 0]", 0.0)));
  const std::vector<double> uneven = tooth_peaks_n(cut_on(machine_with("[0.008, 0.002, -0.004, -0.006]", 0.0)));
  EXPECT_LT(spread(even), 0.02);    // four equal teeth: equal peaks
  EXPECT_GT(spread(uneven), 0.15);  // chips 0.05 ± up to 0.014 mm: peaks tens of percent apart
}

TEST(MachineFile, HelixOffsetChangesTheShapeNotTheMean) {
  const SimulationResult catalogue = cut_on(machine_with("[0, 0, 0, 0]", 0.0));
  const SimulationResult steeper = cut_on(machine_with("[0, 0, 0, 0]", 5.0));
  const double mean_change = steeper.summary.mean_force_in_contact_n / catalogue.summary.mean_force_in_contact_n - 1.0;
  const double peak_change = steeper.summary.max_revolution_peak_n / catalogue.summary.max_revolution_peak_n - 1.0;
  std::printf("helix +5 deg: mean %+.2f %%, peak %+.2f %%\n", 100 * mean_change, 100 * peak_change);
  EXPECT_LT(std::abs(mean_change), 0.03);
  EXPECT_GT(std::abs(peak_change), 0.03);
}

}  // namespace
}  // namespace feedplan::sim
