// A study run in the harness (run_study, harness/study/study.h), with the reference and a toy engine only: the
// suites and searches go into the study's folder (each after the first with extend), each sweep into
// OUT/sweeps/NAME, with engines.json and provenance.json in each; kinds left out are not run; one pool of
// workers serves every part, no part waiting for another.
#include "harness/study/study.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "simulators/catalog.h"
#include "suite_test_support.h"

namespace ib {
namespace study_run_test {

namespace fs = std::filesystem;

// Where every run notes its scenario and when it ran (each in its worker process; appended, one line a run).
std::string g_run_log;

// A simulator under its own name that runs another (the reference, or the reference as "toy") and notes its
// scenario, start and end on the steady clock (one clock for every process of the machine) in g_run_log.
// The toy also takes a fifth of a second, so that runs of one part have time to overlap runs of another.
class Noted final : public Simulator {
 public:
  Noted(std::string name, std::unique_ptr<Simulator> inner) : name_(std::move(name)), inner_(std::move(inner)) {}
  std::string name() const override { return name_; }
  std::string version() const override { return "test"; }
  std::vector<std::pair<std::string, std::string>> option_help() const override { return inner_->option_help(); }
  RunResult run(const Scenario& s, const RunSettings& settings) override {
    const double start_s = seconds_now();
    RunResult result = inner_->run(s, settings);
    if (name_ == "toy") std::this_thread::sleep_for(std::chrono::milliseconds(200));
    std::ofstream(g_run_log, std::ios::app) << s.name << " " << start_s << " " << seconds_now() << "\n";
    return result;
  }

 private:
  static double seconds_now() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  }
  std::string name_;
  std::unique_ptr<Simulator> inner_;
};

std::unique_ptr<Simulator> noted_factory(const std::string& name) {
  if (name == "toy") return std::make_unique<Noted>("toy", make_simulator("reference"));
  if (name == "reference") return std::make_unique<Noted>("reference", make_simulator("reference"));
  return nullptr;
}

struct NotedRun {
  std::string scenario;
  double start_s = 0, end_s = 0;
};

class StudyRun : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = test::fresh_test_folder("impactbench_study_run_");
    test::write_short_free_vibration(root_ / "scenarios");
    g_run_log = (root_ / "runs.log").string();
    SuiteSettings suite;
    suite.inputs = {(root_ / "scenarios").string()};
    suite.engines = {"reference", "toy"};
    suite.laws = {ContactLaw::hertz, ContactLaw::viscoelastic};
    suite.simulators = catalog();
    SuiteSettings other = suite;  // another law, no series: shares the hertz runs with the first part
    other.laws = {ContactLaw::hertz, ContactLaw::newton};
    other.measurement.series = SeriesOutput::none;
    SweepSettings sweep;
    sweep.scenario_path = std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/paper/resonance.toml";
    sweep.engines = {"toy"};
    sweep.ratios = {0.95, 1.0};
    sweep.starts = {SweepStart::up};
    sweep.rest_duration_s = 2;
    sweep.continuation_duration_s = 2;
    sweep.window_s = 1;
    sweep.measurement.series = SeriesOutput::none;
    sweep.simulators = catalog();
    parts_ = {{StudyPartKind::suite, "first", suite},
              {StudyPartKind::suite, "second", other},
              {StudyPartKind::sweep, "coarse", sweep}};
    settings_.out = (root_ / "out").string();
    settings_.jobs = 2;
  }
  void TearDown() override { fs::remove_all(root_); }

  static SimulatorCatalog catalog() {
    SimulatorCatalog c = simulator_catalog();
    c.make = noted_factory;
    return c;
  }
  std::vector<NotedRun> runs() const {
    std::vector<NotedRun> out;
    std::ifstream in(g_run_log);
    for (NotedRun r; in >> r.scenario >> r.start_s >> r.end_s;) out.push_back(r);
    return out;
  }

  fs::path root_;
  std::vector<StudyPart> parts_;
  StudySettings settings_;
};

TEST_F(StudyRun, PlacingSetsEachPartsFolderAndTheStudyWideSettings) {
  StepSearchSettings search;
  parts_.insert(parts_.begin() + 2, {StudyPartKind::search, "search", std::get<SuiteSettings>(parts_[0].settings)});
  std::get<SuiteSettings>(parts_[2].settings).step_search = search;
  settings_.shard = Shard{2, 3};
  settings_.resume = true;
  settings_.reference_cache = (root_ / "cache").string();
  const std::vector<StudyPart> placed = place_study_parts(parts_, settings_);
  ASSERT_EQ(placed.size(), 4u);
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& s = std::get<SuiteSettings>(placed[i].settings);
    EXPECT_EQ(s.out, settings_.out);
    EXPECT_EQ(s.extend, i > 0) << placed[i].name;  // the first makes the folder, the others add to it
    EXPECT_EQ(s.reference_cache, settings_.reference_cache);
    EXPECT_EQ(s.jobs, 2);
    EXPECT_TRUE(s.resume && s.shard && s.shard->index == 2 && s.shard->count == 3);
  }
  const auto& sweep = std::get<SweepSettings>(placed[3].settings);
  EXPECT_EQ(sweep.out, settings_.out + "/sweeps/coarse");
  EXPECT_TRUE(sweep.resume && sweep.shard && sweep.jobs == 2);
}

TEST_F(StudyRun, SuitesGoIntoTheFolderAndEachSweepIntoSweepsName) {
  const StudyOutcome outcome = run_study(parts_, settings_);
  ASSERT_TRUE(outcome.suites);
  // hertz: reference, toy (both parts'); viscoelastic and newton: reference, toy each
  EXPECT_EQ(outcome.suites->jobs_total, 6);
  EXPECT_EQ(outcome.suites->not_ok_recorded, 0);
  ASSERT_EQ(outcome.sweeps.size(), 1u);
  EXPECT_EQ(outcome.sweeps[0].name, "coarse");
  EXPECT_EQ(outcome.sweeps[0].outcome.rows_total, 2);
  EXPECT_EQ(outcome.sweeps[0].outcome.rows_run, 2);
  const fs::path out = settings_.out;
  EXPECT_EQ(test::line_count(out / "suite.jsonl"), 2u);  // each part's settings line
  EXPECT_EQ(test::line_count(out / "runs.jsonl"), 6u);
  EXPECT_EQ(test::line_count(out / "sweeps" / "coarse" / "sweep.csv"), 3u);  // its header and a row per ratio
  for (const fs::path& folder : {out, out / "sweeps" / "coarse"}) {
    EXPECT_TRUE(fs::exists(folder / "engines.json")) << folder;
    EXPECT_TRUE(fs::exists(folder / "provenance.json")) << folder;
  }
}

TEST_F(StudyRun, KindsLeftOutAreNotRun) {
  settings_.left_out = {StudyPartKind::sweep};
  const StudyOutcome suites_alone = run_study(parts_, settings_);
  EXPECT_TRUE(suites_alone.suites);
  EXPECT_TRUE(suites_alone.sweeps.empty());
  EXPECT_FALSE(fs::exists(fs::path(settings_.out) / "sweeps"));
  for (const NotedRun& run : runs()) EXPECT_EQ(run.scenario, "short_free") << "a run of a part left out";
  fs::remove(g_run_log);

  settings_.out = (root_ / "sweep_alone").string();
  settings_.left_out = {StudyPartKind::suite, StudyPartKind::search};
  const StudyOutcome sweep_alone = run_study(parts_, settings_);
  EXPECT_FALSE(sweep_alone.suites);
  ASSERT_EQ(sweep_alone.sweeps.size(), 1u);
  EXPECT_FALSE(fs::exists(fs::path(settings_.out) / "runs.jsonl"));
  EXPECT_TRUE(fs::exists(fs::path(settings_.out) / "sweeps" / "coarse" / "sweep.csv"));
  for (const NotedRun& run : runs()) EXPECT_EQ(run.scenario, "resonance") << "a run of a part left out";
}

TEST_F(StudyRun, OnePoolServesEveryPartAndNoPartWaitsForAnother) {
  run_study(parts_, settings_);
  const std::vector<NotedRun> all = runs();
  ASSERT_EQ(all.size(), 6u + 2u);  // the suites' jobs and the sweep's two ratios (one chain)
  // at no moment more runs than the study's workers, whatever their part
  for (const NotedRun& at : all) {
    const auto running = std::count_if(
        all.begin(), all.end(), [&](const NotedRun& r) { return r.start_s <= at.start_s && at.start_s < r.end_s; });
    EXPECT_LE(running, settings_.jobs) << "at " << at.start_s;
  }
  // and the sweep's chain ran while the suites' jobs did: it did not wait for them to end, nor they for it
  bool overlapped = false;
  for (const NotedRun& sweep : all)
    for (const NotedRun& suite : all)
      if (sweep.scenario == "resonance" && suite.scenario == "short_free")
        overlapped = overlapped || (sweep.start_s < suite.end_s && suite.start_s < sweep.end_s);
  EXPECT_TRUE(overlapped);
}

TEST_F(StudyRun, ThePlanHasALinePerPartTheSweepsLast) {
  std::swap(parts_[0], parts_[2]);  // a sweep first among the parts: its line is still after the suites'
  settings_.left_out = {StudyPartKind::search};
  const std::vector<std::string> lines = describe_study(parts_, settings_);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0].rfind("suite \"second\": ", 0), 0u) << lines[0];
  EXPECT_EQ(lines[1].rfind("suite \"first\": ", 0), 0u) << lines[1];
  EXPECT_EQ(lines[2].rfind("sweep \"coarse\": ", 0), 0u) << lines[2];
  EXPECT_NE(lines[2].find("; 2 ratios; engines toy; laws hertz;"), std::string::npos) << lines[2];
  const std::string folder = " -> " + settings_.out + "/sweeps/coarse";  // the plan line ends with its folder
  EXPECT_EQ(lines[2].substr(lines[2].size() - std::min(lines[2].size(), folder.size())), folder) << lines[2];
  settings_.left_out = {StudyPartKind::sweep};
  EXPECT_EQ(describe_study(parts_, settings_).size(), 2u);
}

}  // namespace study_run_test
}  // namespace ib
