// The ODE adapter's options and run settings: every option is described, bad values are errors that
// name the option and what is allowed, the defaults are the documented ones, and the registry has it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>

#include "adapters/common/rig.h"
#include "adapters/ode/ode_simulator.h"
#include "reference_fixtures.h"
#include "simulators/catalog.h"

namespace ib {
namespace ode_options_test {

double diagnostic(const RunResult& r, const std::string& name) {
  for (const auto& [key, value] : r.diagnostics)
    if (key == name) return value;
  ADD_FAILURE() << "no diagnostic " << name;
  return NAN;
}

bool has_diagnostic(const RunResult& r, const std::string& name) {
  for (const auto& entry : r.diagnostics)
    if (entry.first == name) return true;
  return false;
}

Scenario short_free_vibration() {
  Scenario s = testing::paper_scenario("free_vibration");
  s.duration_s = 0.01;
  s.scoring_window_s = 0.01;
  return s;
}

std::string error_of(const std::map<std::string, std::string>& options, double time_step_s = 0) {
  RunSettings settings;
  settings.law = ContactLaw::viscoelastic;
  settings.options = options;
  settings.time_step_s = time_step_s;
  try {
    make_ode_simulator()->run(short_free_vibration(), settings);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(OdeOptions, EveryOptionIsDescribedAndTheRegistryHasTheEngine) {
  const auto simulator = make_simulator("ode");
  ASSERT_TRUE(simulator);
  EXPECT_EQ(simulator->name(), "ode");
  std::set<std::string> names;
  for (const auto& [name, description] : simulator->option_help()) {
    names.insert(name);
    EXPECT_FALSE(description.empty()) << name;
  }
  EXPECT_EQ(names, (std::set<std::string>{"contact", "springs", "stepper", "iterations", "links", "chain_damping"}));
}

TEST(OdeOptions, BadValuesAreErrorsThatSayWhatIsAllowed) {
  EXPECT_NE(error_of({{"colour", "red"}}).find("unknown ode option 'colour'"), std::string::npos);
  EXPECT_NE(error_of({{"contact", "soft"}}).find("matched, injected, native"), std::string::npos);
  EXPECT_NE(error_of({{"springs", "stiff"}}).find("implicit, explicit"), std::string::npos);
  EXPECT_NE(error_of({{"stepper", "rk4"}}).find("world, quick"), std::string::npos);
  EXPECT_NE(error_of({{"links", "0"}}).find("links"), std::string::npos);
  EXPECT_NE(error_of({{"iterations", "50"}}).find("only with stepper=quick"), std::string::npos);
  EXPECT_NE(error_of({{"stepper", "quick"}, {"iterations", "0"}}).find("iterations"), std::string::npos);
  EXPECT_NE(error_of({}, -1e-4).find("time step"), std::string::npos);
  EXPECT_EQ(error_of({{"stepper", "quick"}, {"iterations", "50"}, {"links", "4"}, {"contact", "native"}}), "");
}

TEST(OdeOptions, DefaultsAreTheDocumentedOnes) {
  const Scenario s = short_free_vibration();
  const auto simulator = make_ode_simulator();
  RunSettings settings;
  settings.law = ContactLaw::viscoelastic;
  EXPECT_EQ(simulator->chain_links(s, settings), default_links(s));
  settings.options = {{"links", "4"}};
  EXPECT_EQ(simulator->chain_links(s, settings), 4);

  settings.options = {};
  const RunResult r = simulator->run(s, settings);
  ASSERT_EQ(r.status, RunStatus::ok) << r.reason;
  EXPECT_EQ(diagnostic(r, "time_step_s"), 1e-4);  // the default step when the settings give none
  EXPECT_EQ(diagnostic(r, "chain_links"), default_links(s));
  EXPECT_EQ(r.cost.steps, 100);
  // implicit springs (hinge stops) and the matched spring-dashpot contact are the defaults
  EXPECT_TRUE(has_diagnostic(r, "frame1_hinge_stop_erp"));
  EXPECT_TRUE(has_diagnostic(r, "contact_soft_erp"));
  EXPECT_FALSE(has_diagnostic(r, "quick_step_iterations"));
  EXPECT_EQ(diagnostic(r, "world_erp"), 0.2);  // ODE's defaults for the hinges' own rows
  EXPECT_EQ(diagnostic(r, "world_cfm"), 1e-10);

  settings.options = {{"stepper", "quick"}};
  EXPECT_EQ(diagnostic(simulator->run(s, settings), "quick_step_iterations"), 20);  // ODE's own default
  settings.options = {{"stepper", "quick"}, {"iterations", "75"}};
  EXPECT_EQ(diagnostic(simulator->run(s, settings), "quick_step_iterations"), 75);
}

TEST(OdeOptions, EachLawHasItsContactSettings) {
  const Scenario s = short_free_vibration();
  RunSettings settings;
  settings.time_step_s = 1e-5;
  settings.law = ContactLaw::newton;
  RunResult r = make_ode_simulator()->run(s, settings);
  EXPECT_EQ(diagnostic(r, "contact_bounce"), 0.8);
  EXPECT_GE(diagnostic(r, "contact_bounce_threshold_m_s"), 0.0);  // a negative threshold disables bounce
  EXPECT_EQ(diagnostic(r, "contact_soft_erp"), 0.0);
  // Hertz has no form in ODE: its force comes from the tip states, and no ODE contact is made
  settings.law = ContactLaw::hertz;
  r = make_ode_simulator()->run(s, settings);
  EXPECT_FALSE(has_diagnostic(r, "contact_joint_steps"));
  // native: ODE's contact joint without soft parameters or bounce
  settings.options = {{"contact", "native"}};
  r = make_ode_simulator()->run(s, settings);
  EXPECT_TRUE(has_diagnostic(r, "contact_joint_steps"));
  EXPECT_FALSE(has_diagnostic(r, "contact_soft_erp"));
  EXPECT_FALSE(has_diagnostic(r, "contact_bounce"));
}

// dWorldQuickStep's projected Gauss-Seidel converges to dWorldStep's direct solution as its iterations
// grow: on the free vibration's first impact (0.3 s at the default step), ODE's own default of 20
// iterations agrees with the direct solver to 1e-6 of the amplitude, 5 iterations do not (to 1e-3).
TEST(OdeOptions, QuickStepIterationsControlItsAgreementWithTheDirectSolver) {
  Scenario s = testing::paper_scenario("free_vibration");
  s.duration_s = 0.3;
  s.scoring_window_s = 0.3;
  RunSettings settings;
  settings.law = ContactLaw::viscoelastic;
  const Trajectory direct = make_ode_simulator()->run(s, settings).trajectory;
  const auto largest_difference = [&](const std::string& iterations) {
    settings.options = {{"stepper", "quick"}, {"iterations", iterations}};
    const Trajectory quick = make_ode_simulator()->run(s, settings).trajectory;
    double difference = 0;
    for (std::size_t k = 0; k < direct.size(); ++k)
      difference = std::max(difference, std::abs(quick.displacement_m[0][k] - direct.displacement_m[0][k]));
    return difference;
  };
  const double amplitude = std::abs(s.initial.frame1_tip_displacement_m);
  const double with_default = largest_difference("20"), with_few = largest_difference("5");
  std::printf(
      "quick step against dWorldStep: largest tip difference %.3g m (20 iterations), %.3g m (5), amplitude %.3g m\n",
      with_default, with_few, amplitude);
  EXPECT_LT(with_default, 1e-6 * amplitude);
  EXPECT_GT(with_few, 1e-3 * amplitude);
}

}  // namespace ode_options_test
}  // namespace ib
