// The published resonance case with the spring-dashpot law, against the reference on the same chain: the
// impacting regime (impacts per motor cycle) and frame 1's sensor peak acceleration.
//
// The reference on the K = 8 chain settles by about 6 s into one impact every two motor cycles (0.50 per
// cycle) and stays there (tests/ode_resonance_test.cpp): the run is cut to 12 s and scored over its last
// 6 s. Simbody's force element is the published (unclipped) law, so the reference runs that law too.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "adapters/simbody/simbody_simulator.h"
#include "engine_measurements.h"
#include "harness/jobs/run_job.h"
#include "harness/scoring/metrics.h"

namespace ib {
namespace simbody_resonance_test {

// Matched spring-dashpot, semi-explicit Euler at 5e-5 s (the default step; the contact's omega h = 0.26):
// stable, impacts per cycle within 0.05 of the reference's, frame 1's sensor peak within 10 %. The peak is
// the mean over the sensor grid's phases (docs/statistics.md): at this step the maximum on one grid is a
// sample of that spread (on the tuned chain: 7.54 to 8.79 g over two phases against the reference's 7.71 g).
TEST(SimbodyResonance, SpringDashpotImpactsPerCycleMatchTheReference) {
  Scenario s = testing::settled_resonance();
  const testing::ResonanceComparison c =
      testing::compare_resonance(*make_simbody_simulator(), s, 5e-5, {{"contact", "matched"}});
  const RunResult &run = c.run;
  ASSERT_EQ(run.status, RunStatus::ok) << run.reason;
  const Metrics &reference = c.reference, &sb = c.engine;

  std::printf("reference: %.4f impacts/cycle (%d impacts, %.1f cycles), frame 1 sensor peak %.3f g, e %.3f\n",
              reference.impacts_per_cycle, reference.impacts, reference.excitation_cycles,
              reference.frames[0].sensor_peak_acceleration_g, reference.mean_restitution);
  std::printf(
      "simbody h = 5e-5 s: %.4f impacts/cycle (%d impacts), frame 1 sensor peak %.3f g (%+.1f %%), e %.3f; "
      "%.2f us/step\n",
      sb.impacts_per_cycle, sb.impacts, sb.frames[0].sensor_peak_acceleration_g,
      100 * (sb.frames[0].sensor_peak_acceleration_g / reference.frames[0].sensor_peak_acceleration_g - 1),
      sb.mean_restitution, 1e6 * run.cost.cpu_time_s / run.cost.steps);
  ASSERT_GT(reference.impacts, 0);
  EXPECT_LE(std::abs(sb.impacts_per_cycle - reference.impacts_per_cycle), 0.05);
  const GridPhaseSpread &engine_peak = sb.sensor_peak_over_grid_phases[0],
                        &reference_peak = reference.sensor_peak_over_grid_phases[0];
  std::printf("frame 1 sensor peak over %d grid phases: %.3f g (%.3f to %.3f), reference %.3f g (%+.1f %%)\n",
              engine_peak.phases_read, engine_peak.mean_g, engine_peak.min_g, engine_peak.max_g, reference_peak.mean_g,
              100 * (engine_peak.mean_g / reference_peak.mean_g - 1));
  ASSERT_GE(engine_peak.phases_read, 2);
  EXPECT_NEAR(engine_peak.mean_g / reference_peak.mean_g, 1, 0.10);
}

}  // namespace simbody_resonance_test
}  // namespace ib
