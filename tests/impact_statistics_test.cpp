// Each impact's own figures (harness/scoring/impact_statistics.h) on a trajectory with known impacts: each
// contact a constant acceleration pulse inside one sensor window, so that its sensor reading is A tau / T,
// its true peak A and its duration tau, all recovered exactly, impact by impact; and their percentiles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "harness/scoring/impact_statistics.h"
#include "harness/scoring/metrics.h"
#include "metric_signals.h"

namespace ib {
namespace impact_statistics_test {

using namespace test;

constexpr double kSensorRate = 2048, kSamplesPerWindow = 16, kRate = kSensorRate * kSamplesPerWindow;

// A contact: from sample `onset` for `samples` samples, frame 1 pushed at A, frame 2 at -A / 2.
struct Pulse {
  int onset = 0;
  int samples = 0;
  double acceleration_m_s2 = 0;
  double approach_velocity_m_s = 0;
  double restitution = 0;
  double onset_s() const { return onset / kRate; }
  double end_s() const { return (onset + samples) / kRate; }
};

// Onsets 2 to 8 samples into a sensor window, contacts short enough to end inside it; 3 ms and more apart,
// more than the merge window. The last lies after the scoring window [0, 0.5 s].
const std::vector<Pulse> kPulses = {{16 * 100 + 2, 8, 3000, 0.20, 0.60},
                                    {16 * 300 + 5, 10, 5000, 0.35, 0.70},
                                    {16 * 500 + 8, 4, 2000, 0.10, 0.50},
                                    {16 * 700 + 3, 12, 4000, 0.25, 0.80},
                                    {16 * 1100 + 2, 6, 9000, 0.50, 0.40}};

// The tips' velocity with every pulse: piecewise linear, its corners on samples, so that the series read
// between samples (linearly) is exact.
Motion tip(double scale) {
  Motion m;
  m.v = [scale](double t) {
    double v = 0;
    for (const Pulse& p : kPulses)
      v += scale * p.acceleration_m_s2 * std::clamp(t - p.onset_s(), 0.0, p.end_s() - p.onset_s());
    return v;
  };
  m.a = [scale](double t) {
    for (const Pulse& p : kPulses)
      if (t >= p.onset_s() && t <= p.end_s()) return scale * p.acceleration_m_s2;
    return 0.0;
  };
  return m;
}

Trajectory with_pulses() {
  Trajectory t = sampled(kRate, 0, static_cast<std::size_t>(0.6 * kRate), tip(1), tip(-0.5));
  for (const Pulse& p : kPulses) {
    ContactEvent e = episode(p.onset_s(), p.end_s());
    e.approach_velocity_m_s = p.approach_velocity_m_s;
    e.rebound_velocity_m_s = p.restitution * p.approach_velocity_m_s;
    t.events.push_back(e);
  }
  return t;
}

TEST(ImpactStatistics, EachImpactsPeakDurationAndVelocitiesAreItsOwn) {
  const Metrics m = compute_metrics(with_pulses(), window(0, 0.5));
  const ImpactSamples& s = m.impact_samples;
  ASSERT_EQ(m.impacts, 4);
  ASSERT_EQ(s.contact_duration_s.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    const Pulse& p = kPulses[i];
    const double tau = p.end_s() - p.onset_s();
    // a pulse inside one window [t - T/2, t + T/2]: that window reads the velocity change over T
    const double sensor_g = p.acceleration_m_s2 * tau * kSensorRate / g;
    EXPECT_NEAR(s.sensor_peak_g[0][i], sensor_g, 1e-9 * sensor_g) << "impact " << i;
    EXPECT_NEAR(s.sensor_peak_g[1][i], sensor_g / 2, 1e-9 * sensor_g) << "impact " << i;
    EXPECT_DOUBLE_EQ(s.true_peak_g[0][i], p.acceleration_m_s2 / g) << "impact " << i;
    EXPECT_DOUBLE_EQ(s.true_peak_g[1][i], p.acceleration_m_s2 / 2 / g) << "impact " << i;
    EXPECT_DOUBLE_EQ(s.contact_duration_s[i], tau) << "impact " << i;
    EXPECT_DOUBLE_EQ(s.approach_velocity_m_s[i], p.approach_velocity_m_s) << "impact " << i;
    EXPECT_NEAR(s.restitution[i], p.restitution, 1e-15) << "impact " << i;
  }
  // the largest impact's reading is the run's sensor peak
  EXPECT_DOUBLE_EQ(*std::max_element(s.sensor_peak_g[0].begin(), s.sensor_peak_g[0].end()),
                   m.frames[0].sensor_peak_acceleration_g);
}

// The columns: after every existing metric, each distribution's median and 95th percentile.
TEST(ImpactStatistics, PercentileColumnsFollowTheExistingMetrics) {
  const Metrics m = compute_metrics(with_pulses(), window(0, 0.5));
  const auto flat = flatten(m);
  auto value = [&](const std::string& name) {
    for (const auto& [n, v] : flat)
      if (n == name) return v;
    ADD_FAILURE() << "no " << name;
    return 0.0;
  };
  // durations 8, 10, 4, 12 samples: sorted 4, 8, 10, 12; the median 9, the 95th percentile at 2.85: 11.7
  EXPECT_NEAR(value("contact_duration_p50_s"), 9 / kRate, 1e-15);
  EXPECT_NEAR(value("contact_duration_p95_s"), 11.7 / kRate, 1e-15);
  EXPECT_NEAR(value("frame1_true_peak_p50_g"), 3500 / g, 1e-12);
  EXPECT_NEAR(value("restitution_p50"), 0.65, 1e-12);
  EXPECT_NEAR(value("approach_velocity_p95_m_s"), 0.25 + 0.85 * (0.35 - 0.25), 1e-12);
  for (const char* name : {"frame1_sensor_peak_p95_g", "frame2_sensor_peak_p50_g", "frame2_true_peak_p95_g"})
    EXPECT_GT(value(name), 0) << name;
  std::size_t energy = 0;
  while (energy < flat.size() && flat[energy].first != "energy_change_relative") ++energy;
  ASSERT_LT(energy, flat.size());
  EXPECT_EQ(flat[energy + 1].first, "frame1_sensor_peak_phase_mean_g");
  EXPECT_EQ(flat.back().first, "restitution_p95");
}

TEST(ImpactStatistics, AWindowWithoutImpactsHasNoPercentiles) {
  const Metrics m = compute_metrics(with_pulses(), window(0, 0.01));
  EXPECT_EQ(m.impacts, 0);
  for (const auto& [name, value] : flatten_percentiles(m.impact_samples)) EXPECT_TRUE(std::isnan(value)) << name;
}

}  // namespace impact_statistics_test
}  // namespace ib
