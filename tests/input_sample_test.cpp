// A validation's input sample (harness/validation/input_sample.h): its first point is the nominal rig, each
// input's marginal over the sample has its distribution's mean and standard deviation (a Sobol' sequence fills
// each axis evenly), and the files it writes are the scenarios a study runs, written again unchanged on a resume.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "harness/records/run_files.h"
#include "harness/validation/input_sample.h"
#include "model/scenario.h"
#include "model/scenario_toml.h"
#include "scenario_files.h"

namespace ib {
namespace input_sample_test {

namespace fs = std::filesystem;
const std::string kPaperInputs = std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/paper_inputs.toml";

TEST(InputSample, TheFirstPointIsTheNominalRigAndEachMarginalHasItsDistributionsMoments) {
  const UncertainInputs inputs = load_uncertain_inputs(kPaperInputs);
  const int points = 256;
  const auto values = sobol_input_values(inputs, points);
  ASSERT_EQ(values.size(), static_cast<std::size_t>(points));
  for (std::size_t i = 0; i < inputs.inputs.size(); ++i) {
    const UncertainInput& input = inputs.inputs[i];
    EXPECT_DOUBLE_EQ(values[0][i], input.nominal) << input.name;
    double sum = 0, squares = 0;
    for (const auto& point : values) sum += point[i];
    const double mean = sum / points;
    for (const auto& point : values) squares += (point[i] - mean) * (point[i] - mean);
    const double deviation = std::sqrt(squares / (points - 1));
    // a random sample's mean would stray by sigma / 16 here; the sequence's by far less
    EXPECT_NEAR(mean, input.nominal, 0.02 * input.standard_deviation()) << input.name;
    EXPECT_NEAR(deviation / input.standard_deviation(), 1, 0.03) << input.name;
  }
}

TEST(InputSample, ItsFilesAreTheScenariosAtEachPointAndAResumeLeavesThemAsTheyAre) {
  const UncertainInputs inputs = load_uncertain_inputs(kPaperInputs);
  const fs::path folder = fs::temp_directory_path() / ("impactbench-input-sample-" + std::to_string(::getpid()));
  fs::remove_all(folder);
  const std::vector<std::string> cases = {testing::paper_file("resonance"), testing::paper_file("free_vibration")};
  const InputSampleFiles files = write_input_sample(inputs, cases, 3, folder.string());
  ASSERT_EQ(files.scenario_files.size(), 6u);
  EXPECT_EQ(fs::path(files.scenario_files[4]).filename(), "free_vibration_p001.toml");
  const auto values = sobol_input_values(inputs, 3);
  const Scenario second = load_scenario(files.scenario_files[1]);
  EXPECT_EQ(second.name, "resonance_p001");
  std::size_t gap = 0;
  while (inputs.inputs[gap].name != "gap_m") ++gap;
  EXPECT_DOUBLE_EQ(second.gap_m, values[1][gap]);
  const std::string csv = read_text_file((folder / "sample.csv").string());
  EXPECT_EQ(csv.substr(0, csv.find('\n')).find("case,point,scenario,scenario_file,frame1_column_thickness_m"), 0u);
  EXPECT_NE(csv.find("\nfree_vibration,2,free_vibration_p002,"), std::string::npos) << csv;
  EXPECT_TRUE(fs::exists(folder / "inputs.json"));
  const auto written = fs::last_write_time(files.scenario_files[0]);
  write_input_sample(inputs, cases, 3, folder.string());
  EXPECT_EQ(fs::last_write_time(files.scenario_files[0]), written);
  fs::remove_all(folder);
}

}  // namespace input_sample_test
}  // namespace ib
