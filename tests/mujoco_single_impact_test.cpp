// One impact at a small step against the reference on the same chain: frame 1 released 3 mm from
// frame 2 (the free-vibration case) hits it once in the first 0.07 s. Contact duration and
// restitution within 2 % (issue 4), for the spring-dashpot law on the matched path (as published,
// and clipped at zero tension), on the injected path, and for Hertz.
//
// A contact episode lasts while the tips exchange a force, for the reference and the engines alike.
// MuJoCo's contact cannot pull: with the spring-dashpot as published (which pulls near separation) its
// force ends while the tips still overlap, a no-tension tail of about 2 zeta / omega (4 % of the contact
// here) that the reference's episode includes. For that case the overlap measured on MuJoCo's series
// is compared with the reference's episode too, and the force episode with the episode shortened by the
// tail (closed form, adapters/mujoco/mujoco_contact_mapping.h).
#include <gtest/gtest.h>

#include <cmath>
#include <ostream>
#include <string>

#include "adapters/common/rig.h"
#include "adapters/mujoco/mujoco_contact_mapping.h"
#include "adapters/mujoco/mujoco_simulator.h"
#include "engine_measurements.h"
#include "harness/scoring/metrics.h"

namespace ib {
namespace mujoco_single_impact_test {

// The first overlap of the tips in a sampled trajectory: times where delta = u1 - u2 - gap crosses
// zero and the relative speeds there, linearly interpolated between samples.
struct Overlap {
  double duration_s = 0;
  double restitution = 0;
};

Overlap first_overlap(const Trajectory& t, double gap) {
  auto delta = [&](std::size_t k) { return t.displacement_m[0][k] - t.displacement_m[1][k] - gap; };
  auto rate = [&](std::size_t k) { return t.velocity_m_s[0][k] - t.velocity_m_s[1][k]; };
  std::size_t k = 1;
  while (k < t.size() && !(delta(k - 1) <= 0 && delta(k) > 0)) ++k;
  EXPECT_LT(k, t.size()) << "no contact";
  if (k >= t.size()) return {};
  double w = -delta(k - 1) / (delta(k) - delta(k - 1));
  const double onset = t.time_s[k - 1] + w * (t.time_s[k] - t.time_s[k - 1]);
  const double approach = rate(k - 1) + w * (rate(k) - rate(k - 1));
  while (k < t.size() && !(delta(k - 1) > 0 && delta(k) <= 0)) ++k;
  EXPECT_LT(k, t.size()) << "no separation";
  if (k >= t.size()) return {};
  w = delta(k - 1) / (delta(k - 1) - delta(k));
  const double end = t.time_s[k - 1] + w * (t.time_s[k] - t.time_s[k - 1]);
  const double rebound = -(rate(k - 1) + w * (rate(k) - rate(k - 1)));
  return {end - onset, rebound / approach};
}

struct Case {
  ContactLaw law;
  bool clip_tension;
  std::string path;
  std::string name;
};

void PrintTo(const Case& c, std::ostream* out) { *out << c.name; }  // names the case in test listings

class MujocoSingleImpact : public ::testing::TestWithParam<Case> {};

TEST_P(MujocoSingleImpact, DurationAndRestitutionMatchTheReference) {
  const Case& c = GetParam();
  Scenario s = testing::paper_scenario("free_vibration");
  s.duration_s = 0.07;  // the first impact starts at 0.048 s and lasts about 0.6 ms (0.23 ms Hertz)
  s.scoring_window_s = s.duration_s;
  s.contact.viscoelastic->clip_tension = c.clip_tension;
  RunSettings run;
  run.law = c.law;
  run.time_step_s = 1e-5;    // small: 60 steps per spring-dashpot contact, 23 per Hertz contact
  run.output_rate_hz = 1e5;  // every step
  run.series_start_s = 0.04;
  run.options = {{"contact", c.path}};
  const testing::EngineAndReference runs = testing::run_with_reference(*make_mujoco_simulator(), s, run);
  const RunResult &engine = runs.engine, &reference = runs.reference;
  ASSERT_EQ(engine.status, RunStatus::ok) << engine.reason;
  ASSERT_EQ(reference.status, RunStatus::ok) << reference.reason;
  ASSERT_EQ(reference.trajectory.events.size(), 1u);
  ASSERT_EQ(engine.trajectory.events.size(), 1u) << "one impact, no flicker";
  const ContactEvent& ref = reference.trajectory.events[0];
  const ContactEvent& episode = engine.trajectory.events[0];
  const double ref_duration = ref.end_time_s - ref.onset_time_s;

  // The published spring-dashpot pulls; MuJoCo's own contact (matched) cannot.
  const bool law_pulls_engine_cannot = c.law == ContactLaw::viscoelastic && !c.clip_tension && c.path == "matched";
  if (law_pulls_engine_cannot) {
    const Overlap overlap = first_overlap(engine.trajectory, s.gap_m);
    std::printf("%s: overlap %.5e s (reference %.5e, %+.2f %%), e %.5f (reference %.5f, %+.2f %%)\n", c.name.c_str(),
                overlap.duration_s, ref_duration, 100 * (overlap.duration_s / ref_duration - 1), overlap.restitution,
                ref.restitution, 100 * (overlap.restitution / ref.restitution - 1));
    EXPECT_NEAR(overlap.duration_s / ref_duration, 1, 0.02);
    EXPECT_NEAR(overlap.restitution / ref.restitution, 1, 0.02);
  }

  // What the harness's metrics see: the force episode, and its restitution.
  double force_fraction = 1;
  if (law_pulls_engine_cannot) {
    const RigSpec rig = build_rig(s, c.law, runs.links);
    const double zeta = s.contact.viscoelastic->damping_n_s_per_m /
                        (2 * std::sqrt(s.contact.viscoelastic->stiffness_n_per_m * rig.contact_effective_mass_kg));
    force_fraction = clipped_contact_phase(zeta) / M_PI;
  }
  const double episode_duration = episode.end_time_s - episode.onset_time_s;
  std::printf("%s: force episode %.5e s (predicted %.5e), e %.5f (%+.2f %% vs reference)\n", c.name.c_str(),
              episode_duration, force_fraction * ref_duration, episode.restitution,
              100 * (episode.restitution / ref.restitution - 1));
  // the episode's ends are read at steps: 2 % and one step of quantisation (4.4 % of a 0.23 ms Hertz contact)
  EXPECT_NEAR(episode_duration / (force_fraction * ref_duration), 1,
              0.02 + run.time_step_s / (force_fraction * ref_duration));
  EXPECT_NEAR(episode.restitution / ref.restitution, 1, 0.02);
}

INSTANTIATE_TEST_SUITE_P(Laws, MujocoSingleImpact,
                         ::testing::Values(Case{ContactLaw::viscoelastic, false, "matched",
                                                "spring_dashpot_as_published"},
                                           Case{ContactLaw::viscoelastic, true, "matched", "spring_dashpot_clipped"},
                                           Case{ContactLaw::viscoelastic, false, "injected", "spring_dashpot_injected"},
                                           Case{ContactLaw::hertz, false, "matched", "hertz"}),
                         [](const auto& info) { return info.param.name; });

}  // namespace mujoco_single_impact_test
}  // namespace ib
