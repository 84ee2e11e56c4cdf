// --resume reads runs.jsonl back (repair_and_list_runs): runs.csv is rebuilt with every value under its
// own header's column whatever the order or the gaps of a line's keys (a hand-edited or foreign line),
// and a line that is not a run's record (no job_id or verdict) is dropped so that its job runs again.
// (Damaged records, duplicates and missing run folders: suite_records_test.cpp.)
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "harness/records/reporters.h"
#include "harness/records/run_record.h"

namespace ib {
namespace resume_repair_test {

namespace fs = std::filesystem;

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.push_back("");
  return cells;
}

TEST(ResumeRepair, RowsAreLaidOutByTheHeaderWhateverTheKeyOrder) {
  const fs::path folder = fs::temp_directory_path() / ("impactbench_resume_repair_" + std::to_string(getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  std::ofstream(folder / "runs.jsonl")
      << R"({"verdict":"ok","impacts":3,"job_id":"s/reference/hertz","scenario":"s"})"
         "\n"
      << R"({"job_id":"s/reference/newton","scenario":"s"})"
         "\n"  // no verdict: not a record
      << R"({"job_id":"s/engine_a/hertz","verdict":"unstable","reason":"a, b","law":"hertz"})"
         "\n";
  for (const char* id : {"s/reference/hertz", "s/engine_a/hertz"}) {  // a run that ran has its folder
    fs::create_directories(folder / "runs" / id);
    std::ofstream(folder / "runs" / id / "summary.json") << "{}\n";
  }
  const auto ids = repair_and_list_runs(folder.string());
  EXPECT_EQ(ids, (std::set<std::string>{"s/reference/hertz", "s/engine_a/hertz"}));
  std::ifstream csv(folder / "runs.csv");
  std::string header, first, second, extra;
  std::getline(csv, header);
  std::getline(csv, first);
  std::getline(csv, second);
  EXPECT_FALSE(std::getline(csv, extra));
  const auto names = split(header);
  auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
  };
  ASSERT_EQ(names.size(), fields(RunRecord{}).size());
  const auto a = split(first);
  ASSERT_EQ(a.size(), names.size()) << first;
  EXPECT_EQ(a[column("job_id")], "s/reference/hertz");
  EXPECT_EQ(a[column("verdict")], "ok");
  EXPECT_EQ(a[column("impacts")], "3");
  EXPECT_EQ(a[column("law")], "");
  EXPECT_NE(second.find("unstable,\"a, b\""), std::string::npos) << second;  // reason quoted, after verdict
  fs::remove_all(folder);
}

}  // namespace resume_repair_test
}  // namespace ib
