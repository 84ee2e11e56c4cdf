// Bullet's chains without contact (gap 1 m), both articulation paths: the first frequency and the decay
// rate of a free decay against the modes of the same K-link chain (rig.md section 4), which the
// reference builds from the same LinkChain. Checks the body masses, inertias, joint placement, the
// hinge springs and their stiffness-proportional damping as Bullet realises them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "adapters/bullet/bullet_simulator.h"
#include "physics/link_chain.h"
#include "reference/reference_simulator.h"
#include "reference_fixtures.h"

namespace ib {
namespace bullet_free_decay_test {

constexpr int kLinks = 8;  // the default for the paper's rig (first frequency 0.2 % above the beam's)

struct Decay {
  double frequency_hz = 0;  // from the upward zero crossings
  double zeta = 0;          // from the decay of the peaks: ln A = a - zeta omega t
  int cycles = 0;
};

// Frame 1's tip displacement from settle_s on: the mean period between upward zero crossings
// (interpolated linearly), and a least-squares line through the log of the peaks (each refined by
// a parabola through its three samples).
Decay measure_decay(const Trajectory& t, double settle_s) {
  const auto& u = t.displacement_m[0];
  const auto& time = t.time_s;
  std::vector<double> crossings, peak_t, peak_log;
  for (std::size_t k = 1; k + 1 < u.size(); ++k) {
    if (time[k] < settle_s) continue;
    if (u[k - 1] < 0 && u[k] >= 0)
      crossings.push_back(time[k - 1] + (time[k] - time[k - 1]) * -u[k - 1] / (u[k] - u[k - 1]));
    if (u[k] > u[k - 1] && u[k] >= u[k + 1] && u[k] > 0) {
      const double a = u[k - 1], b = u[k], c = u[k + 1], dt = time[k + 1] - time[k];
      const double offset = 0.5 * (a - c) / (a - 2 * b + c);
      peak_t.push_back(time[k] + offset * dt);
      peak_log.push_back(std::log(b - 0.25 * (a - c) * offset));
    }
  }
  Decay d;
  if (crossings.size() < 3 || peak_t.size() < 3) return d;
  d.cycles = static_cast<int>(crossings.size()) - 1;
  d.frequency_hz = d.cycles / (crossings.back() - crossings.front());
  const double n = static_cast<double>(peak_t.size());
  double st = 0, sl = 0, stt = 0, stl = 0;
  for (std::size_t i = 0; i < peak_t.size(); ++i) {
    st += peak_t[i];
    sl += peak_log[i];
    stt += peak_t[i] * peak_t[i];
    stl += peak_t[i] * peak_log[i];
  }
  const double slope = (n * stl - st * sl) / (n * stt - st * st);
  d.zeta = -slope / (2 * M_PI * d.frequency_hz);
  return d;
}

// The paper's free vibration without contact. frame = 1 releases frame 1's chain; frame = 2 swaps
// the frames so that frame 2's (lighter) chain is the one released.
Scenario contact_free_decay(int frame) {
  Scenario s = testing::paper_scenario("free_vibration");
  if (frame == 2) std::swap(s.frames[0], s.frames[1]);
  s.gap_m = 1.0;
  // 4 s: 28 cycles of frame 1, over which the amplitude falls by e^-0.53 at zeta = 0.003
  s.duration_s = 4.0;
  s.scoring_window_s = 4.0;
  return s;
}

RunSettings settings(const std::map<std::string, std::string>& options) {
  RunSettings r;
  r.law = ContactLaw::viscoelastic;  // never used: the tips stay 1 m apart
  r.output_rate_hz = 2000;           // 290 samples per cycle: peaks within 6e-5 before refinement
  r.series_start_s = 0;
  r.time_step_s =
      5e-5;  // the adapter's default: explicit hinge springs and damping are stable below 1.65e-4 s at K = 8
  r.options = options;
  return r;
}

class BulletFreeDecay : public ::testing::TestWithParam<std::tuple<std::string, int>> {};

TEST_P(BulletFreeDecay, FrequencyAndDecayAreThoseOfTheChain) {
  const auto& [articulation, frame] = GetParam();
  const Scenario s = contact_free_decay(frame);
  const RunResult bullet =
      make_bullet_simulator()->run(s, settings({{"articulation", articulation}, {"links", std::to_string(kLinks)}}));
  ASSERT_EQ(bullet.status, RunStatus::ok) << bullet.reason;
  EXPECT_TRUE(bullet.trajectory.events.empty());

  // The chain's own first mode (what the reference on the chain runs), and the same estimator on
  // the reference's run so that the estimator's own bias is known.
  const LinkChain chain = build_link_chain(s.frames[0], kLinks);
  const double f_chain = chain_modes(chain).omega_rad_s[0] / (2 * M_PI);
  const RunResult reference = make_reference_simulator()->run(s, settings(chain_reference_options(kLinks)));
  const double settle = 0.5;  // past the start; the tip-load shape puts 2e-4 of mode 1's amplitude in mode 2
  const Decay measured = measure_decay(bullet.trajectory, settle);
  const Decay expected = measure_decay(reference.trajectory, settle);
  ASSERT_GE(measured.cycles, 20);
  // the estimator on the exact solution: within 0.01 % and 1 % of the chain's mode
  EXPECT_NEAR(expected.frequency_hz / f_chain, 1.0, 1e-4);
  EXPECT_NEAR(expected.zeta / chain.damping_ratio, 1.0, 0.01);

  // the tolerances: 0.5 % on the frequency, 10 % on the decay rate
  EXPECT_NEAR(measured.frequency_hz / f_chain, 1.0, 0.005);
  EXPECT_NEAR(measured.zeta / chain.damping_ratio, 1.0, 0.10);
  std::printf("[ measured ] %s frame %d: f = %.6f Hz (chain %.6f Hz, %+.4f %%), zeta = %.6f (%+.2f %%), %.1f us/step\n",
              articulation.c_str(), frame, measured.frequency_hz, f_chain, 100 * (measured.frequency_hz / f_chain - 1),
              measured.zeta, 100 * (measured.zeta / chain.damping_ratio - 1),
              1e6 * bullet.cost.cpu_time_s / static_cast<double>(bullet.cost.steps));
}

INSTANTIATE_TEST_SUITE_P(Articulations, BulletFreeDecay,
                         ::testing::Combine(::testing::Values("multibody", "constraints"), ::testing::Values(1, 2)),
                         [](const auto& info) {
                           return std::get<0>(info.param) + "_frame" + std::to_string(std::get<1>(info.param));
                         });

}  // namespace bullet_free_decay_test
}  // namespace ib
