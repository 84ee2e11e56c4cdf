// One impact of the free vibration case (frame 1 released 3 mm from frame 2, first impact at 48 ms)
// against the reference on the same chain, for every Simbody contact path and law: duration and
// restitution measured the same way on both runs from the sampled tip motion. The rigid Newton contact
// never overlaps: its restitution is measured in tests/simbody_contact_mapping_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>

#include "adapters/common/rig.h"
#include "adapters/simbody/simbody_simulator.h"
#include "harness/scoring/metrics.h"
#include "reference/reference_simulator.h"
#include "reference_fixtures.h"

namespace ib {
namespace {

constexpr double kSeriesStart_s = 0.04;   // the first impact starts at 48 ms
constexpr double kDuration_s = 0.055;     // and ends by 49 ms
constexpr double kOutputRate_hz = 2e6;    // dense enough to place the tip crossings to 0.5 us

Scenario first_impact(bool clip_tension) {
  Scenario s = testing::paper_scenario("free_vibration");
  s.duration_s = kDuration_s;
  s.scoring_window_s = kDuration_s;
  s.contact.viscoelastic->clip_tension = clip_tension;
  return s;
}

// From the indentation's upward zero crossing (touch) to its downward one (separation), with the relative
// tip velocities there (linear interpolation between samples), as rig.md section 5 defines an impact.
struct Impact {
  double duration_s = 0, restitution = 0, approach_m_s = 0;
};

std::optional<Impact> measure_impact(const Trajectory& t, double gap_m) {
  const auto indentation = [&](std::size_t k) { return t.displacement_m[0][k] - t.displacement_m[1][k] - gap_m; };
  const auto closing = [&](std::size_t k) { return t.velocity_m_s[0][k] - t.velocity_m_s[1][k]; };
  const auto crossing = [&](std::size_t k, double& time, double& rate) {
    const double a = indentation(k - 1), b = indentation(k), w = a / (a - b);
    time = t.time_s[k - 1] + w * (t.time_s[k] - t.time_s[k - 1]);
    rate = closing(k - 1) + w * (closing(k) - closing(k - 1));
  };
  double onset = 0, approach = 0, end = 0, rebound = 0;
  std::size_t k = 1;
  while (k < t.size() && !(indentation(k - 1) <= 0 && indentation(k) > 0)) ++k;
  if (k >= t.size()) return std::nullopt;
  crossing(k, onset, approach);
  while (k < t.size() && !(indentation(k - 1) > 0 && indentation(k) <= 0)) ++k;
  if (k >= t.size()) return std::nullopt;
  crossing(k, end, rebound);
  return Impact{end - onset, -rebound / approach, approach};
}

RunSettings settings_for(ContactLaw law, double h, std::map<std::string, std::string> options) {
  RunSettings settings;
  settings.law = law;
  settings.output_rate_hz = kOutputRate_hz;
  settings.series_start_s = kSeriesStart_s;
  settings.time_step_s = h;
  settings.options = std::move(options);
  return settings;
}

Impact reference_impact(const Scenario& s, ContactLaw law) {
  const RunResult r = make_reference_simulator()->run(s, settings_for(law, 0, chain_reference_options(default_links(s))));
  const auto impact = measure_impact(r.trajectory, s.gap_m);
  if (!impact) throw std::runtime_error("the reference has no impact");
  return *impact;
}

struct SimbodyImpact {
  Impact impact;
  RunResult run;
};

SimbodyImpact simbody_impact(const Scenario& s, ContactLaw law, double h, std::map<std::string, std::string> options) {
  RunResult r = make_simbody_simulator()->run(s, settings_for(law, h, std::move(options)));
  if (r.status != RunStatus::ok) throw std::runtime_error("simbody run not ok: " + r.reason);
  const auto impact = measure_impact(r.trajectory, s.gap_m);
  if (!impact) throw std::runtime_error("the simbody run has no impact");
  return {*impact, std::move(r)};
}

void expect_impact_near(const char* what, const Impact& got, const Impact& reference, double restitution_tolerance,
                        double duration_tolerance) {
  const double e_error = got.restitution / reference.restitution - 1, t_error = got.duration_s / reference.duration_s - 1;
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
  const Scenario s = first_impact(false);
  const Impact reference = reference_impact(s, ContactLaw::hertz);
  struct Step {
    double h, restitution_tolerance, duration_tolerance;
  };
  for (const Step& step : {Step{1e-5, 0.005, 0.01}, Step{2e-6, 0.002, 0.002}}) {
    const double h = step.h;
    const SimbodyImpact sb = simbody_impact(s, ContactLaw::hertz, h, {});
    char what[64];
    std::snprintf(what, sizeof what, "hertz matched h = %g s", h);
    expect_impact_near(what, sb.impact, reference, step.restitution_tolerance, step.duration_tolerance);
  }
}

// Error-controlled integration (the integrator picks its steps; the run's step is only the recording
// interval, 2e-6 s here to place the crossings): at accuracy 1e-8 both Runge-Kutta-Merson and CPodes give
// the reference's impact to 0.01 % (measured); tolerance 0.1 %.
TEST(SimbodySingleImpact, MatchedHertzErrorControlled) {
  const Scenario s = first_impact(false);
  const Impact reference = reference_impact(s, ContactLaw::hertz);
  for (const char* integrator : {"rkm", "cpodes"}) {
    const SimbodyImpact sb = simbody_impact(s, ContactLaw::hertz, 2e-6, {{"integrator", integrator}, {"accuracy", "1e-8"}});
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
    const Scenario s = first_impact(clip);
    const Impact reference = reference_impact(s, ContactLaw::viscoelastic);
    const SimbodyImpact sb = simbody_impact(s, ContactLaw::viscoelastic, 1e-5, {});
    expect_impact_near(clip ? "spring-dashpot (clipped) matched h = 1e-5 s" : "spring-dashpot matched h = 1e-5 s",
                       sb.impact, reference, 0.01, 0.01);
  }
}

// The harness's force from the tip states at each step's start, held over the step, applied by the chain's
// Force::Custom: at 2e-6 s within 0.1 % of the reference (measured); tolerance 0.5 %.
TEST(SimbodySingleImpact, InjectedLawsMatchThePublishedLaws) {
  const Scenario s = first_impact(false);
  for (ContactLaw law : {ContactLaw::hertz, ContactLaw::viscoelastic}) {
    const Impact reference = reference_impact(s, law);
    const SimbodyImpact sb = simbody_impact(s, law, 2e-6, {{"contact", "injected"}});
    expect_impact_near(law == ContactLaw::hertz ? "hertz injected h = 2e-6 s" : "spring-dashpot injected h = 2e-6 s",
                       sb.impact, reference, 0.005, 0.005);
  }
}

}  // namespace
}  // namespace ib
