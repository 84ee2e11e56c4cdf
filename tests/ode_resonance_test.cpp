// The published resonance case with the spring-dashpot law, against the reference on the same chain:
// the impacting regime (impacts per motor cycle) and frame 1's sensor peak acceleration.
//
// Measured (reference on the K = 8 chain): the impacts settle by about 6 s into one impact every two
// motor cycles (0.50 per cycle) with frame 1's sensor peak near 7.9 g (7.5 g with the hinge chain damping,
// whose fast modes stop ringing sooner; 8.6 g with the law clipped as ODE's contact is), and stay there
// through 30 s. So
// the run is cut to 12 s and scored over its last 6 s (42 cycles).
//
// The step is 2e-5 s: ODE's soft contact (backward Euler, omega h = 0.10 for the contact) then loses
// about 12 % of the restitution per impact (0.68 instead of 0.78), which the structure's response
// absorbs: the regime and the peaks stay the reference's. At the default 1e-4 s (omega h = 0.52) the
// restitution drops to 0.44 and the rig settles into a different regime (an impact every cycle at
// about half the peak): see adapters/ode/README.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "adapters/ode/ode_simulator.h"
#include "engine_measurements.h"
#include "harness/jobs/run_job.h"
#include "harness/scoring/metrics.h"
#include "physics/modal_model.h"

namespace ib {
namespace ode_resonance_test {

TEST(OdeResonance, SpringDashpotImpactsPerCycleAndSensorPeakMatchTheReference) {
  Scenario s = testing::settled_resonance();
  // ODE's contact only pushes: the reference runs the same, clipped, law (tests/ode_single_impact_test.cpp)
  s.contact.viscoelastic->clip_tension = true;
  // Explicit springs: stable at 2e-5 s (limit 1.65e-4 s with the modal chain damping) and, unlike the default
  // implicit ones, without numerical damping. The implicit springs add omega h / 2 to every mode's zeta, 0.0046
  // to mode 2's 0.003 at 2e-5 s, which shortens the ringing the sensor peak catches: -11.6 % (docs/engines.md).
  const testing::ResonanceComparison c =
      testing::compare_resonance(*make_ode_simulator(), s, 2e-5, {{"springs", "explicit"}});
  const RunResult& run = c.run;
  ASSERT_EQ(run.status, RunStatus::ok) << run.reason;
  const Metrics &reference = c.reference, &ode = c.engine;

  std::printf(
      "reference: %.4f impacts/cycle (%d impacts, %.1f cycles), frame 1 sensor peak %.3f g, frame 2 %.3f g, e %.3f\n",
      reference.impacts_per_cycle, reference.impacts, reference.excitation_cycles,
      reference.frames[0].sensor_peak_acceleration_g, reference.frames[1].sensor_peak_acceleration_g,
      reference.mean_restitution);
  std::printf(
      "ode h = 2e-5 s: %.4f impacts/cycle (%d impacts), frame 1 sensor peak %.3f g (%+.1f %%), frame 2 %.3f g, e %.3f; "
      "%.1f s CPU, %.2f us/step\n",
      ode.impacts_per_cycle, ode.impacts, ode.frames[0].sensor_peak_acceleration_g,
      100 * (ode.frames[0].sensor_peak_acceleration_g / reference.frames[0].sensor_peak_acceleration_g - 1),
      ode.frames[1].sensor_peak_acceleration_g, ode.mean_restitution, run.cost.cpu_time_s,
      1e6 * run.cost.cpu_time_s / run.cost.steps);
  ASSERT_GT(reference.impacts, 0);
  // equal, up to the one impact by which a window edge can cut a two-cycle pattern differently
  EXPECT_LE(std::abs(ode.impacts_per_cycle - reference.impacts_per_cycle), 1.0 / reference.excitation_cycles + 1e-12);
  EXPECT_NEAR(ode.frames[0].sensor_peak_acceleration_g / reference.frames[0].sensor_peak_acceleration_g, 1, 0.10);
}

}  // namespace ode_resonance_test
}  // namespace ib
