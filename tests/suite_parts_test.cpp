// A study's suites run as one plan (run_suites): they record what the same suites run one after another
// into one folder record (suite.jsonl lines, runs, metrics), a job two parts plan runs once, parts that
// would decide a shared job's result differently are refused, and a resumed run of the parts runs nothing twice.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "harness/suite/suite.h"
#include "mirror_simulator.h"
#include "simulators/catalog.h"
#include "suite_test_support.h"

namespace ib {
namespace suite_parts_test {

namespace fs = std::filesystem;

using test::Mirror;

std::unique_ptr<Simulator> test_factory(const std::string& name) {
  if (name == "mirror") return std::make_unique<Mirror>();
  return make_simulator(name);
}

class SuiteParts : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = test::fresh_test_folder("impactbench_parts_");
    test::write_short_free_vibration(root_ / "scenarios");
    SuiteSettings s;
    s.inputs = {(root_ / "scenarios").string()};
    s.engines = {"reference", "mirror"};
    s.laws = {ContactLaw::hertz};
    s.jobs = 2;
    s.simulators = simulator_catalog();
    s.simulators.make = test_factory;
    first_ = s;
    second_ = s;  // another law and no series: shares the hertz beam reference with the first part
    second_.laws = {ContactLaw::hertz, ContactLaw::newton};
    second_.measurement.series = SeriesOutput::none;
  }
  void TearDown() override { fs::remove_all(root_); }

  // job id -> the runs.jsonl fields a run's physics decides (its costs and times aside)
  static std::map<std::string, nlohmann::json> physics(const fs::path& folder) {
    std::map<std::string, nlohmann::json> out;
    for (nlohmann::json line : test::json_lines(folder / "runs.jsonl")) {
      for (auto it = line.begin(); it != line.end();) {
        const std::string& key = it.key();
        const bool cost = key.find("time") != std::string::npos || key.find("per_s") != std::string::npos ||
                          key.find("cpu") != std::string::npos || key.find("steps_per") != std::string::npos ||
                          key == "load_average";  // the machine's, not the run's
        it = cost ? line.erase(it) : std::next(it);
      }
      out[line["job_id"]] = line;
    }
    return out;
  }
  static std::vector<nlohmann::json> settings_lines(const fs::path& folder) {
    return test::json_lines(folder / "suite.jsonl");
  }

  fs::path root_;
  SuiteSettings first_, second_;
};

TEST_F(SuiteParts, TwoPartsInOneRunRecordWhatTheTwoSuitesRecordOneAfterTheOther) {
  first_.out = second_.out = (root_ / "together").string();
  const SuiteOutcome together = run_suites({first_, second_});
  EXPECT_EQ(together.not_ok, 0);

  first_.out = second_.out = (root_ / "in_turn").string();
  run_suite(first_);
  second_.extend = true;
  run_suite(second_);

  const auto a = physics(root_ / "together"), b = physics(root_ / "in_turn");
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(a, b);
  EXPECT_EQ(settings_lines(root_ / "together"), settings_lines(root_ / "in_turn"));
}

TEST_F(SuiteParts, AJobBothPartsPlanRunsOnceAndBothRecordIt) {
  first_.out = second_.out = (root_ / "out").string();
  const SuiteOutcome outcome = run_suites({first_, second_});
  // hertz: beam, chain, mirror (shared); newton: beam, chain, mirror
  EXPECT_EQ(outcome.jobs_total, 6);
  EXPECT_EQ(test::line_count(root_ / "out" / "runs.jsonl"), 6u);
  const auto lines = settings_lines(root_ / "out");
  ASSERT_EQ(lines.size(), 2u);
  const std::string shared = "short_free/reference/hertz";
  for (const auto& line : lines) {
    const auto jobs = line["jobs"].get<std::vector<std::string>>();
    EXPECT_NE(std::find(jobs.begin(), jobs.end(), shared), jobs.end()) << line.dump();
  }
}

TEST_F(SuiteParts, PartsThatWouldDecideASharedJobDifferentlyAreRefusedBeforeAnythingRuns) {
  first_.out = second_.out = (root_ / "out").string();
  second_.output_rate_hz = 2048;  // result-deciding: the shared reference would be sampled otherwise
  try {
    run_suites({first_, second_});
    FAIL() << "two parts sharing a job under other output rates were accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("planned by two parts"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("output_rate_hz"), std::string::npos) << error.what();
  }
  EXPECT_EQ(test::line_count(root_ / "out" / "runs.jsonl"), 0u);
}

// An ensemble's start is the same run in any part of the same displacement step: start 0 is the single run of
// a part without an ensemble; two ensembles of other steps would give one job id two runs.
TEST_F(SuiteParts, AnEnsembleSharesItsStartsWithOtherPartsOfTheSameStepOnly) {
  first_.out = second_.out = (root_ / "out").string();
  first_.ensemble.engine_starts = 2;
  first_.ensemble.reference_starts = 3;
  SuiteSettings other_step = first_;
  other_step.laws = {ContactLaw::newton, ContactLaw::hertz};
  other_step.ensemble.displacement_step_m = 2e-7;
  try {
    run_suites({first_, other_step});
    FAIL() << "two ensembles of other steps sharing their starts were accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("ensemble displacement_step_m"), std::string::npos) << error.what();
  }
  EXPECT_EQ(test::line_count(root_ / "out" / "runs.jsonl"), 0u);
  const SuiteOutcome outcome = run_suites({first_, second_});
  // hertz: 3 beam starts, 2 chain and 2 mirror starts; newton (the second part's alone): beam, chain, mirror
  EXPECT_EQ(outcome.jobs_total, 10);
  EXPECT_EQ(outcome.not_ok_recorded, 0);
  for (const nlohmann::json& line : test::json_lines(root_ / "out" / "runs.jsonl"))
    EXPECT_EQ(line["verdict"], "ok") << line["job_id"] << ": " << line["reason"];
  // a reference start an engine start is compared with keeps its series; one beyond the engines' only its metrics
  const fs::path runs = root_ / "out" / "runs" / "short_free" / "reference" / "hertz";
  EXPECT_TRUE(fs::exists(runs / "start=1" / "series.csv.gz"));
  EXPECT_TRUE(fs::exists(runs / "start=2" / "summary.json"));
  EXPECT_FALSE(fs::exists(runs / "start=2" / "series.csv.gz"));
}

TEST_F(SuiteParts, ResumingThePartsRunsNothingTwice) {
  first_.out = second_.out = (root_ / "out").string();
  run_suites({first_, second_});
  first_.resume = second_.resume = true;
  const SuiteOutcome again = run_suites({first_, second_});
  EXPECT_EQ(again.jobs_run, 0);
  EXPECT_EQ(again.jobs_skipped, 6);
  EXPECT_EQ(test::line_count(root_ / "out" / "runs.jsonl"), 6u);
  EXPECT_EQ(settings_lines(root_ / "out").size(), 2u);
}

}  // namespace suite_parts_test
}  // namespace ib
