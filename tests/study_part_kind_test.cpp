// A new kind of study part, added as docs/layout.md says (a class implementing PartOfItsOwnKind,
// harness/study/study.h) and nothing else of the harness changed: a toy kind, "tally", whose units are processes
// that note when they ran. run_study runs it in OUT/tally/NAME on the study's pool beside a suite, --plan
// describes it after the others, its bad setting stops the study before anything runs, and it can be left out.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "harness/study/study.h"
#include "simulators/catalog.h"
#include "suite_test_support.h"

namespace ib {
namespace study_part_kind_test {

namespace fs = std::filesystem;

double steady_now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The tally's units: each a process that takes unit_s and writes FOLDER/unit-K with its start and end [s].
class TallySource final : public UnitSource {
 public:
  TallySource(std::string folder, int units, double unit_s)
      : folder_(std::move(folder)), units_(units), unit_s_(unit_s) {}
  std::optional<double> next_cost() override { return next_ < units_ ? std::optional<double>(unit_s_) : std::nullopt; }
  std::string start_next(ProcessPool& pool) override {
    const std::string id = "tally/" + std::to_string(next_);
    const std::string file = folder_ + "/unit-" + std::to_string(next_++);
    const double unit_s = unit_s_;
    pool.start({id, 0, "", false}, [file, unit_s](int) {  // no time limit, its output the test's
      const double start_s = steady_now_s();
      std::this_thread::sleep_for(std::chrono::duration<double>(unit_s));
      { std::ofstream(file) << start_s << " " << steady_now_s() << "\n"; }
      _exit(unit_s > 0 ? 0 : 1);  // a unit of no duration fails: how the test makes a part end not ok
    });
    return id;
  }
  void ended(const ProcessEnd& end) override { failed_ += end.status != 0; }
  int failed() const { return failed_; }

 private:
  std::string folder_;
  int units_, next_ = 0, failed_ = 0;
  double unit_s_;
};

// The toy kind: its settings (how many units, how long each) and what a kind gives the study.
class Tally final : public PartOfItsOwnKind {
 public:
  Tally(int units, double unit_s) : units_(units), unit_s_(unit_s) {}
  std::string kind() const override { return "tally"; }
  std::unique_ptr<UnitSource> prepare(const std::string& folder, const StudySettings&) const override {
    if (units_ < 1) throw std::invalid_argument("tally units " + std::to_string(units_) + ": allowed: 1 or more");
    fs::create_directories(folder);
    return std::make_unique<TallySource>(folder, units_, unit_s_);
  }
  std::string plan(const std::string& folder) const override { return std::to_string(units_) + " units -> " + folder; }
  CampaignEnd finish(UnitSource& source) const override {
    CampaignEnd end;
    end.not_ok_recorded = static_cast<TallySource&>(source).failed();
    return end;
  }

 private:
  int units_;
  double unit_s_;
};

class StudyPartKindTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = test::fresh_test_folder("impactbench_part_kind_");
    test::write_short_free_vibration(root_ / "scenarios");
    SuiteSettings suite;
    suite.inputs = {(root_ / "scenarios").string()};
    suite.engines = {"reference"};
    suite.laws = {ContactLaw::hertz, ContactLaw::newton};
    suite.simulators = simulator_catalog();
    parts_ = {{StudyPartKind::suite, "suite", suite},
              {StudyPartKind::other, "count", std::make_shared<const Tally>(3, 0.2)}};
    settings_.out = (root_ / "out").string();
    settings_.jobs = 2;
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path root_;
  std::vector<StudyPart> parts_;
  StudySettings settings_;
};

TEST_F(StudyPartKindTest, AToyKindRunsInItsFolderOnTheStudysPoolBesideASuite) {
  const StudyOutcome outcome = run_study(parts_, settings_);
  ASSERT_EQ(outcome.others.size(), 1u);
  EXPECT_EQ(outcome.others[0].name, "count");
  EXPECT_EQ(result_of(outcome).status, CampaignStatus::ok);
  ASSERT_TRUE(outcome.suites);
  EXPECT_EQ(test::line_count(fs::path(settings_.out) / "runs.jsonl"), 2u);
  const fs::path folder = fs::path(settings_.out) / "tally" / "count";
  std::vector<std::pair<double, double>> units;
  for (int k = 0; k < 3; ++k) {
    std::ifstream in(folder / ("unit-" + std::to_string(k)));
    double start_s = 0, end_s = 0;
    ASSERT_TRUE(in >> start_s >> end_s) << "unit " << k;
    units.push_back({start_s, end_s});
  }
  // the study's two workers: three units of the toy never all at once
  for (const auto& at : units) {
    int running = 0;
    for (const auto& u : units) running += u.first <= at.first && at.first < u.second;
    EXPECT_LE(running, settings_.jobs);
  }
}

TEST_F(StudyPartKindTest, HowItEndedCountsInTheStudysEnd) {
  parts_[1].settings = std::make_shared<const Tally>(2, 0.0);  // units that fail
  const StudyOutcome outcome = run_study(parts_, settings_);
  ASSERT_EQ(outcome.others.size(), 1u);
  EXPECT_EQ(outcome.others[0].end.not_ok_recorded, 2);
  EXPECT_EQ(outcome.suites->not_ok_recorded, 0) << "the suite's runs are ok";
  EXPECT_EQ(result_of(outcome).status, CampaignStatus::not_ok);
}

TEST_F(StudyPartKindTest, ThePlanDescribesItAfterTheOthers) {
  const std::vector<std::string> lines = describe_study(parts_, settings_);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].rfind("suite \"suite\": ", 0), 0u) << lines[0];
  EXPECT_EQ(lines[1], "tally \"count\": 3 units -> " + settings_.out + "/tally/count");
}

TEST_F(StudyPartKindTest, ItsBadSettingStopsTheStudyBeforeAnythingRuns) {
  parts_[1].settings = std::make_shared<const Tally>(0, 0.2);
  EXPECT_THROW(run_study(parts_, settings_), std::invalid_argument);
  EXPECT_EQ(test::line_count(fs::path(settings_.out) / "runs.jsonl"), 0u);
  EXPECT_FALSE(fs::exists(fs::path(settings_.out) / "tally"));
}

TEST_F(StudyPartKindTest, ItCanBeLeftOut) {
  settings_.left_out = {StudyPartKind::other};
  const StudyOutcome outcome = run_study(parts_, settings_);
  EXPECT_TRUE(outcome.others.empty());
  EXPECT_FALSE(fs::exists(fs::path(settings_.out) / "tally"));
  EXPECT_EQ(test::line_count(fs::path(settings_.out) / "runs.jsonl"), 2u);
}

}  // namespace study_part_kind_test
}  // namespace ib
