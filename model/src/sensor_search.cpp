#include "sensor_search.hpp"

#include <cmath>
#include <limits>

namespace feedplan::model::detail {
namespace {

constexpr double kMaxDamping = 0.5;
constexpr int kAxisRounds = 2;
constexpr double kAngleStepDeg = 5.0;

struct Search {
  const SensorSearchData& data;
  std::vector<double> frequencies_hz;
  std::vector<double> dampings;
  SensorResponse best;
  double best_residual = std::numeric_limits<double>::infinity();

  void consider(const SensorResponse& sensor) {
    const double r = sensor_residual(data, sensor);
    if (r < best_residual) {
      best_residual = r;
      best = sensor;
    }
  }

  //! Both modes at once (step 1), or mode `m` with the other held (step 2).
  void grid(int m) {
    const SensorResponse start = best;
    for (double f : frequencies_hz) {
      for (double zeta : dampings) {
        SensorResponse s = start;
        if (m < 0) {
          s.modes[0] = s.modes[1] = {f, zeta};
        } else {
          s.modes[static_cast<std::size_t>(m)] = {f, zeta};
        }
        consider(s);
      }
    }
  }
};

}  // namespace

double sensor_residual(const SensorSearchData& data, const SensorResponse& sensor) {
  Eigen::MatrixXd a(data.measured.size(), 4);
  Eigen::Index row = 0;
  for (std::size_t i = 0; i < data.binnings.size(); ++i) {
    const Eigen::MatrixXd rows = data.binnings[i]->rows(data.spectra[i], sensor);
    a.middleRows(row, rows.rows()) = rows;
    row += rows.rows();
  }
  const Eigen::VectorXd x = a.colPivHouseholderQr().solve(data.measured);
  return (a * x - data.measured).squaredNorm();
}

SensorResponse search_sensor(const SensorSearchData& data, double min_hz, double max_hz) {
  Search search{data, {}, {}, {}, std::numeric_limits<double>::infinity()};
  for (double f = min_hz; f <= max_hz; f *= kSensorSearchFrequencyRatio) search.frequencies_hz.push_back(f);
  for (double zeta = kSensorSearchMinDamping; zeta < kMaxDamping; zeta *= 2.0) search.dampings.push_back(zeta);

  search.grid(-1);
  for (int round = 0; round < kAxisRounds; ++round) {
    search.grid(0);
    search.grid(1);
  }
  const SensorResponse modes = search.best;
  for (double theta = -45.0 + kAngleStepDeg; theta <= 45.0; theta += kAngleStepDeg) {
    SensorResponse s = modes;
    s.mode_angle_deg = theta;
    search.consider(s);
  }
  search.grid(0);
  search.grid(1);
  return search.best;
}

}  // namespace feedplan::model::detail
