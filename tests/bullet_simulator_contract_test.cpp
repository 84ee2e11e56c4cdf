// The Bullet simulator as the harness sees it: its name, version and options, every
// contact path and articulation running the first impact of the free vibration, the diagnostics that
// document the mapping, and instability reported as a result with the time and quantity, never a crash.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "adapters/bullet/bullet_simulator.h"
#include "physics/link_chain.h"
#include "reference_fixtures.h"

namespace ib {
namespace bullet_simulator_contract_test {

TEST(BulletSimulator, NameVersionAndOptions) {
  const auto bullet = make_bullet_simulator();
  EXPECT_EQ(bullet->name(), "bullet");
  EXPECT_EQ(bullet->version(), "Bullet 3.24 (double precision)");
  const auto options = bullet->option_help();
  const std::map<std::string, std::string> help(options.begin(), options.end());
  for (const char* option : {"contact", "articulation", "links"}) EXPECT_TRUE(help.count(option)) << option;
  const Scenario s = testing::paper_scenario("resonance");
  RunSettings settings;
  EXPECT_EQ(bullet->chain_links(s, settings), 8);  // the default K for the paper's rig
  settings.options = {{"links", "4"}};
  EXPECT_EQ(bullet->chain_links(s, settings), 4);
}

TEST(BulletSimulator, RejectsUnknownOptionsAndValues) {
  const auto bullet = make_bullet_simulator();
  const Scenario s = testing::paper_scenario("free_vibration");
  for (const auto& [name, value] : std::map<std::string, std::string>{
           {"contact", "soft"}, {"articulation", "ropes"}, {"links", "0"}, {"links", "2.5"}, {"substeps", "4"}}) {
    RunSettings settings;
    settings.options = {{name, value}};
    EXPECT_THROW(bullet->run(s, settings), std::invalid_argument) << name << "=" << value;
  }
}

Scenario first_impact() {
  Scenario s = testing::paper_scenario("free_vibration");
  s.duration_s = 0.07;  // frame 1 meets frame 2 once, at about 0.048 s
  s.scoring_window_s = 0.07;
  return s;
}

double diagnostic(const RunResult& r, const std::string& name) {
  for (const auto& [key, value] : r.diagnostics)
    if (key == name) return value;
  ADD_FAILURE() << "no diagnostic " << name;
  return NAN;
}

// Every path with every law gives one impact there at the adapter's default step, with a positive
// force and a plausible rebound, and says in its diagnostics what it set.
TEST(BulletSimulator, EveryPathRunsEveryLaw) {
  const Scenario s = first_impact();
  for (const char* articulation : {"multibody", "constraints"})
    for (const char* path : {"matched", "injected", "native"})
      for (ContactLaw law : {ContactLaw::hertz, ContactLaw::viscoelastic, ContactLaw::newton}) {
        const std::string what = std::string(articulation) + "/" + path + "/" + to_string(law);
        RunSettings settings;
        settings.law = law;
        settings.series_start_s = 0;
        settings.options = {{"articulation", articulation}, {"contact", path}};
        const RunResult r = make_bullet_simulator()->run(s, settings);
        ASSERT_EQ(r.status, RunStatus::ok) << what << ": " << r.reason;
        ASSERT_GE(r.trajectory.events.size(), 1u) << what;
        const ContactEvent& e = r.trajectory.events.front();
        EXPECT_NEAR(e.onset_time_s, 0.048, 1e-3) << what;
        EXPECT_GT(e.peak_force_n, 0) << what;
        EXPECT_GE(e.restitution, -1e-6) << what;  // native: inelastic, the tips part at the same speed
        EXPECT_LE(e.restitution, 1) << what;
        EXPECT_EQ(diagnostic(r, "time_step_s"), 5e-5) << what;
        EXPECT_EQ(diagnostic(r, "chain_links"), 8) << what;
        EXPECT_EQ(r.cost.steps, 1400) << what;
        const bool injected =
            std::string(path) == "injected" || (std::string(path) == "matched" && law == ContactLaw::hertz);
        EXPECT_EQ(diagnostic(r, "contact_injected"), injected ? 1 : 0) << what;
        if (std::string(path) == "native") {
          // Bullet's defaults: a rigid, inelastic, frictional contact
          EXPECT_EQ(diagnostic(r, "contact_restitution"), 0) << what;
          EXPECT_EQ(diagnostic(r, "contact_friction"), 0.25) << what;
          EXPECT_LT(e.restitution, 0.3) << what;
        }
      }
}

TEST(BulletSimulator, MatchedDiagnosticsNameTheBulletParameters) {
  const Scenario s = first_impact();
  RunSettings settings;
  settings.law = ContactLaw::viscoelastic;
  settings.time_step_s = 1e-5;
  const RunResult r = make_bullet_simulator()->run(s, settings);
  ASSERT_EQ(r.status, RunStatus::ok) << r.reason;
  const double k = s.contact.viscoelastic->stiffness_n_per_m, c = s.contact.viscoelastic->damping_n_s_per_m, h = 1e-5;
  EXPECT_NEAR(diagnostic(r, "contact_stiffness_n_per_m") / k, 1.0, 1e-15);
  EXPECT_EQ(diagnostic(r, "contact_damping_n_s_per_m"), c);
  EXPECT_NEAR(diagnostic(r, "contact_erp"), h * k / (h * k + c), 1e-15);
  EXPECT_NEAR(diagnostic(r, "contact_cfm_m_per_n_s"), 1 / (h * k + c), 1e-18);
  EXPECT_EQ(diagnostic(r, "split_impulse"), 0);
  settings.law = ContactLaw::newton;
  const RunResult n = make_bullet_simulator()->run(s, settings);
  EXPECT_EQ(diagnostic(n, "contact_restitution"), s.contact.newton->restitution);
  EXPECT_EQ(diagnostic(n, "restitution_velocity_threshold_m_s"), 0);
  EXPECT_EQ(diagnostic(n, "split_impulse"), 1);
  EXPECT_EQ(diagnostic(n, "warm_starting"), 1);
  EXPECT_EQ(diagnostic(n, "contact_erp2"), 0);
}

// The hinge springs are explicit: above the chain's stability limit the run diverges, and the
// adapter says where and when instead of crashing.
TEST(BulletSimulator, InstabilityIsReportedWithTimeAndQuantity) {
  Scenario s = first_impact();
  s.duration_s = s.scoring_window_s = 0.3;  // 750 steps: the constraints' modal chain takes about 220 to diverge
  // the limit of K = 8: 1.65e-4 s with modal damping (every mode zeta = 0.003: about 2 / omega_max), 7.5e-5 s
  // with hinge damping (its fastest mode has zeta 0.85); 4e-4 s is beyond both
  const std::pair<const char*, double> limits[] = {{"modal", 1.65e-4}, {"hinge", 7.5e-5}};
  for (const auto& [damping, limit_s] : limits)
    for (const char* articulation : {"multibody", "constraints"}) {
      RunSettings settings;
      settings.law = ContactLaw::viscoelastic;
      settings.time_step_s = 4e-4;
      settings.series_start_s = 0;
      settings.options = {{"articulation", articulation}, {kChainDampingOption, damping}};
      const RunResult r = make_bullet_simulator()->run(s, settings);
      EXPECT_EQ(r.status, RunStatus::unstable) << articulation << " " << damping;
      EXPECT_NE(r.reason.find("at t = "), std::string::npos) << r.reason;
      EXPECT_TRUE(r.reason.find("tip displacement") != std::string::npos ||
                  r.reason.find("non-finite") != std::string::npos)
          << r.reason;
      EXPECT_LT(r.cost.steps, 750) << articulation << " " << damping;  // stopped there, not run to the end
      EXPECT_NEAR(diagnostic(r, "hinge_step_limit_s"), limit_s, 0.04 * limit_s) << articulation << " " << damping;
    }
}

}  // namespace bullet_simulator_contract_test
}  // namespace ib
