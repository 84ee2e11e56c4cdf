// A result that cannot be written (a full disk, an unwritable folder, a path under a file) is a clear
// error naming the file, the OS's reason and what to do; a suite stops with exit code 3 and keeps what
// it had recorded. A full disk is /dev/full behind a symlink (its writes fail with ENOSPC, even for
// root); a path under a file gives ENOTDIR; a folder without write permission (EACCES) only when not
// running as root, whom chmod does not stop.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "command_test_support.h"
#include "harness/records/reporters.h"
#include "harness/records/run_files.h"
#include "harness/records/run_record.h"
#include "harness/suite/suite.h"
#include "reference/reference_simulator.h"
#include "simulators/catalog.h"
#include "suite_test_support.h"

namespace ib {
namespace output_errors_test {

namespace fs = std::filesystem;

const std::string kFullDiskReason = "No space left on device";

class OutputErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("impactbench_output_errors_" + std::to_string(getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override {
    fs::permissions(root_, fs::perms::owner_all, fs::perm_options::add);
    fs::remove_all(root_);
  }
  // A file whose writes fail as on a full disk.
  std::string full_disk_file(const std::string& name) {
    const fs::path link = root_ / name;
    fs::create_symlink("/dev/full", link);
    return link.string();
  }
  std::string under_a_file(const std::string& name) {
    std::ofstream(root_ / "a_file") << "not a folder";
    return (root_ / "a_file" / name).string();
  }
  fs::path root_;
};

// The message of the OutputError `write` throws; a failed test if it throws none.
template <class Write>
std::string output_error(Write write) {
  try {
    write();
  } catch (const OutputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no OutputError thrown";
  return "";
}

Trajectory two_samples() {
  Trajectory t;
  for (int k = 0; k < 2; ++k) {
    t.time_s.push_back(k * 1e-3);
    for (int f = 0; f < 2; ++f) {
      t.displacement_m[f].push_back(0);
      t.velocity_m_s[f].push_back(0);
      t.acceleration_m_s2[f].push_back(0);
      t.peak_abs_acceleration_m_s2[f].push_back(0);
    }
    t.contact_force_n.push_back(0);
    t.peak_contact_force_n.push_back(0);
  }
  t.events.push_back(ContactEvent{});
  return t;
}

RunRecord a_record() {
  RunRecord r;
  r.job_id = "s/reference/hertz";
  r.scenario = "s";
  r.engine = "reference";
  r.law = "hertz";
  return r;
}

TEST_F(OutputErrors, AFullDiskUnderARunsFilesNamesTheFileTheReasonAndWhatToDo) {
  for (const std::string name : {"series.csv.gz", "series.csv", "events.csv", "summary.json"}) {
    const std::string path = full_disk_file(name);
    const std::string message = output_error([&] {
      if (name.rfind("series.csv", 0) == 0) write_series_csv(path, two_samples());
      if (name == "events.csv") write_events_csv(path, two_samples());
      if (name == "summary.json") write_summary_json(path, a_record());
    });
    EXPECT_EQ(message.rfind(path + ": cannot write: " + kFullDiskReason, 0), 0u) << message;
    EXPECT_NE(message.find("free space on that disk"), std::string::npos) << message;
  }
}

TEST_F(OutputErrors, AFullDiskUnderTheSuitesTablesNamesTheTable) {
  full_disk_file("runs.jsonl");
  std::string message = output_error([&] { append_run(root_.string(), a_record()); });
  EXPECT_EQ(message.rfind((root_ / "runs.jsonl").string() + ": cannot append to: " + kFullDiskReason, 0), 0u)
      << message;
  fs::remove(root_ / "runs.jsonl");
  full_disk_file("runs.csv");
  message = output_error([&] { append_run(root_.string(), a_record()); });
  EXPECT_EQ(message.rfind((root_ / "runs.csv").string() + ": cannot append to: " + kFullDiskReason, 0), 0u) << message;
}

TEST_F(OutputErrors, APathUnderAFileSaysThatAPartOfItIsAFile) {
  const std::string path = under_a_file("series.csv");
  const std::string message = output_error([&] { write_series_csv(path, two_samples()); });
  EXPECT_EQ(message.rfind(path + ": cannot create: Not a directory", 0), 0u) << message;
  EXPECT_NE(message.find("a part of the path is a file"), std::string::npos) << message;
}

TEST_F(OutputErrors, AFolderWithoutWritePermissionSaysSo) {
  if (geteuid() == 0)
    GTEST_SKIP() << "running as root: chmod 0555 does not stop root's writes; the full-disk (/dev/full) and "
                    "path-under-a-file (ENOTDIR) tests cover the same error path";
  fs::permissions(root_, fs::perms::owner_read | fs::perms::owner_exec);
  const std::string path = (root_ / "series.csv").string();
  const std::string message = output_error([&] { write_series_csv(path, two_samples()); });
  EXPECT_EQ(message.rfind(path + ": cannot create: Permission denied", 0), 0u) << message;
  EXPECT_NE(message.find("make the folder writable"), std::string::npos) << message;
}

// ---- The suite: a write error stops it with the message, and what was recorded stays.

// Runs the reference, after pointing its job's series.csv at /dev/full: a job's own files fail inside
// the job's process, and the message must reach the suite.
std::string g_full_series;  // the path to break; set by the test, inherited by the job's process
class FillsTheDisk final : public Simulator {
 public:
  std::string name() const override { return "fills_the_disk"; }
  std::string version() const override { return "test"; }
  std::vector<std::pair<std::string, std::string>> option_help() const override { return {}; }
  RunResult run(const Scenario& s, const RunSettings& settings) override {
    fs::create_symlink("/dev/full", g_full_series);
    RunSettings reference = settings;
    reference.options.clear();
    reference.time_step_s = 0;
    return make_reference_simulator()->run(s, reference);
  }
};

std::unique_ptr<Simulator> factory(const std::string& name) {
  if (name == "fills_the_disk") return std::make_unique<FillsTheDisk>();
  return make_simulator(name);
}

SuiteSettings short_suite(const fs::path& out) {
  SuiteSettings s;
  s.inputs = {std::string(IMPACTBENCH_TEST_DATA_DIR) + "/report_suite/short_free_vibration.toml"};
  s.laws = {ContactLaw::hertz};
  s.out = out.string();
  s.jobs = 1;
  s.simulators = simulator_catalog();
  s.simulators.make = factory;
  return s;
}

TEST_F(OutputErrors, AJobsFilesOnAFullDiskStopTheSuiteWithTheirNameAndKeepWhatWasRecorded) {
  SuiteSettings s = short_suite(root_ / "out");
  s.engines = {"reference", "fills_the_disk"};
  g_full_series = s.out + "/runs/short_free_vibration/fills_the_disk/hertz/series.csv.gz";
  const std::string message = output_error([&] { run_suite(s); });
  EXPECT_EQ(message.rfind(g_full_series + ": cannot write: " + kFullDiskReason, 0), 0u) << message;
  EXPECT_EQ(test::line_count(root_ / "out" / "runs.jsonl"), 1u);  // the reference, recorded before, is kept
  EXPECT_EQ(test::line_count(root_ / "out" / "runs.csv"), 2u);
}

TEST_F(OutputErrors, ARunsFolderThatCannotBeMadeStopsTheSuite) {
  SuiteSettings s = short_suite(root_ / "out");
  fs::create_directories(root_ / "out");
  std::ofstream(root_ / "out" / "runs") << "a file where the run folders go";
  const std::string message = output_error([&] { run_suite(s); });
  EXPECT_EQ(message.rfind(s.out + "/runs: cannot create the run folders' folder", 0), 0u) << message;
  EXPECT_FALSE(fs::exists(root_ / "out" / "runs.jsonl")) << "stopped before anything ran";
}

// ---- The command: exit code 3 and the message on stderr.

using Output = test::CommandOutput;

Output impactbench(const std::string& arguments, const fs::path& log) { return test::run_impactbench(arguments, log); }

TEST_F(OutputErrors, TheSuiteCommandExitsWith3AndResumesOnceThereIsRoom) {
  const fs::path out = root_ / "out";
  fs::create_directories(out);
  fs::create_symlink("/dev/full", out / "runs.csv");
  const std::string arguments = "suite " + std::string(IMPACTBENCH_TEST_DATA_DIR) +
                                "/report_suite/short_free_vibration.toml --laws hertz,newton --jobs 1 --out " +
                                out.string();
  const Output full = impactbench(arguments, root_ / "log.txt");
  EXPECT_EQ(full.exit_code, 3) << full.text;
  EXPECT_NE(full.text.find(
                "impactbench: " + (out / "runs.csv").string() + ": cannot append to: " + kFullDiskReason +
                "; free space on that disk (or choose another output folder), then continue the suite with --resume"),
            std::string::npos)
      << full.text;
  EXPECT_EQ(test::line_count(out / "runs.jsonl"),
            1u);  // the first result is in runs.jsonl, the record of what finished
  // room again: --resume rebuilds runs.csv from runs.jsonl and runs the rest
  fs::remove(out / "runs.csv");
  const Output resumed = impactbench(arguments + " --resume", root_ / "log.txt");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.text;
  EXPECT_NE(resumed.text.find("1 runs recorded"), std::string::npos) << resumed.text;
  EXPECT_NE(resumed.text.find("(1 skipped as already done)"), std::string::npos) << resumed.text;
  EXPECT_EQ(test::line_count(out / "runs.jsonl"), 2u);
  EXPECT_EQ(test::line_count(out / "runs.csv"), 3u);
}

TEST_F(OutputErrors, TheRunAndExportCommandsExitWith3) {
  const std::string scenario = std::string(IMPACTBENCH_TEST_DATA_DIR) + "/report_suite/short_free_vibration.toml";
  const std::string folder = under_a_file("out");
  const Output run = impactbench("run " + scenario + " --out " + folder, root_ / "log.txt");
  EXPECT_EQ(run.exit_code, 3) << run.text;
  EXPECT_NE(run.text.find(folder + ": cannot create the run folder: Not a directory"), std::string::npos) << run.text;
  // the reference's model (its modal model as JSON): in every build, and written as an engine's is
  const std::string model = full_disk_file("model.json");
  const Output exported = impactbench("export " + scenario + " --engine reference --out " + model, root_ / "log.txt");
  EXPECT_EQ(exported.exit_code, 3) << exported.text;
  EXPECT_NE(exported.text.find(model + ": cannot write: " + kFullDiskReason), std::string::npos) << exported.text;
}

TEST_F(OutputErrors, TheReportCommandSaysItsFolderCannotBeMade) {
  fs::create_directories(root_ / "suite");
  std::ofstream(root_ / "suite" / "runs.csv") << "job_id\n";
  const std::string folder = under_a_file("report");
  const Output report = impactbench("report " + (root_ / "suite").string() + " --out " + folder, root_ / "log.txt");
  EXPECT_EQ(report.exit_code, 3) << report.text;
  EXPECT_NE(report.text.find(folder + ": cannot create the report folder: Not a directory"), std::string::npos)
      << report.text;
}

}  // namespace output_errors_test
}  // namespace ib
