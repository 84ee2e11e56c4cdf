// The chain MuJoCo simulates is the chain the reference builds: frame 1 released from its static
// tip-load shape with the frames far apart (no contact), its tip's free decay measured in MuJoCo, and
// the first two natural frequencies and decay rates read off it compared with the reference's chain
// modes (physics/link_chain.h). Both frames' chains (frame 2's by swapping the frames), both
// integrators.
#include <gtest/gtest.h>

#include <algorithm>
#include <complex>
#include <vector>

#include "adapters/mujoco/mujoco_simulator.h"
#include "modal_identification.h"
#include "physics/link_chain.h"
#include "reference_fixtures.h"

namespace ib {
namespace mujoco_chain_free_decay_test {

using Mode = test::DampedMode;

class MujocoChainFreeDecay : public ::testing::TestWithParam<std::tuple<int, std::string>> {};

TEST_P(MujocoChainFreeDecay, FirstTwoModesAreTheReferenceChains) {
  const auto [frame, integrator] = GetParam();
  Scenario s = testing::paper_scenario("free_vibration");
  if (frame == 1) std::swap(s.frames[0], s.frames[1]);  // frame 2's chain in the deflected position
  s.gap_m = 1.0;                                        // no contact
  // 20 um: the geometric nonlinearity (relative size u/L squared) stays far below the second mode,
  // which the tip-load shape excites at about 2e-4 of the first
  s.initial.frame1_tip_displacement_m = -2e-5;
  s.duration_s = 0.4;  // 2.8 periods of mode 1; the pencil needs no more on noise-free samples
  s.scoring_window_s = s.duration_s;
  RunSettings run;
  run.law = ContactLaw::viscoelastic;
  run.time_step_s = 1e-4;     // the default step: what the suite runs
  run.output_rate_hz = 5000;  // every other step; above twice the fastest chain mode (1.96 kHz)
  run.series_start_s = 0;
  run.options = {{"integrator", integrator}};
  const auto simulator = make_mujoco_simulator();
  const int links = *simulator->chain_links(s, run);
  const RunResult result = simulator->run(s, run);
  ASSERT_EQ(result.status, RunStatus::ok) << result.reason;

  const ModalBasis reference = chain_modes(build_link_chain(s.frames[0], links));
  // all 2K poles of the chain's tip response
  std::vector<Mode> modes =
      test::matrix_pencil_modes(result.trajectory.displacement_m[0], 1 / run.output_rate_hz, 2 * links);
  ASSERT_GE(modes.size(), 2u);
  modes.resize(2);
  std::sort(modes.begin(), modes.end(), [](const Mode& a, const Mode& b) { return a.frequency_hz < b.frequency_hz; });
  for (int n = 0; n < 2; ++n) {
    const double f_ref = reference.omega_rad_s[n] / (2 * M_PI), zeta_ref = reference.zeta[n];
    std::printf("frame %d %s mode %d: %.6f Hz (reference %.6f, %+.4f %%), zeta %.6f (reference %.6f, %+.3f %%)\n",
                frame + 1, integrator.c_str(), n + 1, modes[n].frequency_hz, f_ref,
                100 * (modes[n].frequency_hz / f_ref - 1), modes[n].damping_ratio, zeta_ref,
                100 * (modes[n].damping_ratio / zeta_ref - 1));
    EXPECT_NEAR(modes[n].frequency_hz / f_ref, 1, 0.005) << "mode " << n + 1;  // issue 4: 0.5 %
    // the scenario's zeta = 0.003 in both modes (modal chain damping, the default: MuJoCo's hinges have no
    // dampers and the loop's torques -C theta' give each mode zeta)
    EXPECT_NEAR(modes[n].damping_ratio / zeta_ref, 1, 0.10) << "mode " << n + 1;  // issue 4: 10 %
  }
  EXPECT_NEAR(reference.zeta[0], s.frames[0].damping_ratio, 1e-12);
  EXPECT_NEAR(reference.zeta[1], s.frames[0].damping_ratio, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(FramesAndIntegrators, MujocoChainFreeDecay,
                         ::testing::Combine(::testing::Values(0, 1), ::testing::Values("euler", "rk4")),
                         [](const auto& info) {
                           return "frame" + std::to_string(std::get<0>(info.param) + 1) + "_" + std::get<1>(info.param);
                         });

}  // namespace mujoco_chain_free_decay_test
}  // namespace ib
