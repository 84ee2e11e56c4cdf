// A suite's folder holds one record per job, of one suite's settings, written by one process at a time:
//   - --resume refuses other result-deciding settings (naming them) unless --extend, and --extend refuses
//     a job the folder recorded under other settings;
//   - a second suite on a folder in use is refused; a dead holder does not hold it;
//   - damaged records (a job twice, the same or not, a value of the wrong type, a run folder gone, runs.jsonl
//     gone) are repaired or refused, and what was done is said;
//   - a malformed scenario is recorded once, and its row goes when the file is fixed;
//   - two scenario files with one name are refused; two unreadable files with one stem get two job ids;
//   - a resumed suite's outcome covers every result in the folder.
#include "catalog_engines.h"
#include "harness/records/folder_lock.h"
#include "harness/records/reporters.h"
#include "harness/suite/suite.h"
#include "simulators/catalog.h"
#include "suite_test_support.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace ib {
namespace suite_records_test {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::map<std::string, int> records_per_job(const fs::path& out) {
  std::map<std::string, int> count;
  for (const auto& j : test::json_lines(out / "runs.jsonl")) ++count[j["job_id"].get<std::string>()];
  return count;
}

class SuiteRecords : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = test::fresh_test_folder("impactbench_records_");
    test::write_short_free_vibration(root_ / "scenarios");
    settings_.inputs = {(root_ / "scenarios").string()};
    settings_.out = (root_ / "out").string();
    settings_.laws = {ContactLaw::hertz};
    settings_.jobs = 2;
    settings_.simulators = simulator_catalog();
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(root_);
  }
  fs::path out() const { return settings_.out; }
  fs::path root_;
  SuiteSettings settings_;
};

TEST_F(SuiteRecords, ResumeRefusesOtherSettingsNamingThem) {
  run_suite(settings_);
  settings_.resume = true;
  settings_.max_duration_s = 0.2;  // another --duration
  try {
    run_suite(settings_);
    FAIL() << "a resume with another --duration was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("max_duration_s differ"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--extend"), std::string::npos) << e.what();
  }
  settings_.max_duration_s = 0;
  settings_.laws = {ContactLaw::hertz, ContactLaw::viscoelastic};  // another --laws
  try {
    run_suite(settings_);
    FAIL() << "a resume with other --laws was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("laws differ"), std::string::npos) << e.what();
  }
  settings_.output_rate_hz = 2048;  // and another --rate: both named
  try {
    run_suite(settings_);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("laws, output_rate_hz differ"), std::string::npos) << e.what();
  }
  EXPECT_EQ(test::line_count(out() / "runs.jsonl"), 1u);  // nothing ran
}

TEST_F(SuiteRecords, ExtendAddsJobsButNeverMixesSettings) {
  run_suite(settings_);
  // another law: new jobs, the folder's reference of Hertz untouched
  settings_.extend = true;
  settings_.laws = {ContactLaw::viscoelastic};
  const SuiteOutcome added = run_suite(settings_);
  EXPECT_EQ(added.jobs_run, 1);
  EXPECT_EQ(test::line_count(out() / "suite.jsonl"), 2u);
  // Hertz again at another duration shares a recorded job run at the first duration: refused
  settings_.laws = {ContactLaw::hertz};
  settings_.max_duration_s = 0.2;
  try {
    run_suite(settings_);
    FAIL() << "--extend mixed two durations in one job's record";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(
        std::string(e.what()).find("job short_free/reference/hertz was recorded with other settings (max_duration_s"),
        std::string::npos)
        << e.what();
  }
  // what a run keeps of its series is not a result (a reference keeps its window whatever --series says):
  // a study's part without series shares the references of one with them
  settings_.max_duration_s = 0;
  settings_.measurement.series = SeriesOutput::none;
  EXPECT_EQ(run_suite(settings_).jobs_run, 0);
  settings_.measurement.series = SeriesOutput::window;
  // a resume of either suite is the same suite again: nothing runs
  settings_.extend = false;
  settings_.resume = true;
  settings_.max_duration_s = 0;
  EXPECT_EQ(run_suite(settings_).jobs_run, 0);
  settings_.laws = {ContactLaw::viscoelastic};
  EXPECT_EQ(run_suite(settings_).jobs_run, 0);
}

TEST_F(SuiteRecords, AnEditedScenarioFileIsNotResumedAsTheSameSuite) {
  run_suite(settings_);
  std::ofstream(root_ / "scenarios" / "short_free.toml", std::ios::app) << "\n# edited\n";
  settings_.resume = true;
  EXPECT_THROW(run_suite(settings_), std::invalid_argument);
  settings_.extend = true;
  try {
    run_suite(settings_);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("short_free.toml (changed since)"), std::string::npos) << e.what();
  }
}

TEST_F(SuiteRecords, AFolderInUseIsRefusedAndADeadHolderHoldsNothing) {
  fs::create_directories(out());
  {
    const FolderLock held(out().string(), "test");
    try {
      run_suite(settings_);
      FAIL() << "a second suite ran in a folder in use";
    } catch (const FolderBusy& e) {
      EXPECT_NE(std::string(e.what()).find("another impactbench command is writing into this folder (test, process " +
                                           std::to_string(getpid())),
                std::string::npos)
          << e.what();
    }
  }
  // a holder killed with SIGKILL
  const pid_t child = fork();
  if (child == 0) {
    const FolderLock held(out().string(), "doomed");
    pause();
    _exit(0);
  }
  for (int i = 0; i < 200 && read_text(out() / ".impactbench.lock").find("doomed") == std::string::npos; ++i)
    usleep(10000);
  EXPECT_THROW(run_suite(settings_), FolderBusy);
  kill(child, SIGKILL);
  waitpid(child, nullptr, 0);
  EXPECT_EQ(run_suite(settings_).jobs_run, 1);
}

TEST_F(SuiteRecords, DamagedRecordsAreRepairedOnePerJobAndSaidSo) {
  settings_.engines = {"reference"};
  const std::vector<std::string> engines = test::engines_among(simulator_names());
  if (!engines.empty()) settings_.engines.push_back(engines.front());  // any engine: the records are the harness's
  settings_.time_steps_s = {1e-4};
  run_suite(settings_);
  const auto whole = records_per_job(out());
  ASSERT_GE(whole.size(), 1u);
  const std::string jsonl = read_text(out() / "runs.jsonl");
  const std::string first_line = jsonl.substr(0, jsonl.find('\n') + 1);
  const std::string first_id = nlohmann::json::parse(first_line)["job_id"];
  // the first record twice, the same: kept once, nothing runs
  std::ofstream(out() / "runs.jsonl", std::ios::app) << first_line;
  std::vector<std::string> repairs;
  EXPECT_EQ(repair_and_list_runs(out().string(), &repairs).size(), whole.size());
  ASSERT_EQ(repairs.size(), 1u);
  EXPECT_NE(repairs[0].find(first_id + " recorded again, the same; kept once"), std::string::npos) << repairs[0];
  EXPECT_EQ(records_per_job(out()), whole);
  // again with another value: both lines dropped, the job runs again
  std::string other = first_line;
  other.replace(other.find("\"verdict\":\"ok\""), 14, "\"verdict\":\"unstable\"");
  std::ofstream(out() / "runs.jsonl", std::ios::app) << other;
  settings_.resume = true;
  SuiteOutcome resumed = run_suite(settings_);
  EXPECT_EQ(resumed.jobs_run, 1);
  EXPECT_EQ(records_per_job(out()), whole);
  // a value of the wrong type: dropped and run again
  std::string text = read_text(out() / "runs.jsonl");
  const auto at = text.find("\"duration_s\":");
  ASSERT_NE(at, std::string::npos);
  text.insert(at + 13, "\"long\",\"x\":");
  std::ofstream(out() / "runs.jsonl", std::ios::trunc) << text;
  repairs.clear();
  repair_and_list_runs(out().string(), &repairs);
  ASSERT_EQ(repairs.size(), 1u);
  EXPECT_NE(repairs[0].find("duration_s is \"long\", expected a number"), std::string::npos) << repairs[0];
  // a run folder gone: its record dropped and the job run again
  const std::string last = std::prev(whole.end())->first;
  fs::remove_all(out() / "runs" / last);
  resumed = run_suite(settings_);
  EXPECT_GE(resumed.jobs_run, 1);
  EXPECT_EQ(records_per_job(out()), whole);
  EXPECT_TRUE(fs::exists(out() / "runs" / last / "summary.json"));
  // runs.jsonl gone, runs.csv kept: refused rather than run everything into runs.csv again
  fs::remove(out() / "runs.jsonl");
  try {
    run_suite(settings_);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("runs.jsonl: missing, but"), std::string::npos) << e.what();
  }
}

TEST_F(SuiteRecords, AMalformedScenarioIsRecordedOnceAndGoesWhenFixed) {
  const fs::path broken = root_ / "scenarios" / "broken.toml";
  std::ofstream(broken) << "[scenario]\nname = \"broken\"\ncolour = \"red\"\n";
  const SuiteOutcome first = run_suite(settings_);
  EXPECT_EQ(first.not_ok_recorded, 1);
  settings_.resume = true;
  const SuiteOutcome again = run_suite(settings_);
  EXPECT_EQ(again.jobs_run, 0);
  EXPECT_EQ(again.not_ok_recorded, 1);  // the resumed suite's outcome covers every result
  EXPECT_EQ(records_per_job(out())["broken/unreadable"], 1);
  // fixed: a copy of the good one under another name
  std::string text = read_text(root_ / "scenarios" / "short_free.toml");
  text.replace(text.find("name = \"short_free\""), 19, "name = \"fixed\"");
  std::ofstream(broken, std::ios::trunc) << text;
  const SuiteOutcome fixed = run_suite(settings_);
  EXPECT_EQ(fixed.jobs_run, 1);
  const auto records = records_per_job(out());
  EXPECT_EQ(records.count("broken/unreadable"), 0u);
  EXPECT_EQ(records.count("fixed/reference/hertz"), 1u);
  EXPECT_EQ(fixed.not_ok_recorded, 0);
}

TEST_F(SuiteRecords, TwoScenariosWithOneNameAreRefusedNamingBothFiles) {
  fs::create_directories(root_ / "more");
  fs::copy_file(root_ / "scenarios" / "short_free.toml", root_ / "more" / "copy.toml");
  settings_.inputs.push_back((root_ / "more").string());
  try {
    run_suite(settings_);
    FAIL() << "one of two scenarios named alike was dropped silently";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("copy.toml: [scenario] name = \"short_free\" is also the name of "), std::string::npos) << what;
    EXPECT_NE(what.find("short_free.toml"), std::string::npos) << what;
  }
  // the same file reached twice (its folder and itself) is one scenario
  settings_.inputs = {(root_ / "scenarios").string(), (root_ / "scenarios" / "short_free.toml").string()};
  EXPECT_EQ(run_suite(settings_).jobs_run, 1);
}

TEST_F(SuiteRecords, UnreadableFilesGetAJobIdEachThatFitsAFileName) {
  for (const char* folder : {"a", "b"}) {
    fs::create_directories(root_ / "scenarios" / folder);
    std::ofstream(root_ / "scenarios" / folder / "bad.toml") << "[scenario\n";
  }
  const std::string long_name(300, 'x');
  std::ofstream(root_ / "scenarios" / "long.toml") << "[scenario]\nname = \"" << long_name << "\"\n";
  const SuiteOutcome outcome = run_suite(settings_);
  const auto records = records_per_job(out());
  EXPECT_EQ(records.size(), 4u);  // short_free, two bad.toml, long.toml
  int bad = 0;
  for (const auto& [id, n] : records) {
    EXPECT_EQ(n, 1) << id;
    for (const auto& part : fs::path(id)) EXPECT_LE(part.string().size(), 80u) << id;
    bad += id.rfind("bad-", 0) == 0 ? 1 : 0;
  }
  EXPECT_EQ(bad, 2);
  EXPECT_EQ(outcome.not_ok_recorded, 3);
  const std::string jsonl = read_text(out() / "runs.jsonl");
  EXPECT_NE(jsonl.find("scenario.name"), std::string::npos) << "the long name's reason names the key";
  EXPECT_NE(jsonl.find("1 to 64 characters"), std::string::npos) << jsonl;
}

}  // namespace suite_records_test
}  // namespace ib
