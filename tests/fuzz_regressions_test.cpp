// Every input the fuzzers found a problem with (tests/data/fuzz_regressions/<target>/) and every seed
// they start from (tests/data/fuzz_seeds/<target>/) goes through the same reader as in fuzz/, in the
// normal build: each is read, or refused with a message that names the file; never a crash, a
// sanitizer report (in build-sanitize/) or another kind of exception.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "entries.h"

namespace ib {
namespace fuzz_regressions_test {

namespace fs = std::filesystem;

const fs::path kData = IMPACTBENCH_TEST_DATA_DIR;

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The files of tests/data/<kind>/<target>/, sorted; none when the folder does not exist.
std::vector<fs::path> inputs(const std::string& kind, const std::string& target) {
  std::vector<fs::path> files;
  const fs::path folder = kData / kind / target;
  if (fs::is_directory(folder))
    for (const auto& entry : fs::directory_iterator(folder))
      if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

// Feeds every input of a target; an error must start with the name of the file read.
void feed_all(const std::string& target, const std::string& file_name,
              const std::function<std::string(const std::string&)>& feed, std::size_t at_least) {
  std::size_t fed = 0;
  for (const std::string kind : {"fuzz_seeds", "fuzz_regressions"}) {
    for (const fs::path& input : inputs(kind, target)) {
      SCOPED_TRACE(input.string());
      std::string error;
      ASSERT_NO_THROW(error = feed(read_bytes(input)));
      if (!error.empty()) {
        EXPECT_EQ(error.rfind(file_name + ":", 0), 0u) << error;
      }
      ++fed;
    }
  }
  EXPECT_GE(fed, at_least) << "the seeds of " << target << " are missing";
}

TEST(FuzzRegressions, ScenarioFilesAreReadOrRefusedWithTheFileNamed) {
  feed_all(
      "fuzz_scenario_toml", "fuzz.toml", [](const std::string& text) { return fuzz::feed_scenario_toml(text); }, 1);
}

TEST(FuzzRegressions, AcceptedScenariosGiveTheirFrequencies) {
  feed_all(
      "fuzz_scenario_frequencies", "fuzz.toml",
      [](const std::string& text) { return fuzz::feed_scenario_frequencies(text); }, 1);
}

TEST(FuzzRegressions, SavedSeriesAreReadOrRefusedWithTheFileNamed) {
  feed_all(
      "fuzz_series_csv", "series.csv", [](const std::string& text) { return fuzz::feed_series_csv(text); }, 1);
}

TEST(FuzzRegressions, SavedEventsAreReadOrRefusedWithTheFileNamed) {
  feed_all(
      "fuzz_events_csv", "events.csv", [](const std::string& text) { return fuzz::feed_events_csv(text); }, 1);
}

TEST(FuzzRegressions, SavedRunsAreRepairedForResume) {
  const std::string folder =
      (fs::temp_directory_path() / ("impactbench_fuzz_regressions_" + std::to_string(getpid()))).string();
  feed_all(
      "fuzz_runs_jsonl", "runs.jsonl", [&](const std::string& text) { return fuzz::feed_runs_jsonl(text, folder); }, 1);
  fs::remove_all(folder);
}

}  // namespace fuzz_regressions_test
}  // namespace ib
