// The suite runner with engines that misbehave on purpose: a job that aborts or hangs is recorded
// with its reason and the suite finishes; --resume repeats no finished job; a malformed scenario in a
// folder fails that scenario alone; the reference of each scenario and law runs once.
#include "harness/suite/suite.h"
#include "simulators/catalog.h"
#include "suite_test_support.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "harness/records/reporters.h"
#include "mirror_simulator.h"

namespace ib {
namespace suite_runner_test {

namespace fs = std::filesystem;

using test::Mirror;

// Dies inside its library, as ODE does on an internal error.
class Aborter final : public Simulator {
 public:
  std::string name() const override { return "aborter"; }
  std::string version() const override { return "test"; }
  std::vector<std::pair<std::string, std::string>> option_help() const override { return {}; }
  RunResult run(const Scenario&, const RunSettings&) override {
    std::fprintf(stderr, "aborter: internal error, giving up\n");
    std::abort();
  }
};

// Never returns.
class Hanger final : public Simulator {
 public:
  std::string name() const override { return "hanger"; }
  std::string version() const override { return "test"; }
  std::vector<std::pair<std::string, std::string>> option_help() const override { return {}; }
  RunResult run(const Scenario&, const RunSettings&) override {
    for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
  }
};

std::unique_ptr<Simulator> test_factory(const std::string& name) {
  if (name == "mirror") return std::make_unique<Mirror>();
  if (name == "aborter") return std::make_unique<Aborter>();
  if (name == "hanger") return std::make_unique<Hanger>();
  return make_simulator(name);
}

struct Row {
  std::string job_id, engine, law, verdict, reason;
  nlohmann::json json;
};

std::vector<Row> rows(const std::string& folder) {
  std::vector<Row> out;
  std::ifstream in(folder + "/runs.jsonl");
  for (std::string line; std::getline(in, line);) {
    const auto j = nlohmann::json::parse(line);
    out.push_back({j["job_id"], j["engine"], j["law"], j["verdict"], j["reason"], j});
  }
  return out;
}

const Row* find(const std::vector<Row>& rows, const std::string& job_id) {
  for (const Row& r : rows)
    if (r.job_id == job_id) return &r;
  return nullptr;
}

class SuiteRunner : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = test::fresh_test_folder("impactbench_suite_");
    test::write_short_free_vibration(root_ / "scenarios");
    settings_.inputs = {(root_ / "scenarios").string()};
    settings_.out = (root_ / "out").string();
    settings_.laws = {ContactLaw::hertz};
    settings_.jobs = 2;
    settings_.time_limit_s = 3;
    settings_.simulators = simulator_catalog();
    settings_.simulators.make = test_factory;
  }
  void TearDown() override { fs::remove_all(root_); }
  fs::path root_;
  SuiteSettings settings_;
};

TEST_F(SuiteRunner, AbortingAndHangingJobsAreRecordedAndTheSuiteFinishes) {
  settings_.engines = {"mirror", "aborter", "hanger"};
  const SuiteOutcome outcome = run_suite(settings_);
  const auto all = rows(settings_.out);
  ASSERT_EQ(all.size(), 5u);  // beam reference, chain reference, three engines
  EXPECT_EQ(outcome.jobs_run, 5);
  EXPECT_EQ(outcome.not_ok, 2);
  const Row* aborted = find(all, "short_free/aborter/hertz");
  ASSERT_TRUE(aborted);
  EXPECT_EQ(aborted->verdict, "failed");
  EXPECT_NE(aborted->reason.find("signal 6"), std::string::npos) << aborted->reason;
  EXPECT_NE(aborted->reason.find("aborter: internal error, giving up"), std::string::npos) << aborted->reason;
  const Row* hung = find(all, "short_free/hanger/hertz");
  ASSERT_TRUE(hung);
  EXPECT_EQ(hung->verdict, "failed");
  EXPECT_NE(hung->reason.find("time limit of 3 s"), std::string::npos) << hung->reason;
  // the mirror agrees with the reference on its own chain (to the 9 digits its saved series holds: the
  // suite reads a reference back from its files), and differs from the beam's by the 4-link
  // discretisation; its verdict is judged on its own chain
  const Row* mirror = find(all, "short_free/mirror/hertz");
  ASSERT_TRUE(mirror);
  EXPECT_EQ(mirror->verdict, "ok") << mirror->reason;
  EXPECT_LT(std::abs(mirror->json["vs_chain_reference_frame1_sensor_peak_relative_error"].get<double>()), 1e-8);
  EXPECT_LT(mirror->json["vs_chain_reference_frame1_displacement_relative_rms_error"].get<double>(), 1e-8);
  EXPECT_GT(mirror->json["vs_reference_frame1_displacement_relative_rms_error"].get<double>(), 1e-3);
  EXPECT_EQ(mirror->json["chain_links"].get<double>(), 4);
  EXPECT_TRUE(find(all, "short_free/reference/hertz/links=4;modes=chain"));
  // per-run files
  EXPECT_TRUE(fs::exists(fs::path(settings_.out) / "runs/short_free/mirror/hertz/series.csv.gz"));
  EXPECT_TRUE(fs::exists(fs::path(settings_.out) / "runs/short_free/aborter/hertz/log.txt"));
  // runs.csv has the header and one row per run
  std::ifstream csv(settings_.out + "/runs.csv");
  int lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  EXPECT_EQ(lines, 6);
}

TEST_F(SuiteRunner, ResumeRepeatsNoFinishedJob) {
  settings_.engines = {"reference", "mirror"};
  settings_.time_steps_s = {1e-4, 2e-4};
  SuiteOutcome first = run_suite(settings_);
  EXPECT_EQ(first.jobs_run, 4);  // the reference once, its 4-link chain once, the mirror at two steps
  const std::string before = [&] {
    std::ifstream in(settings_.out + "/runs.jsonl");
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }();
  // without --resume an existing suite is not overwritten
  EXPECT_THROW(run_suite(settings_), std::invalid_argument);
  settings_.resume = true;
  SuiteOutcome again = run_suite(settings_);
  EXPECT_EQ(again.jobs_run, 0);
  EXPECT_EQ(again.jobs_skipped, 4);
  const auto after = rows(settings_.out);
  EXPECT_EQ(after.size(), 4u);
  // a kill that cut the last line short: that job, and only it, runs again
  {
    std::string cut = before.substr(0, before.size() - 40);
    std::ofstream(settings_.out + "/runs.jsonl", std::ios::trunc) << cut;
  }
  SuiteOutcome repaired = run_suite(settings_);
  EXPECT_EQ(repaired.jobs_run, 1);
  EXPECT_EQ(rows(settings_.out).size(), 4u);
  std::ifstream csv(settings_.out + "/runs.csv");
  int lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  EXPECT_EQ(lines, 5);  // header + 4: runs.csv rebuilt from runs.jsonl, no duplicate
}

TEST_F(SuiteRunner, AMalformedScenarioInAFolderFailsAlone) {
  std::ofstream(root_ / "scenarios" / "broken.toml") << "[scenario]\nname = \"broken\"\ncolour = \"red\"\n";
  settings_.engines = {"reference"};
  const SuiteOutcome outcome = run_suite(settings_);
  const auto all = rows(settings_.out);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(outcome.not_ok, 1);
  const Row* broken = find(all, "broken/unreadable");
  ASSERT_TRUE(broken);
  EXPECT_EQ(broken->verdict, "failed");
  EXPECT_NE(broken->reason.find("broken.toml:3: scenario.colour: unknown key"), std::string::npos) << broken->reason;
  const Row* good = find(all, "short_free/reference/hertz");
  ASSERT_TRUE(good);
  EXPECT_EQ(good->verdict, "ok");
  EXPECT_GT(good->json["impacts"].get<double>(), 0);
}

TEST_F(SuiteRunner, ALawWithoutParametersIsRecordedNotSkipped) {
  settings_.engines = {"reference"};
  settings_.laws = {ContactLaw::hertz, ContactLaw::newton};
  // drop the Newton table from the scenario
  const fs::path file = root_ / "scenarios" / "short_free.toml";
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text = text.substr(0, text.find("[contact.newton]"));
  std::ofstream(file, std::ios::trunc) << text;
  run_suite(settings_);
  const auto all = rows(settings_.out);
  const Row* newton = find(all, "short_free/newton/unavailable");
  ASSERT_TRUE(newton);
  EXPECT_EQ(newton->verdict, "failed");
  EXPECT_NE(newton->reason.find("no [contact.newton] table"), std::string::npos);
}

TEST_F(SuiteRunner, AnOutputFolderThatCannotBeMadeIsAClearError) {
  std::ofstream(root_ / "a_file") << "not a folder";
  settings_.out = (root_ / "a_file" / "out").string();
  try {
    run_suite(settings_);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(settings_.out + ": cannot create the output folder"), std::string::npos)
        << e.what();
  }
}

}  // namespace suite_runner_test
}  // namespace ib
