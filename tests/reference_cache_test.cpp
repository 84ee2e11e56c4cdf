// References shared between output folders (--reference-cache): a second folder copies the references it
// has in common with the first instead of solving them, and records exactly what solving them records; an
// entry is checked by the scenario's content, never by its name; a damaged entry is a miss.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "harness/suite/suite.h"
#include "simulators/catalog.h"
#include "suite_test_support.h"

namespace ib {
namespace reference_cache_test {

namespace fs = std::filesystem;

class ReferenceCache : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = test::fresh_test_folder("impactbench_cache_");
    test::write_short_free_vibration(root_ / "scenarios");
    settings_.inputs = {(root_ / "scenarios").string()};
    settings_.engines = {"reference"};
    settings_.laws = {ContactLaw::hertz, ContactLaw::newton};
    settings_.jobs = 2;
    settings_.simulators = simulator_catalog();
    settings_.reference_cache = (root_ / "cache").string();
  }
  void TearDown() override { fs::remove_all(root_); }

  SuiteOutcome run_into(const std::string& name) {
    SuiteSettings s = settings_;
    s.out = (root_ / name).string();
    return run_suite(s);
  }
  // job id -> its runs.jsonl line
  std::map<std::string, nlohmann::json> rows(const std::string& name) const {
    std::map<std::string, nlohmann::json> out;
    for (const auto& line : test::json_lines(root_ / name / "runs.jsonl")) out[line["job_id"]] = line;
    return out;
  }

  fs::path root_;
  SuiteSettings settings_;
};

TEST_F(ReferenceCache, ASecondFolderCopiesTheReferencesAndRecordsWhatSolvingThemRecorded) {
  const SuiteOutcome first = run_into("first");
  EXPECT_EQ(first.references_from_cache, 0);
  const SuiteOutcome second = run_into("second");
  EXPECT_EQ(second.references_from_cache, 2);
  EXPECT_EQ(second.jobs_run, 2);
  EXPECT_EQ(rows("first"), rows("second"));  // costs included: they are the cached run's, as its log says
  std::ifstream log(root_ / "second" / "runs" / "short_free" / "reference" / "hertz" / "log.txt");
  const std::string text((std::istreambuf_iterator<char>(log)), {});
  EXPECT_NE(text.find("restored from the reference cache"), std::string::npos) << text;
  EXPECT_TRUE(fs::exists(root_ / "second" / "runs" / "short_free" / "reference" / "hertz" / "series.csv.gz"));
}

TEST_F(ReferenceCache, AScenarioOfTheSameNameButOtherContentIsSolvedAgain) {
  run_into("first");
  // the same file, its name kept, its stiffness changed
  const fs::path file = root_ / "scenarios" / "short_free.toml";
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  in.close();
  const auto at = text.find("stiffness");
  ASSERT_NE(at, std::string::npos);
  const auto eq = text.find('=', at), end = text.find('\n', eq);
  const double stiffness = std::stod(text.substr(eq + 1, end - eq - 1));
  text.replace(eq + 1, end - eq - 1, " " + std::to_string(stiffness * 2));
  std::ofstream(file) << text;
  const SuiteOutcome second = run_into("second");
  EXPECT_EQ(second.references_from_cache, 0);
  EXPECT_NE(rows("first").at("short_free/reference/hertz")["contact_duration_mean_s"],
            rows("second").at("short_free/reference/hertz")["contact_duration_mean_s"]);
}

TEST_F(ReferenceCache, ADamagedEntryIsAMissAndOtherSettingsAreOtherEntries) {
  run_into("first");
  for (const auto& entry : fs::directory_iterator(root_ / "cache")) std::ofstream(entry.path() / "key.json") << "{";
  EXPECT_EQ(run_into("second").references_from_cache, 0);
  settings_.output_rate_hz = 2048;  // result-deciding: a key of its own
  EXPECT_EQ(run_into("third").references_from_cache, 0);
  EXPECT_EQ(run_into("fourth").references_from_cache, 2);
}

}  // namespace reference_cache_test
}  // namespace ib
