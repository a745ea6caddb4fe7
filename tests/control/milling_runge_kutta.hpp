#pragma once
// Test helper: seed 004's plant (Eq. 3) and reference model (Eq. 6) integrated together by classical
// Runge–Kutta, written here from the paper's equations — apart from the module's state-space form, its
// matrix exponential and its substep simulator — as the continuous truth the discretisation and the
// controllers are judged against.
//
//   plant:      τ_m ḟ_a = f(t) − f_a,   τ_c Ḟ_p = K_p f_a − F_p,
//               f(kT + τ) = f_c,k + β (f_c,k − f_c,k−1) τ/T  (the β-FROH's output)
//   reference:  ÿ_m + 2ξω_n ẏ_m + ω_n² y_m = ω_n² F_r
//
// The hold's output is smooth inside a period and the steps are aligned with the periods, so RK4 keeps its
// fourth order; ∫ |F_p − y_m| dt and ∫ (F_p − y_m) dt are summed by the trapezoid rule on the RK grid.

#include <array>
#include <cmath>

namespace feedplan::control::test {

//! K_p / ((τ_m s + 1)(τ_c s + 1)).
struct PlantOde {
  double gain_n_s_per_mm = 0.0;
  double feed_drive_time_constant_s = 0.0;
  double cutting_time_constant_s = 0.0;
};

//! ω_n² / (s² + 2ξω_n s + ω_n²).
struct ReferenceOde {
  double damping_ratio = 0.75;
  double natural_frequency_rad_per_s = 1.0;
};

//! What a β-FROH holds over one period: f(kT + τ) = value + β (value − previous) τ/T.
struct HeldSamples {
  double value = 0.0;
  double previous = 0.0;
  double beta = 0.0;
};

//! Plant and reference model side by side, from rest.
struct ContinuousTruth {
  std::array<double, 2> plant{0.0, 0.0};      // f_a (mm/s), F_p (N)
  std::array<double, 2> reference{0.0, 0.0};  // y_m (N), ẏ_m (N/s)
  double absolute_area_n_s = 0.0;             // ∫ |F_p − y_m| dt so far
  double signed_area_n_s = 0.0;               // ∫ (F_p − y_m) dt so far

  //! One period T of `substeps` RK4 steps: the plant behind the β-FROH of (command, previous_command), the
  //! reference model under the constant `reference_input_n`. Returns F_p at the period's end.
  double step(const PlantOde& p, const ReferenceOde& r, double command, double previous_command, double beta,
              double reference_input_n, double period_s, int substeps) {
    return step(p, r, {command, previous_command, beta}, {reference_input_n, reference_input_n, 0.0}, period_s, substeps);
  }

  //! One period as above with the reference model behind its own hold `reference_input`.
  double step(const PlantOde& p, const ReferenceOde& r, const HeldSamples& command, const HeldSamples& reference_input,
              double period_s, int substeps) {
    const double h = period_s / substeps;
    const double wn = r.natural_frequency_rad_per_s;
    using State = std::array<double, 4>;
    auto rate = [&](const State& s, double tau_s) {
      const double fraction = tau_s / period_s;
      const double feed = command.value + command.beta * (command.value - command.previous) * fraction;
      const double force = reference_input.value + reference_input.beta * (reference_input.value - reference_input.previous) * fraction;
      return State{(feed - s[0]) / p.feed_drive_time_constant_s, (p.gain_n_s_per_mm * s[0] - s[1]) / p.cutting_time_constant_s,
                   s[3], wn * wn * (force - s[2]) - 2.0 * r.damping_ratio * wn * s[3]};
    };
    auto plus = [](const State& a, const State& b, double f) {
      return State{a[0] + f * b[0], a[1] + f * b[1], a[2] + f * b[2], a[3] + f * b[3]};
    };
    State s{plant[0], plant[1], reference[0], reference[1]};
    for (int i = 0; i < substeps; ++i) {
      const double t = i * h;
      const double error_before = s[1] - s[2];
      const State k1 = rate(s, t), k2 = rate(plus(s, k1, 0.5 * h), t + 0.5 * h), k3 = rate(plus(s, k2, 0.5 * h), t + 0.5 * h),
                  k4 = rate(plus(s, k3, h), t + h);
      for (int j = 0; j < 4; ++j) s[static_cast<std::size_t>(j)] += h / 6.0 * (k1[static_cast<std::size_t>(j)] + 2.0 * k2[static_cast<std::size_t>(j)] + 2.0 * k3[static_cast<std::size_t>(j)] + k4[static_cast<std::size_t>(j)]);
      const double error_after = s[1] - s[2];
      absolute_area_n_s += 0.5 * h * (std::abs(error_before) + std::abs(error_after));
      signed_area_n_s += 0.5 * h * (error_before + error_after);
    }
    plant = {s[0], s[1]};
    reference = {s[2], s[3]};
    return plant[1];
  }
};

}  // namespace feedplan::control::test
