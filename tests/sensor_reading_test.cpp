// The accelerometer's reading (rig.md section 5: the velocity change over each 1/f_s window) on signals
// whose readings are known in closed form: a velocity jump on and off the sensor grid, a sine, and two
// frames moving differently, each read from its own motion.
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
namespace sensor_reading_test {

using namespace test;

// ---- 2. velocity jump (a Newton impact) ------------------------------------------------------------

constexpr double kJump = 0.3;  // dv [m/s]

Motion velocity_step_at(double t_jump) {
  Motion m;
  m.v = [t_jump](double t) { return t >= t_jump ? kJump : 0.0; };
  return m;
}

// Series at 4096 Hz on the 2048 Hz sensor grid, starting at 0.1 s (not a binary fraction, so the
// window edges land a rounding error off the samples). The jump, between series samples 1228 and 1229,
// lies in sensor window 614: that window reads dv f_s and every other one reads exactly 0.
TEST(Metrics, VelocityJumpOnTheSensorGridFillsExactlyOneSensorSample) {
  const double t0 = 0.1, fs = 2048;
  const double t_jump = t0 + 1228.5 / 4096;
  const Trajectory t = sampled(4096, t0, 4097, velocity_step_at(t_jump));
  const SensorSeries sensor = sensor_acceleration(t, 0, t0, t0 + 1, fs);

  ASSERT_EQ(sensor.acceleration_m_s2.size(), 2048u);
  for (std::size_t k = 0; k < sensor.acceleration_m_s2.size(); ++k) {
    EXPECT_NEAR(sensor.time_s[k], t0 + (k + 0.5) / fs, 1e-12);
    if (k == 614)
      EXPECT_NEAR(sensor.acceleration_m_s2[k], kJump * fs, 1e-9);
    else
      EXPECT_EQ(sensor.acceleration_m_s2[k], 0.0) << "sensor sample " << k;
  }
  const Metrics m = compute_metrics(t, window(t0, t0 + 1));
  EXPECT_NEAR(m.frames[0].sensor_peak_acceleration_g, kJump * fs / g, 1e-9);
}

// Series at 3000 Hz: the sampled step becomes a ramp between samples 1464 (0.488 s) and 1465, and the
// sensor window edge 1000/2048 s = 0.48828125 s cuts that ramp at 0.84375 of its length (1464.84375
// samples). So sensor window 999 reads 0.84375 dv f_s, window 1000 reads 0.15625 dv f_s, all others 0,
// and the readings still add up to the velocity change: sum a_s T = dv.
TEST(Metrics, VelocityJumpOffTheSensorGridIsSharedByTheTwoWindowsItsRampSpans) {
  const double fs = 2048;
  const Trajectory t = sampled(3000, 0, 3001, velocity_step_at(0.4882));
  const SensorSeries sensor = sensor_acceleration(t, 0, 0, 1, fs);

  ASSERT_EQ(sensor.acceleration_m_s2.size(), 2048u);
  double velocity_change = 0;
  for (std::size_t k = 0; k < sensor.acceleration_m_s2.size(); ++k) {
    const double expected = k == 999 ? 0.84375 * kJump * fs : k == 1000 ? 0.15625 * kJump * fs : 0.0;
    EXPECT_NEAR(sensor.acceleration_m_s2[k], expected, 1e-9) << "sensor sample " << k;
    velocity_change += sensor.acceleration_m_s2[k] / fs;
  }
  EXPECT_NEAR(velocity_change, kJump, 1e-12);
  EXPECT_NEAR(compute_metrics(t, window(0, 1)).frames[0].sensor_peak_acceleration_g, 0.84375 * kJump * fs / g, 1e-9);
}

// The window average of a = A sin(w t) over [t - T/2, t + T/2] is a(t) sin(w T/2) / (w T/2).
TEST(Metrics, SensorReadsASineScaledByTheWindowAveragesSinc) {
  const double A = 50, f = 200, w = 2 * kPi * f, fs = 2048, T = 1 / fs;
  Motion m;
  m.v = [=](double t) { return -A / w * std::cos(w * t); };
  m.a = [=](double t) { return A * std::sin(w * t); };
  const Trajectory t = sampled(8192, 0, 8193, m);
  const SensorSeries sensor = sensor_acceleration(t, 0, 0, 1, fs);
  ASSERT_EQ(sensor.acceleration_m_s2.size(), 2048u);
  const double sinc = std::sin(w * T / 2) / (w * T / 2);
  for (std::size_t k = 0; k < sensor.acceleration_m_s2.size(); ++k)
    EXPECT_NEAR(sensor.acceleration_m_s2[k], sinc * m.a(sensor.time_s[k]), 1e-9);
}

TEST(Metrics, SensorWindowsStayInsideTheWindowAndTheSeries) {
  const Trajectory t = sampled(4096, 0, 4097, velocity_step_at(0.5));  // series over [0, 1] s
  // 0.25 s holds 512 whole windows; 0.2501 s still 512
  EXPECT_EQ(sensor_acceleration(t, 0, 0.5, 0.75, 2048).time_s.size(), 512u);
  EXPECT_EQ(sensor_acceleration(t, 0, 0.5, 0.7501, 2048).time_s.size(), 512u);
  // a window reaching 0.5 s past the series' end keeps only the windows the series reaches
  const SensorSeries past_end = sensor_acceleration(t, 0, 0.75, 1.5, 2048);
  EXPECT_EQ(past_end.time_s.size(), 512u);
  EXPECT_LE(past_end.time_s.back() + 0.5 / 2048, 1.0 + 1e-12);
  // and one starting before the series drops the windows before its first sample
  const Trajectory late = sampled(4096, 0.5, 2049, velocity_step_at(0.75));  // series over [0.5, 1] s
  const SensorSeries early = sensor_acceleration(late, 0, 0, 1, 2048);
  EXPECT_EQ(early.time_s.size(), 1024u);
  EXPECT_NEAR(early.time_s.front(), 0.5 + 0.5 / 2048, 1e-12);
}

// ---- 9. two frames, two motions ---------------------------------------------------------------------

// a = A cos(w (t - t_crest)), v = (A / w) sin(w (t - t_crest)): the sensor window's average of a is
// A cos(w (t - t_crest)) sinc(w T / 2), and with t_crest a sensor sample time the reading's peak is
// A sinc(w T / 2) exactly there.
struct Tone {
  double amplitude_m_s2, frequency_hz, crest_s;
  double omega() const { return 2 * kPi * frequency_hz; }
  Motion motion() const {
    Motion m;
    const double A = amplitude_m_s2, w = omega(), t_crest = crest_s;
    m.u = [=](double t) { return -A / (w * w) * std::cos(w * (t - t_crest)); };
    m.v = [=](double t) { return A / w * std::sin(w * (t - t_crest)); };
    m.a = [=](double t) { return A * std::cos(w * (t - t_crest)); };
    return m;
  }
  double window_average_factor(double sensor_rate_hz) const {
    const double half_window_phase = omega() / sensor_rate_hz / 2;
    return std::sin(half_window_phase) / half_window_phase;
  }
  double reading(double t, double sensor_rate_hz) const {
    return amplitude_m_s2 * std::cos(omega() * (t - crest_s)) * window_average_factor(sensor_rate_hz);
  }
  double sensor_peak(double sensor_rate_hz) const { return amplitude_m_s2 * window_average_factor(sensor_rate_hz); }
};

// The two frames carry one accelerometer each (rig.md section 5): frame 1's tip rings softly at 150 Hz and
// frame 2's hard at 400 Hz, crests at different sensor samples. Each frame's reading must follow its own
// tip, sample by sample, and each frame's sensor peak must be its own tone's (about 4.0 g and 28.7 g): a
// reading taken from the other frame's velocity series would be off by a factor of seven.
TEST(Metrics, EachFramesSensorReadsItsOwnTipsMotion) {
  const double fs = 2048;
  const Tone frame1{40, 150, 300.5 / fs}, frame2{300, 400, 1000.5 / fs};
  // 8192 Hz from 0: every sensor window edge k / 2048 s is a series sample, no interpolation
  const Trajectory t = sampled(8192, 0, 8193, frame1.motion(), frame2.motion());
  const Tone tones[2] = {frame1, frame2};
  for (int f = 0; f < 2; ++f) {
    const SensorSeries sensor = sensor_acceleration(t, f, 0, 1, fs);
    ASSERT_EQ(sensor.acceleration_m_s2.size(), 2048u);
    for (std::size_t k = 0; k < sensor.acceleration_m_s2.size(); ++k)
      ASSERT_NEAR(sensor.acceleration_m_s2[k], tones[f].reading(sensor.time_s[k], fs), 1e-9)
          << "frame " << f + 1 << " sensor sample " << k;
  }
  const Metrics m = compute_metrics(t, window(0, 1));
  EXPECT_NEAR(m.frames[0].sensor_peak_acceleration_g, frame1.sensor_peak(fs) / g, 1e-9);
  EXPECT_NEAR(m.frames[1].sensor_peak_acceleration_g, frame2.sensor_peak(fs) / g, 1e-9);
}

}  // namespace sensor_reading_test
}  // namespace ib
