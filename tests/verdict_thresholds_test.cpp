// Every verdict threshold pinned to its stated value (docs/verdicts: the defaults of VerdictSettings),
// just inside and just outside: a threshold made looser or tighter by any factor fails here. The values
// are the documented ones, written out, not read from the code that judges.
#include "harness/scoring/verdict.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

namespace ib {
namespace verdict_thresholds_test {

// Both tips at rest, 1 s at 100 Hz, mechanical energy 1 mJ: ok by every bound.
RunResult quiet_run() {
  RunResult r;
  Trajectory& t = r.trajectory;
  for (int k = 0; k <= 100; ++k) {
    t.time_s.push_back(k * 0.01);
    for (int f = 0; f < 2; ++f) {
      t.displacement_m[f].push_back(0);
      t.velocity_m_s[f].push_back(0);
      t.acceleration_m_s2[f].push_back(0);
      t.peak_abs_acceleration_m_s2[f].push_back(0);
    }
    t.contact_force_n.push_back(0);
    t.peak_contact_force_n.push_back(0);
    t.mechanical_energy_j.push_back(1e-3);
  }
  return r;
}

Scenario free_rig(double gap_m = 1e-3) {
  Scenario s = default_rig();
  s.motor.reset();
  s.gap_m = gap_m;
  return s;
}

Verdict with_energy_rise(double relative_rise) {
  RunResult r = quiet_run();
  r.trajectory.mechanical_energy_j[60] = 1e-3 * (1 + relative_rise);
  return judge_stability(free_rig(), r, {}).verdict;
}

TEST(VerdictThresholds, EnergyGrowthWithoutInputIsOneThousandth) {
  EXPECT_EQ(with_energy_rise(0.99e-3), Verdict::ok);
  EXPECT_EQ(with_energy_rise(1.01e-3), Verdict::unstable);
}

Verdict with_tip_displacement(int frame, double u_m) {
  RunResult r = quiet_run();
  r.trajectory.displacement_m[frame][40] = u_m;
  // toward the other tip, the other moves along: no overlap, the displacement bound alone
  if ((frame == 0 && u_m > 0) || (frame == 1 && u_m < 0)) r.trajectory.displacement_m[1 - frame][40] = u_m;
  return judge_stability(free_rig(), r, {}).verdict;
}

TEST(VerdictThresholds, TipDisplacementIsATenthOfTheFrameLength) {
  // the published frames are 0.300 m long: the bound is 0.030 m, either sign
  for (int frame = 0; frame < 2; ++frame)
    for (double sign : {1.0, -1.0}) {
      EXPECT_EQ(with_tip_displacement(frame, sign * 0.0299), Verdict::ok) << frame;
      EXPECT_EQ(with_tip_displacement(frame, sign * 0.0301), Verdict::unstable) << frame;
    }
}

Verdict with_overlap(double gap_m, double overlap_m, bool in_event) {
  RunResult r = quiet_run();
  if (in_event) {
    ContactEvent e;
    e.onset_time_s = 0.3;
    e.end_time_s = 0.301;
    e.max_indentation_m = overlap_m;
    r.trajectory.events.push_back(e);
  } else {
    r.trajectory.displacement_m[0][30] = gap_m + overlap_m;  // frame 2 at rest: overlap = u1 - u2 - gap
    r.trajectory.contact_force_n[30] = 1;
  }
  return judge_stability(free_rig(gap_m), r, {}).verdict;
}

TEST(VerdictThresholds, PenetrationIsTenGapsWithACentimetreFloor) {
  for (bool in_event : {false, true}) {
    // 2 mm gap: 20 mm
    EXPECT_EQ(with_overlap(2e-3, 19.9e-3, in_event), Verdict::ok);
    EXPECT_EQ(with_overlap(2e-3, 20.1e-3, in_event), Verdict::unstable);
    // 1 mm gap (the published rig): 10 mm, the floor too
    EXPECT_EQ(with_overlap(1e-3, 9.9e-3, in_event), Verdict::ok);
    EXPECT_EQ(with_overlap(1e-3, 10.1e-3, in_event), Verdict::unstable);
    // a tiny gap, and none: the floor of 10 mm, so that a contact of tens of micrometres is not "unstable"
    for (double gap : {1e-7, 0.0}) {
      EXPECT_EQ(with_overlap(gap, 30e-6, in_event), Verdict::ok) << gap;
      EXPECT_EQ(with_overlap(gap, 9.9e-3, in_event), Verdict::ok) << gap;
      EXPECT_EQ(with_overlap(gap, 10.1e-3, in_event), Verdict::unstable) << gap;
    }
  }
}

TEST(VerdictThresholds, ARunWithoutSamplesIsNeverOk) {
  RunResult r;
  const Judgement j = judge_stability(free_rig(), r, {});
  EXPECT_EQ(j.verdict, Verdict::failed);
  EXPECT_NE(j.reason.find("no samples"), std::string::npos) << j.reason;
}

// Each headline error alone, at 0.999 and 1.001 times its tolerance, both signs.
TEST(VerdictThresholds, AccuracyTolerancesAreTenPercentAndATenthOfAnImpactPerCycle) {
  const auto verdict = [](auto set, double error) {
    MetricErrors e;
    set(e, error);
    return judge_accuracy(e, {}, "beam").verdict;
  };
  const std::vector<std::pair<const char*, std::function<void(MetricErrors&, double)>>> errors = {
      {"frame 1 sensor peak", [](MetricErrors& e, double x) { e.sensor_peak_relative_error[0] = x; }},
      {"frame 2 sensor peak", [](MetricErrors& e, double x) { e.sensor_peak_relative_error[1] = x; }},
      {"contact duration", [](MetricErrors& e, double x) { e.contact_duration_relative_error = x; }},
      {"impacts per cycle", [](MetricErrors& e, double x) { e.impacts_per_cycle_difference = x; }},
      {"frame 1 log decrement", [](MetricErrors& e, double x) { e.log_decrement_relative_error[0] = x; }},
  };
  constexpr double kTolerance = 0.10;  // relative for the first three and the decrement, absolute for impacts per cycle
  for (const auto& [name, set] : errors)
    for (double sign : {1.0, -1.0}) {
      EXPECT_EQ(verdict(set, sign * 0.999 * kTolerance), Verdict::ok) << name;
      EXPECT_EQ(verdict(set, sign * 1.001 * kTolerance), Verdict::inaccurate) << name;
    }
}

}  // namespace verdict_thresholds_test
}  // namespace ib
