#pragma once
// Random cycles, force models and machines for the planner's seeded property tests (STYLE.md kind 2):
// corner roundings, trochoids, spirals and helical borings with random tools, cutting conditions, models
// rising in t_m, machines and plan options. The draws depend only on the generator's state, so a seed
// gives the same cases in every test that uses them (reproduce with FEEDPLAN_TEST_SEED and
// FEEDPLAN_TEST_COUNT, which the tests print).

#include <algorithm>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>

#include "feedplan/cycles/spec.hpp"
#include "feedplan/model/response_surface_model.hpp"
#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::planner::testing {

//! The unsigned number in the environment variable `name`, or `fallback` when it is not set.
inline unsigned env_or(const char* name, unsigned fallback) {
  const char* text = std::getenv(name);
  return text && *text ? static_cast<unsigned>(std::strtoul(text, nullptr, 10)) : fallback;
}

//! One random cycle and what to plan it with.
struct RandomCase {
  cycles::CycleSpec spec;
  PlanSettings settings;
  std::string description;
};

// A response-surface model that rises in t_m over [0, t_max] for every contact length up to
// `max_contact_mm` (a full turn of the tool circle, beyond the fitted L range too), as the physics does
// (redrawn until it does). A model falling somewhere would predict more force at a lower feed, and no
// feed schedule can hold a target then.
inline model::ResponseSurfaceModel random_model(std::mt19937_64& rng, double max_contact_mm) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (;;) {
    model::ResponseSurfaceModel model;
    model.chip_center_mm = 0.02 + 0.08 * u(rng);
    model.chip_scale_mm = 0.01 + 0.05 * u(rng);
    model.contact_length_center_mm = 1.0 + 6.0 * u(rng);
    model.contact_length_scale_mm = 0.5 + 3.0 * u(rng);
    model.beta = {100.0 + 400.0 * u(rng), 50.0 + 250.0 * u(rng), 100.0 * u(rng),
                  -10.0 + 20.0 * u(rng), -10.0 + 15.0 * u(rng),  -10.0 + 30.0 * u(rng)};
    model.range = {0.002 + 0.01 * u(rng), 0.1 + 0.2 * u(rng), 0.0, 4.0 + 12.0 * u(rng)};
    model.axial_depth_mm = 2.0 + 10.0 * u(rng);
    bool rising = true;
    for (int a = 0; a <= 20 && rising; ++a) {
      const double chip = model.range.chip_max_mm * a / 20.0;
      for (int b = 0; b <= 10 && rising; ++b) {
        const double length = max_contact_mm * b / 10.0;
        const double x1 = (chip - model.chip_center_mm) / model.chip_scale_mm;
        const double x2 = (length - model.contact_length_center_mm) / model.contact_length_scale_mm;
        rising = model.beta[1] + 2.0 * model.beta[3] * x1 + model.beta[5] * x2 > 0.0;
      }
    }
    if (rising) return model;
  }
}

//! A random cycle (corner, trochoid, spiral or helical boring) with its tool, machine, model and options.
inline RandomCase random_case(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uniform_int_distribution<int> pick(0, 3);
  RandomCase c;
  cycles::CycleSpec& spec = c.spec;
  const double d = 4.0 + 16.0 * u(rng);
  spec.tool = {"random", d, 2 + static_cast<int>(4 * u(rng)), 30.0};
  spec.spindle_rpm = 1000.0 + 9000.0 * u(rng);
  spec.axial_depth_mm = 0.5 * d + d * u(rng);
  const double r = 0.5 * d;
  const cycles::Direction direction = u(rng) < 0.5 ? cycles::Direction::kCcw : cycles::Direction::kCw;
  std::ostringstream text;
  switch (pick(rng)) {
    case 0: {
      cycles::CornerSpec corner;
      corner.corner_radius_mm = r * (1.05 + 3.0 * u(rng));
      corner.radial_depth_mm = d * (0.05 + 0.5 * u(rng));
      corner.corner_angle_deg = 45.0 + 130.0 * u(rng);
      corner.entry_heading_deg = 360.0 * u(rng);
      corner.wall_length_mm = d * (0.5 + 2.0 * u(rng));
      corner.direction = direction;
      spec.cycle = "corner";
      spec.geometry = corner;
      text << "corner R " << corner.corner_radius_mm << " R_d " << corner.radial_depth_mm;
      break;
    }
    case 1: {
      cycles::TrochoidSpec trochoid;
      trochoid.pitch_mm = d * (0.02 + 0.2 * u(rng));
      trochoid.loop_radius_mm = std::max(trochoid.pitch_mm * 1.5, d * (0.3 + 1.2 * u(rng)));
      trochoid.start = {0.0, 0.0};
      trochoid.end = {trochoid.pitch_mm * (1 + static_cast<int>(3 * u(rng))), 0.0};
      trochoid.direction = direction;
      spec.cycle = "trochoid";
      spec.geometry = trochoid;
      text << "trochoid R_t " << trochoid.loop_radius_mm << " p " << trochoid.pitch_mm;
      break;
    }
    case 2: {
      cycles::SpiralSpec spiral;
      spiral.initial_radius_mm = r * (1.1 + 1.5 * u(rng));
      spiral.pitch_mm = d * (0.05 + 0.2 * u(rng));
      spiral.final_radius_mm = spiral.initial_radius_mm + spiral.pitch_mm * (1 + static_cast<int>(2 * u(rng)));
      spiral.direction = direction;
      spec.cycle = "spiral";
      spec.geometry = spiral;
      text << "spiral R " << spiral.initial_radius_mm << "→" << spiral.final_radius_mm;
      break;
    }
    default: {
      cycles::HelicalBoringSpec bore;
      bore.hole_diameter_mm = d * (1.1 + 0.85 * u(rng));
      bore.pitch_mm = d * (0.05 + 0.2 * u(rng));
      bore.depth_mm = bore.pitch_mm * (1.0 + 2.0 * u(rng));
      bore.direction = direction;
      spec.cycle = "helical_boring";
      spec.axial_depth_mm = 0.0;
      spec.geometry = bore;
      text << "helical boring D_h " << bore.hole_diameter_mm << " pitch " << bore.pitch_mm;
      break;
    }
  }
  geometry::MachineLimits& m = spec.machine;
  m.max_feed_mm_per_min = 2000.0 + 18000.0 * u(rng);
  m.min_feed_mm_per_min = 1.0 + 99.0 * u(rng);
  m.max_accel_mm_per_s2 = 200.0 + 9800.0 * u(rng);
  m.rapid_feed_mm_per_min = 10000.0 + 30000.0 * u(rng);
  m.block_time_min_s = 0.005 * u(rng);
  c.settings.model = random_model(rng, 3.14159265358979 * d);
  c.settings.target_force_n = c.settings.model.beta[0] * (0.9 + 1.1 * u(rng));
  c.settings.spindle_rpm = spec.spindle_rpm;
  c.settings.machine = m;
  const double resolutions[] = {0.1, 1.0, 5.0};
  c.settings.options.feed_resolution_mm_per_min = resolutions[static_cast<int>(3 * u(rng)) % 3];
  c.settings.options.merge_tolerance = 0.05 * u(rng);
  text << ", D " << d << ", target " << c.settings.target_force_n << " N, a " << m.max_accel_mm_per_s2;
  c.description = text.str();
  return c;
}

}  // namespace feedplan::planner::testing
