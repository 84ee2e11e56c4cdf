// The sharded suite's tests' shared part (suite_sharding_test.cpp, shard_merge_errors_test.cpp): a small suite
// run whole and as shards through the command, each when a test first needs it, and the comparisons of two
// suite folders.
#pragma once

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
inline const std::set<std::string> kRunTimingFields(ib::timing_field_names().begin(), ib::timing_field_names().end());
inline const std::set<std::string> kStepTimingFields = {"probes_wall_time_s"};
constexpr int kShards = 3;

// The reference and the build's first two engines (tests/catalog_engines.h): sharding is the harness's, any engine
// does.
inline std::string engines() {
  return ib::test::engines_option("reference", ib::test::engines_among(ib::simulator_names()), 2);
}

inline std::string quoted(const fs::path& path) { return "'" + path.string() + "'"; }

inline std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A .jsonl file as key -> record without the timing fields; a key recorded twice fails the test.
inline std::map<std::string, Json> records(const fs::path& file, const std::string& key,
                                           const std::set<std::string>& timing) {
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
inline std::vector<std::string> cells_of(const std::string& line) {
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
inline std::map<std::string, std::vector<std::string>> csv_rows(const fs::path& file,
                                                                const std::set<std::string>& timing,
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
inline void expect_same_results(const fs::path& expected, const fs::path& actual, bool steps = false) {
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
inline void expect_engine_jobs_divided(const fs::path& whole, const std::vector<fs::path>& shards) {
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
inline fs::path copy_records(const fs::path& from, const fs::path& to) {
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
  inline static fs::path* root_ = nullptr;
  inline static std::map<fs::path, int>* done_ = nullptr;  // suites run so far: folder -> exit code
};

}  // namespace suite_sharding_test
