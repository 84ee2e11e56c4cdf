// The metric catalog (harness/scoring/metric_catalog.h) is what the harness judges and writes: each metric's
// error is the one the verdict judges against the tolerance the catalog names, its columns are runs.csv's,
// every tolerance of AccuracyTolerances has one key, the step search searches the metrics marked so, and
// metrics.json (harness/records/metrics_file.h) carries the catalog with the default tolerances.
#include "harness/scoring/metric_catalog.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "harness/records/metrics_file.h"
#include "harness/suite/step_search.h"

namespace ib {
namespace metric_catalog_test {

// Each scored error set in MetricErrors by hand, independently of the catalog's error_of.
const std::map<std::string, std::function<void(MetricErrors&, double)>>& setters() {
  static const std::map<std::string, std::function<void(MetricErrors&, double)>> set = {
      {"frame1_sensor_peak", [](MetricErrors& e, double x) { e.sensor_peak_relative_error[0] = x; }},
      {"frame2_sensor_peak", [](MetricErrors& e, double x) { e.sensor_peak_relative_error[1] = x; }},
      {"contact_duration", [](MetricErrors& e, double x) { e.contact_duration_relative_error = x; }},
      {"impacts_per_cycle", [](MetricErrors& e, double x) { e.impacts_per_cycle_difference = x; }},
      {"frame1_log_decrement", [](MetricErrors& e, double x) { e.log_decrement_relative_error[0] = x; }}};
  return set;
}

// Each tolerance different, so that a metric pointing at another's tolerance is judged differently.
AccuracyTolerances distinct_tolerances() {
  AccuracyTolerances t;
  t.sensor_peak_relative = 0.11;
  t.contact_duration_relative = 0.22;
  t.impacts_per_cycle_difference = 0.33;
  t.log_decrement_relative = 0.44;
  return t;
}

TEST(MetricCatalog, EachMetricIsJudgedByTheVerdictAgainstItsOwnTolerance) {
  VerdictSettings settings;
  settings.accuracy = distinct_tolerances();
  ASSERT_EQ(scored_metrics().size(), setters().size());
  for (const ScoredMetric& m : scored_metrics()) {
    ASSERT_TRUE(setters().count(m.name)) << m.name;
    const double tolerance = tolerance_of(m, settings.accuracy);
    for (const double factor : {0.9, 1.1}) {
      MetricErrors e;
      setters().at(m.name)(e, -factor * tolerance);  // an error beyond the tolerance either way is inaccurate
      EXPECT_EQ(m.error_of(e), -factor * tolerance) << m.name;
      const Verdict expected = factor > 1 ? Verdict::inaccurate : Verdict::ok;
      EXPECT_EQ(judge_accuracy(e, settings, "beam").verdict, expected) << m.name << " at " << factor << " x tolerance";
    }
  }
}

TEST(MetricCatalog, ColumnsAreRunsCsvsAndEveryToleranceHasOneKey) {
  std::set<std::string> metric_columns;
  for (const auto& [name, value] : flatten(Metrics{})) metric_columns.insert(name);
  std::vector<double AccuracyTolerances::*> members;  // member pointers have no order: a vector, each once
  std::map<std::string, double AccuracyTolerances::*> member_of_key;
  for (const ScoredMetric& m : scored_metrics()) {
    EXPECT_TRUE(metric_columns.count(m.column)) << m.column;
    MetricErrors e;
    setters().at(m.name)(e, 0.5);
    for (const ScoringReference& r : scoring_references()) {
      bool found = false;
      for (const auto& [name, value] : flatten(e, r.error_prefix))
        if (name == r.error_prefix + m.error_column) found = value == 0.5;
      EXPECT_TRUE(found) << r.error_prefix << m.error_column;
    }
    if (std::find(members.begin(), members.end(), m.tolerance) == members.end()) members.push_back(m.tolerance);
    const auto [at, added] = member_of_key.emplace(m.tolerance_key, m.tolerance);
    EXPECT_EQ(at->second, m.tolerance) << m.tolerance_key << ": one key, one tolerance";
  }
  EXPECT_EQ(members.size(), sizeof(AccuracyTolerances) / sizeof(double)) << "a tolerance that judges no metric";
  EXPECT_EQ(member_of_key.size(), members.size());
}

// The settings record of suite.jsonl and the reference cache's key hold the tolerances as an array: its order
// is what folders written before the catalog hold, so that they resume and their cached references are found.
TEST(MetricCatalog, TheTolerancesArrayKeepsItsOrder) {
  const AccuracyTolerances t = distinct_tolerances();
  EXPECT_EQ(tolerance_values(t), (std::vector<double>{t.sensor_peak_relative, t.contact_duration_relative,
                                                      t.impacts_per_cycle_difference, t.log_decrement_relative}));
}

TEST(MetricCatalog, TheStepSearchSearchesTheMetricsMarkedSo) {
  std::set<std::string> searched, marked;
  for (HeadlineMetric h : kHeadlineMetrics) {
    searched.insert(to_string(h));
    EXPECT_EQ(tolerance_of(distinct_tolerances(), h), tolerance_of(scored_metric(to_string(h)), distinct_tolerances()));
  }
  for (const ScoredMetric& m : scored_metrics())
    if (m.step_searched) marked.insert(m.name);
  EXPECT_EQ(searched, marked);
  EXPECT_THROW(scored_metric("frame3_sensor_peak"), std::invalid_argument);
}

TEST(MetricCatalog, MetricsJsonHoldsTheCatalogWithTheDefaultTolerances) {
  const nlohmann::json j = nlohmann::json::parse(metrics_json());
  ASSERT_EQ(j["metrics"].size(), scored_metrics().size());
  std::set<std::string> references;
  for (const auto& r : j["references"]) references.insert(r["name"].get<std::string>());
  for (std::size_t i = 0; i < scored_metrics().size(); ++i) {
    const ScoredMetric& m = scored_metrics()[i];
    const nlohmann::json& written = j["metrics"][i];
    EXPECT_EQ(written["name"], m.name);
    EXPECT_EQ(written["error_column"], m.error_column);
    EXPECT_EQ(written["kind"], m.kind == ErrorKind::relative ? "relative" : "difference");
    EXPECT_EQ(written["default_tolerance"].get<double>(), 0.10) << m.name << ": docs/verdicts' default";
    EXPECT_EQ(written["better"], "smaller |error|");
    for (const auto& against : written["scored_against"]) EXPECT_TRUE(references.count(against)) << against;
  }
  EXPECT_NE(j["tolerances"].get<std::string>().find("commands.jsonl"), std::string::npos);
}

}  // namespace metric_catalog_test
}  // namespace ib
