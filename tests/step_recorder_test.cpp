// The recorder that turns a fixed-step engine's states into a trajectory: samples between steps,
// per-step accelerations and their peaks, and contact episodes from the applied force.
#include "step_recorder.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ib {
namespace {

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
  EXPECT_EQ(t.acceleration_m_s2[0][10], 0.0);   // 0.50 s
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

}  // namespace
}  // namespace ib
