// Per-impact figures, their distributions against the reference's, and the sensor peak over grid phases
// (docs/statistics.md). Everything here is linear in the samples of the window, or sorts the impacts.
#include "harness/scoring/impact_statistics.h"

#include <algorithm>
#include <cmath>

#include "harness/scoring/empirical_distribution.h"
#include "harness/scoring/metrics.h"

namespace ib {
namespace {

constexpr double kNoImpactFigure = std::numeric_limits<double>::quiet_NaN();

// The largest |a_s| of the sensor windows [t - T/2, t + T/2] that overlap [onset, end]; NaN if none does.
double sensor_peak_near(const SensorSeries& sensor, double half_window_s, double onset_s, double end_s) {
  const auto& centres = sensor.time_s;
  auto k = std::lower_bound(centres.begin(), centres.end(), onset_s - half_window_s);
  double peak = kNoImpactFigure;
  for (; k != centres.end() && *k - half_window_s <= end_s; ++k) {
    const double reading = std::abs(sensor.acceleration_m_s2[static_cast<std::size_t>(k - centres.begin())]);
    peak = std::isnan(peak) ? reading : std::max(peak, reading);
  }
  return peak;
}

// The largest |a| over the sample intervals (t_{k-1}, t_k] that overlap [onset, end], within the samples
// of [start, end of window]: the peak columns where the series has them (exact between samples), else the
// samples at both ends of those intervals. NaN where no sample of the window is near.
double true_peak_near(const Trajectory& t, int frame, std::size_t first, std::size_t last, double onset_s,
                      double end_s) {
  if (first >= last) return kNoImpactFigure;
  const auto begin = t.time_s.begin() + static_cast<std::ptrdiff_t>(first);
  const auto stop = t.time_s.begin() + static_cast<std::ptrdiff_t>(last);
  const auto from = static_cast<std::size_t>(std::lower_bound(begin, stop, onset_s) - t.time_s.begin());
  const auto to = static_cast<std::size_t>(std::lower_bound(begin, stop, end_s) - t.time_s.begin());
  const bool peak_columns = t.peak_abs_acceleration_m_s2[frame].size() == t.size();
  double peak = kNoImpactFigure;
  for (std::size_t k = from; k <= to && k < last; ++k) {
    // the window's first sample's peak column covers time before the window: its own value only
    double here =
        peak_columns && k > first ? t.peak_abs_acceleration_m_s2[frame][k] : std::abs(t.acceleration_m_s2[frame][k]);
    if (!peak_columns && k > first) here = std::max(here, std::abs(t.acceleration_m_s2[frame][k - 1]));
    peak = std::isnan(peak) ? here : std::max(peak, here);
  }
  return peak;
}

// Whether every edge start + k T of a sensor grid is a sample of the series (to a rounding error): then
// its readings need no velocity between samples. Linear velocity across a contact that one sample interval
// spans under-reads a window that cuts it, by several percent (docs/statistics.md): such grids are not read.
bool edges_on_samples(const Trajectory& t, double grid_start_s, double sensor_rate_hz) {
  if (t.output_rate_hz <= 0) return false;
  const auto whole = [](double x) { return std::abs(x - std::round(x)) < 1e-6; };
  return whole(t.output_rate_hz / sensor_rate_hz) && whole((grid_start_s - t.start_time_s) * t.output_rate_hz);
}

double peak_of(const SensorSeries& sensor) {
  if (sensor.acceleration_m_s2.empty()) return kNoImpactFigure;
  double peak = 0;
  for (double a : sensor.acceleration_m_s2) peak = std::max(peak, std::abs(a));
  return peak;
}

}  // namespace

std::array<ImpactDistribution, kImpactDistributions> impact_distributions(const ImpactSamples& s) {
  return {{{"frame1_sensor_peak", "_g", &s.sensor_peak_g[0]},
           {"frame2_sensor_peak", "_g", &s.sensor_peak_g[1]},
           {"frame1_true_peak", "_g", &s.true_peak_g[0]},
           {"frame2_true_peak", "_g", &s.true_peak_g[1]},
           {"contact_duration", "_s", &s.contact_duration_s},
           {"approach_velocity", "_m_s", &s.approach_velocity_m_s},
           {"restitution", "", &s.restitution}}};
}

ImpactSamples impact_samples(const Trajectory& trajectory, const std::vector<Impact>& impacts,
                             const std::array<SensorSeries, 2>& sensor, double sensor_rate_hz, double start_s,
                             double end_s) {
  ImpactSamples s;
  const double half_window_s = sensor_rate_hz > 0 ? 0.5 / sensor_rate_hz : 0;
  // the window's samples, with the tolerance of a window edge that lands a rounding error off a sample
  const double tolerance_s = trajectory.output_rate_hz > 0 ? 1e-6 / trajectory.output_rate_hz : 0;
  const auto& time = trajectory.time_s;
  const auto first =
      static_cast<std::size_t>(std::lower_bound(time.begin(), time.end(), start_s - tolerance_s) - time.begin());
  const auto last =
      static_cast<std::size_t>(std::upper_bound(time.begin(), time.end(), end_s + tolerance_s) - time.begin());
  for (const Impact& impact : impacts) {
    for (int f = 0; f < 2; ++f) {
      s.sensor_peak_g[f].push_back(sensor_peak_near(sensor[f], half_window_s, impact.onset_time_s, impact.end_time_s) /
                                   kStandardGravity_m_s2);
      s.true_peak_g[f].push_back(true_peak_near(trajectory, f, first, last, impact.onset_time_s, impact.end_time_s) /
                                 kStandardGravity_m_s2);
    }
    s.contact_duration_s.push_back(impact.end_time_s - impact.onset_time_s);
    s.approach_velocity_m_s.push_back(impact.approach_velocity_m_s);
    s.restitution.push_back(impact.restitution);
  }
  return s;
}

GridPhaseSpread sensor_peak_over_grid_phases(const Trajectory& trajectory, int frame, double start_s, double end_s,
                                             double sensor_rate_hz, int phases) {
  return sensor_peak_over_grid_phases(trajectory, frame,
                                      sensor_acceleration(trajectory, frame, start_s, end_s, sensor_rate_hz), start_s,
                                      end_s, sensor_rate_hz, phases);
}

GridPhaseSpread sensor_peak_over_grid_phases(const Trajectory& trajectory, int frame, const SensorSeries& on_grid,
                                             double start_s, double end_s, double sensor_rate_hz, int phases) {
  GridPhaseSpread spread;
  if (phases < 1 || sensor_rate_hz <= 0) return spread;
  double sum = 0;
  int read = 0;
  for (int j = 0; j < phases; ++j) {
    const double phase = static_cast<double>(j) / phases;
    if (j > 0 && !edges_on_samples(trajectory, start_s + phase / sensor_rate_hz, sensor_rate_hz)) continue;
    const double peak_g =
        peak_of(j == 0 ? on_grid : sensor_acceleration(trajectory, frame, start_s, end_s, sensor_rate_hz, phase)) /
        kStandardGravity_m_s2;
    if (std::isnan(peak_g)) return GridPhaseSpread{};  // a grid the series does not reach: no spread to speak of
    sum += peak_g;
    spread.min_g = read == 0 ? peak_g : std::min(spread.min_g, peak_g);
    spread.max_g = read == 0 ? peak_g : std::max(spread.max_g, peak_g);
    ++read;
  }
  spread.mean_g = sum / read;
  spread.phases_read = read;
  return spread;
}

DistributionDistances distribution_distances(const ImpactSamples& run, const ImpactSamples& reference) {
  DistributionDistances out;
  const auto run_distributions = impact_distributions(run), reference_distributions = impact_distributions(reference);
  for (std::size_t i = 0; i < kImpactDistributions; ++i) {
    const std::vector<double>& a = *run_distributions[i].sample;
    const std::vector<double>& b = *reference_distributions[i].sample;
    out[i].wasserstein1 = wasserstein1_distance(a, b);
    out[i].kolmogorov_smirnov = kolmogorov_smirnov_statistic(a, b);
    const double reference_median = quantile(b, 0.5);
    out[i].wasserstein1_relative = std::isnan(reference_median) || reference_median == 0
                                       ? kNoImpactFigure
                                       : out[i].wasserstein1 / std::abs(reference_median);
  }
  return out;
}

std::vector<std::pair<std::string, double>> flatten_percentiles(const ImpactSamples& samples) {
  std::vector<std::pair<std::string, double>> out;
  for (const ImpactDistribution& d : impact_distributions(samples)) {
    out.emplace_back(d.stem + "_p50" + d.unit_suffix, quantile(*d.sample, 0.5));
    out.emplace_back(d.stem + "_p95" + d.unit_suffix, quantile(*d.sample, 0.95));
  }
  return out;
}

std::vector<std::pair<std::string, double>> flatten(const DistributionDistances& distances, const std::string& prefix) {
  std::vector<std::pair<std::string, double>> out;
  const ImpactSamples no_samples;
  const auto names = impact_distributions(no_samples);
  for (std::size_t i = 0; i < kImpactDistributions; ++i) {
    out.emplace_back(prefix + names[i].stem + "_w1" + names[i].unit_suffix, distances[i].wasserstein1);
    out.emplace_back(prefix + names[i].stem + "_w1_relative", distances[i].wasserstein1_relative);
    out.emplace_back(prefix + names[i].stem + "_ks", distances[i].kolmogorov_smirnov);
  }
  return out;
}

}  // namespace ib
