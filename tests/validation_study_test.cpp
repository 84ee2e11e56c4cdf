// A study's [[validation]] part (harness/validation/validation_part.h) through the command: each published case
// at every sample point run by the reference into OUT/validation/NAME (the study's own tables untouched), its
// sample beside, a resume running nothing twice, and its mistakes named (exit 2) before anything runs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "command_test_support.h"

namespace validation_study_test {

namespace fs = std::filesystem;

fs::path study_file(const std::string& name, const std::string& text) {
  return ib::test::temporary_toml_file("impactbench-validation-", name, text);
}

ib::test::CommandOutput study(const std::string& arguments) {
  return ib::test::run_impactbench_logged_as("study " + arguments, "validation-study-test-");
}

int lines_of(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  int lines = 0;
  while (std::getline(in, line)) ++lines;
  return lines;
}

// Two cases at three points, a fraction of a second each: the pre-resonance (a motor) and the free vibration (none);
// beside them each case from two starts and once at tight tolerances: 6 + 4 + 2 runs.
std::string tiny_validation(const std::string& extra = "") {
  return R"([[validation]]
name = "tiny"
scenarios = ["scenarios/paper/pre_resonance.toml", "scenarios/paper/free_vibration.toml"]
inputs = "scenarios/paper_inputs.toml"
points = 3
nominal_starts = 2
duration_s = 0.3
window_s = 0.2
)" + extra;
}

TEST(ValidationStudy, EachCaseRunsAtEveryPointIntoItsOwnFolderAndAResumeRunsNothingTwice) {
  const fs::path folder = ib::test::fresh_command_folder("impactbench-validation-", "run");
  const fs::path file = study_file("run", tiny_validation());
  const auto plan = study(file.string() + " --plan --out " + folder.string());
  ASSERT_EQ(plan.exit_code, 0) << plan.text;
  EXPECT_NE(plan.text.find("3 points of"), std::string::npos) << plan.text;
  EXPECT_NE(plan.text.find("  validation \"tiny\": 12 runs, about "), std::string::npos) << plan.text;
  EXPECT_NE(plan.text.find("\ntotal: 12 runs, about "), std::string::npos) << plan.text;  // counted in the total
  const auto first = study(file.string() + " --no-report --out " + folder.string());
  ASSERT_EQ(first.exit_code, 0) << first.text;
  const fs::path part = folder / "validation" / "tiny";
  EXPECT_EQ(lines_of(part / "runs.csv"), 1 + 12);
  EXPECT_EQ(lines_of(part / "sample.csv"), 1 + 6);
  EXPECT_TRUE(fs::exists(part / "inputs.json"));
  EXPECT_TRUE(fs::exists(part / "scenarios" / "pre_resonance" / "pre_resonance_p002.toml"));
  EXPECT_FALSE(fs::exists(folder / "runs.csv"));  // no suite: the study's own tables hold no sample point
  std::ifstream runs(part / "runs.csv");
  std::stringstream text;
  text << runs.rdbuf();
  EXPECT_NE(text.str().find("pre_resonance_p001"), std::string::npos);
  const std::string recorded = text.str();
  const auto again = study(file.string() + " --no-report --resume --out " + folder.string());
  ASSERT_EQ(again.exit_code, 0) << again.text;
  EXPECT_NE(again.text.find("validation \"tiny\": recorded in " + part.string() + ", 0 unstable or failed there"),
            std::string::npos)
      << again.text;
  EXPECT_EQ(lines_of(part / "runs.csv"), 1 + 12);
  std::ifstream runs_again(part / "runs.csv");
  std::stringstream text_again;
  text_again << runs_again.rdbuf();
  EXPECT_EQ(text_again.str(), recorded);  // nothing run again
  fs::remove(file);
  fs::remove_all(folder);
}

TEST(ValidationStudy, MistakesAreNamedBeforeAnythingRuns) {
  const fs::path folder = ib::test::fresh_command_folder("impactbench-validation-", "bad");
  const std::string no_points = tiny_validation();
  const std::string zero = no_points.substr(0, no_points.find("points = 3")) + "points = 0\n" +
                           no_points.substr(no_points.find("duration_s"));
  const auto bad_points = study(study_file("zero", zero).string() + " --no-report --out " + folder.string());
  EXPECT_EQ(bad_points.exit_code, 2) << bad_points.text;
  EXPECT_NE(bad_points.text.find(":5: validation 1.points = 0: not allowed; allowed: an integer >= 1"),
            std::string::npos)
      << bad_points.text;
  const fs::path inputs =
      fs::temp_directory_path() / ("impactbench-validation-" + std::to_string(::getpid()) + "_inputs.toml");
  std::ofstream(inputs) << "[inputs]\ndescription = \"x\"\n\n[[input]]\nname = \"gap_m\"\nkeys = [\"rig.gap\"]\n"
                           "nominal = 1e-3\ndistribution = \"uniform\"\nhalf_width = 1e-4\nsource = \"x\"\n";
  const std::string typo =
      "[[validation]]\nname = \"typo\"\nscenarios = [\"scenarios/paper/resonance.toml\"]\n"
      "inputs = \"" +
      inputs.string() + "\"\n";
  const auto bad_key = study(study_file("typo", typo).string() + " --no-report --out " + folder.string());
  EXPECT_EQ(bad_key.exit_code, 2) << bad_key.text;
  EXPECT_NE(bad_key.text.find(inputs.string() + ":4:"), std::string::npos) << bad_key.text;
  EXPECT_NE(bad_key.text.find("rig.gap"), std::string::npos) << bad_key.text;
  const auto engines = study(study_file("engines", tiny_validation("engines = [\"reference\"]\n")).string() +
                             " --no-report --out " + folder.string());
  EXPECT_EQ(engines.exit_code, 2) << engines.text;
  EXPECT_NE(engines.text.find("engines: unknown key; allowed keys in [[validation]]"), std::string::npos)
      << engines.text;
  EXPECT_FALSE(fs::exists(folder / "validation"));
  fs::remove(inputs);
  for (const char* name : {"zero", "typo", "engines"})
    fs::remove(fs::temp_directory_path() /
               ("impactbench-validation-" + std::to_string(::getpid()) + "-" + name + ".toml"));
}

}  // namespace validation_study_test
