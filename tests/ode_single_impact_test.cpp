// One impact of the free vibration case (frame 1 released 3 mm from frame 2, first impact at 48 ms)
// against the reference on the same chain. Spring-dashpot through ODE's soft contact: the contact
// duration and restitution converge to the reference's as the step shrinks, the restitution at first
// order (ODE's soft contact is a backward-Euler spring: it loses energy at long steps). Newton through
// dContactBounce: the target restitution.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "adapters/ode/ode_simulator.h"
#include "engine_measurements.h"
#include "harness/scoring/metrics.h"

namespace ib {
namespace ode_single_impact_test {

using testing::engine_impact;
using testing::first_impact_scenario;
using testing::first_impact_settings;
using testing::kFirstImpactEnd_s;
using testing::reference_impact;
using Impact = testing::CrossingImpact;  // the impact as rig.md section 5 defines it, from the sampled tip motion

testing::EngineImpact ode_impact(const Scenario& s, ContactLaw law, double h, const std::string& contact) {
  return engine_impact(*make_ode_simulator(), s, first_impact_settings(law, h, {{"contact", contact}}));
}

// ODE's contact joint only pushes (lambda >= 0): it realises the spring-dashpot clipped at zero force,
// so the reference runs the clipped law too and only ODE's stepping is measured. The contact's
// frequency is omega = sqrt(k / m_eff) = 5200 rad/s. Tolerances from the backward-Euler loss
// exp(-0.9 pi omega h / 2) (tests/ode_soft_constraint_test.cpp): 7 % at h = 1e-5 s, 1.5 % at 2e-6 s;
// and from the onset, which a step-based contact detects up to one step late: h / 0.62 ms = 1.6 %
// and 0.3 % of the duration.
TEST(OdeSingleImpact, SpringDashpotConvergesToTheReferenceAsTheStepShrinks) {
  const Scenario s = first_impact_scenario(true);
  const Impact reference = reference_impact(s, ContactLaw::viscoelastic);
  std::printf("reference (chain, clipped law): duration %.4f ms, restitution %.4f, approach %.4f m/s\n",
              1e3 * reference.duration_s, reference.restitution, reference.approach_m_s);
  struct Step {
    double h, restitution_tolerance, duration_tolerance;
  };
  std::vector<double> restitution_errors;
  for (const Step& step : {Step{1e-5, 0.10, 0.03}, Step{2e-6, 0.025, 0.01}}) {
    const testing::EngineImpact ode = ode_impact(s, ContactLaw::viscoelastic, step.h, "matched");
    const double restitution_error = ode.impact.restitution / reference.restitution - 1;
    const double duration_error = ode.impact.duration_s / reference.duration_s - 1;
    restitution_errors.push_back(restitution_error);
    const Metrics m = compute_metrics(ode.run.trajectory, MetricSettings{0, kFirstImpactEnd_s});
    std::printf(
        "ode h = %g s: duration %.4f ms (%+.2f %%), restitution %.4f (%+.2f %%); harness's event: duration "
        "%.4f ms, restitution %.4f\n",
        step.h, 1e3 * ode.impact.duration_s, 100 * duration_error, ode.impact.restitution, 100 * restitution_error,
        1e3 * m.contact_duration_mean_s, m.mean_restitution);
    EXPECT_LT(restitution_error, 0) << "backward Euler loses energy, h = " << step.h;
    EXPECT_LT(std::abs(restitution_error), step.restitution_tolerance) << "h = " << step.h;
    EXPECT_LT(std::abs(duration_error), step.duration_tolerance) << "h = " << step.h;
  }
  // first order: the error shrinks with the step (5 times shorter: at least 3 times smaller)
  EXPECT_LT(std::abs(restitution_errors[1]) * 3, std::abs(restitution_errors[0]));
}

// The injected path applies the published (unclipped) law from the tip states at each step's start:
// explicit in the force, no backward-Euler loss; at h = 2e-6 s (omega h = 0.01) within 1 %.
TEST(OdeSingleImpact, InjectedSpringDashpotMatchesThePublishedLaw) {
  const Scenario s = first_impact_scenario(false);
  const Impact reference = reference_impact(s, ContactLaw::viscoelastic);
  const Impact ode = ode_impact(s, ContactLaw::viscoelastic, 2e-6, "injected").impact;
  std::printf("injected h = 2e-6 s: duration %.4f ms (reference %.4f), restitution %.4f (reference %.4f)\n",
              1e3 * ode.duration_s, 1e3 * reference.duration_s, ode.restitution, reference.restitution);
  EXPECT_NEAR(ode.restitution / reference.restitution, 1, 0.01);
  EXPECT_NEAR(ode.duration_s / reference.duration_s, 1, 0.01);
}

// dContactBounce with bounce = e: the closing speed is reversed with factor e within the step the
// spheres are found overlapping. Measured by the harness (the recorder's event: closing speeds before
// and after the contact steps; the crossing measure above does not apply, as the series interpolates
// the velocity jump linearly across the step), at the default step and a finer one; target e = 0.8
// within 2 %.
TEST(OdeSingleImpact, NewtonBounceRealisesTheTargetRestitution) {
  const Scenario s = first_impact_scenario(false);
  const double target = s.contact.newton->restitution;
  for (double h : {1e-4, 1e-5}) {
    const testing::EngineImpact ode = ode_impact(s, ContactLaw::newton, h, "matched");
    const Metrics m = compute_metrics(ode.run.trajectory, MetricSettings{0, kFirstImpactEnd_s});
    std::printf("newton h = %g s: restitution %.5f over %d impact(s)\n", h, m.mean_restitution, m.impacts);
    EXPECT_EQ(m.impacts, 1);
    EXPECT_NEAR(m.mean_restitution / target, 1, 0.02) << "h = " << h;
  }
}

}  // namespace ode_single_impact_test
}  // namespace ib
