// One impact of the free vibration case (frame 1 released 3 mm from frame 2, first impact at 48 ms)
// against the reference on the same chain. DART has no compliant contact for rigid bodies, so the
// compliant laws come in as the harness's force from the tip states (matched = injected for them); Newton
// goes through DART's restitution, whose hard-coded bounce threshold (no bounce when e v <= 0.1 model
// units per second) decides whether there is a rebound at all: the finding of adapters/dart/README.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "adapters/dart/dart_simulator.h"
#include "engine_measurements.h"
#include "harness/scoring/metrics.h"

namespace ib {
namespace dart_single_impact_test {

using testing::CrossingImpact;
using testing::measure_impact;

constexpr double kSeriesStart_s = 0.03;  // the first impact starts at 48 ms (40 ms when released 3 times further)
constexpr double kDuration_s = testing::kFirstImpactEnd_s;

Scenario first_impact() { return testing::first_impact_scenario(false); }

CrossingImpact reference_impact(const Scenario& s, ContactLaw law) {
  return testing::reference_impact(s, law, kSeriesStart_s);
}

RunResult dart_run(const Scenario& s, ContactLaw law, double h, std::map<std::string, std::string> options) {
  RunResult r =
      make_dart_simulator()->run(s, testing::first_impact_settings(law, h, std::move(options), kSeriesStart_s));
  if (r.status != RunStatus::ok) throw std::runtime_error("dart run not ok: " + r.reason);
  return r;
}

// The compliant laws as tip forces, explicit in the force over a step: at h = 2e-6 s (omega h = 0.01 for
// the spring-dashpot's contact frequency 5200 rad/s) duration and restitution within 1 % of the law's.
TEST(DartSingleImpact, CompliantLawsAsTipForcesMatchTheReference) {
  const Scenario s = first_impact();
  for (ContactLaw law : {ContactLaw::viscoelastic, ContactLaw::hertz}) {
    const CrossingImpact reference = reference_impact(s, law);
    for (const char* path : {"matched", "injected"}) {
      const auto dart = measure_impact(dart_run(s, law, 2e-6, {{"contact", path}}).trajectory, s.gap_m);
      ASSERT_TRUE(dart) << to_string(law) << " " << path;
      std::printf("%s %s: duration %.4f ms (reference %.4f), restitution %.4f (reference %.4f), approach %.4f m/s\n",
                  to_string(law), path, 1e3 * dart->duration_s, 1e3 * reference.duration_s, dart->restitution,
                  reference.restitution, dart->approach_m_s);
      EXPECT_NEAR(dart->restitution / reference.restitution, 1, 0.01) << to_string(law) << " " << path;
      EXPECT_NEAR(dart->duration_s / reference.duration_s, 1, 0.01) << to_string(law) << " " << path;
    }
  }
}

// Newton through DART's restitution: sqrt(e) on each sphere, the pair's product is e. The rebound happens
// only when e times the closing speed exceeds DART's bounce threshold, 0.1 model units per second. In
// centimetres (threshold 1 mm/s) the first impact rebounds with e within 2 %; measured by the harness's
// event (closing speeds before and after the contact steps).
double newton_restitution(const Scenario& s, double h, const std::string& unit, int& impacts, double& approach_m_s) {
  const RunResult r = dart_run(s, ContactLaw::newton, h, {{"contact", "matched"}, {"length_unit", unit}});
  const Metrics m = compute_metrics(r.trajectory, MetricSettings{0, kDuration_s});
  impacts = m.impacts;
  approach_m_s = m.mean_approach_velocity_m_s;
  return m.mean_restitution;
}

TEST(DartSingleImpact, NewtonInCentimetresRealisesTheTargetRestitution) {
  const Scenario s = first_impact();
  const double target = s.contact.newton->restitution;
  for (double h : {1e-4, 1e-5}) {
    int impacts = 0;
    double approach = 0;
    const double e = newton_restitution(s, h, "cm", impacts, approach);
    std::printf("cm, h = %g s: restitution %.5f at %.4f m/s closing, %d impact(s)\n", h, e, approach, impacts);
    EXPECT_EQ(impacts, 1);
    EXPECT_NEAR(e / target, 1, 0.02) << "h = " << h;
  }
}

// The same impact in metres, and in metres with the closing speed scaled up past the threshold: the
// threshold acts on e v in m/s, 0.1 m/s. Below it the impact is plastic (the tips stay together and part
// later, when the structure pulls them apart: e near 0); above it DART gives e. The rig's impacts close at
// 0.02 to 0.16 m/s, so with e = 0.8 most of them are below: reported as a finding, not hidden.
TEST(DartSingleImpact, NewtonBelowTheBounceThresholdIsPlasticInMetres) {
  const double target = 0.8, threshold_m_s = 0.1;
  for (double release_scale : {1.0, 3.0}) {  // released 2 mm from rest: closing at 0.075 m/s; 6 mm: 0.26 m/s
    Scenario s = first_impact();
    s.contact.newton->restitution = target;
    s.initial.frame1_tip_displacement_m *= release_scale;
    int impacts = 0;
    double approach = 0;
    const double e = newton_restitution(s, 1e-5, "m", impacts, approach);
    std::printf("m, release x%.1f: closing %.4f m/s, e v = %.4f m/s: restitution %.4f\n", release_scale, approach,
                target * approach, e);
    ASSERT_GE(impacts, 1);
    if (target * approach < threshold_m_s)
      EXPECT_LT(e, 0.1) << "below the threshold DART gives no bounce";
    else
      EXPECT_NEAR(e / target, 1, 0.02) << "above the threshold DART gives e";
  }
}

}  // namespace dart_single_impact_test
}  // namespace ib
