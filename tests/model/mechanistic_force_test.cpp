// The mechanistic force kernel against truths it does not compute itself: Altintas' closed-form mean
// forces of a straight cut, the size effect at one tooth element written out by hand, and a chip
// below the smallest chip (a constant size factor); the validation messages.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "feedplan/model/mechanistic_force.hpp"

namespace feedplan::model {
namespace {

constexpr double kPi = std::numbers::pi;

// Altintas' mean forces of a straight cut (Manufacturing Automation, 2nd ed., ch. 2, "average cutting
// forces"; docs/method.md §6.1), derived here. A tooth at immersion φ with chip h = c·sin φ feels, per
// unit axial depth, F_x = −(K_tc h + K_te) cos φ − (K_rc h + K_re) sin φ and
// F_y = (K_tc h + K_te) sin φ − (K_rc h + K_re) cos φ. The N teeth sweep each immersion once per
// revolution, so the mean is (N a / 2π) ∫_{φ_st}^{φ_ex} F dφ, with ∫ sin φ cos φ = −cos 2φ / 4,
// ∫ sin² φ = (2φ − sin 2φ) / 4:
//   F̄_x = (N a c / 8π)[K_tc cos 2φ − K_rc (2φ − sin 2φ)] + (N a / 2π)[−K_te sin φ + K_re cos φ],
//   F̄_y = (N a c / 8π)[K_tc (2φ − sin 2φ) + K_rc cos 2φ] − (N a / 2π)[K_te cos φ + K_re sin φ],
//   F̄_z = (N a / 2π)[−K_ac c cos φ + K_ae φ],   each from φ_st to φ_ex.
// The helix shifts each element's immersion but not the set of immersions swept: the mean does not
// depend on it.
MechanisticForce textbook_mean(int n, double a_mm, double c_mm, double phi_st, double phi_ex, const MechanisticModel& k) {
  auto fx = [&](double p) {
    return n * a_mm * c_mm / (8 * kPi) * (k.ktc_n_per_mm2 * std::cos(2 * p) - k.krc_n_per_mm2 * (2 * p - std::sin(2 * p))) +
           n * a_mm / (2 * kPi) * (-k.kte_n_per_mm * std::sin(p) + k.kre_n_per_mm * std::cos(p));
  };
  auto fy = [&](double p) {
    return n * a_mm * c_mm / (8 * kPi) * (k.ktc_n_per_mm2 * (2 * p - std::sin(2 * p)) + k.krc_n_per_mm2 * std::cos(2 * p)) -
           n * a_mm / (2 * kPi) * (k.kte_n_per_mm * std::cos(p) + k.kre_n_per_mm * std::sin(p));
  };
  auto fz = [&](double p) { return n * a_mm / (2 * kPi) * (-k.kac_n_per_mm2 * c_mm * std::cos(p) + k.kae_n_per_mm * p); };
  return {fx(phi_ex) - fx(phi_st), fy(phi_ex) - fy(phi_st), fz(phi_ex) - fz(phi_st)};
}

// Al7075-T6 (Altintas; docs/method.md §6.2).
MechanisticModel al7075() {
  MechanisticModel k;
  k.ktc_n_per_mm2 = 796;
  k.krc_n_per_mm2 = 169;
  k.kac_n_per_mm2 = 222;
  k.kte_n_per_mm = 27.7;
  k.kre_n_per_mm = 30.8;
  k.kae_n_per_mm = 1.4;
  return k;
}

// Mean of predicted_force over `steps` spindle angles of one revolution.
MechanisticForce sampled_mean(const MechanisticModel& model, std::span<const EngagedSection> sections,
                              const CutterGeometry& cutter, double fz_mm, int steps) {
  MechanisticForce mean;
  for (int i = 0; i < steps; ++i) {
    const MechanisticForce f = predicted_force(model, sections, cutter, fz_mm, 2 * kPi * (i + 0.5) / steps);
    mean.fx_n += f.fx_n / steps;
    mean.fy_n += f.fy_n / steps;
    mean.fz_n += f.fz_n / steps;
  }
  return mean;
}

// Relative error of `got` against `truth` in the XY plane (and z), over the size of the XY truth.
double relative_xy_error(const MechanisticForce& got, const MechanisticForce& truth) {
  return std::hypot(got.fx_n - truth.fx_n, got.fy_n - truth.fy_n) / std::hypot(truth.fx_n, truth.fy_n);
}

TEST(MechanisticForce, DesignCheckMeanForcesOfAl7075) {
  // docs/method.md §6.1: N 4, a 10, c 0.1, a_e 1.5 on r 5, down milling → F̄x 180.5 N, F̄y 295.2 N.
  const double phi_st = kPi - std::acos(1 - 1.5 / 5.0);
  const std::vector<ImmersionArc> arcs{{phi_st, kPi}};
  const std::vector<EngagedSection> sections{{0.0, 10.0, arcs}};
  const MechanisticForce mean = predicted_mean_force(al7075(), sections, {5.0, 4, 30.0}, 0.1);
  std::printf("Al7075 a_e 1.5 down: mean Fx %.2f N Fy %.2f N (docs: 180.5, 295.2)\n", mean.fx_n, mean.fy_n);
  EXPECT_NEAR(mean.fx_n, 180.5, 0.1);
  EXPECT_NEAR(mean.fy_n, 295.2, 0.1);
}

TEST(MechanisticForce, MeanOverARevolutionMatchesAltintasClosedForm) {
  struct Case {
    const char* name;
    double ae_mm;
    bool down;
  };
  const Case cases[] = {{"slot", 10, true}, {"down a_e 1.5", 1.5, true}, {"down a_e 7", 7, true},
                        {"up a_e 3", 3, false}, {"up a_e 0.5", 0.5, false}};
  double worst_sampled = 0.0, worst_mean = 0.0;
  for (int flutes : {3, 4}) {
    for (double helix : {0.0, 30.0, 45.0}) {
      for (const Case& c : cases) {
        const double alpha = std::acos(1 - std::min(c.ae_mm, 10.0) / 5.0);
        const double st = c.down ? kPi - alpha : 0.0, ex = c.down ? kPi : alpha;
        const std::vector<ImmersionArc> arcs{{st, ex}};
        // Two sections with the same arc: the kernel must add them as one 8 mm depth.
        const std::vector<EngagedSection> sections{{0.0, 3.0, arcs}, {3.0, 8.0, arcs}};
        const CutterGeometry cutter{5.0, flutes, helix};
        const MechanisticForce truth = textbook_mean(flutes, 8.0, 0.08, st, ex, al7075());
        const MechanisticForce sampled = sampled_mean(al7075(), sections, cutter, 0.08, 3600);
        const MechanisticForce mean = predicted_mean_force(al7075(), sections, cutter, 0.08);
        worst_sampled = std::max(worst_sampled, relative_xy_error(sampled, truth));
        worst_mean = std::max(worst_mean, relative_xy_error(mean, truth));
        EXPECT_LT(relative_xy_error(sampled, truth), 0.005) << c.name << " N " << flutes << " helix " << helix;
        EXPECT_LT(relative_xy_error(mean, truth), 0.005) << c.name << " N " << flutes << " helix " << helix;
        EXPECT_NEAR(sampled.fz_n, truth.fz_n, 0.005 * std::abs(truth.fz_n)) << c.name;
        EXPECT_NEAR(mean.fz_n, truth.fz_n, 0.005 * std::abs(truth.fz_n)) << c.name;
      }
    }
  }
  std::printf("closed-form mean forces: worst XY error %.2e (mean of 3600 angles), %.2e (predicted_mean_force)\n",
              worst_sampled, worst_mean);
}

TEST(MechanisticForce, RunoutMovesChipBetweenTeethButKeepsTheMeanWhileEveryToothCuts) {
  // On [π/4, 3π/4] with f_z 0.1 every tooth keeps h > 0 with runout {0.008, 0, 0, 0}: the teeth's chips
  // still add to N·f_z·sin φ, so the mean is the closed form's (the numerical path on 1° cells).
  MechanisticModel model = al7075();
  model.runout_mm = {0.008, 0.0, 0.0, 0.0};
  const std::vector<ImmersionArc> arcs{{kPi / 4, 3 * kPi / 4}};
  const std::vector<EngagedSection> sections{{0.0, 6.0, arcs}};
  const CutterGeometry cutter{5.0, 4, 30.0};
  const MechanisticForce truth = textbook_mean(4, 6.0, 0.1, kPi / 4, 3 * kPi / 4, model);
  const MechanisticForce sampled = sampled_mean(model, sections, cutter, 0.1, 3600);
  const MechanisticForce mean = predicted_mean_force(model, sections, cutter, 0.1);
  std::printf("runout, mid immersion: mean XY error %.2e (sampled), %.2e (predicted_mean_force)\n",
              relative_xy_error(sampled, truth), relative_xy_error(mean, truth));
  EXPECT_LT(relative_xy_error(sampled, truth), 0.005);
  EXPECT_LT(relative_xy_error(mean, truth), 0.005);
  // But the peak grows: tooth 0 cuts 0.008 mm more than the others.
  MechanisticModel true_tool = model;
  true_tool.runout_mm.clear();
  EXPECT_GT(predicted_peak_force_n(model, sections, cutter, 0.1), 1.02 * predicted_peak_force_n(true_tool, sections, cutter, 0.1));
}

TEST(MechanisticForce, SizeEffectAtOneStraightToothElement) {
  // One straight flute (helix 0), its tip at φ = 1 rad in a slot, a = 2 mm: the whole flute cuts
  // h = f_z sin 1, so F_t = a (K_tc (h/h_ref)^−m h + K_te), F_r likewise, by hand.
  MechanisticModel model = al7075();
  model.size_exponent = 0.25;
  model.size_reference_chip_mm = 0.05;
  const std::vector<ImmersionArc> arcs{{0.0, kPi}};
  const std::vector<EngagedSection> sections{{1.0, 3.0, arcs}};
  const double phi = 1.0, fz = 0.06;
  const double h = fz * std::sin(phi);
  const double s = std::pow(h / 0.05, -0.25);
  const double ft = 2.0 * (796 * s * h + 27.7), fr = 2.0 * (169 * s * h + 30.8), fa = 2.0 * (222 * s * h + 1.4);
  const MechanisticForce f = predicted_force(model, sections, {5.0, 1, 0.0}, fz, phi);
  EXPECT_NEAR(f.fx_n, -ft * std::cos(phi) - fr * std::sin(phi), 1e-9);
  EXPECT_NEAR(f.fy_n, ft * std::sin(phi) - fr * std::cos(phi), 1e-9);
  EXPECT_NEAR(f.fz_n, fa, 1e-9);
}

TEST(MechanisticForce, ChipsBelowTheSmallestChipScaleByAConstant) {
  // With h_min above every chip, the size factor is (h_min / h_ref)^−m everywhere: the forces are the
  // closed form's with the cutting coefficients scaled by it (helical flutes, numerical path).
  MechanisticModel model = al7075();
  model.size_exponent = 0.3;
  model.size_reference_chip_mm = 0.1;
  model.size_min_chip_mm = 0.05;  // above f_z = 0.04
  const double factor = std::pow(0.5, -0.3);
  MechanisticModel scaled = al7075();
  scaled.ktc_n_per_mm2 *= factor;
  scaled.krc_n_per_mm2 *= factor;
  scaled.kac_n_per_mm2 *= factor;
  const double alpha = std::acos(1 - 2.0 / 5.0);
  const std::vector<ImmersionArc> arcs{{kPi - alpha, kPi}};
  const std::vector<EngagedSection> sections{{0.0, 10.0, arcs}};
  const MechanisticForce truth = textbook_mean(4, 10.0, 0.04, kPi - alpha, kPi, scaled);
  const MechanisticForce mean = predicted_mean_force(model, sections, {5.0, 4, 30.0}, 0.04);
  EXPECT_LT(relative_xy_error(mean, truth), 0.005);
  EXPECT_LT(relative_xy_error(sampled_mean(model, sections, {5.0, 4, 30.0}, 0.04, 720), truth), 0.005);
}

// The largest |F_xy| by a dense scan of predicted_force, 256 angles per tooth period over the whole
// revolution, with every local maximum refined by golden-section search to 1e-6 rad.
double dense_peak_n(const MechanisticModel& model, std::span<const EngagedSection> sections,
                    const CutterGeometry& cutter, double fz_mm) {
  auto xy = [&](double angle) {
    const MechanisticForce f = predicted_force(model, sections, cutter, fz_mm, angle);
    return std::hypot(f.fx_n, f.fy_n);
  };
  const int count = 256 * cutter.flutes;
  const double step = 2 * kPi / count;
  std::vector<double> force(count);
  for (int i = 0; i < count; ++i) force[i] = xy(i * step);
  double peak = 0.0;
  for (int i = 0; i < count; ++i) {
    if (force[i] < force[(i + count - 1) % count] || force[i] < force[(i + 1) % count]) continue;
    double lo = (i - 1) * step, hi = (i + 1) * step;
    constexpr double kInvPhi = 0.6180339887498949;
    double x1 = hi - kInvPhi * (hi - lo), x2 = lo + kInvPhi * (hi - lo);
    double f1 = xy(x1), f2 = xy(x2);
    while (hi - lo > 1e-6) {
      if (f1 > f2) {
        hi = x2, x2 = x1, f2 = f1, x1 = hi - kInvPhi * (hi - lo), f1 = xy(x1);
      } else {
        lo = x1, x1 = x2, f1 = f2, x2 = lo + kInvPhi * (hi - lo), f2 = xy(x2);
      }
    }
    peak = std::max({peak, force[i], f1, f2});
  }
  return peak;
}

TEST(MechanisticForce, PeakWithRunoutMatchesADenseScanOverRandomEngagements) {
  std::mt19937 random(20261125);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0.0;
  for (int trial = 0; trial < 60; ++trial) {
    const CutterGeometry cutter{5.0, 2 + trial % 3, 45.0 * unit(random)};
    MechanisticModel model = al7075();
    if (trial % 2 == 0) model.size_exponent = 0.2;
    for (int j = 0; j < cutter.flutes; ++j) model.runout_mm.push_back(0.015 * (unit(random) - 0.5));
    std::vector<std::vector<ImmersionArc>> arcs;
    std::vector<EngagedSection> sections;
    const int count = 1 + trial % 3;
    for (int i = 0; i < count; ++i) {
      const double entry = -0.3 + (kPi - 0.2) * unit(random);
      arcs.push_back({{entry, std::min(kPi + 0.3, entry + 0.2 + (kPi - 0.2) * unit(random))}});
    }
    for (int i = 0; i < count; ++i) sections.push_back({3.0 * i, 3.0 * (i + 1), arcs[i]});
    const double fz_mm = 0.02 + 0.15 * unit(random);
    const double truth = dense_peak_n(model, sections, cutter, fz_mm);
    const double peak = predicted_peak_force_n(model, sections, cutter, fz_mm);
    ASSERT_GT(truth, 0.0);
    EXPECT_NEAR(peak, truth, 1e-4 * truth) << "trial " << trial;
    worst = std::max(worst, std::abs(peak - truth) / truth);
  }
  std::printf("peak with runout against a dense scan: worst relative error %.2e\n", worst);
}

// Many angles at once (one set-up for them all) give each angle's regressors exactly, with the size effect and
// runout whose tables the set-up builds; and with runout alone, the force they give averaged over a revolution
// is the closed form's mean (every tooth cuts on [π/4, 3π/4], as above).
TEST(MechanisticForce, RegressorsAtManyAnglesAreThoseAtEachAngle) {
  MechanisticModel model = al7075();
  model.size_exponent = 0.2;
  model.runout_mm = {0.008, -0.003, 0.0, 0.002};
  const std::vector<ImmersionArc> low{{1.6, 2.9}}, high{{0.4, 2.2}, {2.5, 3.0}};
  const std::vector<EngagedSection> sections{{0.0, 4.0, low}, {4.0, 10.0, high}};
  const CutterGeometry cutter{5.0, 4, 30.0};
  std::vector<double> angles;
  for (int i = 0; i < 97; ++i) angles.push_back(-1.0 + 0.0731 * i);
  const std::vector<ForceRegressors> many = regressors_at_angles(model, sections, cutter, 0.07, angles);
  ASSERT_EQ(many.size(), angles.size());
  for (std::size_t i = 0; i < angles.size(); ++i) {
    const ForceRegressors one = regressors(model, sections, cutter, 0.07, angles[i]);
    for (std::size_t row = 0; row < one.rows.size(); ++row) {
      for (std::size_t c = 0; c < one.rows[row].size(); ++c) {
        EXPECT_EQ(many[i].rows[row][c], one.rows[row][c]) << "angle " << angles[i] << " row " << row << " column " << c;
      }
    }
  }

  model.size_exponent = 0.0;
  model.runout_mm = {0.008, 0.0, 0.0, 0.0};
  const std::vector<ImmersionArc> mid{{kPi / 4, 3 * kPi / 4}};
  const std::vector<EngagedSection> cut{{0.0, 6.0, mid}};
  std::vector<double> revolution;
  for (int i = 0; i < 3600; ++i) revolution.push_back(2 * kPi * (i + 0.5) / 3600);
  const std::array<double, 6> k = coefficients(model);
  MechanisticForce mean;
  for (const ForceRegressors& r : regressors_at_angles(model, cut, cutter, 0.1, revolution)) {
    for (std::size_t c = 0; c < k.size(); ++c) {
      mean.fx_n += r.rows[0][c] * k[c] / 3600;
      mean.fy_n += r.rows[1][c] * k[c] / 3600;
    }
  }
  EXPECT_LT(relative_xy_error(mean, textbook_mean(4, 6.0, 0.1, kPi / 4, 3 * kPi / 4, model)), 0.005);
}

TEST(MechanisticForce, NothingEngagedGivesNoForce) {
  const std::vector<ImmersionArc> back{{-kPi / 2, 0.0}};  // behind the feed: no chip without runout
  const std::vector<EngagedSection> sections{{0.0, 10.0, back}, {10.0, 10.0, {}}};
  EXPECT_EQ(predicted_peak_force_n(al7075(), sections, {5.0, 4, 30.0}, 0.1), 0.0);
}

TEST(MechanisticForce, ValidationNamesEveryField) {
  MechanisticModel model = al7075();
  model.ktc_n_per_mm2 = std::nan("");
  model.kae_n_per_mm = INFINITY;
  model.size_exponent = 1.0;
  model.size_reference_chip_mm = 0.0;
  model.size_min_chip_mm = -0.001;
  model.runout_mm = {0.01, std::nan(""), 0.0};
  const CutterGeometry cutter{-5.0, 4, 90.0};
  std::vector<std::string> got;
  for (const InputProblem& p : validate(model, cutter)) got.push_back(to_string(p));
  const std::vector<std::string> expected{
      "mechanistic.ktc_n_per_mm2 = nan: must be finite",
      "mechanistic.kae_n_per_mm = inf: must be finite",
      "mechanistic.size_exponent = 1: must be in [0, 1)",
      "mechanistic.size_reference_chip_mm = 0: must be finite and > 0",
      "mechanistic.size_min_chip_mm = -0.001: must be finite and > 0",
      "mechanistic.runout_mm[1] = nan: must be finite",
      "mechanistic.cutter.radius_mm = -5: must be finite and > 0",
      "mechanistic.cutter.helix_deg = 90: must be in (−90, 90)",
      "mechanistic.runout_mm has 3 values: must be empty or one per flute (4)",
  };
  EXPECT_EQ(got, expected);
  EXPECT_TRUE(validate(al7075(), CutterGeometry{}).empty());
  const CutterGeometry no_flutes{5.0, 0, 30.0};
  ASSERT_EQ(validate(al7075(), no_flutes, "model.").size(), 1u);
  EXPECT_EQ(to_string(validate(al7075(), no_flutes, "model.")[0]), "model.cutter.flutes = 0: must be ≥ 1");
}

}  // namespace
}  // namespace feedplan::model
