// Timed runs are separate from the logged run and repeated: run_job runs the simulator once to record
// (series, events, metrics) and then Measurement::timed_repeats times more with nothing written; the
// record's cost is the median of those, with their spread and the logged run's own time beside it.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "harness/jobs/run_job.h"
#include "model/scenario_toml.h"
#include "reference/reference_simulator.h"
#include "simulators/catalog.h"
#include "suite_test_support.h"

namespace ib {
namespace timed_runs_test {

// The reference under another name whose reported run times are scripted: the logged run takes 100 s,
// the timed ones take the times given, in order. Counts its runs in `runs` (which outlives it: run_job
// owns the simulator and drops it when it returns).
class ScriptedClock final : public Simulator {
 public:
  ScriptedClock(std::vector<double> timed_wall_s, int& runs) : timed_wall_s_(std::move(timed_wall_s)), runs_(runs) {}
  std::string name() const override { return "scripted"; }
  std::string version() const override { return "test"; }
  std::vector<std::pair<std::string, std::string>> option_help() const override { return {}; }
  RunResult run(const Scenario& s, const RunSettings& settings) override {
    RunResult r = make_reference_simulator()->run(s, settings);
    const double wall = runs_ == 0 ? 100.0 : timed_wall_s_.at(runs_ - 1);
    r.cost.wall_time_s = wall;
    r.cost.cpu_time_s = wall / 2;
    ++runs_;
    return r;
  }

 private:
  std::vector<double> timed_wall_s_;
  int& runs_;
};

struct Fixture {
  Scenario scenario;
  JobSpec job;
  Fixture(const std::filesystem::path& folder) {
    test::write_short_free_vibration(folder);
    scenario = load_scenario((folder / "short_free.toml").string());
    job.scenario_path = scenario.source_path;
    job.engine = "scripted";
  }
};

TEST(TimedRuns, TheCostIsTheMedianOfTheTimedRunsWithTheirSpreadAndTheLoggedRunBeside) {
  const auto folder = test::fresh_test_folder("timed_runs_");
  Fixture f(folder);
  int runs = 0;
  const SimulatorFactory factory = [&](const std::string&) {
    return std::make_unique<ScriptedClock>(std::vector<double>{5.0, 1.0, 3.0}, runs);
  };
  Measurement measurement;
  measurement.timed_repeats = 3;
  const RunRecord r =
      run_job(f.scenario, f.job, measurement, nullptr, nullptr, (folder / "run").string(), nullptr, factory);
  EXPECT_EQ(runs, 4);  // one logged, three timed
  EXPECT_EQ(r.timed_runs, 3);
  EXPECT_DOUBLE_EQ(r.cost.wall_time_s, 3.0);
  EXPECT_DOUBLE_EQ(r.cost.cpu_time_s, 1.5);
  EXPECT_DOUBLE_EQ(r.wall_time_min_s, 1.0);
  EXPECT_DOUBLE_EQ(r.wall_time_max_s, 5.0);
  EXPECT_DOUBLE_EQ(r.logged_wall_time_s, 100.0);
  // summary.json carries the same, written after the timed runs
  std::ifstream summary(folder / "run" / "summary.json");
  const nlohmann::json j = nlohmann::json::parse(summary);
  EXPECT_DOUBLE_EQ(j.at("wall_time_s").get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(j.at("timed_runs").get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(j.at("logged_wall_time_s").get<double>(), 100.0);
}

TEST(TimedRuns, WithoutTimedRunsTheCostIsTheLoggedRunsAndNoSpreadIsClaimed) {
  const auto folder = test::fresh_test_folder("timed_runs_");
  Fixture f(folder);
  int runs = 0;
  const SimulatorFactory factory = [&](const std::string&) {
    return std::make_unique<ScriptedClock>(std::vector<double>{}, runs);
  };
  Measurement measurement;
  measurement.timed_repeats = 0;
  const RunRecord r = run_job(f.scenario, f.job, measurement, nullptr, nullptr, "", nullptr, factory);
  EXPECT_EQ(runs, 1);
  EXPECT_EQ(r.timed_runs, 0);
  EXPECT_DOUBLE_EQ(r.cost.wall_time_s, 100.0);
  for (const Field& field : fields(r)) {
    if (field.name == "wall_time_min_s" || field.name == "wall_time_max_s") {
      EXPECT_TRUE(std::isnan(std::get<double>(field.value))) << field.name;
    }
  }
}

// The cost per simulated second is per second the run actually simulated: a fixed-step run stopped as
// unstable after 200 steps of 1e-4 s (0.02 s of 20 s) cost 0.02 s CPU for 0.02 s, 1 s/s, not 0.001 s/s.
TEST(TimedRuns, ARunStoppedEarlyCostsPerSecondItSimulated) {
  RunRecord r;
  r.duration_s = 20;
  r.time_step_s = 1e-4;
  r.cost.steps = 200;
  r.cost.cpu_time_s = 0.02;
  r.cost.wall_time_s = 0.04;
  auto value = [&](const std::string& name) {
    for (const Field& field : fields(r))
      if (field.name == name) return std::get<double>(field.value);
    ADD_FAILURE() << "no " << name;
    return std::nan("");
  };
  EXPECT_DOUBLE_EQ(value("simulated_time_s"), 0.02);
  EXPECT_DOUBLE_EQ(value("cpu_time_per_simulated_s"), 1.0);
  EXPECT_DOUBLE_EQ(value("wall_time_per_simulated_s"), 2.0);
  r.cost.steps = 200000;  // the whole run: its duration
  EXPECT_DOUBLE_EQ(value("simulated_time_s"), 20.0);
  EXPECT_DOUBLE_EQ(value("cpu_time_per_simulated_s"), 0.001);
  r.time_step_s = 0;  // the adaptive reference: its duration
  r.cost.steps = 123;
  EXPECT_DOUBLE_EQ(value("simulated_time_s"), 20.0);
}

TEST(TimedRuns, TimedRunsDoNotChangeWhatIsMeasured) {
  const auto folder = test::fresh_test_folder("timed_runs_");
  Fixture f(folder);
  f.job.engine = "reference";
  Measurement once, repeated;
  once.timed_repeats = 0;
  repeated.timed_repeats = 2;
  const RunRecord a = run_job(f.scenario, f.job, once, nullptr, nullptr, "", nullptr, make_simulator);
  const RunRecord b = run_job(f.scenario, f.job, repeated, nullptr, nullptr, "", nullptr, make_simulator);
  ASSERT_TRUE(a.metrics && b.metrics);
  const auto fa = flatten(*a.metrics), fb = flatten(*b.metrics);
  ASSERT_EQ(fa.size(), fb.size());
  for (std::size_t i = 0; i < fa.size(); ++i)
    if (!std::isnan(fa[i].second)) {
      EXPECT_EQ(fa[i].second, fb[i].second) << fa[i].first;
    }
  EXPECT_EQ(b.timed_runs, 2);
  EXPECT_LE(b.wall_time_min_s, b.cost.wall_time_s);
  EXPECT_LE(b.cost.wall_time_s, b.wall_time_max_s);
}

}  // namespace timed_runs_test
}  // namespace ib
