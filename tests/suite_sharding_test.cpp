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
// again; a shard no folder holds is reported too. Bad --shard values, a folder that does not exist, a
// header of another layout, two shards that disagree on a job and an OUT that is not empty are errors.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "catalog_engines.h"
#include "command_test_support.h"
#include "harness/records/run_record.h"
#include "simulators/catalog.h"
#include "suite_test_support.h"

namespace suite_sharding_test {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using ib::test::CommandOutput;

// What may differ between two runs of one job: its measured cost.
const std::set<std::string> kRunTimingFields(ib::timing_field_names().begin(), ib::timing_field_names().end());
const std::set<std::string> kStepTimingFields = {"probes_wall_time_s"};
constexpr int kShards = 3;

// The reference and the build's first two engines (tests/catalog_engines.h): sharding is the harness's, any engine
// does.
std::string engines() {
  return ib::test::engines_option("reference", ib::test::engines_among(ib::simulator_names()), 2);
}

std::string quoted(const fs::path& path) { return "'" + path.string() + "'"; }

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A .jsonl file as key -> record without the timing fields; a key recorded twice fails the test.
std::map<std::string, Json> records(const fs::path& file, const std::string& key, const std::set<std::string>& timing) {
  std::map<std::string, Json> by_key;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    Json j = Json::parse(line);
    for (const std::string& field : timing) j.erase(field);
    const std::string id = j[key];
    EXPECT_EQ(by_key.count(id), 0u) << "recorded twice in " << file << ": " << id;
    by_key[id] = j;
  }
  return by_key;
}

// One CSV line's cells (quoted cells may hold commas and doubled quotes).
std::vector<std::string> cells_of(const std::string& line) {
  std::vector<std::string> cells(1);
  bool quoted_cell = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted_cell && c == '"' && i + 1 < line.size() && line[i + 1] == '"')
      cells.back() += line[++i];
    else if (c == '"')
      quoted_cell = !quoted_cell;
    else if (c == ',' && !quoted_cell)
      cells.emplace_back();
    else
      cells.back() += c;
  }
  return cells;
}

// A CSV file as first cell -> row with the timing cells masked; its header in `header`.
std::map<std::string, std::vector<std::string>> csv_rows(const fs::path& file, const std::set<std::string>& timing,
                                                         std::string& header) {
  std::ifstream in(file);
  std::getline(in, header);
  const std::vector<std::string> names = cells_of(header);
  std::map<std::string, std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells = cells_of(line);
    EXPECT_EQ(cells.size(), names.size()) << file << ": " << line;
    for (std::size_t i = 0; i < cells.size() && i < names.size(); ++i)
      if (timing.count(names[i])) cells[i] = "<time>";
    EXPECT_EQ(rows.count(cells[0]), 0u) << "twice in " << file << ": " << cells[0];
    rows[cells[0]] = cells;
  }
  return rows;
}

// Two suite folders hold the same results: the same job ids, every non-timing field of runs.jsonl and
// runs.csv equal, every run's files equal byte for byte; and the same steps.csv rows when `steps`.
void expect_same_results(const fs::path& expected, const fs::path& actual, bool steps = false) {
  const auto want = records(expected / "runs.jsonl", "job_id", kRunTimingFields);
  const auto got = records(actual / "runs.jsonl", "job_id", kRunTimingFields);
  ASSERT_FALSE(want.empty());
  EXPECT_EQ(got.size(), want.size());
  for (const auto& [id, record] : want) {
    ASSERT_EQ(got.count(id), 1u) << "missing in " << actual << ": " << id;
    EXPECT_EQ(got.at(id), record) << id;
  }
  std::string want_header, got_header;
  EXPECT_EQ(csv_rows(actual / "runs.csv", kRunTimingFields, got_header),
            csv_rows(expected / "runs.csv", kRunTimingFields, want_header));
  EXPECT_EQ(got_header, want_header);
  for (const auto& [id, record] : want)
    for (const char* file : {"series.csv.gz", "events.csv", "impact.csv.gz"}) {
      const fs::path a = expected / "runs" / id / file, b = actual / "runs" / id / file;
      EXPECT_EQ(fs::exists(b), fs::exists(a)) << b;
      if (fs::exists(a)) {
        EXPECT_TRUE(read_text(a) == read_text(b)) << b << " differs from " << a;
      }
    }
  if (!steps) return;
  EXPECT_EQ(records(actual / "steps.jsonl", "group_id", kStepTimingFields),
            records(expected / "steps.jsonl", "group_id", kStepTimingFields));
  EXPECT_EQ(csv_rows(actual / "steps.csv", kStepTimingFields, got_header),
            csv_rows(expected / "steps.csv", kStepTimingFields, want_header));
  EXPECT_EQ(got_header, want_header);
}

// The shards divide the whole suite's engine jobs (step-search probes included) among them, each job to
// exactly one shard, and each shard runs the references its own jobs are compared with, no other.
void expect_engine_jobs_divided(const fs::path& whole, const std::vector<fs::path>& shards) {
  std::map<std::string, int> engine_jobs;  // job id -> shards that ran it
  for (const fs::path& shard : shards) {
    std::set<std::string> references, needed;
    for (const auto& [id, r] : records(shard / "runs.jsonl", "job_id", {})) {
      const std::string beam = r["scenario"].get<std::string>() + "/reference/" + r["law"].get<std::string>();
      if (r["engine"] == "reference") {
        references.insert(id);
        if (id != beam) needed.insert(beam);  // a chain reference is compared with the beam's
        continue;
      }
      ++engine_jobs[id];
      needed.insert(beam);
      if (r["chain_links"] > 0)
        needed.insert(beam + "/links=" + std::to_string(r["chain_links"].get<int>()) + ";modes=chain");
    }
    EXPECT_FALSE(references.empty()) << shard;
    EXPECT_EQ(references, needed) << shard << " runs other references than its jobs need";
  }
  std::size_t whole_engine_jobs = 0;
  for (const auto& [id, r] : records(whole / "runs.jsonl", "job_id", {})) {
    if (r["engine"] == "reference") continue;
    ++whole_engine_jobs;
    EXPECT_EQ(engine_jobs[id], 1) << "not in exactly one shard: " << id;
  }
  EXPECT_EQ(engine_jobs.size(), whole_engine_jobs);
  EXPECT_GE(whole_engine_jobs, 4u);
}

// Copies a suite folder's record files (not its runs/): enough for merge's checks, which come before it
// writes anything.
fs::path copy_records(const fs::path& from, const fs::path& to) {
  fs::create_directories(to);
  for (const char* file : {"runs.jsonl", "runs.csv", "shard.jsonl", "steps.jsonl", "steps.csv"})
    if (fs::exists(from / file)) fs::copy_file(from / file, to / file);
  if (fs::exists(from / "runs")) fs::copy(from / "runs", to / "runs", fs::copy_options::recursive);
  return to;
}

// The whole suite and its shards, each run when a test first needs it (ctest runs every test in a
// process of its own, so a test pays only for the suites it uses).
class SuiteSharding : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(fs::temp_directory_path() / ("impactbench_sharding_" + std::to_string(getpid())));
    fs::remove_all(*root_);
    ib::test::write_short_free_vibration(*root_ / "scenarios");
    fs::copy_file(std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/paper/resonance.toml",
                  *root_ / "scenarios/resonance.toml");
    done_ = new std::map<fs::path, int>;
  }
  static void TearDownTestSuite() {
    if (!::testing::UnitTest::GetInstance()->Failed()) fs::remove_all(*root_);
    delete root_;
    delete done_;
  }

  // The small suite's command line with `extra` options, into `out`.
  static std::string suite_arguments(const std::string& extra, const fs::path& out) {
    return "suite " + quoted(*root_ / "scenarios") + " --engines " + engines() +
           " --laws hertz,viscoelastic --dt 1e-4,5e-5 --duration 1 --repeat 0 --jobs 2 " + extra + " --out " +
           quoted(out);
  }
  // Runs the small suite into `out` (once) and returns its exit code: 0, or 1 when a run is unstable or failed.
  static int suite(const std::string& extra, const fs::path& out) {
    if (!done_->count(out)) {
      const CommandOutput run = command(suite_arguments(extra, out));
      EXPECT_LE(run.exit_code, 1) << run.text;
      (*done_)[out] = run.exit_code;
    }
    return done_->at(out);
  }
  static fs::path whole() {
    suite("", *root_ / "whole");
    return *root_ / "whole";
  }
  static fs::path shard(int k) {
    const fs::path out = *root_ / ("shard-" + std::to_string(k));
    suite("--shard " + std::to_string(k) + "/" + std::to_string(kShards), out);
    return out;
  }
  static std::string shard_list() {
    std::string list;
    for (int k = 1; k <= kShards; ++k) list += " " + quoted(shard(k));
    return list;
  }
  static CommandOutput command(const std::string& arguments) {
    static int n = 0;
    return ib::test::run_impactbench(arguments, *root_ / ("command" + std::to_string(++n) + ".log"));
  }
  static fs::path* root_;
  static std::map<fs::path, int>* done_;  // suites run so far: folder -> exit code
};
fs::path* SuiteSharding::root_ = nullptr;
std::map<fs::path, int>* SuiteSharding::done_ = nullptr;

TEST_F(SuiteSharding, ShardsMergedGiveTheWholeSuite) {
  std::vector<fs::path> shards;
  for (int k = 1; k <= kShards; ++k) shards.push_back(shard(k));
  expect_engine_jobs_divided(whole(), shards);

  // joined, they are the whole suite; the report is made by the code of `report`, from the joined folder
  const CommandOutput merge = command("merge " + quoted(*root_ / "merged") + shard_list());
  ASSERT_EQ(merge.exit_code, 0) << merge.text;
  expect_same_results(whole(), *root_ / "merged");
  // the merged folder names the engines that made it, as each shard's does (harness/records/engines_file.h)
  EXPECT_TRUE(fs::exists(*root_ / "merged" / "engines.json"));
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
