// Metrics computed once, outside every simulator, from a trajectory and its contact events
// (rig.md section 5), so that every simulator is measured alike. Plain records; flatten() names
// every figure with its unit for the reporters.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "harness/scoring/impact_statistics.h"
#include "model/scenario.h"
#include "model/trajectory.h"

namespace ib {

constexpr double kStandardGravity_m_s2 = 9.80665;

struct MetricSettings {
  ScoringWindow window;                // where the metrics are taken (scoring_window(), model/scenario.h)
  double excitation_frequency_hz = 0;  // the motor's; 0: no excitation, no per-cycle metrics
  double natural_frequency_hz = 0;     // frame 1's f_1; with the excitation, defines the beat period
  double sensor_rate_hz = 2048;        // accelerometer sample rate f_s [Hz]
  double merge_window_s = 0.002;       // onsets closer than this belong to one impact [s]
  // the sensor peak is also read on grids shifted by j / P of 1/f_s, j = 0 .. P-1, those whose edges are
  // samples of the series (impact_statistics.h)
  int sensor_grid_phases = 8;
};

// One impact: contact episodes whose onsets follow each other within the merge window.
struct Impact {
  double onset_time_s = 0;           // first onset
  double end_time_s = 0;             // last separation
  double approach_velocity_m_s = 0;  // at the first onset
  double rebound_velocity_m_s = 0;   // at the last separation
  double restitution = 0;            // rebound / approach
  double peak_force_n = 0;           // largest of the episodes (NaN for instantaneous impacts)
  double impulse_n_s = 0;            // sum over the episodes
  double max_indentation_m = 0;      // largest of the episodes
  int onsets = 0;                    // raw contact episodes merged into this impact
};

// Impacts whose first onset lies in [start, end], merging onsets closer than merge_window_s.
std::vector<Impact> merge_impacts(const std::vector<ContactEvent>& events, double start_s, double end_s,
                                  double merge_window_s);

// The sensor's reading (rig.md section 5): a_s[k] = (u'(t_k + T/2) - u'(t_k - T/2)) / T, T = 1/f_s,
// at t_k = start + (k + 1/2) T for every window [t_k - T/2, t_k + T/2] inside [start, end]. The tip
// velocity is read from the series, linearly interpolated where the series has no sample at t_k +- T/2
// (none is needed when the series rate is a multiple of f_s and starts on the sensor's grid).
// grid_phase in [0, 1) shifts the grid by that fraction of T (t_k = start + (k + phase + 1/2) T): the
// experiment's grid is one of many, and where an impact falls on it moves the peak (docs/statistics.md).
struct SensorSeries {
  std::vector<double> time_s;
  std::vector<double> acceleration_m_s2;
};
SensorSeries sensor_acceleration(const Trajectory& trajectory, int frame, double start_s, double end_s,
                                 double sensor_rate_hz, double grid_phase = 0);

struct FrameMetrics {
  double sensor_peak_acceleration_g = 0;  // max |a_s| [g]
  double true_peak_acceleration_g = 0;    // max |a| the simulator resolves, between samples too [g]
  double rms_acceleration_g = 0;          // RMS of the sampled acceleration [g]
  double peak_displacement_m = 0;         // max |u| [m]
  // logarithmic decrement per cycle of the tip's displacement peaks over the window (amplitude_decay.h);
  // a free vibration's only (NaN with a motor: a forced steady state does not decay)
  double log_decrement = 0;
};

struct Metrics {
  std::array<FrameMetrics, 2> frames;
  int impacts = 0;                     // after merging
  int raw_onsets = 0;                  // contact episodes before merging (exposes flicker)
  double contact_duration_mean_s = 0;  // per impact, first onset to last separation; NaN without impacts
  double contact_duration_min_s = 0;
  double contact_duration_max_s = 0;
  double excitation_cycles = 0;           // window x excitation frequency
  double impacts_per_cycle = 0;           // NaN without excitation
  double beat_period_s = 0;               // 1 / |f_exc - f_1|; NaN when there is no beating
  double impacts_per_beat = 0;            // NaN when there is no beating
  double mean_restitution = 0;            // NaN without impacts
  double mean_approach_velocity_m_s = 0;  // NaN without impacts
  double max_penetration_m = 0;           // largest indentation of any impact (0 without impacts)
  double mean_impulse_n_s = 0;            // impulse per impact; NaN without impacts
  // (E(end of window) - E(0)) / E(0) of the rig's mechanical energy: the energy drift of an unforced run
  // (with elastic contact and no damping it must stay 0). NaN with a motor or without energy data.
  double energy_change_relative = 0;
  // Beside the maxima (impact_statistics.h): each frame's sensor peak over sensor_grid_phases grid phases,
  // and each impact's own figures, of which runs.csv holds the median and 95th percentile.
  std::array<GridPhaseSpread, 2> sensor_peak_over_grid_phases{};
  ImpactSamples impact_samples;
};

Metrics compute_metrics(const Trajectory& trajectory, const MetricSettings& settings);

// A run against the reference run of the same scenario and law.
struct MetricErrors {
  std::array<double, 2> sensor_peak_relative_error{};             // (run - ref) / ref [-]
  double contact_duration_relative_error = 0;                     // mean contact duration [-]
  double impacts_per_cycle_difference = 0;                        // run - ref [-]
  std::array<double, 2> displacement_relative_rms_error{};        // RMS(u - u_ref) / RMS(u_ref) over the window [-]
  std::array<double, 2> log_decrement_relative_error{};           // free decay [-]; NaN with a motor
  std::array<double, 2> sensor_peak_phase_mean_relative_error{};  // of the mean over grid phases [-]
  DistributionDistances impact_distribution_distances{};          // per-impact distributions (W1, KS)
};
MetricErrors compare_metrics(const Metrics& run, const Trajectory& run_trajectory, const Metrics& reference,
                             const Trajectory& reference_trajectory, const MetricSettings& settings);

// Every figure with its name and unit, in a fixed order: the one place the reporters take names from.
std::vector<std::pair<std::string, double>> flatten(const Metrics& metrics);
std::vector<std::pair<std::string, double>> flatten(const MetricErrors& errors, const std::string& prefix);

}  // namespace ib
