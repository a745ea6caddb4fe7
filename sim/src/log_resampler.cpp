#include "log_resampler.hpp"

namespace feedplan::sim::detail {

namespace {

// The row at time `t_s` between `before` and `after`, weight `w` of `after` (0 ≤ w ≤ 1).
force_log::ForceLogRow interpolated(const force_log::ForceLogRow& before, const force_log::ForceLogRow& after,
                                    double t_s, double w) {
  auto mix = [&](double a, double b) { return a + w * (b - a); };
  force_log::ForceLogRow out;
  out.t_s = t_s;
  out.x_mm = mix(before.x_mm, after.x_mm);
  out.y_mm = mix(before.y_mm, after.y_mm);
  out.z_mm = mix(before.z_mm, after.z_mm);
  out.fx_n = mix(before.fx_n, after.fx_n);
  out.fy_n = mix(before.fy_n, after.fy_n);
  out.fz_n = mix(before.fz_n, after.fz_n);
  out.feed_mm_per_min = mix(before.feed_mm_per_min, after.feed_mm_per_min);
  out.spindle_rpm = w < 0.5 ? before.spindle_rpm : after.spindle_rpm;
  out.ix_a = mix(before.ix_a, after.ix_a);
  out.iy_a = mix(before.iy_a, after.iy_a);
  out.iz_a = mix(before.iz_a, after.iz_a);
  return out;
}

}  // namespace

void LogResampler::add(const force_log::ForceLogRow& step_row) {
  const double t = step_row.t_s;
  while (next_log_ * log_dt_ <= t + 1e-12) {
    const double tl = next_log_ * log_dt_;
    if (!have_previous_row_ || t <= previous_row_.t_s) {
      force_log::ForceLogRow out = step_row;
      out.t_s = tl;
      sink_.add(out);
    } else {
      const double w = (tl - previous_row_.t_s) / (t - previous_row_.t_s);
      sink_.add(interpolated(previous_row_, step_row, tl, w));
    }
    ++next_log_;
  }
  previous_row_ = step_row;
  have_previous_row_ = true;
}

}  // namespace feedplan::sim::detail
