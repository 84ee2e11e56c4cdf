// The DART simulator as the harness sees it: its name, version and options; bad options refused before
// anything runs; the length unit of the model changes nothing in the physics (DART is unit-free, and
// only its contact solver's constants have units); every path gives one first impact with the settings it
// used in its diagnostics; instability is a result with its time and quantity, never a crash.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "adapters/dart/dart_simulator.h"
#include "harness/scoring/metrics.h"
#include "reference_fixtures.h"

namespace ib {
namespace dart_simulator_contract_test {

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

TEST(DartSimulator, NameVersionAndOptions) {
  const auto dart = make_dart_simulator();
  EXPECT_EQ(dart->name(), "dart");
  EXPECT_EQ(dart->version(), "DART 6.12.1");
  const auto options = dart->option_help();
  const std::map<std::string, std::string> help(options.begin(), options.end());
  for (const char* option : {"contact", "length_unit", "lcp", "links"}) EXPECT_TRUE(help.count(option)) << option;
  const Scenario s = testing::paper_scenario("resonance");
  RunSettings settings;
  EXPECT_EQ(dart->chain_links(s, settings), 8);
  settings.options = {{"links", "4"}};
  EXPECT_EQ(dart->chain_links(s, settings), 4);
}

TEST(DartSimulator, RejectsUnknownOptionsAndValues) {
  const auto dart = make_dart_simulator();
  const Scenario s = first_impact();
  for (const auto& [name, value] : std::map<std::string, std::string>{
           {"contact", "soft"}, {"length_unit", "inch"}, {"lcp", "lemke"}, {"links", "0"}, {"substeps", "4"}}) {
    RunSettings settings;
    settings.options = {{name, value}};
    EXPECT_THROW(dart->run(s, settings), std::invalid_argument) << name << "=" << value;
  }
  RunSettings settings;
  settings.time_step_s = -1e-4;
  EXPECT_THROW(dart->run(s, settings), std::invalid_argument);
}

// Metres, centimetres and millimetres give the same tip motion: lengths, forces and moments of inertia
// scale together, the angles do not change. With the injected spring-dashpot (no DART contact involved)
// the three series agree to rounding, far below the motion's 2 mm amplitude.
TEST(DartSimulator, TheModelsLengthUnitChangesNothingButTheContactConstants) {
  const Scenario s = first_impact();
  std::map<std::string, Trajectory> runs;
  for (const char* unit : {"m", "cm", "mm"}) {
    RunSettings settings;
    settings.law = ContactLaw::viscoelastic;
    settings.time_step_s = 1e-5;
    settings.series_start_s = 0;
    settings.options = {{"contact", "injected"}, {"length_unit", unit}};
    const RunResult r = make_dart_simulator()->run(s, settings);
    ASSERT_EQ(r.status, RunStatus::ok) << unit << ": " << r.reason;
    runs[unit] = r.trajectory;
  }
  for (const char* unit : {"cm", "mm"}) {
    ASSERT_EQ(runs[unit].size(), runs["m"].size());
    double largest_difference_m = 0;
    for (int f = 0; f < 2; ++f)
      for (std::size_t k = 0; k < runs["m"].size(); ++k)
        largest_difference_m =
            std::max(largest_difference_m, std::abs(runs[unit].displacement_m[f][k] - runs["m"].displacement_m[f][k]));
    EXPECT_LT(largest_difference_m, 1e-10) << unit;
  }
}

// Every path with every law: one impact, the contact force DART reports where DART makes the contact,
// and the diagnostics say what was set.
TEST(DartSimulator, EveryPathRunsEveryLaw) {
  const Scenario s = first_impact();
  for (const char* path : {"matched", "injected", "native"})
    for (ContactLaw law : {ContactLaw::hertz, ContactLaw::viscoelastic, ContactLaw::newton}) {
      RunSettings settings;
      settings.law = law;
      settings.time_step_s = 1e-5;
      settings.series_start_s = 0;
      settings.options = {{"contact", path}, {"length_unit", "cm"}};
      const RunResult r = make_dart_simulator()->run(s, settings);
      ASSERT_EQ(r.status, RunStatus::ok) << path << " " << to_string(law) << ": " << r.reason;
      const Metrics m = compute_metrics(r.trajectory, MetricSettings{0, s.duration_s});
      EXPECT_GE(m.impacts, 1) << path << " " << to_string(law);
      const bool dart_contact =
          std::string(path) == "native" || (std::string(path) == "matched" && law == ContactLaw::newton);
      EXPECT_EQ(diagnostic(r, "contact_force_from_tip_states"), dart_contact ? 0 : 1) << path << " " << to_string(law);
      if (dart_contact) {
        EXPECT_GT(diagnostic(r, "contact_steps"), 0) << path;
        EXPECT_GT(*std::max_element(r.trajectory.peak_contact_force_n.begin(), r.trajectory.peak_contact_force_n.end()),
                  0)
            << path;
        EXPECT_DOUBLE_EQ(diagnostic(r, "bounce_threshold_m_s"), 1e-3);
        EXPECT_DOUBLE_EQ(diagnostic(r, "restitution_of_pair"), std::string(path) == "native" ? 0.0 : 0.8);
      }
    }
}

// The injected Hertz force, explicit over a 1 ms step, throws the tips apart: the run stops at the
// divergence bound and says when and what, instead of handing DART a state it would abort on.
TEST(DartSimulator, InstabilityIsReportedWithTimeAndQuantity) {
  const Scenario s = first_impact();
  RunSettings settings;
  settings.law = ContactLaw::hertz;
  settings.time_step_s = 1e-3;
  settings.series_start_s = 0;
  settings.options = {{"contact", "injected"}};
  const RunResult r = make_dart_simulator()->run(s, settings);
  EXPECT_EQ(r.status, RunStatus::unstable) << r.reason;
  EXPECT_NE(r.reason.find("at t = "), std::string::npos) << r.reason;
  EXPECT_LT(r.cost.steps, 70);
}

}  // namespace dart_simulator_contract_test
}  // namespace ib
