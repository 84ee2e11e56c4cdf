// The chains Simbody builds (MobilizedBody::Pin with MobilityLinearSpring and MobilityLinearDamper) vibrate
// at the reference chain's frequency with its damping: a contact-free free decay (gap 1 m) of each frame,
// released from its static tip-load shape, against the chain's closed-form first mode (chain_modes). The
// hinge springs are forces integrated explicitly by every Simbody integrator: no numerical damping below
// the step limit, a divergence above it (tests/simbody_simulator_contract_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "adapters/common/rig.h"
#include "adapters/simbody/simbody_simulator.h"
#include "physics/link_chain.h"
#include "reference_fixtures.h"

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

RunResult run_simbody(const Scenario& s, double h, std::map<std::string, std::string> options) {
  RunSettings settings;
  settings.law = ContactLaw::viscoelastic;
  settings.series_start_s = 0;
  settings.time_step_s = h;
  settings.options = std::move(options);
  return make_simbody_simulator()->run(s, settings);
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

void expect_chain_mode(const char* what, const Scenario& s, const RunResult& r, double zeta_tolerance) {
  ASSERT_EQ(r.status, RunStatus::ok) << what << ": " << r.reason;
  const Decay d = measure_decay(r.trajectory, kMeasureFrom_s);
  const ChainMode mode = reference_mode(s);
  std::printf("%s: f = %.5f Hz (chain %.5f Hz, %+.4f %%), zeta = %.6f (chain %.4f, %+.2f %%), %d peaks, %.2f us/step\n",
              what, d.frequency_hz, mode.damped_frequency_hz, 100 * (d.frequency_hz / mode.damped_frequency_hz - 1),
              d.damping_ratio, mode.zeta, 100 * (d.damping_ratio / mode.zeta - 1), d.peaks,
              1e6 * r.cost.cpu_time_s / r.cost.steps);
  ASSERT_GE(d.peaks, 5) << what;
  EXPECT_NEAR(d.frequency_hz / mode.damped_frequency_hz, 1, 0.002) << what;
  EXPECT_NEAR(d.damping_ratio / mode.zeta, 1, zeta_tolerance) << what;
}

// Semi-explicit Euler at the default step (5e-5 s, below the 7.5e-5 s limit): both frames' first mode.
// Symplectic Euler adds no damping to an undamped mode and shifts its frequency by (omega h)^2 / 24
// (1e-6 here); zeta within 2 %, the frequency within 0.2 %.
TEST(SimbodyFreeDecay, SemiExplicitEulerGivesTheChainModeAtTheDefaultStep) {
  for (bool swap : {false, true}) {
    const Scenario s = contact_free_decay(swap);
    expect_chain_mode(swap ? "light frame, euler 5e-5 s" : "heavy frame, euler 5e-5 s", s, run_simbody(s, 0, {}), 0.02);
  }
}

// The other fixed-step integrators at 5e-5 s, and Runge-Kutta-Merson with error control (accuracy 1e-6,
// recorded every 5e-5 s): the same mode, zeta within 2 %.
TEST(SimbodyFreeDecay, EveryIntegratorGivesTheChainMode) {
  const Scenario s = contact_free_decay(false);
  for (const char* integrator : {"rk2", "rk3", "rkm", "verlet"})
    expect_chain_mode((std::string(integrator) + " 5e-5 s").c_str(), s,
                      run_simbody(s, 5e-5, {{"integrator", integrator}}), 0.02);
  expect_chain_mode("rkm accuracy 1e-6", s, run_simbody(s, 5e-5, {{"accuracy", "1e-6"}}), 0.02);
}

}  // namespace
}  // namespace ib
