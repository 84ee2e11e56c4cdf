// The chains ODE builds vibrate at the reference chain's frequencies with its damping: a contact-free
// free decay (gap 1 m) of each frame, released from its static tip-load shape. The implicit hinge
// springs (backward Euler) add a damping ratio of omega h / 2, so zeta is matched only at short steps;
// the explicit springs (semi-implicit Euler) add none but need a step below their stability limit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "physics/link_chain.h"
#include "adapters/ode/ode_simulator.h"
#include "reference_fixtures.h"
#include "reference/reference_simulator.h"
#include "adapters/common/rig.h"

namespace ib {
namespace {

// The published free vibration without contact, for 1 s. swap: the frames trade places, so that the
// released frame is the lighter one (frame 2's specification) and both chains are measured.
Scenario contact_free_decay(bool swap) {
  Scenario s = testing::paper_scenario("free_vibration");
  s.gap_m = 1.0;
  s.duration_s = 1.0;
  s.scoring_window_s = 1.0;
  if (swap) std::swap(s.frames[0], s.frames[1]);
  return s;
}

// Frequency and damping ratio of the released frame's tip from its positive peaks after from_s (by
// then the second mode, damped at zeta omega_2 / omega_1 = 0.03, has decayed below 1e-3 of its start):
// the peaks' spacing gives the damped frequency, the slope of their logarithm -zeta omega.
struct Decay {
  double frequency_hz = 0;
  double damping_ratio = 0;
  int peaks = 0;
};

Decay measure_decay(const Trajectory& t, double from_s) {
  const std::vector<double>& u = t.displacement_m[0];
  const double dt = 1 / t.output_rate_hz;
  std::vector<double> times, logs;
  for (std::size_t k = 1; k + 1 < u.size(); ++k) {
    if (t.time_s[k] < from_s || !(u[k] > 0 && u[k] > u[k - 1] && u[k] >= u[k + 1])) continue;
    // parabola through the three samples around the peak
    const double a = u[k - 1], b = u[k], c = u[k + 1], shift = 0.5 * (a - c) / (a - 2 * b + c);
    times.push_back(t.time_s[k] + shift * dt);
    logs.push_back(std::log(b - 0.25 * (a - c) * shift));
  }
  Decay d;
  d.peaks = static_cast<int>(times.size());
  if (d.peaks < 3) return d;
  d.frequency_hz = (d.peaks - 1) / (times.back() - times.front());
  double mean_t = 0, mean_log = 0;
  for (int i = 0; i < d.peaks; ++i) mean_t += times[i] / d.peaks, mean_log += logs[i] / d.peaks;
  double sxy = 0, sxx = 0;
  for (int i = 0; i < d.peaks; ++i) sxy += (times[i] - mean_t) * (logs[i] - mean_log), sxx += std::pow(times[i] - mean_t, 2);
  const double omega_d = 2 * M_PI * d.frequency_hz;
  const double decay_rate = -sxy / sxx;  // zeta omega
  // zeta omega / omega_d = zeta / sqrt(1 - zeta^2)
  const double ratio = decay_rate / omega_d;
  d.damping_ratio = ratio / std::sqrt(1 + ratio * ratio);
  return d;
}

RunResult run_ode(const Scenario& s, double h, const std::string& springs) {
  RunSettings settings;
  settings.law = ContactLaw::viscoelastic;
  settings.series_start_s = 0;
  settings.time_step_s = h;
  settings.options = {{"springs", springs}};
  return make_ode_simulator()->run(s, settings);
}

struct ChainMode {
  double damped_frequency_hz, zeta, omega_rad_s;
};
ChainMode reference_mode(const Scenario& s) {
  const ModalBasis modes = chain_modes(build_link_chain(s.frames[0], default_links(s)));
  const double omega = modes.omega_rad_s[0], zeta = modes.zeta[0];
  return {omega * std::sqrt(1 - zeta * zeta) / (2 * M_PI), zeta, omega};
}

constexpr double kMeasureFrom_s = 0.2;

// The estimator itself, on the reference's run of the same chain: it must find the chain's mode.
TEST(OdeFreeDecay, TheEstimatorFindsTheReferenceChainsMode) {
  const Scenario s = contact_free_decay(false);
  RunSettings settings;
  settings.law = ContactLaw::viscoelastic;
  settings.series_start_s = 0;
  settings.options = chain_reference_options(default_links(s));
  const Decay d = measure_decay(make_reference_simulator()->run(s, settings).trajectory, kMeasureFrom_s);
  const ChainMode mode = reference_mode(s);
  EXPECT_NEAR(d.frequency_hz / mode.damped_frequency_hz, 1, 1e-4);
  EXPECT_NEAR(d.damping_ratio / mode.zeta, 1, 0.01);
}

// Implicit springs at h = 5e-6 s: their numerical damping omega_1 h / 2 is 1.1e-4 (frame 1) and
// 1.3e-4 (frame 2), 4 % of zeta = 0.003, inside the 10 % asked for. (At the default 1e-4 s it is
// 70 % of zeta: see the next test.) 200 000 steps per frame, about 4 s of CPU each.
TEST(OdeFreeDecay, ImplicitSpringsGiveTheChainFrequenciesAndZetaAtShortSteps) {
  const double h = 5e-6;
  for (bool swap : {false, true}) {
    const Scenario s = contact_free_decay(swap);
    const RunResult r = run_ode(s, h, "implicit");
    ASSERT_EQ(r.status, RunStatus::ok) << r.reason;
    const Decay d = measure_decay(r.trajectory, kMeasureFrom_s);
    const ChainMode mode = reference_mode(s);
    std::printf("%s frame: f = %.5f Hz (chain %.5f Hz, %+.4f %%), zeta = %.6f (chain %.4f, %+.1f %%), %d peaks, %.2f us/step\n",
                swap ? "light" : "heavy", d.frequency_hz, mode.damped_frequency_hz,
                100 * (d.frequency_hz / mode.damped_frequency_hz - 1), d.damping_ratio, mode.zeta,
                100 * (d.damping_ratio / mode.zeta - 1), d.peaks, 1e6 * r.cost.cpu_time_s / r.cost.steps);
    ASSERT_GE(d.peaks, 5);
    EXPECT_NEAR(d.frequency_hz / mode.damped_frequency_hz, 1, 0.005);
    EXPECT_NEAR(d.damping_ratio / mode.zeta, 1, 0.10);
  }
}

// At the default step the implicit springs' extra damping is what backward Euler predicts, omega h / 2
// (within 3 % of it): a property of the path, documented, not a defect to hide.
TEST(OdeFreeDecay, ImplicitSpringsAddOmegaHOverTwoToTheDamping) {
  const double h = 1e-4;
  const Scenario s = contact_free_decay(false);
  const Decay d = measure_decay(run_ode(s, h, "implicit").trajectory, kMeasureFrom_s);
  const ChainMode mode = reference_mode(s);
  const double added = d.damping_ratio - mode.zeta, predicted = mode.omega_rad_s * h / 2;
  std::printf("h = %g s: zeta = %.6f, added %.6f, omega h / 2 = %.6f; f = %.5f Hz (chain %.5f Hz)\n", h, d.damping_ratio,
              added, predicted, d.frequency_hz, mode.damped_frequency_hz);
  EXPECT_NEAR(added / predicted, 1, 0.03);
  EXPECT_NEAR(d.frequency_hz / mode.damped_frequency_hz, 1, 0.005);
}

// Explicit springs below their stability limit (7.5e-5 s for K = 8): no numerical damping, so zeta
// within 2 % and the frequency within 0.5 % at h = 2e-5 s.
TEST(OdeFreeDecay, ExplicitSpringsGiveTheChainModeBelowTheirStepLimit) {
  const double h = 2e-5;
  const Scenario s = contact_free_decay(false);
  const RunResult r = run_ode(s, h, "explicit");
  ASSERT_EQ(r.status, RunStatus::ok) << r.reason;
  const Decay d = measure_decay(r.trajectory, kMeasureFrom_s);
  const ChainMode mode = reference_mode(s);
  std::printf("explicit, h = %g s: f = %.5f Hz (chain %.5f Hz), zeta = %.6f (chain %.4f), %.2f us/step\n", h,
              d.frequency_hz, mode.damped_frequency_hz, d.damping_ratio, mode.zeta, 1e6 * r.cost.cpu_time_s / r.cost.steps);
  EXPECT_NEAR(d.frequency_hz / mode.damped_frequency_hz, 1, 0.005);
  EXPECT_NEAR(d.damping_ratio / mode.zeta, 1, 0.02);
}

}  // namespace
}  // namespace ib
