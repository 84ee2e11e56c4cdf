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

#include "adapters/simbody/simbody_simulator.h"
#include "engine_measurements.h"

namespace ib {
namespace simbody_free_decay_test {

using testing::contact_free_decay;
using testing::free_decay_settings;

RunResult run_simbody(const Scenario& s, double h, std::map<std::string, std::string> options) {
  return make_simbody_simulator()->run(s, free_decay_settings(h, std::move(options)));
}

void expect_chain_mode(const std::string& what, const Scenario& s, const RunResult& r, double zeta_tolerance) {
  testing::expect_chain_mode(what, s, r, 0.002, zeta_tolerance);  // the frequency within 0.2 %
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
// recorded every 5e-5 s): the same mode, zeta within 2 %. RK2 amplifies an undamped mode by 1 + (omega h)^4 / 8
// per step, which only the mode's own damping zeta omega h can hold: with the modal chain damping (zeta = 0.003
// in the fastest mode, omega h = 0.62 at 5e-5 s) it grows by about 1.7 % a step and the run diverges within
// 0.1 s (it needs h < (8 zeta)^(1/3) / omega_max = 2.3e-5 s); with hinge damping (zeta 0.85 there) it is stable.
TEST(SimbodyFreeDecay, EveryIntegratorGivesTheChainMode) {
  const Scenario s = contact_free_decay(false);
  for (const char* integrator : {"rk3", "rkm", "verlet"})
    expect_chain_mode((std::string(integrator) + " 5e-5 s").c_str(), s,
                      run_simbody(s, 5e-5, {{"integrator", integrator}}), 0.02);
  expect_chain_mode("rk2 5e-5 s, hinge damping", s,
                    run_simbody(s, 5e-5, {{"integrator", "rk2"}, {"chain_damping", "hinge"}}), 0.02);
  Scenario short_run = s;
  short_run.duration_s = short_run.scoring_window_s = 0.2;
  const RunResult rk2_modal = run_simbody(short_run, 5e-5, {{"integrator", "rk2"}});
  EXPECT_EQ(rk2_modal.status, RunStatus::unstable) << "rk2, modal damping, 5e-5 s";
  expect_chain_mode("rkm accuracy 1e-6", s, run_simbody(s, 5e-5, {{"accuracy", "1e-6"}}), 0.02);
}

}  // namespace simbody_free_decay_test
}  // namespace ib
