// The native contact path is each engine's own contact as a user leaves it: the scenario's contact law
// and its parameters play no part. The suite relies on it, running the native path once and scoring that
// run against every law's references (harness/suite/suite.cpp), so each engine is checked here: the same
// native run, bit for bit, whatever law the settings name, over impacts.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "model/simulator.h"
#include "reference_fixtures.h"
#include "simulators/catalog.h"

namespace ib {
namespace native_contact_law_test {

// Free vibration over its first 0.2 s: frame 1 released 2.5 mm toward frame 2, several impacts.
Scenario first_impacts() {
  Scenario s = testing::paper_scenario("free_vibration");
  s.duration_s = 0.2;
  s.scoring_window_s = 0.2;
  return s;
}

RunResult native_run(const std::string& engine, ContactLaw law) {
  RunSettings settings;
  settings.law = law;
  settings.time_step_s = 5e-5;
  settings.series_start_s = 0;
  settings.options["contact"] = "native";
  return make_simulator(engine)->run(first_impacts(), settings);
}

class NativeContact : public ::testing::TestWithParam<std::string> {};

TEST_P(NativeContact, IgnoresTheScenariosLaw) {
  const RunResult hertz = native_run(GetParam(), ContactLaw::hertz);
  ASSERT_GT(hertz.trajectory.events.size(), 0u) << "the case must have impacts to show anything";
  for (ContactLaw law : {ContactLaw::viscoelastic, ContactLaw::newton}) {
    const RunResult other = native_run(GetParam(), law);
    SCOPED_TRACE(to_string(law));
    EXPECT_EQ(other.status, hertz.status);
    ASSERT_EQ(other.trajectory.size(), hertz.trajectory.size());
    for (int f = 0; f < 2; ++f)
      EXPECT_EQ(other.trajectory.displacement_m[f], hertz.trajectory.displacement_m[f]) << "frame " << f + 1;
    EXPECT_EQ(other.trajectory.contact_force_n, hertz.trajectory.contact_force_n);
    EXPECT_EQ(other.trajectory.events.size(), hertz.trajectory.events.size());
  }
}

std::vector<std::string> engines_in_build() {
  std::vector<std::string> engines;
  for (const std::string& name : simulator_names())
    if (name != "reference") engines.push_back(name);
  return engines;
}

INSTANTIATE_TEST_SUITE_P(Engines, NativeContact, ::testing::ValuesIn(engines_in_build()),
                         [](const auto& info) { return info.param; });

}  // namespace native_contact_law_test
}  // namespace ib
