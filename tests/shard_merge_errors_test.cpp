// What suite --shard and merge refuse, each an exit 2 with a message that names it: bad --shard values, a
// shard's folder resumed as another shard, a folder that does not exist, a header of another layout, two
// shards that disagree on a job and an OUT that is not empty (the suite and its shards: suite_sharding_support.h).
#include "suite_sharding_support.h"

namespace suite_sharding_test {

TEST_F(SuiteSharding, BadShardValuesAreClearErrors) {
  for (const std::string value : {"0/3", "4/3", "a/b", "3", "1/0", "2/-3"}) {
    const CommandOutput run = command("suite --out " + quoted(*root_ / "never") + " --shard " + value);
    EXPECT_EQ(run.exit_code, 2) << value << ": " << run.text;
    EXPECT_NE(run.text.find("--shard " + value + ": allowed: K/N with whole numbers 1 <= K <= N"), std::string::npos)
        << run.text;
  }
  EXPECT_FALSE(fs::exists(*root_ / "never"));
  // a shard's folder continues that shard alone (a reference-only suite: quick)
  const std::string tiny = "suite " + quoted(*root_ / "scenarios" / "short_free.toml") + " --laws hertz --out " +
                           quoted(*root_ / "tiny") + " --shard 1/2";
  ASSERT_EQ(command(tiny).exit_code, 0);
  const CommandOutput other = command(tiny.substr(0, tiny.size() - 3) + "2/2 --resume");
  EXPECT_EQ(other.exit_code, 2) << other.text;
  EXPECT_NE(other.text.find("holds shard 1/2 of a suite (shard.jsonl), not --shard 2/2: resume it with --shard 1/2"),
            std::string::npos)
      << other.text;
}

TEST_F(SuiteSharding, MergeRefusesWhatItCannotJoin) {
  const std::string out = quoted(*root_ / "refused");
  // a folder that does not exist
  const CommandOutput nowhere =
      command("merge " + out + shard_list() + " " + quoted(*root_ / "shard-4") + " --no-report");
  EXPECT_EQ(nowhere.exit_code, 2) << nowhere.text;
  EXPECT_NE(nowhere.text.find((*root_ / "shard-4").string() + ": no such folder"), std::string::npos) << nowhere.text;
  // a runs.csv of another layout
  const fs::path renamed = copy_records(shard(3), *root_ / "renamed");
  std::string csv = read_text(renamed / "runs.csv");
  csv.replace(csv.find(",verdict,"), 9, ",outcome,");
  std::ofstream(renamed / "runs.csv") << csv;
  const CommandOutput header = command("merge " + out + " " + quoted(shard(1)) + " " + quoted(shard(2)) + " " +
                                       quoted(renamed) + " --no-report");
  EXPECT_EQ(header.exit_code, 2) << header.text;
  EXPECT_NE(
      header.text.find((renamed / "runs.csv").string() + ": header differs from this build's: column 11 is 'outcome', "
                                                         "expected 'verdict'"),
      std::string::npos)
      << header.text;
  // two shards that disagree on a job (a reference both ran)
  const fs::path changed = copy_records(shard(3), *root_ / "changed");
  const auto in_shard_1 = records(shard(1) / "runs.jsonl", "job_id", {});
  std::string jsonl, reference;
  std::ifstream in(changed / "runs.jsonl");
  for (std::string line; std::getline(in, line);) {
    Json j = Json::parse(line);
    if (reference.empty() && j["engine"] == "reference" && in_shard_1.count(j["job_id"])) {
      reference = j["job_id"];
      j["impacts"] = j["impacts"].get<double>() + 1;
    }
    jsonl += j.dump() + "\n";
  }
  in.close();
  std::ofstream(changed / "runs.jsonl") << jsonl;
  ASSERT_FALSE(reference.empty());
  const CommandOutput conflict =
      command("merge " + out + " " + quoted(shard(1)) + " " + quoted(changed) + " --no-report");
  EXPECT_EQ(conflict.exit_code, 2) << conflict.text;
  EXPECT_NE(conflict.text.find(shard(1).string() + " and " + changed.string() + " disagree on job " + reference +
                               ": field impacts is "),
            std::string::npos)
      << conflict.text;
  // a shard whose run folders are gone
  const fs::path hollow = copy_records(shard(3), *root_ / "hollow");
  fs::remove_all(hollow / "runs");
  const CommandOutput damaged =
      command("merge " + out + " " + quoted(shard(1)) + " " + quoted(hollow) + " --no-report");
  EXPECT_EQ(damaged.exit_code, 2) << damaged.text;
  EXPECT_NE(damaged.text.find(hollow.string() + ": its results are damaged ("), std::string::npos) << damaged.text;
  EXPECT_NE(damaged.text.find("/ (summary.json) is gone"), std::string::npos) << damaged.text;
  EXPECT_NE(damaged.text.find("continue that shard with --resume"), std::string::npos) << damaged.text;
  // a shard whose plan file is damaged
  const fs::path scribbled = copy_records(shard(3), *root_ / "scribbled");
  std::ofstream(scribbled / "shard.jsonl", std::ios::app) << "{\"shard\": \"three\"}\n";
  const CommandOutput plan =
      command("merge " + out + " " + quoted(shard(1)) + " " + quoted(scribbled) + " --no-report");
  EXPECT_EQ(plan.exit_code, 2) << plan.text;
  EXPECT_NE(plan.text.find((scribbled / "shard.jsonl").string() + " line 2: not a shard's plan"), std::string::npos)
      << plan.text;
  // a shard of another suite (other scenarios: other jobs)
  const fs::path stranger = *root_ / "stranger";
  ASSERT_LE(command("suite " + quoted(*root_ / "scenarios" / "short_free.toml") + " --laws hertz --shard 2/3 --out " +
                    quoted(stranger))
                .exit_code,
            1);
  const CommandOutput mixed =
      command("merge " + out + " " + quoted(shard(1)) + " " + quoted(stranger) + " --no-report");
  EXPECT_EQ(mixed.exit_code, 2) << mixed.text;
  EXPECT_NE(mixed.text.find(shard(1).string() + " and " + stranger.string() + " are shards of different suites"),
            std::string::npos)
      << mixed.text;
  EXPECT_FALSE(fs::exists(*root_ / "refused")) << "nothing is written when the input is bad";
  // an OUT that holds something already
  const CommandOutput full = command("merge" + shard_list() + " --no-report");
  EXPECT_EQ(full.exit_code, 2) << full.text;
  EXPECT_NE(
      full.text.find(shard(1).string() + ": not empty (it holds a suite's results); merge writes a new suite folder"),
      std::string::npos)
      << full.text;
}

}  // namespace suite_sharding_test
