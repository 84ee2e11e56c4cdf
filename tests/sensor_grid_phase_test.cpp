// The sensor peak read on grids shifted by fractions of its window T (impact_statistics.h) on a pulse
// whose phase average has a closed form. A constant acceleration A over tau <= T moves the velocity by
// A tau; a window that holds the whole contact reads A tau / T, one that an edge cuts at b after the onset
// holds the larger part, max(b, tau - b). Over a uniform phase the edge cuts the contact with probability
// tau / T, at a uniform b, where max(b, tau - b) averages 3 tau / 4: the mean peak is
// A tau / T (1 - tau / (4 T)). P phases give that mean exactly when the edges fall at the middles of P equal
// cells of [0, T) and tau is a multiple of 2 T / P (the corners of max(b, tau - b) on cell boundaries).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "harness/scoring/impact_statistics.h"
#include "harness/scoring/metrics.h"
#include "metric_signals.h"

namespace ib {
namespace sensor_grid_phase_test {

using namespace test;

constexpr double kSensorRate = 2048, kT = 1 / kSensorRate;
constexpr int kSamplesPerWindow = 64, kPhases = 8;
constexpr double kRate = kSensorRate * kSamplesPerWindow;
constexpr double kA = 4000;  // [m/s^2]

// One pulse of `samples` samples from 4 samples (T / (2 P)) after a sensor window's start, sampled
// finely enough that its velocity's corners are samples (read linearly in between, exactly).
Trajectory pulse(int samples) {
  const double onset_s = (kSamplesPerWindow * 100 + 4) / kRate, end_s = onset_s + samples / kRate;
  Motion m;
  m.v = [=](double t) { return kA * std::clamp(t - onset_s, 0.0, end_s - onset_s); };
  return sampled(kRate, 0, static_cast<std::size_t>(0.1 * kRate) + 1, m);
}

double closed_form_mean_g(double tau_s) { return kA * tau_s / kT * (1 - tau_s / (4 * kT)) / g; }

TEST(SensorGridPhase, MeanOverPhasesIsTheClosedFormPhaseAverage) {
  for (int samples : {32, 16}) {  // tau = T / 2 and T / 4, multiples of 2 T / P
    const double tau_s = samples / kRate;
    const Trajectory t = pulse(samples);
    const GridPhaseSpread spread = sensor_peak_over_grid_phases(t, 0, 0, 0.1, kSensorRate, kPhases);
    EXPECT_NEAR(spread.mean_g, closed_form_mean_g(tau_s), 1e-9 * closed_form_mean_g(tau_s)) << samples;
    // the largest: the whole contact in one window; the smallest: the edge nearest its middle, T / (2 P) off
    EXPECT_NEAR(spread.max_g, kA * tau_s / kT / g, 1e-9 * spread.max_g) << samples;
    EXPECT_NEAR(spread.min_g, kA * (tau_s / 2 + kT / (2 * kPhases)) / kT / g, 1e-9 * spread.max_g) << samples;
  }
}

// One phase is the experiment's grid alone: runs.csv's sensor peak.
TEST(SensorGridPhase, OnePhaseIsTheExperimentsGrid) {
  const Trajectory t = pulse(32);
  MetricSettings s = window(0, 0.1);
  s.sensor_rate_hz = kSensorRate;
  s.sensor_grid_phases = 1;
  const Metrics m = compute_metrics(t, s);
  EXPECT_EQ(m.sensor_peak_over_grid_phases[0].mean_g, m.frames[0].sensor_peak_acceleration_g);
  EXPECT_EQ(m.sensor_peak_over_grid_phases[0].min_g, m.sensor_peak_over_grid_phases[0].max_g);
  s.sensor_grid_phases = kPhases;  // the default's phases include that grid
  const Metrics phased = compute_metrics(t, s);
  EXPECT_LE(phased.sensor_peak_over_grid_phases[0].min_g, m.frames[0].sensor_peak_acceleration_g);
  EXPECT_GE(phased.sensor_peak_over_grid_phases[0].max_g, m.frames[0].sensor_peak_acceleration_g);
}

// A grid whose edges fall between samples would read the velocity linearly across a contact: it is not
// read. At 4096 Hz, two samples per window, phases 0 and 1/2 are read; a rate that is no multiple of f_s
// reads the experiment's grid alone.
TEST(SensorGridPhase, OnlyGridsWhoseEdgesAreSamplesAreRead) {
  const Trajectory fine = pulse(32);
  EXPECT_EQ(sensor_peak_over_grid_phases(fine, 0, 0, 0.1, kSensorRate, kPhases).phases_read, kPhases);

  const double rate = 2 * kSensorRate, onset_s = 0.05 + 0.3 / rate, end_s = onset_s + 0.5 / kSensorRate;
  Motion m;
  m.v = [=](double t) { return kA * std::clamp(t - onset_s, 0.0, end_s - onset_s); };
  const Trajectory coarse = sampled(rate, 0, static_cast<std::size_t>(0.1 * rate) + 1, m);
  const GridPhaseSpread spread = sensor_peak_over_grid_phases(coarse, 0, 0, 0.1, kSensorRate, kPhases);
  EXPECT_EQ(spread.phases_read, 2);
  auto peak_g = [&](double phase) {
    double peak = 0;
    for (double a : sensor_acceleration(coarse, 0, 0, 0.1, kSensorRate, phase).acceleration_m_s2)
      peak = std::max(peak, std::abs(a));
    return peak / g;
  };
  EXPECT_NEAR(spread.mean_g, 0.5 * (peak_g(0) + peak_g(0.5)), 1e-12 * spread.max_g);
  EXPECT_NE(peak_g(0), peak_g(0.5));

  const Trajectory off_grid = sampled(3000, 0, 301, m);
  EXPECT_EQ(sensor_peak_over_grid_phases(off_grid, 0, 0, 0.1, kSensorRate, kPhases).phases_read, 1);
}

// The shifted grids stay inside the window: one window fewer where the shift pushes the last past its end.
TEST(SensorGridPhase, AShiftedGridEndsByTheWindowsEnd) {
  const Trajectory t = pulse(32);
  const SensorSeries on_grid = sensor_acceleration(t, 0, 0, 0.1, kSensorRate);
  // 0.1 s holds 204.8 windows: 204 on the grid, 203 on the grid shifted by 0.9 T
  const SensorSeries shifted = sensor_acceleration(t, 0, 0, 0.1, kSensorRate, 0.9);
  EXPECT_EQ(on_grid.time_s.size(), 204u);
  EXPECT_EQ(shifted.time_s.size(), 203u);
  EXPECT_NEAR(shifted.time_s.front(), 1.4 * kT, 1e-15);  // start + (0 + 0.9 + 1/2) T
  EXPECT_LE(shifted.time_s.back() + kT / 2, 0.1 + 1e-12);
}

}  // namespace sensor_grid_phase_test
}  // namespace ib
