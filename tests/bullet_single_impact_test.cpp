// One impact of the paper's free vibration in Bullet, against the reference on the same K-link chain:
// the spring-dashpot law through Bullet's contact stiffness and damping (contact duration and
// restitution), and Newton's law through Bullet's restitution (the realised coefficient).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "adapters/bullet/bullet_simulator.h"
#include "reference/reference_simulator.h"
#include "reference_fixtures.h"

namespace ib {
namespace bullet_single_impact_test {

constexpr int kLinks = 8;

// Frame 1 released 3 mm from frame 2 meets it once at about 0.048 s; 0.07 s holds the first impact
// and nothing else (the next one is a period later).
Scenario first_impact() {
  Scenario s = testing::paper_scenario("free_vibration");
  s.duration_s = 0.07;
  s.scoring_window_s = 0.07;
  return s;
}

RunSettings settings(ContactLaw law, double time_step_s, const std::map<std::string, std::string>& options) {
  RunSettings r;
  r.law = law;
  r.output_rate_hz = 20000;
  r.series_start_s = 0;
  r.time_step_s = time_step_s;
  r.options = options;
  return r;
}

RunResult run_reference(const Scenario& s, ContactLaw law) {
  return make_reference_simulator()->run(s, settings(law, 0, chain_reference_options(kLinks)));
}

RunResult run_bullet(const Scenario& s, ContactLaw law, double h, const std::string& articulation = "multibody") {
  return make_bullet_simulator()->run(
      s, settings(law, h, {{"contact", "matched"}, {"articulation", articulation}, {"links", std::to_string(kLinks)}}));
}

// How long the reference's contact force stays positive, from its force series sampled every 10 ns
// around the impact: a check on the reference's event, which ends where its force does.
double reference_force_duration(Scenario s, ContactLaw law, double onset_s) {
  s.duration_s = onset_s + 2e-3;
  RunSettings r = settings(law, 0, chain_reference_options(kLinks));
  r.series_start_s = onset_s - 1e-5;
  r.output_rate_hz = 1e8;
  const Trajectory t = make_reference_simulator()->run(s, r).trajectory;
  double first = -1, last = -1;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (t.contact_force_n[k] > 0) {
      if (first < 0) first = t.time_s[k];
      last = t.time_s[k];
    }
  return last - first;
}

double duration(const ContactEvent& e) { return e.end_time_s - e.onset_time_s; }

// Bullet's contact impulse is never tensile, so it realises the clipped spring-dashpot whatever the
// scenario says: the reference runs the clipped law too. A contact episode lasts while the tips
// exchange a force, for Bullet (positive impulse) and the reference alike: the reference's event ends
// where its force does, c/k = 24 us (4 %) before the overlap does; its force series, sampled every
// 10 ns, confirms it below.
// h = 1e-6 s: Bullet's contact is an implicit spring-dashpot (bullet_contact_mapping_test), whose
// restitution falls by about pi omega h / 2 = 0.8 % at omega = 5200 rad/s (0.7 % seen at 2e-6 s, 6 % at 1e-5 s).
TEST(BulletSingleImpact, SpringDashpotDurationAndRestitutionAreTheReferencesAtASmallStep) {
  Scenario s = first_impact();
  s.contact.viscoelastic->clip_tension = true;
  const RunResult reference = run_reference(s, ContactLaw::viscoelastic);
  ASSERT_EQ(reference.trajectory.events.size(), 1u);
  const ContactEvent& r = reference.trajectory.events[0];
  const double force_duration = reference_force_duration(s, ContactLaw::viscoelastic, r.onset_time_s);
  EXPECT_NEAR(duration(r) / force_duration, 1.0, 1e-4);  // 10 ns sampling of a 600 us contact
  const double h = 1e-6;
  for (const std::string articulation : {"multibody", "constraints"}) {
    const RunResult bullet = run_bullet(s, ContactLaw::viscoelastic, h, articulation);
    ASSERT_EQ(bullet.status, RunStatus::ok) << bullet.reason;
    ASSERT_EQ(bullet.trajectory.events.size(), 1u) << articulation;
    const ContactEvent& b = bullet.trajectory.events[0];
    EXPECT_NEAR(duration(b) / force_duration, 1.0, 0.02) << articulation;
    EXPECT_NEAR(b.restitution / r.restitution, 1.0, 0.02) << articulation;
    std::printf(
        "[ measured ] %s, h = %g s: duration %.4g us (reference %.4g us while F > 0: %+.2f %%; %.4g us to delta = 0), "
        "e = %.5f (reference %.5f: %+.2f %%), peak force %.4g N (reference %.4g N)\n",
        articulation.c_str(), h, 1e6 * duration(b), 1e6 * force_duration, 100 * (duration(b) / force_duration - 1),
        1e6 * duration(r), b.restitution, r.restitution, 100 * (b.restitution / r.restitution - 1), b.peak_force_n,
        r.peak_force_n);
  }
}

// Bullet has no Hertz contact: the matched path applies the law as a force from the tip states
// (explicit, from the start of each step), which needs no small step: 23 steps per contact at 1e-5 s.
TEST(BulletSingleImpact, HertzAsAForceFromTheTipStates) {
  const Scenario s = first_impact();
  const RunResult reference = run_reference(s, ContactLaw::hertz);
  ASSERT_EQ(reference.trajectory.events.size(), 1u);
  const ContactEvent& r = reference.trajectory.events[0];
  const double force_duration = reference_force_duration(s, ContactLaw::hertz, r.onset_time_s);
  const RunResult bullet = run_bullet(s, ContactLaw::hertz, 1e-5);
  ASSERT_EQ(bullet.status, RunStatus::ok) << bullet.reason;
  ASSERT_EQ(bullet.trajectory.events.size(), 1u);
  const ContactEvent& b = bullet.trajectory.events[0];
  // the episode's ends are read at steps: 2 % and one step (4.4 % of 0.23 ms) of quantisation
  EXPECT_NEAR(duration(b) / force_duration, 1.0, 0.02 + 1e-5 / force_duration);
  EXPECT_NEAR(b.restitution / r.restitution, 1.0, 0.02);
  std::printf(
      "[ measured ] hertz, h = 1e-5 s: duration %.4g us (reference %.4g us: %+.2f %%), e = %.5f (reference %.5f: %+.2f "
      "%%)\n",
      1e6 * duration(b), 1e6 * force_duration, 100 * (duration(b) / force_duration - 1), b.restitution, r.restitution,
      100 * (b.restitution / r.restitution - 1));
}

// Newton's law through Bullet's restitution with the mapping's solver settings, at the adapter's
// default step: the rebound is one step long, so the step hardly matters (e within 0.002 from 1e-6 s
// to 5e-5 s, measured).
TEST(BulletSingleImpact, NewtonRealisesTheTargetRestitution) {
  const Scenario s = first_impact();
  const double target = s.contact.newton->restitution;
  const RunResult reference = run_reference(s, ContactLaw::newton);
  ASSERT_EQ(reference.trajectory.events.size(), 1u);
  EXPECT_NEAR(reference.trajectory.events[0].restitution, target, 1e-9);
  const double h = 5e-5;
  for (const std::string articulation : {"multibody", "constraints"}) {
    const RunResult bullet = run_bullet(s, ContactLaw::newton, h, articulation);
    ASSERT_EQ(bullet.status, RunStatus::ok) << bullet.reason;
    ASSERT_EQ(bullet.trajectory.events.size(), 1u) << articulation;
    const ContactEvent& b = bullet.trajectory.events[0];
    EXPECT_NEAR(b.restitution / target, 1.0, 0.02) << articulation;
    EXPECT_NEAR(duration(b), h, 1e-12) << articulation;  // one step of impulse
    std::printf("[ measured ] newton, %s, h = %g s: e = %.6f for %.1f (%+.3f %%), impulse %.6g N s (reference %.6g)\n",
                articulation.c_str(), h, b.restitution, target, 100 * (b.restitution / target - 1), b.impulse_n_s,
                reference.trajectory.events[0].impulse_n_s);
  }
}

}  // namespace bullet_single_impact_test
}  // namespace ib
