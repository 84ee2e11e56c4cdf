// The metrics (rig.md section 5) on synthetic signals whose answers are known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "harness/metrics.h"

namespace ib {
namespace {

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
Trajectory sampled(double rate, double t0, std::size_t n, const Motion& frame1, const Motion& frame2 = {}) {
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

ContactEvent episode(double onset, double end) {
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

MetricSettings window(double start, double end) {
  MetricSettings s;
  s.window_start_s = start;
  s.window_end_s = end;
  return s;
}

// ---- 1. half-sine pulse train ----------------------------------------------------------------------

// n pulses a(t) = A sin(pi (t - t_i) / w) on [t_i, t_i + w] of a 1 kg tip, sampled at 10 kHz over 1 s.
// The pulse crests fall between samples, so only the exact peak columns see A.
struct PulseTrain {
  static constexpr double A = 500, w = 0.0021, mass = 1.0;
  static constexpr int n = 5;
  static double onset(int i) { return 0.1 + 0.2 * i + 0.00003; }
  static double a(double t) {
    for (int i = 0; i < n; ++i)
      if (t >= onset(i) && t <= onset(i) + w) return A * std::sin(kPi * (t - onset(i)) / w);
    return 0;
  }
  static double impulse() { return mass * 2 * A * w / kPi; }  // integral of m A sin over one pulse
};

Trajectory pulse_train() {
  Motion m;
  m.a = PulseTrain::a;
  Trajectory t = sampled(10000, 0, 10001, m);
  // exact max |a| over (t_{k-1}, t_k]: the crest where it lies inside, else the larger end (the half
  // sine is monotone on each side of its crest)
  for (std::size_t k = 1; k < t.size(); ++k) {
    double peak = std::max(std::abs(t.acceleration_m_s2[0][k - 1]), std::abs(t.acceleration_m_s2[0][k]));
    for (int i = 0; i < PulseTrain::n; ++i) {
      const double crest = PulseTrain::onset(i) + PulseTrain::w / 2;
      if (crest > t.time_s[k - 1] && crest <= t.time_s[k]) peak = PulseTrain::A;
    }
    t.peak_abs_acceleration_m_s2[0][k] = peak;
  }
  for (int i = 0; i < PulseTrain::n; ++i) {
    ContactEvent e = episode(PulseTrain::onset(i), PulseTrain::onset(i) + PulseTrain::w);
    e.impulse_n_s = PulseTrain::impulse();
    t.events.push_back(e);
  }
  return t;
}

TEST(Metrics, HalfSinePulseTrainCountsDurationsPeaksAndImpulses) {
  const Trajectory t = pulse_train();
  MetricSettings s = window(0, 1);
  s.excitation_frequency_hz = 10;
  const Metrics m = compute_metrics(t, s);

  EXPECT_EQ(m.impacts, PulseTrain::n);
  EXPECT_EQ(m.raw_onsets, PulseTrain::n);
  EXPECT_NEAR(m.contact_duration_mean_s, PulseTrain::w, 1e-15);
  EXPECT_NEAR(m.contact_duration_min_s, PulseTrain::w, 1e-15);
  EXPECT_NEAR(m.contact_duration_max_s, PulseTrain::w, 1e-15);
  EXPECT_DOUBLE_EQ(m.frames[0].true_peak_acceleration_g, PulseTrain::A / g);
  EXPECT_DOUBLE_EQ(m.excitation_cycles, 10.0);
  EXPECT_DOUBLE_EQ(m.impacts_per_cycle, 0.5);
  EXPECT_DOUBLE_EQ(m.mean_impulse_n_s, PulseTrain::impulse());
  EXPECT_DOUBLE_EQ(m.mean_restitution, 0.5);
  EXPECT_DOUBLE_EQ(m.mean_approach_velocity_m_s, 0.2);
  EXPECT_DOUBLE_EQ(m.max_penetration_m, 1e-6);
  // the frame at rest reads nothing
  EXPECT_EQ(m.frames[1].true_peak_acceleration_g, 0.0);
  EXPECT_EQ(m.frames[1].sensor_peak_acceleration_g, 0.0);
}

TEST(Metrics, TruePeakFallsBackToTheSamplesWithoutPeakColumns) {
  Trajectory t = pulse_train();
  const double with_columns = compute_metrics(t, window(0, 1)).frames[0].true_peak_acceleration_g;
  t.peak_abs_acceleration_m_s2[0].clear();
  t.peak_abs_acceleration_m_s2[1].clear();
  const double without = compute_metrics(t, window(0, 1)).frames[0].true_peak_acceleration_g;
  double sampled_peak = 0;
  for (double a : t.acceleration_m_s2[0]) sampled_peak = std::max(sampled_peak, std::abs(a));
  EXPECT_DOUBLE_EQ(without, sampled_peak / g);
  EXPECT_LT(without, with_columns);  // the crests lie between samples
}

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
  EXPECT_NEAR(compute_metrics(t, window(0, 1)).frames[0].sensor_peak_acceleration_g, 0.84375 * kJump * fs / g,
              1e-9);
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

// ---- 3. beating ------------------------------------------------------------------------------------

// u = (sin(2 pi f_exc t) + sin(2 pi f_1 t)) / 2 beats with period 1 / |f_exc - f_1| = 1 s; an impact is
// each excursion of u beyond a gap of 0.9, which only happens near the crests of the beat envelope.
Trajectory beating(double f_exc, double f_1, double duration) {
  Motion m;
  m.u = [=](double t) { return 0.5 * (std::sin(2 * kPi * f_exc * t) + std::sin(2 * kPi * f_1 * t)); };
  const double rate = 10000;
  Trajectory t = sampled(rate, 0, static_cast<std::size_t>(duration * rate) + 1, m);
  const double gap = 0.9;
  for (std::size_t k = 1; k < t.size(); ++k) {
    const double before = t.displacement_m[0][k - 1], now = t.displacement_m[0][k];
    if (before < gap && now >= gap) t.events.push_back(episode(t.time_s[k], t.time_s[k]));
    if (before >= gap && now < gap) t.events.back().end_time_s = t.time_s[k];
  }
  return t;
}

TEST(Metrics, BeatingCountsImpactsPerBeat) {
  const double f_exc = 20, f_1 = 21;
  const Trajectory t = beating(f_exc, f_1, 5);
  MetricSettings s = window(0, 5);
  s.excitation_frequency_hz = f_exc;
  s.natural_frequency_hz = f_1;
  const Metrics m = compute_metrics(t, s);

  ASSERT_GT(m.impacts, 0);
  EXPECT_DOUBLE_EQ(m.beat_period_s, 1.0);
  EXPECT_DOUBLE_EQ(m.impacts_per_beat, m.impacts / 5.0);
  EXPECT_DOUBLE_EQ(m.impacts_per_cycle, m.impacts / 100.0);
  // the impacts cluster at the envelope's crests, t = 0, 1, 2, ... s
  for (const ContactEvent& e : t.events) {
    const double from_crest = std::abs(e.onset_time_s - std::round(e.onset_time_s));
    EXPECT_LT(from_crest, 0.25) << "onset at " << e.onset_time_s;
  }
}

TEST(Metrics, BeatNeedsTwoBeatsInTheWindowAndTwoDistinctFrequencies) {
  const Trajectory t = beating(20, 21, 5);
  MetricSettings s = window(0, 1.5);
  s.excitation_frequency_hz = 20;
  s.natural_frequency_hz = 21;
  Metrics m = compute_metrics(t, s);
  EXPECT_TRUE(std::isnan(m.beat_period_s));
  EXPECT_TRUE(std::isnan(m.impacts_per_beat));

  s.window_end_s = 2;  // exactly two beats is enough
  EXPECT_DOUBLE_EQ(compute_metrics(t, s).beat_period_s, 1.0);

  s.window_end_s = 5;
  s.natural_frequency_hz = 20;  // no beating
  EXPECT_TRUE(std::isnan(compute_metrics(t, s).beat_period_s));
  s.natural_frequency_hz = 0;  // no natural frequency given
  EXPECT_TRUE(std::isnan(compute_metrics(t, s).impacts_per_beat));
  s.natural_frequency_hz = 21;
  s.excitation_frequency_hz = 0;  // free vibration: neither cycles nor beats
  m = compute_metrics(t, s);
  EXPECT_TRUE(std::isnan(m.beat_period_s));
  EXPECT_TRUE(std::isnan(m.impacts_per_cycle));
  EXPECT_EQ(m.excitation_cycles, 0.0);
}

// ---- 4. merge window -------------------------------------------------------------------------------

TEST(Metrics, OnsetsWithinTheMergeWindowAreOneImpact) {
  std::vector<ContactEvent> events = {episode(0.100, 0.1004), episode(0.101, 0.1015),   // 1 ms: one impact
                                      episode(0.200, 0.2004), episode(0.203, 0.2034)};  // 3 ms: two
  events[0].approach_velocity_m_s = 0.4;
  events[0].rebound_velocity_m_s = 0.05;
  events[0].peak_force_n = 300;
  events[0].max_indentation_m = 2e-6;
  events[1].approach_velocity_m_s = 0.05;
  events[1].rebound_velocity_m_s = 0.3;
  events[1].peak_force_n = 50;
  events[1].max_indentation_m = 1e-6;

  const std::vector<Impact> impacts = merge_impacts(events, 0, 1, 0.002);
  ASSERT_EQ(impacts.size(), 3u);
  const Impact& merged = impacts[0];
  EXPECT_EQ(merged.onsets, 2);
  EXPECT_DOUBLE_EQ(merged.onset_time_s, 0.100);
  EXPECT_DOUBLE_EQ(merged.end_time_s, 0.1015);
  EXPECT_DOUBLE_EQ(merged.approach_velocity_m_s, 0.4);  // the first episode's
  EXPECT_DOUBLE_EQ(merged.rebound_velocity_m_s, 0.3);   // the last episode's
  EXPECT_DOUBLE_EQ(merged.restitution, 0.3 / 0.4);
  EXPECT_DOUBLE_EQ(merged.peak_force_n, 300);
  EXPECT_DOUBLE_EQ(merged.impulse_n_s, 0.02);
  EXPECT_DOUBLE_EQ(merged.max_indentation_m, 2e-6);
  EXPECT_EQ(impacts[1].onsets, 1);
  EXPECT_EQ(impacts[2].onsets, 1);

  Trajectory t = sampled(1000, 0, 1001, Motion{});
  t.events = events;
  const Metrics m = compute_metrics(t, window(0, 1));  // default merge window: 2 ms
  EXPECT_EQ(m.impacts, 3);
  EXPECT_EQ(m.raw_onsets, 4);
  EXPECT_DOUBLE_EQ(m.contact_duration_max_s, 0.1015 - 0.100);
  EXPECT_NEAR(m.contact_duration_min_s, 0.0004, 1e-15);
  EXPECT_DOUBLE_EQ(m.max_penetration_m, 2e-6);
}

TEST(Metrics, MergingChainsFromEachOnsetToTheNextAndSortsFirst) {
  // 1.5 ms steps: each onset is within 2 ms of the one before, so all three are one impact
  const std::vector<ContactEvent> events = {episode(0.303, 0.3031), episode(0.300, 0.3001),
                                            episode(0.3015, 0.3016)};
  const std::vector<Impact> impacts = merge_impacts(events, 0, 1, 0.002);
  ASSERT_EQ(impacts.size(), 1u);
  EXPECT_EQ(impacts[0].onsets, 3);
  EXPECT_DOUBLE_EQ(impacts[0].onset_time_s, 0.300);
  EXPECT_DOUBLE_EQ(impacts[0].end_time_s, 0.3031);
}

TEST(Metrics, NewtonImpactsHaveNoPeakForceAndZeroApproachGivesZeroRestitution) {
  ContactEvent newton = episode(0.5, 0.5);
  newton.peak_force_n = std::numeric_limits<double>::quiet_NaN();
  ContactEvent second = newton;
  second.onset_time_s = second.end_time_s = 0.5005;
  EXPECT_TRUE(std::isnan(merge_impacts({newton, second}, 0, 1, 0.002).at(0).peak_force_n));
  // a defined force wins over an undefined one
  second.peak_force_n = 42;
  EXPECT_DOUBLE_EQ(merge_impacts({newton, second}, 0, 1, 0.002).at(0).peak_force_n, 42);

  ContactEvent resting = episode(0.5, 0.6);
  resting.approach_velocity_m_s = 0;
  EXPECT_EQ(merge_impacts({resting}, 0, 1, 0.002).at(0).restitution, 0.0);
}

// ---- 5. window selection ---------------------------------------------------------------------------

TEST(Metrics, EventsAndSamplesOutsideTheWindowAreIgnored) {
  // u = a = 1 inside [0.5, 1.5] s, 100 outside it
  Motion m;
  m.u = [](double t) { return t >= 0.5 && t <= 1.5 ? 1.0 : 100.0; };
  m.a = m.u;
  Trajectory t = sampled(1000, 0, 2001, m);
  // the first sample in the window carries, in its peak column, a peak from before the window
  t.peak_abs_acceleration_m_s2[0][500] = 100;
  t.events = {episode(0.2, 0.201), episode(0.7, 0.701), episode(1.2, 1.201), episode(1.8, 1.801)};
  // an impact that began before the window: its later episode is not a new impact
  t.events.push_back(episode(0.499, 0.4995));
  t.events.push_back(episode(0.5005, 0.501));

  const Metrics metrics = compute_metrics(t, window(0.5, 1.5));
  EXPECT_DOUBLE_EQ(metrics.frames[0].peak_displacement_m, 1.0);
  EXPECT_DOUBLE_EQ(metrics.frames[0].true_peak_acceleration_g, 1.0 / g);
  EXPECT_DOUBLE_EQ(metrics.frames[0].rms_acceleration_g, 1.0 / g);
  EXPECT_EQ(metrics.impacts, 2);
  EXPECT_EQ(metrics.raw_onsets, 3);  // the raw count sees the later episode
}

TEST(Metrics, AnEmptyWindowMeasuresNothing) {
  const Trajectory t = sampled(1000, 0, 1001, Motion{});
  const Metrics m = compute_metrics(t, window(2, 3));  // after the run
  EXPECT_EQ(m.impacts, 0);
  EXPECT_TRUE(std::isnan(m.frames[0].sensor_peak_acceleration_g));
  EXPECT_TRUE(std::isnan(m.frames[0].true_peak_acceleration_g));
  EXPECT_TRUE(std::isnan(m.frames[0].rms_acceleration_g));
  EXPECT_TRUE(std::isnan(m.frames[0].peak_displacement_m));
  EXPECT_TRUE(std::isnan(m.contact_duration_mean_s));
  EXPECT_TRUE(std::isnan(m.contact_duration_min_s));
  EXPECT_TRUE(std::isnan(m.contact_duration_max_s));
  EXPECT_TRUE(std::isnan(m.mean_restitution));
  EXPECT_TRUE(std::isnan(m.mean_approach_velocity_m_s));
  EXPECT_TRUE(std::isnan(m.mean_impulse_n_s));
  EXPECT_EQ(m.max_penetration_m, 0.0);
}

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
  Trajectory run = oscillation(1.1, 4096, 2, 0.0012);   // 10 % larger motion, 20 % longer contacts
  run.events.push_back(episode(1.999, 1.9992));         // and one impact more
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
  MetricErrors e = compare_metrics(compute_metrics(short_run, s), short_run, compute_metrics(reference, s),
                                   reference, s);
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

// ---- 7. RMS ----------------------------------------------------------------------------------------

// The window [0, 1 - dt] holds 1000 samples, exactly 10 periods: the mean of sin^2 over them is 1/2.
TEST(Metrics, RmsOfASineIsItsAmplitudeOverRootTwo) {
  const double A = 30;
  Motion m;
  m.a = [=](double t) { return A * std::sin(2 * kPi * 10 * t); };
  const Trajectory t = sampled(1000, 0, 1001, m);
  const Metrics metrics = compute_metrics(t, window(0, 0.999));
  EXPECT_NEAR(metrics.frames[0].rms_acceleration_g, A / std::sqrt(2.0) / g, 1e-12);
}

// ---- 8. flatten ------------------------------------------------------------------------------------

bool has_unit_suffix(const std::string& name) {
  for (const std::string unit : {"_g", "_m", "_s", "_m_s", "_n_s"})
    if (name.size() > unit.size() && name.compare(name.size() - unit.size(), unit.size(), unit) == 0) return true;
  return false;
}

TEST(Metrics, FlattenNamesEveryFigureOnceWithItsUnit) {
  const Trajectory t = pulse_train();
  MetricSettings s = window(0, 1);
  s.excitation_frequency_hz = 10;
  s.natural_frequency_hz = 12;
  const Metrics m = compute_metrics(t, s);
  const auto flat = flatten(m);

  // counts and ratios carry no unit
  const std::set<std::string> dimensionless = {"impacts", "raw_onsets", "excitation_cycles",
                                               "impacts_per_cycle", "impacts_per_beat", "mean_restitution",
                                               "energy_change_relative", "frame1_log_decrement",
                                               "frame2_log_decrement"};
  std::set<std::string> names;
  for (const auto& [name, value] : flat) {
    EXPECT_TRUE(names.insert(name).second) << "duplicate " << name;
    EXPECT_TRUE(has_unit_suffix(name) || dimensionless.count(name)) << name;
  }
  ASSERT_EQ(flat.size(), 24u);

  auto value = [&](const std::string& name) {
    for (const auto& [n, v] : flat)
      if (n == name) return v;
    ADD_FAILURE() << "no " << name;
    return std::numeric_limits<double>::quiet_NaN();
  };
  EXPECT_EQ(flat.front().first, "frame1_sensor_peak_acceleration_g");
  EXPECT_EQ(flat.back().first, "energy_change_relative");
  EXPECT_EQ(value("frame1_sensor_peak_acceleration_g"), m.frames[0].sensor_peak_acceleration_g);
  EXPECT_EQ(value("frame1_true_peak_acceleration_g"), m.frames[0].true_peak_acceleration_g);
  EXPECT_EQ(value("frame1_rms_acceleration_g"), m.frames[0].rms_acceleration_g);
  EXPECT_EQ(value("frame1_peak_displacement_m"), m.frames[0].peak_displacement_m);
  EXPECT_TRUE(std::isnan(value("frame1_log_decrement")));  // a forced run does not decay
  EXPECT_EQ(value("frame2_true_peak_acceleration_g"), m.frames[1].true_peak_acceleration_g);
  EXPECT_EQ(value("impacts"), m.impacts);
  EXPECT_EQ(value("raw_onsets"), m.raw_onsets);
  EXPECT_EQ(value("contact_duration_mean_s"), m.contact_duration_mean_s);
  EXPECT_EQ(value("contact_duration_min_s"), m.contact_duration_min_s);
  EXPECT_EQ(value("contact_duration_max_s"), m.contact_duration_max_s);
  EXPECT_EQ(value("excitation_cycles"), m.excitation_cycles);
  EXPECT_EQ(value("impacts_per_cycle"), m.impacts_per_cycle);
  EXPECT_EQ(value("beat_period_s"), m.beat_period_s);
  EXPECT_EQ(value("impacts_per_beat"), m.impacts_per_beat);
  EXPECT_EQ(value("mean_restitution"), m.mean_restitution);
  EXPECT_EQ(value("mean_approach_velocity_m_s"), m.mean_approach_velocity_m_s);
  EXPECT_EQ(value("max_penetration_m"), m.max_penetration_m);
  EXPECT_EQ(value("mean_impulse_n_s"), m.mean_impulse_n_s);
}

// The energy drift of an unforced run: the last force-free sample of the window against t = 0.
TEST(Metrics, EnergyChangeIsTheLastForceFreeSampleAgainstTheStart) {
  Trajectory t = sampled(100, 0, 101, {});
  t.initial_mechanical_energy_j = 2e-3;
  for (std::size_t k = 0; k < t.size(); ++k) t.mechanical_energy_j.push_back(2e-3 - 1e-5 * static_cast<double>(k));
  t.contact_force_n.back() = 10;  // in contact at the very end: the sample before counts
  Metrics m = compute_metrics(t, window(0, 1));
  EXPECT_NEAR(m.energy_change_relative, -99e-5 / 2e-3, 1e-12);
  MetricSettings forced = window(0, 1);
  forced.excitation_frequency_hz = 7;  // a motor does work: no drift to speak of
  EXPECT_TRUE(std::isnan(compute_metrics(t, forced).energy_change_relative));
  t.initial_mechanical_energy_j = std::numeric_limits<double>::quiet_NaN();  // unknown start
  EXPECT_TRUE(std::isnan(compute_metrics(t, window(0, 1)).energy_change_relative));
}

TEST(Metrics, FlattenErrorsPrefixesEveryName) {
  MetricErrors e;
  e.sensor_peak_relative_error = {0.1, 0.2};
  e.contact_duration_relative_error = 0.3;
  e.impacts_per_cycle_difference = 0.4;
  e.displacement_relative_rms_error = {0.5, 0.6};
  e.log_decrement_relative_error = {0.7, 0.8};
  const auto flat = flatten(e, "vs_reference_");
  const std::vector<std::pair<std::string, double>> expected = {
      {"vs_reference_frame1_sensor_peak_relative_error", 0.1},
      {"vs_reference_frame2_sensor_peak_relative_error", 0.2},
      {"vs_reference_contact_duration_relative_error", 0.3},
      {"vs_reference_impacts_per_cycle_difference", 0.4},
      {"vs_reference_frame1_displacement_relative_rms_error", 0.5},
      {"vs_reference_frame2_displacement_relative_rms_error", 0.6},
      {"vs_reference_frame1_log_decrement_relative_error", 0.7},
      {"vs_reference_frame2_log_decrement_relative_error", 0.8}};
  EXPECT_EQ(flat, expected);
}

}  // namespace
}  // namespace ib
