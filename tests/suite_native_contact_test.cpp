// The suite runs an engine's native contact path once per scenario, step and options, whatever the law
// (native contact ignores the scenario's law: tests/native_contact_law_test.cpp), and scores that one run
// against every law's references: a row per law, the others naming the run they were scored from,
// sharing its files. A resumed suite that lost such a row runs the native run again and records only
// what was missing.
#include "harness/suite/suite.h"
#include "simulators/catalog.h"
#include "suite_test_support.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "reference/reference_simulator.h"

namespace ib {
namespace suite_native_contact_test {

namespace fs = std::filesystem;

std::string g_run_log;  // each run appends a line here (runs happen in the suite's worker processes)

// An engine whose native contact is the reference's Hertz law whatever law it is asked for (as a real
// engine's own contact ignores the scenario's law), and whose matched contact is the law asked for.
class Counted final : public Simulator {
 public:
  std::string name() const override { return "counted"; }
  std::string version() const override { return "test"; }
  std::vector<std::pair<std::string, std::string>> option_help() const override { return {{"contact", "path"}}; }
  RunResult run(const Scenario& s, const RunSettings& settings) override {
    std::ofstream(g_run_log, std::ios::app) << to_string(settings.law) << " " << settings.options.at("contact") << "\n";
    RunSettings reference = settings;
    reference.options.clear();
    if (settings.options.at("contact") == "native") reference.law = ContactLaw::hertz;
    return make_reference_simulator()->run(s, reference);
  }
};

class SuiteNativeContact : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = test::fresh_test_folder("impactbench_native_");
    test::write_short_free_vibration(root_ / "scenarios");
    g_run_log = (root_ / "runs.log").string();
    settings_.inputs = {(root_ / "scenarios").string()};
    settings_.engines = {"reference", "counted"};
    settings_.contact_paths = {"matched", "native"};
    settings_.out = (root_ / "out").string();
    settings_.jobs = 2;
    settings_.simulators = simulator_catalog();
    settings_.simulators.make = [](const std::string& name) -> std::unique_ptr<Simulator> {
      if (name == "counted") return std::make_unique<Counted>();
      return make_simulator(name);
    };
  }
  void TearDown() override { fs::remove_all(root_); }
  fs::path root_;
  SuiteSettings settings_;
};

TEST_F(SuiteNativeContact, OneNativeRunScoredAgainstEveryLaw) {
  const SuiteOutcome outcome = run_suite(settings_);
  EXPECT_EQ(outcome.not_ok, 0);
  EXPECT_EQ(test::line_count(g_run_log), 4u);  // three matched runs, one native
  std::map<std::string, nlohmann::json> by_id;
  for (const auto& r : test::json_lines(root_ / "out" / "runs.jsonl")) by_id[r["job_id"]] = r;
  const std::string source = "short_free/counted/hertz/contact=native";
  ASSERT_TRUE(by_id.count(source));
  EXPECT_EQ(by_id[source]["same_run_as"], "");
  // A native run equals the Hertz reference: no error against Hertz, a clear one against the others.
  EXPECT_LT(std::abs(by_id[source]["vs_reference_frame1_displacement_relative_rms_error"].get<double>()), 1e-8);
  for (const std::string law : {"viscoelastic", "newton"}) {
    const std::string id = "short_free/counted/" + law + "/contact=native";
    ASSERT_TRUE(by_id.count(id)) << id;
    const auto& row = by_id[id];
    EXPECT_EQ(row["law"], law);
    EXPECT_EQ(row["same_run_as"], source);
    for (const char* same : {"impacts", "frame1_sensor_peak_acceleration_g", "steps", "cpu_time_s"})
      EXPECT_EQ(row[same], by_id[source][same]) << id << " " << same;  // the same run, its own cost
    EXPECT_GT(row["vs_reference_frame1_displacement_relative_rms_error"].get<double>(), 1e-4) << id;
    // its files are the run's, linked, not copied
    const fs::path series = root_ / "out" / "runs" / id / "series.csv.gz";
    ASSERT_TRUE(fs::exists(series)) << series;
    EXPECT_GE(fs::hard_link_count(series), 2u);
    EXPECT_TRUE(fs::exists(root_ / "out" / "runs" / id / "summary.json"));
  }
  // matched runs are each law's own
  for (const std::string law : {"hertz", "viscoelastic", "newton"})
    EXPECT_EQ(by_id["short_free/counted/" + law + "/contact=matched"]["same_run_as"], "") << law;
  // The contact path in a column of its own; a native row keeps the law of the references it was scored
  // against, and says that the engine did not simulate it (docs/results.md).
  for (const auto& [id, row] : by_id) {
    const bool native = id.find("contact=native") != std::string::npos;
    const std::string path = row["engine"] == "reference" ? "" : native ? "native" : "matched";
    EXPECT_EQ(row["contact_path"], path) << id;
    EXPECT_EQ(row["law_simulated"], native ? "no" : "yes") << id;
  }
}

TEST_F(SuiteNativeContact, AResumedSuiteRecordsALostScoredRowAgain) {
  run_suite(settings_);
  const fs::path jsonl = root_ / "out" / "runs.jsonl";
  const std::vector<nlohmann::json> whole = test::json_lines(jsonl);
  // Lose the scored Newton row, as a kill between two appends would.
  std::string kept;
  for (const auto& r : whole)
    if (r["job_id"] != "short_free/counted/newton/contact=native") kept += r.dump() + "\n";
  std::ofstream(jsonl, std::ios::trunc) << kept;
  settings_.resume = true;
  const SuiteOutcome resumed = run_suite(settings_);
  EXPECT_EQ(resumed.jobs_run, 1);                   // the lost row alone is recorded
  EXPECT_EQ(test::line_count(g_run_log), 4u + 1u);  // by running the native run again
  std::map<std::string, nlohmann::json> before, after;
  for (const auto& r : whole) before[r["job_id"]] = r;
  for (const auto& r : test::json_lines(jsonl)) after[r["job_id"]] = r;
  ASSERT_EQ(after.size(), before.size());
  for (auto& [id, r] : after) {
    for (const std::string& timing : timing_field_names()) {
      r.erase(timing);
      before[id].erase(timing);
    }
    EXPECT_EQ(r, before[id]) << id;
  }
}

}  // namespace suite_native_contact_test
}  // namespace ib
