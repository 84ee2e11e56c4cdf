// One impact of the free vibration case (frame 1 released 3 mm from frame 2, first impact at 48 ms)
// against the reference on the same chain, for every Simbody contact path and law: duration and
// restitution measured the same way on both runs from the sampled tip motion. The rigid Newton contact
// never overlaps: its restitution is measured in tests/simbody_contact_mapping_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "adapters/simbody/simbody_simulator.h"
#include "engine_measurements.h"

namespace ib {
namespace simbody_single_impact_test {

using testing::engine_impact;
using testing::first_impact_scenario;
using testing::first_impact_settings;
using testing::reference_impact;
using Impact = testing::CrossingImpact;  // the impact as rig.md section 5 defines it, from the sampled tip motion

testing::EngineImpact simbody_impact(const Scenario& s, ContactLaw law, double h,
                                     std::map<std::string, std::string> options) {
  return engine_impact(*make_simbody_simulator(), s, first_impact_settings(law, h, std::move(options)));
}

void expect_impact_near(const char* what, const Impact& got, const Impact& reference, double restitution_tolerance,
                        double duration_tolerance) {
  const double e_error = got.restitution / reference.restitution - 1,
               t_error = got.duration_s / reference.duration_s - 1;
  std::printf("%s: duration %.4f ms (reference %.4f, %+.2f %%), restitution %.4f (reference %.4f, %+.2f %%)\n", what,
              1e3 * got.duration_s, 1e3 * reference.duration_s, 100 * t_error, got.restitution, reference.restitution,
              100 * e_error);
  EXPECT_LT(std::abs(e_error), restitution_tolerance) << what;
  EXPECT_LT(std::abs(t_error), duration_tolerance) << what;
}

// Hunt-Crossley with the mapped material is the law itself (tests/simbody_contact_mapping_test.cpp): what
// is left is the stepping: semi-explicit Euler, with the force evaluated at the step's start. Measured:
// -0.40 % duration and -0.04 % restitution at 1e-5 s (the 0.23 ms contact in 23 steps), -0.06 % and
// +0.01 % at 2e-6 s. Tolerances: 1 % / 0.5 % at 1e-5 s, 0.2 % / 0.2 % at 2e-6 s (the error falls with h).
TEST(SimbodySingleImpact, MatchedHertzIsTheLawAtShortSteps) {
  const Scenario s = first_impact_scenario(false);
  const Impact reference = reference_impact(s, ContactLaw::hertz);
  struct Step {
    double h, restitution_tolerance, duration_tolerance;
  };
  for (const Step& step : {Step{1e-5, 0.005, 0.01}, Step{2e-6, 0.002, 0.002}}) {
    const double h = step.h;
    const testing::EngineImpact sb = simbody_impact(s, ContactLaw::hertz, h, {});
    char what[64];
    std::snprintf(what, sizeof what, "hertz matched h = %g s", h);
    expect_impact_near(what, sb.impact, reference, step.restitution_tolerance, step.duration_tolerance);
  }
}

// Error-controlled integration (the integrator picks its steps; the run's step is only the recording
// interval, 2e-6 s here to place the crossings): at accuracy 1e-8 both Runge-Kutta-Merson and CPodes give
// the reference's impact to 0.01 % (measured); tolerance 0.1 %.
TEST(SimbodySingleImpact, MatchedHertzErrorControlled) {
  const Scenario s = first_impact_scenario(false);
  const Impact reference = reference_impact(s, ContactLaw::hertz);
  for (const char* integrator : {"rkm", "cpodes"}) {
    const testing::EngineImpact sb =
        simbody_impact(s, ContactLaw::hertz, 2e-6, {{"integrator", integrator}, {"accuracy", "1e-8"}});
    char what[64];
    std::snprintf(what, sizeof what, "hertz matched %s accuracy 1e-8", integrator);
    expect_impact_near(what, sb.impact, reference, 0.001, 0.001);
  }
}

// The force element is the published law (unclipped, it pulls a little before separation), evaluated at
// the state: semi-explicit Euler at 1e-5 s (omega h = 0.05 for the contact). Measured: duration -0.16 %,
// restitution +0.35 % (published law) and +0.09 % (clipped); tolerance 1 %.
TEST(SimbodySingleImpact, MatchedSpringDashpotIsTheLaw) {
  for (bool clip : {false, true}) {
    const Scenario s = first_impact_scenario(clip);
    const Impact reference = reference_impact(s, ContactLaw::viscoelastic);
    const testing::EngineImpact sb = simbody_impact(s, ContactLaw::viscoelastic, 1e-5, {});
    expect_impact_near(clip ? "spring-dashpot (clipped) matched h = 1e-5 s" : "spring-dashpot matched h = 1e-5 s",
                       sb.impact, reference, 0.01, 0.01);
  }
}

// The harness's force from the tip states at each step's start, held over the step, applied by the chain's
// Force::Custom: at 2e-6 s within 0.1 % of the reference (measured); tolerance 0.5 %.
TEST(SimbodySingleImpact, InjectedLawsMatchThePublishedLaws) {
  const Scenario s = first_impact_scenario(false);
  for (ContactLaw law : {ContactLaw::hertz, ContactLaw::viscoelastic}) {
    const Impact reference = reference_impact(s, law);
    const testing::EngineImpact sb = simbody_impact(s, law, 2e-6, {{"contact", "injected"}});
    expect_impact_near(law == ContactLaw::hertz ? "hertz injected h = 2e-6 s" : "spring-dashpot injected h = 2e-6 s",
                       sb.impact, reference, 0.005, 0.005);
  }
}

}  // namespace simbody_single_impact_test
}  // namespace ib
