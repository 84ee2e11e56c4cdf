// The chains ODE builds vibrate at the reference chain's frequencies with its damping: a contact-free
// free decay (gap 1 m) of each frame, released from its static tip-load shape. The implicit hinge
// springs (backward Euler) add a damping ratio of omega h / 2, so zeta is matched only at short steps;
// the explicit springs (semi-implicit Euler) add none but need a step below their stability limit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "adapters/ode/ode_simulator.h"
#include "engine_measurements.h"

namespace ib {
namespace ode_free_decay_test {

using testing::chain_mode;
using testing::ChainMode;
using testing::contact_free_decay;
using testing::Decay;
using testing::free_decay_settings;
using testing::measure_decay;
constexpr double kMeasureFrom_s = testing::kDecayMeasuredFrom_s;

RunResult run_ode(const Scenario& s, double h, const std::string& springs) {
  return make_ode_simulator()->run(s, free_decay_settings(h, {{"springs", springs}}));
}

// The estimator itself, on the reference's run of the same chain: it must find the chain's mode. With the
// hinge damping the higher modes have died out (zeta_n >= 0.03) when it starts measuring: the frequency within
// 1e-4. With the modal damping (the default, what the engines run) they ring on at zeta = 0.003, mode 2 with
// 2e-4 of mode 1's amplitude from the tip-load shape, and shift the refined peaks: within 4e-4. How far depends
// on where mode 2 falls against the estimator's peaks, not on its share of the shape (1e-3 of the tip's
// displacement both ways): seen 1.1e-4 with uniform joints (mode 2 at 10.62 f_1), 2.9e-4 with the tuned joints
// (the beam's 10.53 f_1).
TEST(OdeFreeDecay, TheEstimatorFindsTheReferenceChainsMode) {
  const Scenario s = contact_free_decay(false);
  const ChainMode mode = chain_mode(s);
  for (ChainDamping damping : {ChainDamping::hinge, ChainDamping::modal}) {
    RunSettings settings = free_decay_settings(0, {});
    settings.options = chain_reference_options_with_damping(default_links(s), damping);
    const RunResult r = make_reference_simulator()->run(s, settings);
    const Decay d = measure_decay(r.trajectory, kMeasureFrom_s);
    EXPECT_NEAR(d.frequency_hz / mode.damped_frequency_hz, 1, damping == ChainDamping::hinge ? 1e-4 : 4e-4)
        << to_string(damping);
    EXPECT_NEAR(d.damping_ratio / mode.zeta, 1, 0.01) << to_string(damping);
  }
}

// Implicit springs at h = 5e-6 s: their numerical damping omega_1 h / 2 is 1.1e-4 (frame 1) and
// 1.3e-4 (frame 2), 4 % of zeta = 0.003, inside the 10 % asked for. (At the default 1e-4 s it is
// 70 % of zeta: see the next test.) 200 000 steps per frame, about 4 s of CPU each.
TEST(OdeFreeDecay, ImplicitSpringsGiveTheChainFrequenciesAndZetaAtShortSteps) {
  const double h = 5e-6;
  for (bool swap : {false, true}) {
    const Scenario s = contact_free_decay(swap);
    testing::expect_chain_mode(swap ? "light frame" : "heavy frame", s, run_ode(s, h, "implicit"), 0.005, 0.10);
  }
}

// At the default step the implicit springs' extra damping is what backward Euler predicts, omega h / 2
// (within 3 % of it): a property of the path, documented, not a defect to hide.
TEST(OdeFreeDecay, ImplicitSpringsAddOmegaHOverTwoToTheDamping) {
  const double h = 1e-4;
  const Scenario s = contact_free_decay(false);
  testing::expect_backward_euler_damping(s, run_ode(s, h, "implicit"), h, 0.03);
}

// Explicit springs below their stability limit (7.5e-5 s for K = 8): no numerical damping, so zeta
// within 2 % and the frequency within 0.5 % at h = 2e-5 s.
TEST(OdeFreeDecay, ExplicitSpringsGiveTheChainModeBelowTheirStepLimit) {
  const double h = 2e-5;
  const Scenario s = contact_free_decay(false);
  const RunResult r = run_ode(s, h, "explicit");
  ASSERT_EQ(r.status, RunStatus::ok) << r.reason;
  const Decay d = measure_decay(r.trajectory, kMeasureFrom_s);
  const ChainMode mode = chain_mode(s);
  std::printf("explicit, h = %g s: f = %.5f Hz (chain %.5f Hz), zeta = %.6f (chain %.4f), %.2f us/step\n", h,
              d.frequency_hz, mode.damped_frequency_hz, d.damping_ratio, mode.zeta,
              1e6 * r.cost.cpu_time_s / r.cost.steps);
  EXPECT_NEAR(d.frequency_hz / mode.damped_frequency_hz, 1, 0.005);
  EXPECT_NEAR(d.damping_ratio / mode.zeta, 1, 0.02);
}

}  // namespace ode_free_decay_test
}  // namespace ib
