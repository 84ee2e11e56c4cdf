// The metrics (rig.md section 5) on synthetic signals whose answers are known in closed form: impacts,
// durations, peaks and impulses, beats, the merge window, the scoring window, RMS. The sensor reading and the
// comparison with a reference have their own files (sensor_reading_test.cpp, metric_comparison_test.cpp).
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
namespace metrics_test {

using namespace test;

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

  s.window.end_s = 2;  // exactly two beats is enough
  EXPECT_DOUBLE_EQ(compute_metrics(t, s).beat_period_s, 1.0);

  s.window.end_s = 5;
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
  const std::vector<ContactEvent> events = {episode(0.303, 0.3031), episode(0.300, 0.3001), episode(0.3015, 0.3016)};
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
  const std::set<std::string> dimensionless = {"impacts",
                                               "raw_onsets",
                                               "excitation_cycles",
                                               "impacts_per_cycle",
                                               "impacts_per_beat",
                                               "mean_restitution",
                                               "energy_change_relative",
                                               "frame1_log_decrement",
                                               "frame2_log_decrement",
                                               "restitution_p50",
                                               "restitution_p95",
                                               "sensor_peak_phases_read"};
  std::set<std::string> names;
  for (const auto& [name, value] : flat) {
    EXPECT_TRUE(names.insert(name).second) << "duplicate " << name;
    EXPECT_TRUE(has_unit_suffix(name) || dimensionless.count(name)) << name;
  }
  // 24 figures, then the statistics beside the maxima (impact_statistics.h): 3 grid-phase figures per
  // frame, the phases read, and two percentiles of each per-impact distribution
  ASSERT_EQ(flat.size(), 24u + 7u + 2u * kImpactDistributions);

  auto value = [&](const std::string& name) {
    for (const auto& [n, v] : flat)
      if (n == name) return v;
    ADD_FAILURE() << "no " << name;
    return std::numeric_limits<double>::quiet_NaN();
  };
  EXPECT_EQ(flat.front().first, "frame1_sensor_peak_acceleration_g");
  EXPECT_EQ(flat[23].first, "energy_change_relative");
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
  // the headline errors first, in this order; the statistics' distances after them (impact_statistics.h)
  ASSERT_GT(flat.size(), expected.size());
  EXPECT_EQ(std::vector(flat.begin(), flat.begin() + static_cast<std::ptrdiff_t>(expected.size())), expected);
  for (std::size_t i = expected.size(); i < flat.size(); ++i)
    EXPECT_EQ(flat[i].first.rfind("vs_reference_", 0), 0u) << flat[i].first;
}

}  // namespace metrics_test
}  // namespace ib
