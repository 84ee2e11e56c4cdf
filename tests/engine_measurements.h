// Measurements the engine tests make on a run's sampled tip motion, written once: an impact from the
// indentation's zero crossings (rig.md section 5) and a free decay's frequency and damping ratio from the
// released tip's peaks. Independent of the harness's event detection, so that a test can check it too.
#pragma once

#include <cmath>
#include <optional>
#include <vector>

#include "model/trajectory.h"

namespace ib::testing {

// From the indentation's upward zero crossing (touch) to its downward one (separation), with the relative
// tip velocities there, both interpolated linearly between samples.
struct CrossingImpact {
  double duration_s = 0, restitution = 0, approach_m_s = 0;
};

inline std::optional<CrossingImpact> measure_impact(const Trajectory& t, double gap_m) {
  const auto indentation = [&](std::size_t k) { return t.displacement_m[0][k] - t.displacement_m[1][k] - gap_m; };
  const auto closing = [&](std::size_t k) { return t.velocity_m_s[0][k] - t.velocity_m_s[1][k]; };
  const auto crossing = [&](std::size_t k, double& time, double& rate) {
    const double a = indentation(k - 1), b = indentation(k), w = a / (a - b);
    time = t.time_s[k - 1] + w * (t.time_s[k] - t.time_s[k - 1]);
    rate = closing(k - 1) + w * (closing(k) - closing(k - 1));
  };
  double onset = 0, approach = 0, end = 0, rebound = 0;
  std::size_t k = 1;
  while (k < t.size() && !(indentation(k - 1) <= 0 && indentation(k) > 0)) ++k;
  if (k >= t.size()) return std::nullopt;
  crossing(k, onset, approach);
  while (k < t.size() && !(indentation(k - 1) > 0 && indentation(k) <= 0)) ++k;
  if (k >= t.size()) return std::nullopt;
  crossing(k, end, rebound);
  return CrossingImpact{end - onset, -rebound / approach, approach};
}

// Frequency and damping ratio of frame 1's tip from its positive peaks after from_s: the peaks' spacing
// gives the damped frequency, the slope of their logarithm -zeta omega (each peak refined by a parabola).
struct Decay {
  double frequency_hz = 0;
  double damping_ratio = 0;
  int peaks = 0;
};

inline Decay measure_decay(const Trajectory& t, double from_s) {
  const std::vector<double>& u = t.displacement_m[0];
  const double dt = 1 / t.output_rate_hz;
  std::vector<double> times, logs;
  for (std::size_t k = 1; k + 1 < u.size(); ++k) {
    if (t.time_s[k] < from_s || !(u[k] > 0 && u[k] > u[k - 1] && u[k] >= u[k + 1])) continue;
    const double a = u[k - 1], b = u[k], c = u[k + 1], shift = 0.5 * (a - c) / (a - 2 * b + c);
    times.push_back(t.time_s[k] + shift * dt);
    logs.push_back(std::log(b - 0.25 * (a - c) * shift));
  }
  Decay d;
  d.peaks = static_cast<int>(times.size());
  if (d.peaks < 3) return d;
  d.frequency_hz = (d.peaks - 1) / (times.back() - times.front());
  double mean_t = 0, mean_log = 0;
  for (int i = 0; i < d.peaks; ++i) mean_t += times[i] / d.peaks, mean_log += logs[i] / d.peaks;
  double sxy = 0, sxx = 0;
  for (int i = 0; i < d.peaks; ++i)
    sxy += (times[i] - mean_t) * (logs[i] - mean_log), sxx += (times[i] - mean_t) * (times[i] - mean_t);
  const double omega_d = 2 * M_PI * d.frequency_hz;
  const double ratio = (-sxy / sxx) / omega_d;  // zeta omega / omega_d = zeta / sqrt(1 - zeta^2)
  d.damping_ratio = ratio / std::sqrt(1 + ratio * ratio);
  return d;
}

}  // namespace ib::testing
