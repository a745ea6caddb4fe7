#pragma once
// The Fourier series of a signal that repeats every spindle revolution, from n samples at equal steps over
// one revolution (private to the model module): what the sensor response (sensor_response.hpp) multiplies
// harmonic by harmonic. From the samples and back by Eigen's FFT (n log n for any n; the few hundred
// samples of a revolution are products of small primes); at one angle by the series directly (n/2 terms).
//
// Convention. Samples x_j at Ω_j = Ω_0 + 2π j / n, harmonics c_k = (1/n) Σ_j x_j e^{−ikΩ_j'} with
// Ω_j' = 2π j / n, k = 0 … ⌊n/2⌋, and the real series
//   x(Ω_0 + α) = Re Σ_k a_k c_k e^{ikα},   a_0 = 1, a_k = 2 for 0 < k < n/2, a_{n/2} = 1 (even n),
// which passes through every sample (the harmonic n/2 taken as a cosine through them).

#include <complex>
#include <span>
#include <vector>

#include "feedplan/model/sensor_response.hpp"

namespace feedplan::model::detail {

using Harmonics = std::vector<std::complex<double>>;  //!< c_k, k = 0 … ⌊n/2⌋

//! The harmonics of n ≥ 1 samples.
Harmonics revolution_harmonics(std::span<const double> samples);

//! The series at α = `angle_rad` past the first sample, of a revolution sampled at `samples` points.
double series_value(const Harmonics& harmonics, int samples, double angle_rad);

//! The series at the n = `samples` sample points.
std::vector<double> series_samples(const Harmonics& harmonics, int samples);

//! Multiplies each harmonic pair (x_k, y_k) by sensor_gain(sensor, k · revolution_hz).
void apply_sensor(const SensorResponse& sensor, double revolution_hz, Harmonics& x, Harmonics& y);

}  // namespace feedplan::model::detail
