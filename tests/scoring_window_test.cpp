// The scoring window has one rule (scoring_window, model/scenario.h): the last window of the run, from the
// scenario's scoring_window_s, a --window or a sweep row's, ending at the run's end (the --duration cut's,
// when cut), never before t = 0; and what the harness measures and records is that window.
#include <gtest/gtest.h>

#include "harness/jobs/run_job.h"
#include "model/scenario.h"

namespace ib {
namespace scoring_window_test {

Scenario run_of(double duration_s, double window_s) {
  Scenario s = default_rig();
  s.duration_s = duration_s;
  s.scoring_window_s = window_s;
  return s;
}

TEST(ScoringWindow, IsTheScenariosLastWindowOfTheRun) {
  const ScoringWindow w = scoring_window(run_of(100, 14));
  EXPECT_EQ(w.start_s, 86);
  EXPECT_EQ(w.end_s, 100);
}

TEST(ScoringWindow, AGivenWindowReplacesTheScenarios) {
  const ScoringWindow w = scoring_window(run_of(100, 14), 2.5);
  EXPECT_EQ(w.start_s, 97.5);
  EXPECT_EQ(w.end_s, 100);
}

TEST(ScoringWindow, NeverStartsBeforeTheRun) {
  EXPECT_EQ(scoring_window(run_of(1, 14)).start_s, 0);
  EXPECT_EQ(scoring_window(run_of(100, 14), 250).start_s, 0);
  EXPECT_EQ(scoring_window(run_of(100, 14), 250).end_s, 100);
}

TEST(ScoringWindow, ACutRunKeepsItsWindowAtItsNewEnd) {
  Scenario s = run_of(100, 14);
  ASSERT_TRUE(cut_run(s, 20));
  EXPECT_EQ(scoring_window(s).start_s, 6);
  EXPECT_EQ(scoring_window(s).end_s, 20);
  ASSERT_TRUE(cut_run(s, 10));  // shorter than the window: the whole run
  EXPECT_EQ(scoring_window(s).start_s, 0);
  EXPECT_EQ(scoring_window(s).end_s, 10);
}

TEST(ScoringWindow, IsWhatTheMetricsAreTakenOver) {
  const Scenario s = run_of(30, 14);
  Measurement measurement;
  EXPECT_EQ(metric_settings(s, measurement).window.start_s, 16);
  EXPECT_EQ(metric_settings(s, measurement).window.end_s, 30);
  measurement.window_s = 4;
  EXPECT_EQ(metric_settings(s, measurement).window.start_s, 26);
  EXPECT_EQ(metric_settings(s, measurement).window.end_s, 30);
}

TEST(ScoringWindow, StartsTheSeriesUnlessTheRunSaysOtherwise) {
  const Scenario s = run_of(30, 14);
  RunSettings settings;
  EXPECT_EQ(series_start_s(settings, s), 16);
  settings.series_start_s = 3;
  EXPECT_EQ(series_start_s(settings, s), 3);
}

}  // namespace scoring_window_test
}  // namespace ib
