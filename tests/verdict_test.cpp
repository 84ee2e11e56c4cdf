// Stability and accuracy verdicts on constructed trajectories: each kind of instability is named
// with a reason a person can check.
#include "harness/scoring/verdict.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace ib {
namespace verdict_test {

// A quiet run: both tips at rest, 1 s at 100 Hz, constant energy.
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

Scenario free_rig() {
  Scenario s = default_rig();
  s.motor.reset();
  return s;
}

TEST(Verdict, AQuietRunIsOk) {
  const Judgement j = judge_stability(free_rig(), quiet_run(), {});
  EXPECT_EQ(j.verdict, Verdict::ok);
  EXPECT_TRUE(j.reason.empty());
}

TEST(Verdict, NonFiniteStateIsUnstableWithTheTime) {
  RunResult r = quiet_run();
  r.trajectory.velocity_m_s[1][40] = std::numeric_limits<double>::quiet_NaN();
  const Judgement j = judge_stability(free_rig(), r, {});
  EXPECT_EQ(j.verdict, Verdict::unstable);
  EXPECT_NE(j.reason.find("non-finite state of frame 2 at t = 0.4 s"), std::string::npos) << j.reason;
}

TEST(Verdict, DisplacementBeyondTheBoundIsUnstable) {
  RunResult r = quiet_run();
  r.trajectory.displacement_m[0][70] = -0.05;  // 5 cm on a 0.3 m frame: beyond 0.1 L
  const Judgement j = judge_stability(free_rig(), r, {});
  EXPECT_EQ(j.verdict, Verdict::unstable);
  EXPECT_NE(j.reason.find("frame 1 tip displacement"), std::string::npos) << j.reason;
  EXPECT_NE(j.reason.find("0.03"), std::string::npos) << j.reason;  // the bound
}

TEST(Verdict, PenetrationBeyondTenGapsIsUnstable) {
  RunResult r = quiet_run();
  r.trajectory.displacement_m[0][20] = 0.0125;  // delta = 12.5 mm - 1 mm = 11.5 mm > 10 mm
  Judgement j = judge_stability(free_rig(), r, {});
  EXPECT_EQ(j.verdict, Verdict::unstable);
  EXPECT_NE(j.reason.find("penetration"), std::string::npos) << j.reason;
  // also when only the events see it (between samples)
  r = quiet_run();
  ContactEvent e;
  e.onset_time_s = 0.5;
  e.max_indentation_m = 0.02;
  r.trajectory.events.push_back(e);
  j = judge_stability(free_rig(), r, {});
  EXPECT_EQ(j.verdict, Verdict::unstable);
  EXPECT_NE(j.reason.find("t = 0.5 s"), std::string::npos) << j.reason;
}

TEST(Verdict, EnergyGrowingWithoutInputIsUnstableButNotWithAMotor) {
  RunResult r = quiet_run();
  for (std::size_t k = 50; k < r.trajectory.size(); ++k) r.trajectory.mechanical_energy_j[k] = 1.2e-3;
  Judgement j = judge_stability(free_rig(), r, {});
  EXPECT_EQ(j.verdict, Verdict::unstable);
  EXPECT_NE(j.reason.find("energy grew without input from 0.001 J to 0.0012 J at t = 0.5 s"), std::string::npos)
      << j.reason;
  j = judge_stability(default_rig(), r, {});  // the motor feeds energy in: no verdict from energy
  EXPECT_EQ(j.verdict, Verdict::ok);
  // inside a contact the stored elastic energy may jump with the overlap a step resolves: not judged
  r = quiet_run();
  r.trajectory.mechanical_energy_j[30] = 2e-3;
  r.trajectory.contact_force_n[30] = 50;
  EXPECT_EQ(judge_stability(free_rig(), r, {}).verdict, Verdict::ok);
  // a rise within the tolerance (rounding, say) is fine
  r = quiet_run();
  r.trajectory.mechanical_energy_j.back() = 1e-3 * (1 + 1e-6);
  EXPECT_EQ(judge_stability(free_rig(), r, {}).verdict, Verdict::ok);
}

// The series of a long run covers its last seconds only: energy is judged against the run's start, so a
// run that lost most of its energy is not called unstable for swings late in the run, and a run that
// gained energy before the series began is caught.
TEST(Verdict, EnergyIsJudgedAgainstTheRunsStart) {
  RunResult r = quiet_run();
  r.trajectory.initial_mechanical_energy_j = 5e-3;  // lost 80 % before the series began
  for (std::size_t k = 0; k < r.trajectory.size(); ++k) r.trajectory.mechanical_energy_j[k] = k % 2 ? 1.1e-3 : 0.9e-3;
  EXPECT_EQ(judge_stability(free_rig(), r, {}).verdict, Verdict::ok);
  r = quiet_run();
  r.trajectory.initial_mechanical_energy_j = 0.5e-3;  // doubled before the series began
  const Judgement j = judge_stability(free_rig(), r, {});
  EXPECT_EQ(j.verdict, Verdict::unstable);
  EXPECT_NE(j.reason.find("from 0.0005 J to 0.001 J at t = 0 s"), std::string::npos) << j.reason;
}

TEST(Verdict, TheSimulatorsOwnErrorIsKeptWithItsReason) {
  RunResult r = quiet_run();
  r.status = RunStatus::failed;
  r.reason = "engine said no";
  Judgement j = judge_stability(free_rig(), r, {});
  EXPECT_EQ(j.verdict, Verdict::failed);
  EXPECT_EQ(j.reason, "engine said no");
  r.status = RunStatus::unstable;
  r.reason = "warning: bad inertia";
  j = judge_stability(free_rig(), r, {});
  EXPECT_EQ(j.verdict, Verdict::unstable);
  EXPECT_EQ(j.reason, "warning: bad inertia");
}

TEST(Verdict, ErrorsBeyondToleranceAreInaccurate) {
  MetricErrors e;
  EXPECT_EQ(judge_accuracy(e, {}, "own chain").verdict, Verdict::ok);
  e.sensor_peak_relative_error[1] = -0.25;
  e.impacts_per_cycle_difference = 0.5;
  e.log_decrement_relative_error[0] = 0.46;
  const Judgement j = judge_accuracy(e, {}, "own chain");
  EXPECT_EQ(j.verdict, Verdict::inaccurate);
  // the reference named once, every error signed, every tolerance stated
  EXPECT_EQ(j.reason.rfind("vs own chain: ", 0), 0u) << j.reason;
  EXPECT_NE(j.reason.find("frame 2 sensor peak -25 % (tolerance 10 %)"), std::string::npos) << j.reason;
  EXPECT_NE(j.reason.find("impacts per cycle +0.5 (tolerance 0.1)"), std::string::npos) << j.reason;
  EXPECT_NE(j.reason.find("frame 1 log decrement +46 % (tolerance 10 %)"), std::string::npos) << j.reason;
}

TEST(Verdict, AnErrorAtTheToleranceOrUndefinedIsNotInaccurate) {
  MetricErrors e;
  e.sensor_peak_relative_error = {0.10, -0.10};
  e.contact_duration_relative_error = std::nan("");
  // frame 2's fitted decrement is data, not judged: it first gains from the impacts
  e.log_decrement_relative_error = {std::nan(""), 0.5};
  EXPECT_EQ(judge_accuracy(e, {}, "beam").verdict, Verdict::ok);
  e.log_decrement_relative_error = {0.0999, 0.5};
  EXPECT_EQ(judge_accuracy(e, {}, "beam").verdict, Verdict::ok);
}

TEST(Verdict, NamesRoundTrip) {
  for (Verdict v : {Verdict::ok, Verdict::inaccurate, Verdict::unstable, Verdict::failed})
    EXPECT_EQ(verdict_from_string(to_string(v)), v);
  EXPECT_FALSE(verdict_from_string("fine"));
}

}  // namespace verdict_test
}  // namespace ib
