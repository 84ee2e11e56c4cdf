// The recorder that turns a fixed-step engine's states into a trajectory: samples between steps,
// per-step accelerations and their peaks, and contact episodes from the applied force.
#include "adapters/common/step_recorder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace ib {
namespace step_recorder_test {

// Frame 1 moves at 1 m/s then, at t = 0.5 s, jumps to -1 m/s within one step; a force acts on steps
// 50 and 51 (t in (0.49, 0.51]).
Trajectory bounce(double h = 0.01) {
  StepRecorder recorder(0.0, 1.0, 20);
  StepState s;
  double u = 0, v = 1;
  recorder.record(s);
  for (int k = 1; k <= 100; ++k) {
    const double t = k * h;
    if (k == 51) v = -1;
    u += v * h;
    s.t = t;
    s.displacement_m = {u, 0};
    s.velocity_m_s = {v, 0};
    s.contact_force_n = (k == 50 || k == 51) ? 100.0 : 0.0;
    s.energy_j = 0.5 * v * v;
    recorder.record(s);
  }
  return recorder.finish();
}

TEST(StepRecorder, SamplesInterpolateBetweenSteps) {
  StepRecorder recorder(0.0, 0.1, 40);  // samples every 25 ms, steps every 10 ms
  StepState s;
  recorder.record(s);
  for (int k = 1; k <= 10; ++k) {
    s.t = 0.01 * k;
    s.displacement_m = {2.0 * s.t, -s.t};
    s.velocity_m_s = {2.0, -1.0};
    recorder.record(s);
  }
  const Trajectory t = recorder.finish();
  ASSERT_EQ(t.size(), 5u);
  for (std::size_t k = 0; k < t.size(); ++k) {
    EXPECT_NEAR(t.time_s[k], 0.025 * k, 1e-15);
    EXPECT_NEAR(t.displacement_m[0][k], 0.05 * k, 1e-14);
    EXPECT_NEAR(t.displacement_m[1][k], -0.025 * k, 1e-14);
  }
}

TEST(StepRecorder, AccelerationIsTheVelocityChangeOfAStepAndItsPeakIsKept) {
  const Trajectory t = bounce();
  // the jump of -2 m/s in the step ending at 0.51 s: -200 m/s^2; the sample at 0.55 s carries it as its peak
  ASSERT_EQ(t.size(), 21u);
  EXPECT_EQ(t.acceleration_m_s2[0][10], 0.0);                     // 0.50 s
  EXPECT_NEAR(t.peak_abs_acceleration_m_s2[0][11], 200.0, 1e-9);  // (0.50, 0.55]
  EXPECT_EQ(t.peak_abs_acceleration_m_s2[0][12], 0.0);
}

TEST(StepRecorder, AContactEpisodeIsARunOfStepsWithForce) {
  const Trajectory t = bounce();
  ASSERT_EQ(t.events.size(), 1u);
  const ContactEvent& e = t.events[0];
  EXPECT_NEAR(e.onset_time_s, 0.49, 1e-12);
  EXPECT_NEAR(e.end_time_s, 0.51, 1e-12);
  EXPECT_NEAR(e.impulse_n_s, 2.0, 1e-12);
  EXPECT_NEAR(e.peak_force_n, 100.0, 0);
  EXPECT_NEAR(e.approach_velocity_m_s, 1.0, 0);
  EXPECT_NEAR(e.rebound_velocity_m_s, 1.0, 0);
  EXPECT_NEAR(e.restitution, 1.0, 0);
}

TEST(StepRecorder, AContactStillOpenAtTheEndIsClosedThere) {
  StepRecorder recorder(0.0, 0.05, 100);
  StepState s;
  recorder.record(s);
  for (int k = 1; k <= 5; ++k) {
    s.t = 0.01 * k;
    s.contact_force_n = k >= 3 ? 1.0 : 0.0;
    recorder.record(s);
  }
  const Trajectory t = recorder.finish();
  ASSERT_EQ(t.events.size(), 1u);
  EXPECT_NEAR(t.events[0].onset_time_s, 0.02, 1e-12);
  EXPECT_NEAR(t.events[0].end_time_s, 0.05, 1e-12);
}

// An engine computes the energy only where StepRecorder::needs_energy says so and leaves it NaN
// elsewhere: the series (from 0.3 s, with a step of 0.7 ms that does not land on it) and the impact
// zoom (an onset 0.4 ms after the series start, its 1 ms margin reaching back before it) must hold
// only computed energies, and the initial energy must be there.
TEST(StepRecorder, EnergyIsNeededOnlyWhereTheSeriesAndTheZoomReachIt) {
  const double h = 7e-4, start = 0.3, end = 0.5;
  StepRecorder recorder(start, end, 1000);
  StepState s;
  int computed = 0, steps = 0;
  for (int k = 0; k * h <= end + 1e-12; ++k) {
    s.t = k * h;
    s.displacement_m = {1e-3 * std::sin(10 * s.t), 0};
    s.velocity_m_s = {1e-2 * std::cos(10 * s.t), 0};
    s.contact_force_n = (s.t > start + 4e-4 && s.t < start + 3e-3) ? 50.0 : 0.0;  // one impact in the window
    const bool needed = recorder.needs_energy(s.t, h);
    s.energy_j = needed ? 1.0 + s.t : std::numeric_limits<double>::quiet_NaN();
    computed += needed;
    ++steps;
    recorder.record(s);
  }
  const Trajectory series = recorder.finish();
  const Trajectory impact = recorder.impact_zoom();
  EXPECT_EQ(series.initial_mechanical_energy_j, 1.0);
  ASSERT_FALSE(series.mechanical_energy_j.empty());
  for (double e : series.mechanical_energy_j) EXPECT_TRUE(std::isfinite(e));
  ASSERT_GT(impact.size(), 2u);
  // the zoom starts 1 ms before the onset (the step before the first with a force), not earlier
  ASSERT_EQ(series.events.size(), 1u);
  EXPECT_LT(impact.time_s.front(), start);  // the margin reaches back before the series start
  EXPECT_GE(impact.time_s.front(), series.events[0].onset_time_s - 1e-3 - 1e-12);
  EXPECT_LT(impact.time_s.front(), series.events[0].onset_time_s - 1e-3 + h);
  for (double e : impact.mechanical_energy_j) EXPECT_TRUE(std::isfinite(e));
  EXPECT_LT(computed, steps / 2);  // most of the run before the window went without it
}

// The zoom keeps the window's first impact, not its strongest: every simulator's zoom then shows the
// same impact (the report compares them like with like). An impact before the window does not count.
TEST(StepRecorder, TheZoomHoldsTheFirstImpactOfTheWindow) {
  const double h = 1e-4, start = 0.1, end = 0.3;
  StepRecorder recorder(start, end, 1000);
  StepState s;
  for (int k = 0; k * h <= end + 1e-12; ++k) {
    s.t = k * h;
    const bool before = s.t > 0.05 && s.t<0.052, first = s.t> 0.15 && s.t<0.152, second = s.t> 0.25 && s.t < 0.252;
    s.contact_force_n = before ? 500.0 : first ? 20.0 : second ? 300.0 : 0.0;
    s.energy_j = 1;
    recorder.record(s);
  }
  const Trajectory series = recorder.finish();
  const Trajectory impact = recorder.impact_zoom();
  ASSERT_EQ(series.events.size(), 3u);
  ASSERT_GT(impact.size(), 2u);
  EXPECT_NEAR(impact.time_s.front(), series.events[1].onset_time_s - 1e-3, h);
  EXPECT_NEAR(impact.time_s.back(), series.events[1].end_time_s + 1e-3, h);
  EXPECT_EQ(*std::max_element(impact.contact_force_n.begin(), impact.contact_force_n.end()), 20.0);
}

}  // namespace step_recorder_test
}  // namespace ib
