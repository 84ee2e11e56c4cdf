// The published resonance case (motor at frame 1's f_1) with the spring-dashpot law in Bullet at the
// adapter's default step, against the reference on the same K-link chain: the impacting steady state
// has the reference's impacts per cycle and frame 1's sensor peak acceleration.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "adapters/bullet/bullet_simulator.h"
#include "harness/scoring/metrics.h"
#include "physics/modal_model.h"
#include "reference/reference_simulator.h"
#include "reference_fixtures.h"

namespace ib {
namespace bullet_resonance_test {

constexpr int kLinks = 8;

TEST(BulletResonance, ImpactsPerCycleAndSensorPeakAreTheReferences) {
  Scenario s = testing::paper_scenario("resonance");
  // The reference on the K = 8 chain settles into one impact every two motor cycles: onsets are
  // 2 / f_exc apart to four digits from about 10 s on (measured). 20 s reaches it; the window is the
  // last 40 motor cycles (20 impact periods), so it holds the same number of impacts whatever the
  // phase of the impacts in it.
  s.duration_s = 20;
  const double f_exc = motor_frequency_hz(s);
  s.scoring_window_s = 40 / f_exc;
  MetricSettings window;
  window.window = scoring_window(s);
  window.excitation_frequency_hz = f_exc;
  window.natural_frequency_hz = frame1_first_frequency_hz(s);

  RunSettings settings;
  settings.law = ContactLaw::viscoelastic;
  settings.series_start_s = window.window.start_s;
  settings.options = chain_reference_options(kLinks);
  const RunResult reference = make_reference_simulator()->run(s, settings);
  ASSERT_EQ(reference.status, RunStatus::ok) << reference.reason;
  const Metrics expected = compute_metrics(reference.trajectory, window);
  ASSERT_GT(expected.impacts, 0);

  // Half the adapter's default step. Bullet's implicit contact loses energy (a single impact's restitution
  // is 0.55 instead of 0.78 at 5e-5 s); at 2.5e-5 s the steady state, set by the forcing and the gap, comes
  // out the reference's. At the default 5e-5 s the rig on the tuned chain (rig.md section 4) settles instead
  // into one impact per motor cycle: a finding the studies report, not agreement.
  settings.time_step_s = 2.5e-5;
  settings.options = {{"contact", "matched"}, {"links", std::to_string(kLinks)}};
  const RunResult bullet = make_bullet_simulator()->run(s, settings);
  ASSERT_EQ(bullet.status, RunStatus::ok) << bullet.reason;
  const Metrics measured = compute_metrics(bullet.trajectory, window);

  EXPECT_EQ(measured.impacts, expected.impacts);
  EXPECT_DOUBLE_EQ(measured.impacts_per_cycle, expected.impacts_per_cycle);
  const double peak = measured.frames[0].sensor_peak_acceleration_g,
               expected_peak = expected.frames[0].sensor_peak_acceleration_g;
  EXPECT_NEAR(peak / expected_peak, 1.0, 0.10);
  std::printf(
      "[ measured ] h = 2.5e-5 s: impacts per cycle %.4f (reference %.4f), frame 1 sensor peak %.4f g "
      "(reference %.4f g, %+.2f %%), frame 2 %.4f g (reference %.4f g), %lld steps, %.1f us/step\n",
      measured.impacts_per_cycle, expected.impacts_per_cycle, peak, expected_peak, 100 * (peak / expected_peak - 1),
      measured.frames[1].sensor_peak_acceleration_g, expected.frames[1].sensor_peak_acceleration_g, bullet.cost.steps,
      1e6 * bullet.cost.cpu_time_s / static_cast<double>(bullet.cost.steps));
}

}  // namespace bullet_resonance_test
}  // namespace ib
