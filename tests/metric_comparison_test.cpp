// A run's metrics against a reference's (rig.md section 5): identical runs, a scaled run with known errors,
// displacement errors read at the reference's sample times, and NaN where a comparison is not defined.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "harness/scoring/metrics.h"
#include "metric_signals.h"

namespace ib {
namespace metric_comparison_test {

using namespace test;

// ---- 6. comparison against a reference -------------------------------------------------------------

// A 5 Hz oscillation of frame 1 (frame 2 moves at half the amplitude, in antiphase) over [0, 2] s,
// scaled by `scale`, with a 1 ms impact every 0.1 s.
Trajectory oscillation(double scale, double rate = 4096, double duration = 2, double contact_s = 0.001) {
  const double w = 2 * kPi * 5;
  Motion m1, m2;
  m1.u = [=](double t) { return scale * 1e-3 * std::sin(w * t); };
  m1.v = [=](double t) { return scale * 1e-3 * w * std::cos(w * t); };
  m1.a = [=](double t) { return -scale * 1e-3 * w * w * std::sin(w * t); };
  m2.u = [=](double t) { return -0.5 * m1.u(t); };
  m2.v = [=](double t) { return -0.5 * m1.v(t); };
  m2.a = [=](double t) { return -0.5 * m1.a(t); };
  Trajectory t = sampled(rate, 0, static_cast<std::size_t>(duration * rate) + 1, m1, m2);
  for (int i = 0; i < 20; ++i) t.events.push_back(episode(0.05 + 0.1 * i, 0.05 + 0.1 * i + contact_s));
  return t;
}

MetricSettings forced(double start, double end) {
  MetricSettings s = window(start, end);
  s.excitation_frequency_hz = 5;
  return s;
}

TEST(Metrics, IdenticalRunsHaveNoErrors) {
  const Trajectory t = oscillation(1);
  const MetricSettings s = forced(0, 2);
  const Metrics m = compute_metrics(t, s);
  const MetricErrors e = compare_metrics(m, t, m, t, s);
  for (int f = 0; f < 2; ++f) {
    EXPECT_EQ(e.sensor_peak_relative_error[f], 0.0);
    EXPECT_EQ(e.displacement_relative_rms_error[f], 0.0);
  }
  EXPECT_EQ(e.contact_duration_relative_error, 0.0);
  EXPECT_EQ(e.impacts_per_cycle_difference, 0.0);
}

TEST(Metrics, ScaledRunHasKnownErrors) {
  const MetricSettings s = forced(0, 2);
  const Trajectory reference = oscillation(1);
  Trajectory run = oscillation(1.1, 4096, 2, 0.0012);  // 10 % larger motion, 20 % longer contacts
  run.events.push_back(episode(1.999, 1.9992));        // and one impact more
  const MetricErrors e = compare_metrics(compute_metrics(run, s), run, compute_metrics(reference, s), reference, s);
  for (int f = 0; f < 2; ++f) {
    EXPECT_NEAR(e.displacement_relative_rms_error[f], 0.1, 1e-12);
    EXPECT_NEAR(e.sensor_peak_relative_error[f], 0.1, 1e-12);  // the sensor is linear in the motion
  }
  // 20 impacts of 1.2 ms and one of 0.2 ms against 20 of 1 ms
  EXPECT_NEAR(e.contact_duration_relative_error, (20 * 0.0012 + 0.0002) / 21 / 0.001 - 1, 1e-9);
  EXPECT_NEAR(e.impacts_per_cycle_difference, 1.0 / 10, 1e-12);  // one impact in 10 cycles
}

TEST(Metrics, DisplacementErrorReadsTheRunAtTheReferencesSampleTimes) {
  // a displacement linear in time is interpolated exactly, whatever the run's rate
  Motion ramp;
  ramp.u = [](double t) { return 1e-3 * t; };
  const Trajectory reference = sampled(4096, 0, 4097, ramp, ramp);
  const Trajectory run = sampled(3000, 0, 3001, ramp, ramp);
  const MetricSettings s = window(0.25, 1);
  const MetricErrors e = compare_metrics(compute_metrics(run, s), run, compute_metrics(reference, s), reference, s);
  EXPECT_NEAR(e.displacement_relative_rms_error[0], 0.0, 1e-12);
  EXPECT_NEAR(e.displacement_relative_rms_error[1], 0.0, 1e-12);
}

TEST(Metrics, ComparisonIsNaNWhereItIsNotDefined) {
  const Trajectory reference = oscillation(1);
  // a run that stopped at 1 s does not cover the window [0, 2]
  const Trajectory short_run = oscillation(1, 4096, 1);
  MetricSettings s = window(0, 2);  // no excitation: impacts per cycle is NaN on both sides
  MetricErrors e =
      compare_metrics(compute_metrics(short_run, s), short_run, compute_metrics(reference, s), reference, s);
  EXPECT_TRUE(std::isnan(e.displacement_relative_rms_error[0]));
  EXPECT_TRUE(std::isnan(e.impacts_per_cycle_difference));

  // a reference at rest, without impacts: every relative figure is undefined
  Trajectory at_rest = sampled(4096, 0, 8193, Motion{});
  const Trajectory run = oscillation(1);
  s = forced(0, 2);
  e = compare_metrics(compute_metrics(run, s), run, compute_metrics(at_rest, s), at_rest, s);
  EXPECT_TRUE(std::isnan(e.sensor_peak_relative_error[0]));
  EXPECT_TRUE(std::isnan(e.contact_duration_relative_error));
  EXPECT_TRUE(std::isnan(e.displacement_relative_rms_error[0]));
  EXPECT_DOUBLE_EQ(e.impacts_per_cycle_difference, 2.0);  // 20 impacts in 10 cycles against none
}

}  // namespace metric_comparison_test
}  // namespace ib
