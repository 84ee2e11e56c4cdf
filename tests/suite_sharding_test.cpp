// A suite divided into shards (suite --shard K/N) and joined again (merge OUT SHARD_FOLDER ...) gives what
// the suite gives on one machine. Through the command, as a batch scheduler's tasks run it. A small suite
// (the short free vibration and the resonance cut to 1 s, the reference and up to two engines of this
// build, two laws, two time steps) is run whole into one folder and as 3 shards merged into another:
// every job id once, every field of runs.jsonl and runs.csv equal but the timing ones, every run's
// series.csv.gz, events.csv and impact.csv.gz equal byte for byte; each engine job in exactly one shard; one
// shard of one is the whole suite. A small step search (--find-steps over a narrow range) gives the same
// steps.csv sharded and merged, and there (where shards need different references) each shard runs the
// references its own groups need, no other. A shard stopped early
// is reported by merge with the command that finishes it, and finishing it then gives the whole suite
// again; a shard no folder holds is reported too.
// (Its errors: shard_merge_errors_test.cpp.)
#include "harness/records/metrics_file.h"
#include "suite_sharding_support.h"

namespace suite_sharding_test {

TEST_F(SuiteSharding, ShardsMergedGiveTheWholeSuite) {
  std::vector<fs::path> shards;
  for (int k = 1; k <= kShards; ++k) shards.push_back(shard(k));
  expect_engine_jobs_divided(whole(), shards);

  // joined, they are the whole suite; the report is made by the code of `report`, from the joined folder
  const CommandOutput merge = command("merge " + quoted(*root_ / "merged") + shard_list());
  ASSERT_EQ(merge.exit_code, 0) << merge.text;
  expect_same_results(whole(), *root_ / "merged");
  // the merged folder names the engines that made it and the metrics they were scored on, as each shard's does
  // (harness/records/engines_file.h): the shard's metrics.json, copied
  EXPECT_TRUE(fs::exists(*root_ / "merged" / "engines.json"));
  EXPECT_EQ(read_text(*root_ / "merged" / "metrics.json"), read_text(shards.front() / "metrics.json"));
  EXPECT_EQ(read_text(shards.front() / "metrics.json"), ib::metrics_json());
  EXPECT_NE(merge.text.find("report: " + (*root_ / "merged" / "report" / "index.html").string()), std::string::npos)
      << merge.text;
  const std::string summary = read_text(*root_ / "merged" / "report" / "summary.md");
  EXPECT_NE(summary.find("- suite folder: " + (*root_ / "merged").string()), std::string::npos) << summary;
  // hard links where the file system allows (here, one temporary folder)
  const std::string some_run = records(whole() / "runs.jsonl", "job_id", {}).begin()->first;
  EXPECT_GE(fs::hard_link_count(*root_ / "merged" / "runs" / some_run / "series.csv.gz"), 2u);
  // a shard's folder is a suite's folder of its own
  const CommandOutput report = command("report " + quoted(shard(2)));
  EXPECT_EQ(report.exit_code, 0) << report.text;
  EXPECT_TRUE(fs::exists(shard(2) / "report" / "summary.md"));
}

TEST_F(SuiteSharding, OneShardOfOneIsTheWholeSuite) {
  EXPECT_EQ(suite("--shard 1/1", *root_ / "one"), suite("", *root_ / "whole"));
  expect_same_results(whole(), *root_ / "one");
  EXPECT_TRUE(fs::exists(*root_ / "one" / "shard.jsonl"));
}

TEST_F(SuiteSharding, IncompleteShardsAreReportedAndTheResumeCommandFinishesThem) {
  // shard 2 as a killed array task leaves it: a few results recorded, the rest not
  const fs::path cut = *root_ / "cut";
  const int cut_exit_code = suite("--shard 2/" + std::to_string(kShards), cut);
  std::ifstream in(cut / "runs.jsonl");
  std::string kept;
  int planned = 0;
  for (std::string line; std::getline(in, line); ++planned)
    if (planned < 3) kept += line + "\n";
  in.close();
  std::ofstream(cut / "runs.jsonl") << kept;
  const std::string shards = " " + quoted(shard(1)) + " " + quoted(cut) + " " + quoted(shard(3));
  const CommandOutput partial = command("merge " + quoted(*root_ / "partial") + shards + " --no-report");
  EXPECT_EQ(partial.exit_code, 4) << partial.text;
  EXPECT_FALSE(fs::exists(*root_ / "partial" / "report")) << "--no-report";
  const std::string missing = "shard 2/3 in " + cut.string() + " is missing " + std::to_string(planned - 3) +
                              " of its " + std::to_string(planned) + " jobs";
  EXPECT_NE(partial.text.find(missing), std::string::npos) << partial.text;
  const std::string prefix = "then merge again into an empty folder: impactbench ";
  const auto at = partial.text.find(prefix);
  ASSERT_NE(at, std::string::npos) << partial.text;
  const std::string resume = partial.text.substr(at + prefix.size(), partial.text.find('\n', at) - at - prefix.size());
  EXPECT_NE(resume.find("--shard 2/3"), std::string::npos) << resume;
  EXPECT_NE(resume.find(" --resume"), std::string::npos) << resume;
  // what exists is joined all the same
  std::set<std::string> existing;
  for (const fs::path& folder : {shard(1), cut, shard(3)})
    for (const auto& [id, record] : records(folder / "runs.jsonl", "job_id", {})) existing.insert(id);
  std::set<std::string> joined;
  for (const auto& [id, record] : records(*root_ / "partial" / "runs.jsonl", "job_id", {})) joined.insert(id);
  EXPECT_EQ(joined, existing);
  EXPECT_LT(joined.size(), records(whole() / "runs.jsonl", "job_id", {}).size());
  // a shard that no folder holds (its task never began)
  const CommandOutput absent =
      command("merge " + quoted(*root_ / "absent") + " " + quoted(shard(1)) + " " + quoted(shard(3)) + " --no-report");
  EXPECT_EQ(absent.exit_code, 4) << absent.text;
  EXPECT_NE(absent.text.find("shard 2/3 is in none of the folders given"), std::string::npos) << absent.text;
  EXPECT_NE(absent.text.find("with --shard 2/3 and its own --out"), std::string::npos) << absent.text;
  // the printed command finishes the shard, and the merge is then the whole suite
  const CommandOutput finished = command(resume);
  ASSERT_EQ(finished.exit_code, cut_exit_code) << finished.text;
  EXPECT_NE(finished.text.find("(3 skipped as already done)"), std::string::npos) << finished.text;
  const CommandOutput merge = command("merge " + quoted(*root_ / "finished") + shards + " --no-report");
  ASSERT_EQ(merge.exit_code, 0) << merge.text;
  expect_same_results(whole(), *root_ / "finished");
}

// --find-steps: the step-search groups are divided; the merged steps.csv is the whole search's.
TEST_F(SuiteSharding, StepSearchShardsMergedGiveTheWholeSearch) {
  const std::string search =
      "suite " + quoted(*root_ / "scenarios" / "short_free.toml") + " --engines " + engines() +
      " --laws hertz,viscoelastic --find-steps --step-range 5e-5,2e-4 --repeat 0 --jobs 2 --out ";
  const CommandOutput whole = command(search + quoted(*root_ / "steps-whole"));
  ASSERT_LE(whole.exit_code, 1) << whole.text;
  std::string list;
  std::vector<fs::path> shards;
  for (int k = 1; k <= kShards; ++k) {
    shards.push_back(*root_ / ("steps-shard-" + std::to_string(k)));
    const CommandOutput part =
        command(search + quoted(shards.back()) + " --shard " + std::to_string(k) + "/" + std::to_string(kShards));
    ASSERT_LE(part.exit_code, 1) << part.text;
    list += " " + quoted(shards.back());
  }
  // groups in planned order (law, then engine) divided one by one: shards 2 and 3 need one law's references alone
  expect_engine_jobs_divided(*root_ / "steps-whole", shards);
  const CommandOutput merge = command("merge " + quoted(*root_ / "steps-merged") + list + " --no-report");
  ASSERT_EQ(merge.exit_code, 0) << merge.text;
  expect_same_results(*root_ / "steps-whole", *root_ / "steps-merged", /*steps=*/true);
}

}  // namespace suite_sharding_test
