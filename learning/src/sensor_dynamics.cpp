#include "feedplan/learning/sensor_dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>

#include <unsupported/Eigen/FFT>

#include "feedplan/core/angle.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/geometry/chip_load.hpp"
#include "feedplan/model/mechanistic_force.hpp"
#include "feedplan/model/sensed_peak.hpp"
#include "feedplan/planner/engaged_sections.hpp"

namespace feedplan::learning {

namespace {

// H(iω) of the sensor at frequency f (Hz; negative frequencies give the conjugate).
std::complex<double> response(double f_hz, const SensorDynamics& sensor) {
  const double r = f_hz / sensor.natural_frequency_hz;
  return 1.0 / std::complex<double>(1.0 - r * r, 2.0 * sensor.damping_ratio * r);
}

}  // namespace

void check_sensor_dynamics(const SensorDynamics& sensor, const std::string& frequency_field,
                           const std::string& damping_field) {
  std::vector<InputProblem> problems;
  if (!(std::isfinite(sensor.natural_frequency_hz) && sensor.natural_frequency_hz > 0.0)) {
    problems.push_back({frequency_field, "= " + shortest_number_text(sensor.natural_frequency_hz) +
                                             ": must be the sensor's natural frequency in Hz (> 0)"});
  }
  if (!(sensor.damping_ratio > 0.0 && sensor.damping_ratio <= 2.0)) {
    problems.push_back({damping_field, "= " + shortest_number_text(sensor.damping_ratio) +
                                           ": must be the sensor's damping ratio, in (0, 2]"});
  }
  if (!problems.empty()) throw InputError(std::move(problems));
}

double periodic_peak_gain(const std::vector<double>& waveform, double fundamental_hz, const SensorDynamics& sensor) {
  const std::size_t n = waveform.size();
  const double peak = n < 2 ? 0.0 : *std::max_element(waveform.begin(), waveform.end());
  if (!(peak > 0.0)) return 1.0;
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> spectrum;
  fft.fwd(spectrum, waveform);
  for (std::size_t k = 0; k < n; ++k) {
    // Harmonic k, or −(n − k) above the middle (the conjugate half of a real signal's spectrum).
    const double harmonic = k <= n / 2 ? static_cast<double>(k) : static_cast<double>(k) - static_cast<double>(n);
    spectrum[k] *= response(harmonic * fundamental_hz, sensor);
  }
  std::vector<std::complex<double>> reading;
  fft.inv(reading, spectrum);
  double read_peak = 0.0;
  for (const auto& y : reading) read_peak = std::max(read_peak, y.real());
  return read_peak / peak;
}

std::vector<bool> steady_engagement(const geometry::EngagementProfile& profile, const std::vector<double>& half_window_mm) {
  const std::vector<geometry::EngagementSample>& samples = profile.samples;
  const std::size_t n = samples.size();
  std::vector<bool> steady(n, false);
  if (half_window_mm.size() != n) return steady;
  const auto alike = [](const geometry::EngagementSample& a, const geometry::EngagementSample& b) {
    return b.layer_count > 0 && std::abs(b.engagement_rad - a.engagement_rad) <= kSteadySensorSpreadRad &&
           std::abs(b.axial_depth_mm - a.axial_depth_mm) <= kSteadySensorDepthSpread * a.axial_depth_mm;
  };
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const geometry::EngagementSample& sample = samples[i];
    if (sample.layer_count == 0 || !(half_window_mm[i] >= 0.0)) continue;
    // The two neighbours count however far they are: a coarse profile does not make every sample steady.
    bool all_alike = alike(sample, samples[i - 1]) && alike(sample, samples[i + 1]);
    for (std::size_t j = i + 1; all_alike && j < n && samples[j].s_mm <= sample.s_mm + half_window_mm[i]; ++j) {
      all_alike = alike(sample, samples[j]);
    }
    for (std::size_t j = i; all_alike && j-- > 0 && samples[j].s_mm >= sample.s_mm - half_window_mm[i];) {
      all_alike = alike(sample, samples[j]);
    }
    steady[i] = all_alike;
  }
  return steady;
}

namespace {

// The kernel's factor at one steady sample: its sensed peak over its force's peak, the smallest over the
// model as given and the variants of it the machine may be (kKernelHelixDoubtDeg, kKernelEdgeDoubt), or the
// first at or under the cap; 0 when it has none.
double kernel_gain(const geometry::EngagementProfile& profile, const geometry::EngagementSample& sample,
                   const geometry::Tool& tool, double spindle_rpm, const SensorDynamics& sensor,
                   const model::MechanisticModel& kernel, double feed_per_tooth_mm) {
  model::SensorResponse response;
  response.modes[0] = {sensor.natural_frequency_hz, sensor.damping_ratio};
  response.modes[1] = response.modes[0];
  const model::CutterGeometry cutter = planner::cutter_geometry(tool);
  const planner::SampleSections sections(profile, sample);
  const double helix_deg = kernel.helix_deg.value_or(cutter.helix_deg);
  std::vector<model::MechanisticModel> variants(5, kernel);
  variants[1].helix_deg = helix_deg - kKernelHelixDoubtDeg;
  variants[2].helix_deg = helix_deg + kKernelHelixDoubtDeg;
  for (const double scale : {1.0 / kKernelEdgeDoubt, kKernelEdgeDoubt}) {
    model::MechanisticModel& edge = variants[scale < 1.0 ? 3 : 4];
    edge.kte_n_per_mm *= scale;
    edge.kre_n_per_mm *= scale;
  }
  double smallest = 0.0;
  for (const model::MechanisticModel& variant : variants) {
    const model::SensedPeak peak =
        model::predicted_sensed_peak(variant, sections.sections(), cutter, feed_per_tooth_mm, response, spindle_rpm);
    if (!(peak.force_peak_n > 0.0 && std::isfinite(peak.force_n))) return 0.0;
    const double gain = peak.force_n / peak.force_peak_n;
    smallest = smallest > 0.0 ? std::min(smallest, gain) : gain;
    if (smallest <= kMaxSensorPeakGain) break;  // the cap it is: the other variants cannot raise it
  }
  return smallest;
}

}  // namespace

std::vector<double> sensor_peak_gains(const geometry::EngagementProfile& profile, const geometry::Tool& tool,
                                      double spindle_rpm, const SensorDynamics& sensor, const SensorKernel& kernel) {
  const double tooth_hz = spindle_rpm * tool.flutes / 60.0;
  const bool with_kernel = kernel.model && kernel.feed_mm_per_min.size() == profile.samples.size() &&
                           sensor.damping_ratio < 1.0 && validate(*kernel.model, planner::cutter_geometry(tool)).empty();
  std::vector<double> half_window_mm(profile.samples.size(), -1.0);
  if (with_kernel) {
    for (std::size_t i = 0; i < half_window_mm.size(); ++i) {
      half_window_mm[i] = kSteadySensorToothPeriods * kernel.feed_mm_per_min[i] / (spindle_rpm * tool.flutes);
    }
  }
  const std::vector<bool> steady = steady_engagement(profile, half_window_mm);
  std::vector<double> gains(profile.samples.size(), 1.0);
  // The last kernel evaluation, reused while the engagement and the feed per tooth stay alike.
  const geometry::EngagementSample* cached = nullptr;
  double cached_feed_per_tooth_mm = 0.0, cached_gain = 0.0;
  for (std::size_t i = 0; i < profile.samples.size(); ++i) {
    const geometry::EngagementSample& sample = profile.samples[i];
    if (sample.layer_count == 0) continue;
    const double chip_shape_gain = periodic_peak_gain(geometry::chip_load_waveform_mm(profile, sample, tool), tooth_hz, sensor);
    const double feed_per_tooth_mm = with_kernel ? kernel.feed_mm_per_min[i] / (spindle_rpm * tool.flutes) : 0.0;
    // Where the chip's shape is within the cap, the kernel cannot change the factor (min(chip, max(cap, …))).
    if (steady[i] && feed_per_tooth_mm > 0.0 && chip_shape_gain > kMaxSensorPeakGain) {
      const bool alike = cached && std::abs(cached->engagement_rad - sample.engagement_rad) <= kSteadySensorSpreadRad &&
                         std::abs(cached->axial_depth_mm - sample.axial_depth_mm) <= kSteadySensorDepthSpread * sample.axial_depth_mm &&
                         std::abs(cached_feed_per_tooth_mm - feed_per_tooth_mm) <= kKernelFeedSpread * feed_per_tooth_mm;
      if (!alike) {
        cached = &sample;
        cached_feed_per_tooth_mm = feed_per_tooth_mm;
        cached_gain = kernel_gain(profile, sample, tool, spindle_rpm, sensor, *kernel.model, feed_per_tooth_mm);
      }
      if (cached_gain > 0.0) {  // more than the cap only where the kernel, whatever the machine, agrees
        gains[i] = std::min(chip_shape_gain, std::max(cached_gain, kMaxSensorPeakGain));
        continue;
      }
    }
    gains[i] = std::min(chip_shape_gain, kMaxSensorPeakGain);
  }
  return gains;
}

}  // namespace feedplan::learning
