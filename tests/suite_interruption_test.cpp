// A suite interrupted midway and resumed with --resume loses no finished result and ends with the
// same results and report as an uninterrupted one. Through the command, as a user meets it:
//   - Ctrl-C: SIGINT to the whole process group (the suite and its workers), as a terminal sends it;
//   - SIGTERM to the suite alone (a scheduler's stop): it must stop its workers itself;
//   - SIGKILL to the suite alone (no chance to clean up): its workers must not outlive it;
//   - SIGTERM to every process in no particular order, the workers a few milliseconds before the suite,
//     as Slurm and systemd stop a task: a worker stopped from outside is not a finding about its engine;
//   - SIGTERM to one worker alone: the suite goes on, records nothing for that job and says so.
// Each is sent once a few results are recorded. The suite (two short scenarios, two laws, the reference
// and the build's first engine, tests/catalog_engines.h) is compared with an uninterrupted run of the
// same command: the same job ids and every field of runs.jsonl and runs.csv equal except the timing ones
// (ib::timing_field_names()), compared sorted by job id, and every run's series.csv.gz, events.csv and impact.csv.gz
// equal byte for byte. The report is made from nothing else, so one test (Ctrl-C) also makes both reports (it takes
// matplotlib several seconds each) and compares summary.md with its date, its folder and the timing it shows masked
// (the run-time column, and the "at equal run time" line, whose choice depends on measured times). The report sorts its
// runs by job id, so that the order in which jobs finished does not show.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "catalog_engines.h"
#include "harness/records/run_record.h"
#include "process_control.h"
#include "simulators/catalog.h"

namespace suite_interruption_test {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using namespace process_control;

const std::vector<std::string>& kTimingFields = ib::timing_field_names();

std::vector<std::string> suite_arguments(const fs::path& out) {
  std::vector<std::string> args = {IMPACTBENCH_EXECUTABLE,
                                   "suite",
                                   std::string(IMPACTBENCH_TEST_DATA_DIR) + "/report_suite",
                                   "--laws",
                                   "hertz,viscoelastic",
                                   "--jobs",
                                   "2",
                                   "--out",
                                   out.string()};
  const std::vector<std::string> engines = ib::test::engines_among(ib::simulator_names());
  if (!engines.empty())
    for (const std::string& a : {std::string("--engines"), ib::test::engines_option("reference", engines, 1),
                                 std::string("--dt"), std::string("1e-4")})
      args.push_back(a);
  return args;
}

// runs.jsonl as job id -> record without its timing fields.
std::map<std::string, Json> results(const fs::path& out) {
  std::map<std::string, Json> by_id;
  std::ifstream in(out / "runs.jsonl");
  for (std::string line; std::getline(in, line);) {
    Json j = Json::parse(line);
    for (const std::string& f : kTimingFields) j.erase(f);
    const std::string id = j["job_id"];
    EXPECT_EQ(by_id.count(id), 0u) << "recorded twice: " << id;
    by_id[id] = j;
  }
  return by_id;
}

// runs.csv as job id -> row with the timing cells emptied (the header checked equal separately).
std::map<std::string, std::string> csv_results(const fs::path& out, std::string& header) {
  std::ifstream in(out / "runs.csv");
  std::getline(in, header);
  std::vector<std::string> names;
  std::stringstream h(header);
  for (std::string n; std::getline(h, n, ',');) names.push_back(n);
  std::map<std::string, std::string> by_id;
  for (std::string line; std::getline(in, line);) {
    // no quoted commas in these runs (reasons are empty or plain); split plainly
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string c; std::getline(row, c, ',');) cells.push_back(c);
    std::string masked;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const bool timing =
          i < names.size() && std::find(kTimingFields.begin(), kTimingFields.end(), names[i]) != kTimingFields.end();
      masked += (i ? "," : "") + (timing ? std::string("<time>") : cells[i]);
    }
    by_id[cells.empty() ? "" : cells[0]] = masked;
  }
  return by_id;
}

// summary.md with what legitimately differs between two runs of the same suite masked: when and where it
// was made, the commands (the resumed one says --resume), the load, and every CPU cost (the columns headed
// "CPU [...]" and the engines' median costs).
std::string masked_summary(const fs::path& report) {
  std::istringstream in(read_text(report / "summary.md"));
  std::string out;
  std::vector<int> cost_columns;
  const std::regex engine_cost(R"(at [0-9.e+-]+ s CPU/s)");
  // the answer sentences' costs (answer_sentence.py): "at 0.12 s of CPU per simulated second", "(0.13 s/s)"
  const std::regex sentence_cost(R"(at [0-9.e+-]+ s of CPU per simulated second)");
  const std::regex tie_cost(R"(\([0-9.e+-]+ s/s\))");
  for (std::string line; std::getline(in, line);) {
    for (const char* varying : {"- made:", "- suite folder:", "- commands:", "- load average"})
      if (line.rfind(varying, 0) == 0) line = std::string(varying) + " <varies>";
    line = std::regex_replace(line, engine_cost, "at <cost> s CPU/s");
    line = std::regex_replace(line, sentence_cost, "at <cost> s of CPU per simulated second");
    line = std::regex_replace(line, tie_cost, "(<cost> s/s)");
    if (line.rfind("| ", 0) == 0) {
      std::vector<std::string> cells;
      std::size_t at = 0;
      for (std::size_t next; (next = line.find(" | ", at)) != std::string::npos; at = next + 3)
        cells.push_back(line.substr(at, next - at));
      cells.push_back(line.substr(at));
      bool header = false;
      for (std::size_t i = 0; i < cells.size(); ++i)
        if (cells[i].rfind("CPU [", 0) == 0) {
          if (!header) cost_columns.clear();
          header = true;
          cost_columns.push_back(static_cast<int>(i));
        }
      if (!header)
        for (int column : cost_columns)
          if (column < static_cast<int>(cells.size())) cells[column] = "<cost>";
      line.clear();
      for (std::size_t i = 0; i < cells.size(); ++i) line += (i ? " | " : "") + cells[i];
    } else if (line.rfind("|", 0) != 0) {
      cost_columns.clear();
    }
    out += line + "\n";
  }
  return out;
}

class SuiteInterruption : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("impactbench_interruption_" + std::to_string(getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
    // the uninterrupted suite
    baseline_status_ = wait_for(start(suite_arguments(root_ / "whole"), root_ / "whole.log"));
    ASSERT_TRUE(WIFEXITED(baseline_status_)) << read_text(root_ / "whole.log");
    ASSERT_LE(WEXITSTATUS(baseline_status_), 1) << read_text(root_ / "whole.log");
    jobs_ = lines_of(root_ / "whole" / "runs.jsonl");
    ASSERT_GE(jobs_, 6u);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(root_);
  }

  enum class Target { group, suite, workers_then_suite, one_worker };

  // Starts the suite, waits until `recorded` results are in runs.jsonl, sends `signal` to the group, to
  // the suite alone, to its workers and 5 ms later to the suite, or to one worker alone, and returns the
  // suite's exit status.
  int interrupt(int signal, Target target, std::size_t recorded) {
    const pid_t pid = start(suite_arguments(root_ / "cut"), root_ / "cut.log");
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
    while (lines_of(root_ / "cut" / "runs.jsonl") < recorded && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if (target == Target::group || target == Target::suite) {
      kill(target == Target::group ? -pid : pid, signal);
    } else {
      std::vector<pid_t> workers;  // a worker is running from the first job on, but look until one is seen
      if (target == Target::one_worker) {
        const pid_t frozen = freeze_one_child(pid, deadline);
        if (frozen > 0) workers.push_back(frozen);
      } else {
        while ((workers = children_of(pid)).empty() && std::chrono::steady_clock::now() < deadline)
          std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
      EXPECT_FALSE(workers.empty()) << "no worker to signal";
      for (pid_t worker : workers) kill(worker, signal);
      if (target == Target::one_worker)
        for (pid_t worker : workers) kill(worker, SIGCONT);  // the pending signal is delivered as it resumes
      if (target == Target::workers_then_suite) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        kill(pid, signal);
      }
    }
    const int status = wait_for(pid);
    // no worker outlives the suite, whatever stopped it
    for (int i = 0; i < 200 && live_processes_in_group(pid) > 0; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(25));
    EXPECT_EQ(live_processes_in_group(pid), 0) << "a worker outlived the suite";
    return status;
  }

  void resume_and_compare(std::size_t recorded_before, bool compare_reports = true) {
    std::vector<std::string> args = suite_arguments(root_ / "cut");
    args.push_back("--resume");
    const int status = wait_for(start(args, root_ / "resume.log"));
    const std::string log = read_text(root_ / "resume.log");
    ASSERT_TRUE(WIFEXITED(status)) << log;
    EXPECT_EQ(WEXITSTATUS(status), WEXITSTATUS(baseline_status_)) << log;
    EXPECT_NE(log.find("(" + std::to_string(recorded_before) + " skipped as already done)"), std::string::npos) << log;
    // the same job ids and the same results
    const auto whole = results(root_ / "whole"), cut = results(root_ / "cut");
    ASSERT_EQ(cut.size(), whole.size());
    for (const auto& [id, record] : whole) {
      ASSERT_EQ(cut.count(id), 1u) << "missing after resume: " << id;
      EXPECT_EQ(cut.at(id), record) << id;
    }
    std::string whole_header, cut_header;
    EXPECT_EQ(csv_results(root_ / "cut", cut_header), csv_results(root_ / "whole", whole_header));
    EXPECT_EQ(cut_header, whole_header);
    // and the same files of every run (a killed job's half-written folder was replaced by its rerun)
    int series_compared = 0;
    for (const auto& [id, record] : whole)
      for (const char* file : {"series.csv.gz", "events.csv", "impact.csv.gz"}) {
        const fs::path a = root_ / "whole" / "runs" / id / file, b = root_ / "cut" / "runs" / id / file;
        EXPECT_EQ(fs::exists(b), fs::exists(a)) << b;
        if (fs::exists(a)) {
          EXPECT_TRUE(read_text(a) == read_text(b)) << b << " differs from " << a;
          series_compared += std::string(file) == "series.csv.gz";
        }
      }
    EXPECT_GT(series_compared, 0);  // the gzipped series are written the same way every time
    if (!compare_reports) return;
    // the same report
    for (const char* folder : {"whole", "cut"}) {
      const std::string command = std::string(IMPACTBENCH_EXECUTABLE) + " report " + (root_ / folder).string() + " > " +
                                  (root_ / folder).string() + ".report.log 2>&1";
      ASSERT_EQ(std::system(command.c_str()), 0) << read_text((root_ / folder).string() + ".report.log");
    }
    EXPECT_EQ(masked_summary(root_ / "cut" / "report"), masked_summary(root_ / "whole" / "report"));
  }

  fs::path root_;
  int baseline_status_ = 0;
  std::size_t jobs_ = 0;
};

TEST_F(SuiteInterruption, CtrlCKeepsEveryFinishedResultAndSaysHowToResume) {
  const int status = interrupt(SIGINT, Target::group, 3);
  const std::string log = read_text(root_ / "cut.log");
  ASSERT_TRUE(WIFEXITED(status)) << log;
  EXPECT_EQ(WEXITSTATUS(status), 130) << log;
  const std::size_t recorded = lines_of(root_ / "cut" / "runs.jsonl");
  EXPECT_GE(recorded, 3u);
  EXPECT_LT(recorded, jobs_) << "the suite finished before the interruption: the test proves nothing";
  EXPECT_EQ(lines_of(root_ / "cut" / "runs.csv"), recorded + 1);
  const std::string message = "impactbench: interrupted after " + std::to_string(recorded) + " of " +
                              std::to_string(jobs_) + " jobs; continue with: impactbench suite ";
  EXPECT_NE(log.find(message), std::string::npos) << log;
  EXPECT_NE(log.find(" --resume\n"), std::string::npos) << log;
  EXPECT_EQ(log.find("failed"), std::string::npos) << "a worker stopped by Ctrl-C was recorded as failed:\n" << log;
  resume_and_compare(recorded);
}

TEST_F(SuiteInterruption, SigtermToTheSuiteAloneStopsItsWorkers) {
  const int status = interrupt(SIGTERM, Target::suite, 2);
  const std::string log = read_text(root_ / "cut.log");
  ASSERT_TRUE(WIFEXITED(status)) << log;
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM) << log;
  const std::size_t recorded = lines_of(root_ / "cut" / "runs.jsonl");
  EXPECT_LT(recorded, jobs_) << "the suite finished before the interruption: the test proves nothing";
  EXPECT_NE(log.find("interrupted after " + std::to_string(recorded) + " of " + std::to_string(jobs_) + " jobs"),
            std::string::npos)
      << log;
  resume_and_compare(recorded, /*compare_reports=*/false);  // results and run files equal: so is the report
}

TEST_F(SuiteInterruption, SigkillLosesNoFinishedResult) {
  const int status = interrupt(SIGKILL, Target::suite, 3);
  ASSERT_TRUE(WIFSIGNALED(status));
  const std::size_t recorded = lines_of(root_ / "cut" / "runs.jsonl");
  EXPECT_GE(recorded, 3u);
  EXPECT_LT(recorded, jobs_) << "the suite finished before the kill: the test proves nothing";
  resume_and_compare(recorded, /*compare_reports=*/false);  // results and run files equal: so is the report
}

// Slurm's way: every process of the task gets SIGTERM, the workers first. A job stopped that way decided
// nothing about its engine: --resume runs it, and the results equal an uninterrupted run (this failed 4
// times in 5 before the suite told a signal from outside from a crash).
TEST_F(SuiteInterruption, StaggeredSigtermWorkersFirstLosesNoJob) {
  const int status = interrupt(SIGTERM, Target::workers_then_suite, 2);
  const std::string log = read_text(root_ / "cut.log");
  ASSERT_TRUE(WIFEXITED(status)) << log;
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM) << log;
  EXPECT_EQ(read_text(root_ / "cut" / "runs.jsonl").find("died of signal"), std::string::npos)
      << "a worker stopped from outside was recorded as failed:\n"
      << read_text(root_ / "cut" / "runs.jsonl");
  const std::size_t recorded = lines_of(root_ / "cut" / "runs.jsonl");
  EXPECT_LT(recorded, jobs_) << "the suite finished before the signals: the test proves nothing";
  resume_and_compare(recorded, /*compare_reports=*/false);
}

// One worker stopped from outside (a person, the OOM killer) while the suite goes on: that job is not
// recorded, the suite ends with the signal's exit code and says how to run it, and --resume does.
TEST_F(SuiteInterruption, OneWorkerStoppedFromOutsideIsRunAgainOnResume) {
  const int status = interrupt(SIGTERM, Target::one_worker, 1);
  const std::string log = read_text(root_ / "cut.log");
  ASSERT_TRUE(WIFEXITED(status)) << log;
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM) << log;
  EXPECT_NE(log.find("stopped by signal 15 from outside"), std::string::npos) << log;
  EXPECT_NE(log.find("; run them with: impactbench suite "), std::string::npos) << log;
  const std::size_t recorded = lines_of(root_ / "cut" / "runs.jsonl");
  EXPECT_LT(recorded, jobs_) << log;  // the job stopped, and the jobs compared with it if it was a reference
  resume_and_compare(recorded, /*compare_reports=*/false);
}

}  // namespace suite_interruption_test
