// A step walk (suite --find-steps --step-walk; a study's [[search]] with walk = true), the ladder of an
// error-against-cost front: it probes the grid from its largest step down, one step at a time, through the
// unstable steps at the top, and stops where the error against the beam stops falling (two stable steps in a
// row that lower the best score by at most a tenth of a tolerance), at the grid's end, or at a probe that
// reached the time limit. Through the suite runner, a walk that crosses a step a suite part runs reads that
// run's record instead of running the job again.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "harness/suite/step_search.h"
#include "harness/suite/suite.h"
#include "mirror_simulator.h"
#include "simulators/catalog.h"
#include "suite_test_support.h"

namespace ib {
namespace step_walk_test {

namespace fs = std::filesystem;

constexpr double kUnstableAbove_s = 2e-4;

StepSearchSettings walk_settings(double min_step_s, double max_step_s) {
  StepSearchSettings s;
  s.walk = true;
  s.points_per_octave = 2;
  s.min_step_s = min_step_s;
  s.max_step_s = max_step_s;
  return s;
}

// A run unstable above 2e-4 s whose frame 1 sensor peak is off by `peak_error(dt)` against the beam.
template <typename Error>
ProbeResult probe_at(double dt, Error peak_error) {
  ProbeResult r;
  r.verdict = dt > kUnstableAbove_s ? Verdict::unstable : Verdict::ok;
  r.error[HeadlineMetric::frame1_sensor_peak] = peak_error(dt);
  r.error[HeadlineMetric::contact_duration] = 0;
  r.error[HeadlineMetric::impacts_per_cycle] = 0;
  r.beam_error = r.error;
  return r;
}

ReferenceFacts forced_reference() { return ReferenceFacts{true, 20.0, 1e-3, 0.5}; }

// Walks to the end; returns the grid indices probed, in order.
template <typename Error>
std::vector<int> walk(StepSearch& search, Error peak_error) {
  std::vector<int> probed;
  while (const auto k = search.next_probe()) {
    if (search.probed(*k)) {
      ADD_FAILURE() << "probed twice: " << *k;
      break;
    }
    search.add(*k, probe_at(search.grid()[*k], peak_error));
    probed.push_back(*k);
  }
  return probed;
}

TEST(StepWalk, GoesDownOneGridStepAtATimeUntilTheErrorStopsFalling) {
  // first order in the step above a 5 % floor (a model error the step cannot remove)
  const auto first_order = [](double dt) { return 0.05 + 1000 * dt; };
  StepSearch search(walk_settings(1e-6, 1e-3), forced_reference(), "beam reference");
  const std::vector<int> probed = walk(search, first_order);
  ASSERT_GE(probed.size(), 4u);
  for (std::size_t i = 0; i < probed.size(); ++i) EXPECT_EQ(probed[i], static_cast<int>(i));  // no step skipped
  // the unstable steps at the top (1e-3 to 2.5e-4 s) were walked through, not taken for a flat error
  const auto& grid = search.grid();
  const std::size_t first_stable = static_cast<std::size_t>(std::ceil(2 * std::log2(1e-3 / kUnstableAbove_s)));
  EXPECT_EQ(search.stability().largest_pass_step_s, grid[first_stable]);
  EXPECT_GT(probed.size(), first_stable + 3);
  // the last two steps lowered the score (error over its 10 % tolerance) by at most 0.1, the one before by more
  const auto score = [&](std::size_t back) { return first_order(grid[probed.size() - back]) / 0.1; };
  EXPECT_LE(score(2) - score(1), 0.1);
  EXPECT_LE(score(3) - score(2), 0.1);
  EXPECT_GT(score(4) - score(3), 0.1);
  EXPECT_GT(grid[probed.size() - 1], 1e-5);  // far above the grid's end: where the error stopped falling
  EXPECT_FALSE(search.next_probe());
  EXPECT_EQ(search.probes_left_estimate(), 0);
}

TEST(StepWalk, AnErrorThatKeepsFallingIsFollowedToTheGridsEnd) {
  const auto steep = [](double dt) { return 5e3 * dt; };  // at 1e-5 s still 5 %, and falling by 29 % a step
  StepSearch search(walk_settings(1e-5, 1e-3), forced_reference(), "beam reference");
  const std::vector<int> probed = walk(search, steep);
  EXPECT_EQ(probed.size(), search.grid().size());
  EXPECT_EQ(search.accuracy(HeadlineMetric::frame1_sensor_peak).status, "bracketed to one grid step");
}

TEST(StepWalk, AProbeAtTheTimeLimitEndsTheWalk) {
  StepSearch search(walk_settings(1e-6, 1e-3), forced_reference(), "beam reference");
  for (int k = 0; k < 6; ++k) search.add(k, probe_at(search.grid()[k], [](double dt) { return 1e4 * dt; }));
  ASSERT_EQ(search.next_probe(), 6);
  ProbeResult slow;
  slow.timed_out = true;
  search.add(6, slow);
  EXPECT_FALSE(search.next_probe());  // smaller steps cost more
}

TEST(StepWalk, AMetricNeverWithinItsToleranceFailsDownToTheWalksSmallestStep) {
  StepSearch search(walk_settings(1e-6, 1e-3), forced_reference(), "beam reference");
  walk(search, [](double) { return 0.3; });  // flat at 30 %: three stable steps and the walk ends
  const auto peak = search.accuracy(HeadlineMetric::frame1_sensor_peak);
  EXPECT_EQ(peak.status, "fails down to the walk's smallest step");
  EXPECT_EQ(search.accuracy(HeadlineMetric::contact_duration).status, "bracketed to one grid step");
  EXPECT_EQ(search.probes(), static_cast<int>(std::ceil(2 * std::log2(1e-3 / 2e-4))) + 3);
}

// ---- through the suite runner ------------------------------------------------------------------------

std::unique_ptr<Simulator> test_factory(const std::string& name) {
  if (name == "mirror") return std::make_unique<test::Mirror>();
  return make_simulator(name);
}

TEST(StepWalkSuite, AWalkThroughAStepASuitePartRunsReadsThatRunInsteadOfRunningItAgain) {
  const fs::path root = test::fresh_test_folder("impactbench_walk_");
  test::write_short_free_vibration(root / "scenarios");
  SuiteSettings part;
  part.inputs = {(root / "scenarios").string()};
  part.out = (root / "out").string();
  part.engines = {"reference", "mirror"};
  part.laws = {ContactLaw::hertz};
  part.jobs = 2;
  part.simulators = simulator_catalog();
  part.simulators.make = test_factory;
  SuiteSettings suite = part, search = part;
  suite.time_steps_s = {1e-4};                       // the walk's third grid step
  search.step_search = walk_settings(2.5e-5, 2e-4);  // 2e-4, 1.41e-4, 1e-4, 7.1e-5, 5e-5, 3.5e-5, 2.5e-5
  const SuiteOutcome outcome = run_suites({suite, search});

  const auto runs = test::json_lines(part.out + "/runs.jsonl");
  std::map<std::string, int> times_recorded;
  for (const auto& run : runs) ++times_recorded[run["job_id"].get<std::string>()];
  for (const auto& [id, times] : times_recorded) EXPECT_EQ(times, 1) << id;
  EXPECT_EQ(times_recorded.count("short_free/mirror/hertz/dt=0.0001"), 1u);
  EXPECT_EQ(outcome.jobs_run, static_cast<int>(runs.size()));

  const auto rows = test::json_lines(part.out + "/steps.jsonl");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0]["search"], "walk");
  // the mirror is the reference on its chain at any step: the error against the beam is the same at every
  // step, so the walk stops after three: the first sets the score, two more do not lower it
  EXPECT_EQ(rows[0]["probes"].get<int>(), 3);
  EXPECT_NE(rows[0]["probe_outcomes"].get<std::string>().find("0.0001:"), std::string::npos)
      << rows[0]["probe_outcomes"];
  fs::remove_all(root);
}

}  // namespace step_walk_test
}  // namespace ib
