// Trajectories built by hand for the metric tests (metrics_test, sensor_reading_test,
// metric_comparison_test): synthetic signals whose answers are known in closed form.
#pragma once

#include <cmath>
#include <cstddef>
#include <functional>

#include "harness/scoring/metrics.h"

namespace ib::test {

constexpr double kPi = 3.14159265358979323846;
constexpr double g = kStandardGravity_m_s2;

// ---- building trajectories by hand ----------------------------------------------------------------

// A tip motion as functions of time: displacement, velocity, acceleration.
struct Motion {
  std::function<double(double)> u = [](double) { return 0.0; };
  std::function<double(double)> v = [](double) { return 0.0; };
  std::function<double(double)> a = [](double) { return 0.0; };
};

// n samples at `rate` from t0 of both frames' motions. The peak columns hold the sampled |a|: a
// test that needs peaks between samples overwrites them.
inline Trajectory sampled(double rate, double t0, std::size_t n, const Motion& frame1, const Motion& frame2 = {}) {
  Trajectory t;
  t.output_rate_hz = rate;
  t.start_time_s = t0;
  t.reserve(n);
  const Motion* frames[2] = {&frame1, &frame2};
  for (std::size_t k = 0; k < n; ++k) {
    const double time = t0 + static_cast<double>(k) / rate;
    t.time_s.push_back(time);
    for (int f = 0; f < 2; ++f) {
      t.displacement_m[f].push_back(frames[f]->u(time));
      t.velocity_m_s[f].push_back(frames[f]->v(time));
      t.acceleration_m_s2[f].push_back(frames[f]->a(time));
      t.peak_abs_acceleration_m_s2[f].push_back(std::abs(frames[f]->a(time)));
    }
    t.contact_force_n.push_back(0);
    t.peak_contact_force_n.push_back(0);
  }
  return t;
}

inline ContactEvent episode(double onset, double end) {
  ContactEvent e;
  e.onset_time_s = onset;
  e.end_time_s = end;
  e.approach_velocity_m_s = 0.2;
  e.rebound_velocity_m_s = 0.1;
  e.restitution = 0.5;
  e.peak_force_n = 100;
  e.impulse_n_s = 0.01;
  e.max_indentation_m = 1e-6;
  return e;
}

inline MetricSettings window(double start, double end) {
  MetricSettings s;
  s.window = {start, end};
  return s;
}

}  // namespace ib::test
