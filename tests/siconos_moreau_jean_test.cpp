// Siconos's Moreau-Jean time stepping on the chains impactbench builds (adapters/siconos/README.md): the
// contact-free decay against the chain's closed-form mode, Newton's impact law at the rig's closing speed, the
// smooth laws' first impact against the reference on the same chain, the native path (the library's own
// restitution), and the injected path's instability under theta = 1/2 as a finding with its reason.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "adapters/siconos/siconos_simulator.h"
#include "engine_measurements.h"
#include "harness/scoring/metrics.h"

namespace ib {
namespace siconos_moreau_jean_test {

using testing::engine_impact;
using testing::first_impact_scenario;
using testing::first_impact_settings;
using testing::reference_impact;

double diagnostic(const RunResult& r, const std::string& key) {
  for (const auto& [name, value] : r.diagnostics)
    if (name == key) return value;
  ADD_FAILURE() << "no diagnostic " << key;
  return NAN;
}

// theta = 1/2 is the trapezoidal rule on the linear chain: no numerical damping, the frequency low by
// (omega h)^2 / 12 (1e-5 at the default 1e-4 s). Both frames' first mode: the frequency within 0.1 %, zeta within 2 %.
TEST(SiconosMoreauJean, ContactFreeDecayIsTheChainMode) {
  for (bool swap : {false, true}) {
    const Scenario s = testing::contact_free_decay(swap);
    const RunResult r = make_siconos_simulator()->run(s, testing::free_decay_settings(0, {}));
    testing::expect_chain_mode(swap ? "light frame, theta 1/2, 1e-4 s" : "heavy frame, theta 1/2, 1e-4 s", s, r, 0.001,
                               0.02);
  }
}

// theta = 1 (backward Euler) adds omega h / 2 to a mode's damping ratio: at 1e-4 s that is 0.0022 on top of the
// chain's 0.003; measured against the prediction within 10 %. (Newton's law: the linear system, no contact.)
TEST(SiconosMoreauJean, BackwardEulerAddsItsNumericalDamping) {
  const Scenario s = testing::contact_free_decay(false);
  const double h = 1e-4;
  RunSettings settings = testing::free_decay_settings(h, {{"theta", "1"}});
  settings.law = ContactLaw::newton;
  const RunResult r = make_siconos_simulator()->run(s, settings);
  ASSERT_EQ(r.status, RunStatus::ok) << r.reason;
  testing::expect_backward_euler_damping(s, r, h, 0.10);
}

// Newton's law as NewtonImpactNSL: Moreau-Jean's impact law reverses the gap's velocity with factor e within the
// step that closes the predicted gap (U_k+1 = -e U_k), and the tips' velocities between the samples around it are
// those of the steps before and after: the restitution the harness reads is e to rounding at every step, where the
// regularised engines' rigid contacts lose first order in h (tests/simbody_contact_mapping_test.cpp). Within 1e-9.
TEST(SiconosMoreauJean, NewtonImpactRestitutionAtTheRigsClosingSpeed) {
  for (double h : {1e-5, 2e-6}) {
    auto simulator = make_siconos_simulator();
    const testing::NewtonFirstImpact impact = testing::newton_first_impact(*simulator, h);
    std::printf("newton impact law h = %g s: restitution %.5f at %.4f m/s over %d impact(s), %g impact steps\n", h,
                impact.metrics.mean_restitution, impact.metrics.mean_approach_velocity_m_s, impact.metrics.impacts,
                diagnostic(impact.run, "impact_steps"));
    EXPECT_EQ(impact.metrics.impacts, 1);
    EXPECT_EQ(diagnostic(impact.run, "newton_impact_restitution"),
              testing::paper_scenario("free_vibration").contact.newton->restitution);
    EXPECT_LT(impact.restitution_error, 1e-9);
  }
}

// Hertz and the spring-dashpot as smooth forces of the system, integrated implicitly: the first impact against
// the reference on the same chain, the restitution and the contact's duration within 1 % at 1e-5 s.
TEST(SiconosMoreauJean, SmoothLawsAreTheLawAtShortSteps) {
  for (ContactLaw law : {ContactLaw::hertz, ContactLaw::viscoelastic}) {
    const Scenario s = first_impact_scenario(false);
    const testing::CrossingImpact reference = reference_impact(s, law);
    const testing::EngineImpact got = engine_impact(*make_siconos_simulator(), s, first_impact_settings(law, 1e-5, {}));
    const double e_error = got.impact.restitution / reference.restitution - 1,
                 t_error = got.impact.duration_s / reference.duration_s - 1;
    std::printf("%s smooth force 1e-5 s: duration %+.3f %%, restitution %+.3f %%, %g Newton iterations at most\n",
                law == ContactLaw::hertz ? "hertz" : "spring-dashpot", 100 * t_error, 100 * e_error,
                diagnostic(got.run, "most_newton_iterations"));
    EXPECT_LT(std::abs(e_error), 0.01);
    EXPECT_LT(std::abs(t_error), 0.01);
  }
}

// Moreau-Jean's Newton loop on the smooth force converges in a few iterations at any step when its iteration
// matrix has the forces' Jacobians (the stiffness and the contact's slope): with M alone it converges only while
// omega h theta < 1 for the chain's fastest mode and diverges from about 1.5e-4 s (Siconos's cap of 50 iterations
// reached, the run unstable at its first step). At 2e-4 s, through the first impact: ok, under 10 iterations
// (measured: 5, at the contact's kink).
TEST(SiconosMoreauJean, TheNewtonLoopHasTheForcesJacobians) {
  const Scenario s = first_impact_scenario(false);
  RunSettings settings = first_impact_settings(ContactLaw::hertz, 2e-4, {});
  const RunResult r = make_siconos_simulator()->run(s, settings);
  ASSERT_EQ(r.status, RunStatus::ok) << r.reason;
  EXPECT_LT(diagnostic(r, "most_newton_iterations"), 10);
}

// A step that does not divide the run's length: the loop decides the last step, and Siconos, given no end time of
// its own, has a next time for it (with the run's end as its own it aborted on a NaN one).
TEST(SiconosMoreauJean, AStepThatDoesNotDivideTheRunEndsItOk) {
  Scenario s = testing::paper_scenario("free_vibration");
  s.duration_s = s.scoring_window_s = 0.01;
  for (ContactLaw law : {ContactLaw::hertz, ContactLaw::newton}) {
    RunSettings settings;
    settings.law = law;
    settings.time_step_s = 7.07107e-5;
    const RunResult r = make_siconos_simulator()->run(s, settings);
    EXPECT_EQ(r.status, RunStatus::ok) << r.reason;
  }
}

// Native: NewtonImpactNSL as its users leave it, its default restitution read from the library (0: a plastic
// impact), whatever the law: the tips close and move together, parting only when the chains pull them apart.
TEST(SiconosMoreauJean, NativeIsTheLibrarysDefaultImpact) {
  Scenario s = first_impact_scenario(false);
  for (ContactLaw law : {ContactLaw::hertz, ContactLaw::newton}) {
    const RunResult r = make_siconos_simulator()->run(s, first_impact_settings(law, 1e-5, {{"contact", "native"}}));
    ASSERT_EQ(r.status, RunStatus::ok) << r.reason;
    EXPECT_EQ(diagnostic(r, "newton_impact_restitution"), 0.0);
    EXPECT_EQ(diagnostic(r, "siconos_contact"), 0.0);
    const auto impact = testing::measure_impact(r.trajectory, s.gap_m);
    ASSERT_TRUE(impact.has_value());
    std::printf("native, %s: restitution %.4f after %.3f ms together\n", law == ContactLaw::hertz ? "hertz" : "newton",
                impact->restitution, 1e3 * impact->duration_s);
    EXPECT_LT(impact->restitution, 0.3);
  }
}

}  // namespace siconos_moreau_jean_test
}  // namespace ib
