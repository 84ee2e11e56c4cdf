#include "metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ib {

Metrics compute_metrics(const Trajectory& trajectory, const MetricWindow& window) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  Metrics m;
  m.window_start_s = window.start_s;
  m.window_end_s = window.end_s;
  double duration_sum = 0;
  for (const ContactEvent& e : trajectory.events) {
    if (e.onset_time_s < window.start_s || e.onset_time_s > window.end_s) continue;
    ++m.impacts;
    duration_sum += e.end_time_s - e.onset_time_s;
  }
  m.mean_contact_duration_s = m.impacts > 0 ? duration_sum / m.impacts : nan;
  m.excitation_cycles = (window.end_s - window.start_s) * window.excitation_frequency_hz;
  m.impacts_per_cycle = m.excitation_cycles > 0 ? m.impacts / m.excitation_cycles : nan;
  for (int f = 0; f < 2; ++f) {
    double peak = 0;
    for (std::size_t k = 0; k < trajectory.size(); ++k) {
      const double t = trajectory.time_s[k];
      if (t < window.start_s || t > window.end_s) continue;
      // the first sample of the window has no interval before it inside the window
      const double value = t == window.start_s ? std::abs(trajectory.acceleration_m_s2[f][k])
                                               : trajectory.peak_abs_acceleration_m_s2[f][k];
      peak = std::max(peak, value);
    }
    m.true_peak_acceleration_g[f] = peak / kStandardGravity_m_s2;
  }
  return m;
}

}  // namespace ib
