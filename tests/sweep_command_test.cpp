// `impactbench sweep` as a user runs it: bad input refused with exit 2 naming the option, the value and
// what is allowed, before anything runs; a sweep's tables; an interrupted sweep continued with --resume.
#include <gtest/gtest.h>

#include <csignal>
#include <sstream>
#include <thread>

#include "command_test_support.h"

namespace ib::test {
namespace sweep_command_test {

namespace fs = std::filesystem;

CommandOutput sweep(const std::string& arguments) {
  return run_impactbench_logged_as("sweep " + arguments, "sweep_command_");
}

TEST(SweepCommand, BadInputExitsWith2NamingTheOptionTheValueAndWhatIsAllowed) {
  const fs::path out = fresh_command_folder("sweep_bad_", "out");
  const std::string scenario = paper_scenario("resonance");
  const struct {
    std::string arguments, expected;
  } cases[] = {
      {scenario + " --ratios 1.2:0.9:0.01", "--ratios 1.2:0.9:0.01: allowed: 0.05 <= FROM <= TO <= 20"},
      {scenario + " --ratios 0.9:1.0", "--ratios 0.9:1.0: allowed: FROM:TO:STEP"},
      {scenario + " --start sideways", "--start sideways: allowed: rest, up, down or both"},
      {scenario + " --duration 0", "--duration 0: allowed: 0 < x <= 3600 s"},
      {scenario + " --window 100", "--window 100: allowed: at most the run (--duration 60 s)"},
      {scenario + " --engines nosuchengine", "nosuchengine"},
      {scenario + " --laws glue", "glue"},
      {paper_scenario("free_vibration"), "a sweep needs a motor"},
      {scenario + " --reference-ensemble 0", "--reference-ensemble 0: allowed: 1 <= x <= 100"},
      {scenario + " --reference-ensemble 8 --ensemble-step 1e-5", "--ensemble-step 1e-05: allowed: above 0 m"},
      {scenario + " --reference-ensemble 8 --start up",
       "the ensemble's starts are from rest; needs rest among --start"},
      {scenario + " --start rest --reference-ensemble 8 --ensemble-ratios 1.3",
       "--ensemble-ratios 1.3: 1.3 is not one of the sweep's ratios"},
      {scenario + " --ensemble-ratios 1.0", "--ensemble-ratios 1.0: needs --reference-ensemble N > 1"},
  };
  for (const auto& c : cases) {
    const CommandOutput result = sweep(c.arguments + " --out " + out.string());
    EXPECT_EQ(result.exit_code, 2) << c.arguments << "\n" << result.text;
    EXPECT_NE(result.text.find(c.expected), std::string::npos) << c.arguments << "\n" << result.text;
  }
  EXPECT_FALSE(fs::exists(out / "sweep.csv"));
}

TEST(SweepCommand, WritesItsTablesAndAResumeWithOtherSettingsIsRefused) {
  const fs::path out = fresh_command_folder("sweep_tables_", "out");
  const std::string common = paper_scenario("resonance") +
                             " --ratios 0.99:1.0:0.01 --start up --duration 3 "
                             "--rest-duration 3 --out " +
                             out.string();
  const CommandOutput first = sweep(common + " --window 2");
  ASSERT_EQ(first.exit_code, 0) << first.text;
  std::ifstream table(out / "sweep.csv");
  std::string header, row;
  std::getline(table, header);
  EXPECT_EQ(
      header.rfind("id,scenario,engine,engine_version,law,options,contact_path,law_simulated,time_step_s,start,ratio,"
                   "ensemble_start,ensemble_starts,initial_displacement_offset_m,motor_frequency_hz,",
                   0),
      0u);
  int rows = 0;
  while (std::getline(table, row)) ++rows;
  EXPECT_EQ(rows, 2);
  EXPECT_TRUE(fs::exists(out / "poincare.csv"));
  // the sweep's folder holds the metrics it measured, as a suite's does (harness/records/metrics_file.h)
  EXPECT_TRUE(fs::exists(out / "metrics.json"));
  const CommandOutput again = sweep(common + " --window 2");  // the folder holds a sweep: --resume or another --out
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_NE(again.text.find("--resume"), std::string::npos) << again.text;
  const CommandOutput other = sweep(common + " --resume --window 1");
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_NE(other.text.find("window_s differ"), std::string::npos) << other.text;
  const CommandOutput same = sweep(common + " --window 2 --resume");
  EXPECT_EQ(same.exit_code, 0) << same.text;
  EXPECT_NE(same.text.find("0 run now, 2 already recorded"), std::string::npos) << same.text;
}

// A sweep records its scenario file's content (sweep.json's scenario_digest): the same file name edited between
// a sweep and its --resume is another sweep, refused, not continued into a mix of two.
TEST(SweepCommand, AResumeAfterItsScenarioFileWasEditedIsRefused) {
  const fs::path out = fresh_command_folder("sweep_edited_", "out");
  const fs::path scenario = out.string() + ".toml";
  fs::copy_file(paper_scenario("resonance"), scenario, fs::copy_options::overwrite_existing);
  const std::string common = scenario.string() +
                             " --engines reference --ratios 0.99:1.0:0.01 --start up --duration 3 "
                             "--rest-duration 3 --window 2 --out " +
                             out.string();
  const CommandOutput first = sweep(common);
  ASSERT_EQ(first.exit_code, 0) << first.text;
  std::stringstream text;
  text << std::ifstream(scenario).rdbuf();
  const std::string original = text.str();
  const std::size_t at = original.find("damping_ratio = 0.003");
  ASSERT_NE(at, std::string::npos);
  std::ofstream(scenario) << std::string(original).replace(at, 21, "damping_ratio = 0.004");
  const CommandOutput edited = sweep(common + " --resume");
  EXPECT_EQ(edited.exit_code, 2) << edited.text;
  EXPECT_NE(edited.text.find("scenario_digest differ"), std::string::npos) << edited.text;
  std::ofstream(scenario) << original;
  const CommandOutput same = sweep(common + " --resume");
  EXPECT_EQ(same.exit_code, 0) << same.text;
  fs::remove_all(out);
  fs::remove(scenario);
}

}  // namespace sweep_command_test
}  // namespace ib::test
