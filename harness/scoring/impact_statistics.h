// Statistics that do not hang on one sample (docs/statistics.md): a run's headline peaks are maxima, set by
// one impact and by where it falls on the sensor's sampling grid. Beside them: each impact's own figures
// (their median and 95th percentile), their distributions' distances from the reference's (Wasserstein-1,
// Kolmogorov-Smirnov), and the sensor peak over several phases of the sensor's grid.
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "model/trajectory.h"

namespace ib {

struct Impact;        // metrics.h
struct SensorSeries;  // metrics.h

// One value per impact of the scoring window (merge_impacts), in impact order; NaN where the series does
// not reach the impact (left out of every statistic).
struct ImpactSamples {
  // the largest |a_s| of the sensor windows that overlap the impact's [first onset, last separation] [g]
  std::array<std::vector<double>, 2> sensor_peak_g;
  // the largest |a| the simulator resolved over the sample intervals that overlap it [g] (the Newton law:
  // without the impulse, as the run's true peak)
  std::array<std::vector<double>, 2> true_peak_g;
  std::vector<double> contact_duration_s;     // first onset to last separation
  std::vector<double> approach_velocity_m_s;  // at the first onset
  std::vector<double> restitution;            // rebound at the last separation / approach
};

// The per-impact distributions in their column order, each with its column stem and unit suffix:
// frame1_sensor_peak _g, frame2_sensor_peak _g, frame1_true_peak _g, frame2_true_peak _g,
// contact_duration _s, approach_velocity _m_s, restitution (none).
constexpr std::size_t kImpactDistributions = 7;
struct ImpactDistribution {
  std::string stem;
  std::string unit_suffix;
  const std::vector<double>* sample = nullptr;
};
std::array<ImpactDistribution, kImpactDistributions> impact_distributions(const ImpactSamples& samples);

// Each impact's figures: `sensor` is the reading of each frame on the experiment's grid (phase 0),
// computed at sensor_rate_hz over [start_s, end_s].
ImpactSamples impact_samples(const Trajectory& trajectory, const std::vector<Impact>& impacts,
                             const std::array<SensorSeries, 2>& sensor, double sensor_rate_hz, double start_s,
                             double end_s);

// The sensor peak of one frame read on the grids shifted by j T / P (j = 0 .. P-1, T = 1 / f_s) from the
// experiment's whose edges are all samples of the series: their mean, smallest and largest [g]. Phase 0,
// always read, is runs.csv's frameF_sensor_peak_acceleration_g; the others where the series has a sample
// every T / P or a divisor of it (at the default 4096 Hz: phases 0 and 1/2; from 8 x 2048 Hz: all 8).
struct GridPhaseSpread {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double mean_g = kNaN;
  double min_g = kNaN;
  double max_g = kNaN;
  int phases_read = 0;
};
GridPhaseSpread sensor_peak_over_grid_phases(const Trajectory& trajectory, int frame, double start_s, double end_s,
                                             double sensor_rate_hz, int phases);
// The same with the reading on the unshifted grid (phase 0) given, as compute_metrics has it already.
GridPhaseSpread sensor_peak_over_grid_phases(const Trajectory& trajectory, int frame, const SensorSeries& on_grid,
                                             double start_s, double end_s, double sensor_rate_hz, int phases);

// One per-impact distribution of a run against the reference's: W1 in the figure's unit, W1 over the
// reference's median, and the KS statistic. NaN where either has no impact (or the median is 0).
struct DistributionDistance {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double wasserstein1 = kNaN;
  double wasserstein1_relative = kNaN;
  double kolmogorov_smirnov = kNaN;
};
using DistributionDistances = std::array<DistributionDistance, kImpactDistributions>;
DistributionDistances distribution_distances(const ImpactSamples& run, const ImpactSamples& reference);

// The columns (metrics.h flatten()): each distribution's median and 95th percentile,
// e.g. frame1_sensor_peak_p50_g, frame1_sensor_peak_p95_g, ..., restitution_p95; and
// PREFIX + stem + _w1 + unit, _w1_relative, _ks for each distance.
std::vector<std::pair<std::string, double>> flatten_percentiles(const ImpactSamples& samples);
std::vector<std::pair<std::string, double>> flatten(const DistributionDistances& distances, const std::string& prefix);

}  // namespace ib
