// The resonance case (motor at f_1), spring-dashpot law on the matched path at the default step
// h = 1e-4 s (6 steps per contact), against the reference on the same chain: impacts per cycle equal
// and frame 1's sensor peak acceleration within 10 % (issue 4).
//
// A 20 s run scored over its last 10 s instead of 100 s / 14 s: on this chain the reference settles
// into one impact every second motor cycle within 10 s. Measured with the reference (K = 8): window
// [10, 20] s 0.489 impacts per cycle (34 in 69.5 cycles), frame 1 sensor peak 7.559 g; window
// [86, 100] s of a 100 s run 0.493 (48 in 97.3 cycles), 7.558 g; window [5, 10] s still in the
// transient, 0.518, 7.89 g.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "adapters/mujoco/mujoco_simulator.h"
#include "engine_measurements.h"
#include "harness/jobs/run_job.h"
#include "harness/scoring/metrics.h"

namespace ib {
namespace mujoco_resonance_test {

TEST(MujocoResonance, ImpactsPerCycleAndSensorPeakMatchTheReference) {
  Scenario s = testing::paper_scenario("resonance");
  s.duration_s = 20;
  s.scoring_window_s = 10;
  Measurement measurement;
  const MetricSettings window = metric_settings(s, measurement);
  RunSettings run;
  run.law = ContactLaw::viscoelastic;
  run.time_step_s = 1e-4;
  run.series_start_s = window.window.start_s;
  const testing::EngineAndReference runs = testing::run_with_reference(*make_mujoco_simulator(), s, run);
  const RunResult &engine = runs.engine, &reference = runs.reference;
  ASSERT_EQ(engine.status, RunStatus::ok) << engine.reason;
  ASSERT_EQ(reference.status, RunStatus::ok) << reference.reason;

  const Metrics m = compute_metrics(engine.trajectory, window), r = compute_metrics(reference.trajectory, window);
  std::printf(
      "impacts %d / %d, per cycle %.4f (reference %.4f); sensor peak frame 1 %.3f g (reference %.3f g, %+.2f %%), "
      "frame 2 %.3f g (reference %.3f g); MuJoCo %lld steps in %.2f s CPU\n",
      m.impacts, r.impacts, m.impacts_per_cycle, r.impacts_per_cycle, m.frames[0].sensor_peak_acceleration_g,
      r.frames[0].sensor_peak_acceleration_g,
      100 * (m.frames[0].sensor_peak_acceleration_g / r.frames[0].sensor_peak_acceleration_g - 1),
      m.frames[1].sensor_peak_acceleration_g, r.frames[1].sensor_peak_acceleration_g, engine.cost.steps,
      engine.cost.cpu_time_s);
  ASSERT_GT(r.impacts, 20);  // the window holds the steady impacting motion
  // equal: the same number of impacts in the same window (one impact is 1 / 69.5 per cycle)
  EXPECT_NEAR(m.impacts_per_cycle, r.impacts_per_cycle, 0.5 / m.excitation_cycles);
  EXPECT_NEAR(m.frames[0].sensor_peak_acceleration_g / r.frames[0].sensor_peak_acceleration_g, 1, 0.10);
  EXPECT_EQ(m.raw_onsets, m.impacts) << "contact flicker";
}

}  // namespace mujoco_resonance_test
}  // namespace ib
