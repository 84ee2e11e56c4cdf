// A campaign's folder (harness/jobs/campaign_folder.h), the one policy of suites and sweeps: it is created and
// locked, a folder of the other kind or of another shard is refused, results are continued by the same
// settings' --resume only, and how a campaign ended decides its status.
#include "harness/jobs/campaign_folder.h"
#include "harness/study/study.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>

namespace ib {
namespace campaign_folder_test {

namespace fs = std::filesystem;

class CampaignFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = ::testing::TempDir() + "/campaign_folder_" + std::to_string(::getpid());
    fs::remove_all(root_);
  }
  void TearDown() override { fs::remove_all(root_); }
  std::string root_;
};

TEST_F(CampaignFolder, IsCreatedWithItsRunsAndLockedWhileOpen) {
  const std::string dir = root_ + "/a/b";
  {
    const auto lock = open_campaign_folder(dir, CampaignKind::suite);
    EXPECT_TRUE(fs::is_directory(dir + "/runs"));
    EXPECT_THROW(open_campaign_folder(dir, CampaignKind::suite), FolderBusy) << "a second owner";
  }
  EXPECT_NO_THROW(open_campaign_folder(dir, CampaignKind::suite)) << "the lock ends with its owner";
}

TEST_F(CampaignFolder, RefusesAFolderOfTheOtherKind) {
  const std::string sweep = root_ + "/sweep", suite = root_ + "/suite";
  fs::create_directories(sweep);
  std::ofstream(sweep + "/sweep.json") << "{}\n";
  try {
    open_campaign_folder(sweep, CampaignKind::suite);
    ADD_FAILURE() << "a suite into a sweep's folder";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), sweep + " holds a sweep; choose another --out for a suite");
  }
  EXPECT_NO_THROW(open_campaign_folder(sweep, CampaignKind::sweep)) << "its own kind: --resume decides";
  fs::create_directories(suite);
  std::ofstream(suite + "/suite.jsonl") << "";
  EXPECT_THROW(open_campaign_folder(suite, CampaignKind::sweep), std::invalid_argument);
}

TEST_F(CampaignFolder, AShardsFolderHoldsThatShardAlone) {
  fs::create_directories(root_);
  EXPECT_NO_THROW(check_same_shard(root_, CampaignKind::sweep, std::nullopt, false));
  EXPECT_NO_THROW(check_same_shard(root_, CampaignKind::sweep, Shard{1, 2}, false)) << "an empty folder";
  try {
    check_same_shard(root_, CampaignKind::sweep, Shard{1, 2}, true);
    ADD_FAILURE() << "a shard into a whole sweep's results";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("holds a whole sweep's results, not a shard's"), std::string::npos);
  }
  record_shard_plan(root_, ShardPlan{Shard{1, 2}, "digest", {"a"}, {}, "impactbench sweep --resume"});
  EXPECT_NO_THROW(check_same_shard(root_, CampaignKind::suite, Shard{1, 2}, true)) << "the same shard resumes";
  EXPECT_THROW(check_same_shard(root_, CampaignKind::suite, Shard{2, 2}, true), std::invalid_argument);
  try {
    check_same_shard(root_, CampaignKind::suite, std::nullopt, true);
    ADD_FAILURE() << "a whole suite into a shard's folder";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), root_ + " holds shard 1/2 of a suite (shard.jsonl): resume it with --shard 1/2");
  }
}

// One refusal for both kinds: results in the folder need --resume, and --resume needs the same settings.
TEST_F(CampaignFolder, ResultsAreContinuedByResumeWithTheSameSettingsOnly) {
  fs::create_directories(root_);
  EXPECT_NO_THROW(refuse_results_without_resume(root_, CampaignKind::sweep, false)) << "none yet";
  std::ofstream(root_ + "/sweep.json") << "{}\n";
  EXPECT_NO_THROW(refuse_results_without_resume(root_, CampaignKind::sweep, true));
  try {
    refuse_results_without_resume(root_, CampaignKind::sweep, false);
    ADD_FAILURE() << "a sweep run again into its results without --resume";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), root_ +
                                         " already holds a sweep's results (sweep.json): pass --resume to "
                                         "continue it, or choose another --out");
  }
  try {
    refuse_other_settings(root_, CampaignKind::suite, "window_s", "impactbench suite --window 2");
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), root_ +
                                         " holds a suite with other settings (window_s differ from: impactbench "
                                         "suite --window 2, see " +
                                         root_ +
                                         "/suite.jsonl): --resume continues "
                                         "the same suite only; add --extend to add this suite to the folder, or "
                                         "choose another --out");
  }
  try {
    refuse_other_settings(root_, CampaignKind::sweep, "ratios", "");
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), root_ + " holds a sweep with other settings (ratios differ, see " + root_ +
                                         "/sweep.json): --resume continues the same sweep only; choose another --out");
  }
}

TEST(CampaignEnd, StoppedOverNotOkOverOk) {
  EXPECT_EQ(result_of(CampaignEnd{}).status, CampaignStatus::ok);
  EXPECT_EQ(result_of(CampaignEnd{0, 0, 0, 1}).status, CampaignStatus::not_ok) << "one result recorded not ok";
  const CampaignResult interrupted = result_of(CampaignEnd{SIGINT, 2, SIGKILL, 1});
  EXPECT_EQ(interrupted.status, CampaignStatus::stopped);
  EXPECT_EQ(interrupted.signal, SIGINT) << "the campaign's own interruption names it";
  const CampaignResult from_outside = result_of(CampaignEnd{0, 2, SIGKILL, 0});
  EXPECT_EQ(from_outside.status, CampaignStatus::stopped);
  EXPECT_EQ(from_outside.signal, SIGKILL);
  const CampaignResult not_ok{CampaignStatus::not_ok, 0};
  EXPECT_EQ(worse(CampaignResult{}, not_ok).status, CampaignStatus::not_ok);
  EXPECT_EQ(worse(from_outside, not_ok).signal, SIGKILL);
  EXPECT_EQ(worse(not_ok, CampaignResult{}).status, CampaignStatus::not_ok);
}

// A study ends as the worst of its parts: the suites' (one outcome) and each sweep's.
TEST(CampaignEnd, AStudyEndsAsItsWorstPart) {
  StudyOutcome study;
  EXPECT_EQ(result_of(study).status, CampaignStatus::ok) << "no part";
  study.suites = SuiteOutcome{};
  study.suites->not_ok_recorded = 1;
  study.sweeps.push_back({"fine", SweepOutcome{}});
  EXPECT_EQ(result_of(study).status, CampaignStatus::not_ok);
  study.sweeps.push_back({"coarse", SweepOutcome{}});
  study.sweeps.back().outcome.interrupted_by = SIGTERM;
  EXPECT_EQ(result_of(study).status, CampaignStatus::stopped);
  EXPECT_EQ(result_of(study).signal, SIGTERM);
}

}  // namespace campaign_folder_test
}  // namespace ib
