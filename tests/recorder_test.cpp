// The recorder (harness/jobs/recorder.h), one for suites and sweeps: a unit's row, left in its folder by its
// process, reaches the campaign's tables as the unit ends (appended, header once, its row files gone) or in the
// plan's order (written again from the folders, whatever order they finished in).
#include "harness/jobs/recorder.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace ib {
namespace recorder_test {

namespace fs = std::filesystem;

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

class Recorder : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = ::testing::TempDir() + "/recorder_" + std::to_string(::getpid());
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }
  std::string unit(const std::string& id) {
    const std::string folder = root_ + "/runs/" + id;
    fs::create_directories(folder);
    return folder;
  }
  std::string root_;
};

TEST_F(Recorder, CollectsARowAsItsUnitEnds) {
  const ResultTable table{root_, "runs"};
  for (const std::string id : {"b", "a"}) {  // in the order they end
    const std::string folder = unit(id);
    std::ofstream(folder + "/row.jsonl") << "{\"job_id\":\"" << id << "\",\"peak_g\":1.5}\n";
    std::ofstream(folder + "/row.csv") << id << ",1.5\n";
    EXPECT_EQ(collect_row(table, "job_id,peak_g\n", folder), "{\"job_id\":\"" + id + "\",\"peak_g\":1.5}\n");
    EXPECT_FALSE(fs::exists(folder + "/row.jsonl")) << "collected once: its files go";
    EXPECT_FALSE(fs::exists(folder + "/row.csv"));
  }
  EXPECT_EQ(text_of(root_ + "/runs.csv"), "job_id,peak_g\nb,1.5\na,1.5\n");
  EXPECT_EQ(text_of(root_ + "/runs.jsonl"), "{\"job_id\":\"b\",\"peak_g\":1.5}\n{\"job_id\":\"a\",\"peak_g\":1.5}\n");
}

TEST_F(Recorder, WritesTheTablesInThePlansOrder) {
  const ResultTable table{root_, "sweep"};
  const std::string first = unit("r0.90"), second = unit("r0.95"), missing = unit("r1.00");
  // the second finished first; the third not at all
  std::ofstream(second + "/row.json") << R"({"ratio":0.95,"regime":"1/1, \"single\"","warnings":["slow"]})";
  std::ofstream(second + "/poincare.csv") << "ratio,x_m\n0.95,1e-3\n0.95,2e-3\n";
  std::ofstream(first + "/row.json") << R"({"ratio":0.9,"regime":null,"warnings":[]})";
  std::ofstream(first + "/poincare.csv") << "ratio,x_m\n0.9,5e-4\n";
  EXPECT_EQ(write_table_in_plan_order(table, {first, second, missing}, "row.json", {"poincare.csv"}), 2);
  EXPECT_EQ(text_of(root_ + "/sweep.csv"), "ratio,regime\n0.9,\n0.95,\"1/1, \"\"single\"\"\"\n")
      << "a list is in the JSON lines alone; null is an empty cell; text is escaped";
  EXPECT_EQ(text_of(root_ + "/sweep.jsonl"), R"({"ratio":0.9,"regime":null,"warnings":[]})"
                                             "\n"
                                             R"({"ratio":0.95,"regime":"1/1, \"single\"","warnings":["slow"]})"
                                             "\n");
  EXPECT_EQ(text_of(root_ + "/poincare.csv"), "ratio,x_m\n0.9,5e-4\n0.95,1e-3\n0.95,2e-3\n") << "one header";
  std::ofstream(missing + "/row.json") << "[1, 2]";
  EXPECT_THROW(write_table_in_plan_order(table, {first, missing}, "row.json", {}), std::runtime_error)
      << "a row that is not a JSON object";
}

}  // namespace recorder_test
}  // namespace ib
