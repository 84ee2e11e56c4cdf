// Metrics computed once from any simulator's trajectory and events (rig.md section 5), so that every
// simulator is measured alike. Plain records.
#pragma once

#include <array>

#include "trajectory.h"

namespace ib {

constexpr double kStandardGravity_m_s2 = 9.80665;

// The time window metrics are taken over, and the excitation that defines a cycle.
struct MetricWindow {
  double start_s = 0;
  double end_s = 0;
  double excitation_frequency_hz = 0;   // 0: no excitation (free vibration), no per-cycle metrics
};

struct Metrics {
  double window_start_s = 0, window_end_s = 0;
  int impacts = 0;                       // contact episodes with onset in the window
  double excitation_cycles = 0;          // window length x excitation frequency [-]
  double impacts_per_cycle = 0;          // NaN without excitation
  double mean_contact_duration_s = 0;    // NaN without impacts
  std::array<double, 2> true_peak_acceleration_g{};  // max |tip acceleration| in the window [g]
};

Metrics compute_metrics(const Trajectory& trajectory, const MetricWindow& window);

}  // namespace ib
