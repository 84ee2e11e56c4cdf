// A diverging configuration is a verdict, not a crash: explicit hinge springs at a step far beyond
// their stability limit end the run as unstable, with the time, the quantity and the limit in the
// reason, before ODE would abort on the non-finite state; and when ODE does abort (the same rig stepped
// without the adapter's guard), the suite's job isolation records the abort with ODE's own message.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "adapters/common/rig.h"
#include "adapters/ode/ode_library.h"
#include "adapters/ode/ode_rig.h"
#include "adapters/ode/ode_simulator.h"
#include "harness/scoring/verdict.h"
#include "harness/suite/suite.h"
#include "physics/link_chain.h"
#include "reference_fixtures.h"
#include "simulators/catalog.h"
#include "suite_test_support.h"

namespace ib {
namespace ode_divergence_test {

namespace fs = std::filesystem;

// 6 times the explicit springs' limit of the K = 8 chains (1.65e-4 s with the default modal damping; 13 times
// the 7.5e-5 s of hinge damping): the fastest chain mode grows about tenfold per step.
constexpr double kDivergingStep_s = 1e-3;

double diagnostic(const RunResult& r, const std::string& name) {
  for (const auto& [key, value] : r.diagnostics)
    if (key == name) return value;
  ADD_FAILURE() << "no diagnostic " << name;
  return NAN;
}

TEST(OdeDivergence, ExplicitSpringsBeyondTheirLimitEndUnstableWithAReason) {
  Scenario s = testing::paper_scenario("free_vibration");
  s.duration_s = 0.1;
  s.scoring_window_s = 0.1;
  RunSettings settings;
  settings.law = ContactLaw::viscoelastic;
  settings.time_step_s = kDivergingStep_s;
  settings.options = {{"springs", "explicit"}};
  const RunResult r = make_ode_simulator()->run(s, settings);
  std::printf("reason: %s\n", r.reason.c_str());
  EXPECT_EQ(r.status, RunStatus::unstable);
  EXPECT_NE(r.reason.find("tip displacement |u| = "), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("at t = "), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("explicit hinge springs are stable only below a step of"), std::string::npos) << r.reason;
  // modal damping: zeta = 0.003 in every mode, the limit 2 (sqrt(1 + zeta^2) - zeta) / omega_max, just below
  // 2 / omega_max (1.65e-4 s); hinge damping: far below it, the fastest modes are heavily damped (zeta 0.85)
  const double limit = diagnostic(r, "explicit_spring_step_limit_s");
  double omega_max = 0;
  for (const FrameRig& frame : build_rig(s, settings.law, 8).frames)
    omega_max = std::max(omega_max, chain_modes(frame.chain).omega_rad_s.maxCoeff());
  EXPECT_GT(limit, 0.99 * 2 / omega_max);
  EXPECT_LT(limit, 2 / omega_max);
  settings.options = {{"springs", "explicit"}, {"chain_damping", "hinge"}};
  const RunResult hinge = make_ode_simulator()->run(s, settings);
  EXPECT_EQ(hinge.status, RunStatus::unstable);
  EXPECT_NEAR(diagnostic(hinge, "explicit_spring_step_limit_s"), 7.5e-5, 0.3e-5);
  EXPECT_LT(r.cost.steps, 100) << "stopped within a few steps of the divergence";
  const Judgement verdict = judge_stability(s, r, VerdictSettings{});
  EXPECT_EQ(verdict.verdict, Verdict::unstable);
  EXPECT_EQ(verdict.reason, r.reason);
  // the implicit springs take the same step: backward Euler is stable at any step
  settings.options = {{"springs", "implicit"}};
  const RunResult implicit = make_ode_simulator()->run(s, settings);
  EXPECT_EQ(implicit.status, RunStatus::ok) << implicit.reason;
}

// The adapter's rig without the adapter's guard: explicit springs and hinge dampers (chain_damping=hinge:
// the torques of add_explicit_spring_torques alone) stepped until ODE gives up. ODE's internal assertion on
// the non-finite orientation aborts the process.
class UnguardedOde final : public Simulator {
 public:
  std::string name() const override { return "ode_unguarded"; }
  std::string version() const override { return ode::version_text(); }
  std::vector<std::pair<std::string, std::string>> option_help() const override { return {}; }
  RunResult run(const Scenario& s, const RunSettings& settings) override {
    ode::ensure_initialised();
    const RigSpec rig = build_rig(s, settings.law, default_links(s), ChainDamping::hinge);
    ode::OdeModelSettings model;
    model.time_step_s = settings.time_step_s;
    model.springs = ode::SpringPath::explicit_torques;
    model.tip_spheres = false;
    ode::OdeRig ode_rig(rig, model);
    for (double t = 0; t < s.duration_s; t += model.time_step_s) {
      ode_rig.add_explicit_spring_torques();
      ode_rig.step();
    }
    RunResult survived;
    survived.reason = "ODE survived the divergence";
    return survived;
  }
};

std::unique_ptr<Simulator> factory(const std::string& name) {
  if (name == "ode_unguarded") return std::make_unique<UnguardedOde>();
  return make_simulator(name);
}

TEST(OdeDivergence, TheSuiteRecordsTheVerdictAndAnOdeAbort) {
  const fs::path root = test::fresh_test_folder("impactbench_ode_divergence_");
  test::write_short_free_vibration(root / "scenarios");  // two impacts in 0.4 s
  SuiteSettings settings;
  settings.inputs = {(root / "scenarios").string()};
  settings.out = (root / "out").string();
  settings.engines = {"ode", "ode_unguarded"};
  settings.laws = {ContactLaw::viscoelastic};
  settings.time_steps_s = {kDivergingStep_s};
  settings.engine_options["ode"] = {{"springs", "explicit"}};
  settings.jobs = 2;
  settings.time_limit_s = 120;
  settings.simulators = simulator_catalog();
  settings.simulators.make = factory;
  const SuiteOutcome outcome = run_suite(settings);
  EXPECT_EQ(outcome.not_ok, 2);

  std::map<std::string, nlohmann::json> by_engine;
  std::ifstream rows(settings.out + "/runs.jsonl");
  for (std::string line; std::getline(rows, line);) {
    const auto row = nlohmann::json::parse(line);
    by_engine[row["engine"].get<std::string>()] = row;
  }
  ASSERT_TRUE(by_engine.count("ode"));
  ASSERT_TRUE(by_engine.count("ode_unguarded"));
  const auto& guarded = by_engine["ode"];
  std::printf("ode: %s: %s\n", guarded["verdict"].get<std::string>().c_str(),
              guarded["reason"].get<std::string>().c_str());
  EXPECT_EQ(guarded["verdict"], "unstable");
  EXPECT_NE(guarded["reason"].get<std::string>().find("tip displacement"), std::string::npos);
  EXPECT_NE(guarded["reason"].get<std::string>().find("explicit hinge springs"), std::string::npos);
  const auto& aborted = by_engine["ode_unguarded"];
  std::printf("ode_unguarded: %s: %s\n", aborted["verdict"].get<std::string>().c_str(),
              aborted["reason"].get<std::string>().c_str());
  EXPECT_EQ(aborted["verdict"], "failed");
  EXPECT_NE(aborted["reason"].get<std::string>().find("signal 6"), std::string::npos);
  EXPECT_NE(aborted["reason"].get<std::string>().find("ODE internal error"), std::string::npos);
  fs::remove_all(root);
}

}  // namespace ode_divergence_test
}  // namespace ib
