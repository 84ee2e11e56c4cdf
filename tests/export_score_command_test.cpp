// `impactbench export --engine reference` (the modal model as JSON) and `impactbench score` (a run folder
// measured by the harness's metric code) as a user meets them: score gives a reference run's own runs.csv
// figures back, a run against itself has zero errors, and bad input ends with exit code 2 naming the problem.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "command_test_support.h"

namespace export_score_command_test {

namespace fs = std::filesystem;
using Output = ib::test::CommandOutput;

Output impactbench(const std::string& arguments) {
  return ib::test::run_impactbench_logged_as(arguments, "impactbench_export_score_");
}
std::string paper(const std::string& name) { return ib::test::paper_scenario(name); }
fs::path fresh_folder(const std::string& name) {
  return ib::test::fresh_command_folder("impactbench_export_score_", name);
}

TEST(ExportCommand, WritesTheReferencesModalModel) {
  const fs::path dir = fresh_folder("export");
  fs::create_directories(dir);
  const fs::path file = dir / "model.json";
  const Output out = impactbench("export " + paper("resonance") +
                                 " --engine reference --law viscoelastic --rate 2048 "
                                 "--option n=4 --option rtol=1e-10 --out " +
                                 file.string());
  ASSERT_EQ(out.exit_code, 0) << out.text;
  const auto model = nlohmann::json::parse(std::ifstream(file));
  EXPECT_EQ(model["format"], "impactbench modal model 1");
  EXPECT_EQ(model["omega_rad_s"].size(), 8u);  // 4 modes per frame, stacked
  EXPECT_EQ(model["contact_law"]["name"], "viscoelastic");
  EXPECT_TRUE(model.contains("motor"));
  EXPECT_EQ(model["output_rate_hz"].get<double>(), 2048);
  EXPECT_EQ(model["duration_s"].get<double>(), 100);
  EXPECT_EQ(model["series_start_s"].get<double>(), 86);  // the scoring window, as `run` samples it
  EXPECT_EQ(model["reference_settings"]["rtol"].get<double>(), 1e-10);
  fs::remove_all(dir);
}

TEST(ExportCommand, BadInputExitsWithTwoAndSaysWhy) {
  Output out = impactbench("export " + paper("resonance") + " --engine reference --dt 1e-4");
  EXPECT_EQ(out.exit_code, 2);
  EXPECT_NE(out.text.find("--dt"), std::string::npos) << out.text;
  out = impactbench("export " + paper("resonance") + " --engine reference --option n=0");
  EXPECT_EQ(out.exit_code, 2);
  EXPECT_NE(out.text.find("n=0"), std::string::npos) << out.text;
  out = impactbench("export " + paper("resonance") + " --engine abacus");
  EXPECT_EQ(out.exit_code, 2);
  EXPECT_NE(out.text.find("allowed: reference"), std::string::npos) << out.text;
}

// The run's own figures back from its files (energy_change_relative needs E(0), which the files do not hold).
TEST(ScoreCommand, GivesARunsMetricsBackFromItsFiles) {
  const fs::path dir = fresh_folder("score");
  const std::string scenario = paper("free_vibration");
  Output out = impactbench("run " + scenario + " --engine reference --law hertz --out " + dir.string());
  ASSERT_EQ(out.exit_code, 0) << out.text;
  out = impactbench("score " + dir.string() + " --scenario " + scenario + " --reference " + dir.string() + " --json");
  ASSERT_EQ(out.exit_code, 0) << out.text;
  const auto scored = nlohmann::json::parse(out.text);
  const auto summary = nlohmann::json::parse(std::ifstream(dir / "summary.json"));
  int compared = 0;
  for (const auto& [name, value] : summary.items()) {
    if (!scored.contains(name) || value.is_string() || name == "energy_change_relative" || name.rfind("vs_", 0) == 0)
      continue;  // the reference run has no errors of its own; they are checked below
    ++compared;
    if (value.is_null()) {
      EXPECT_TRUE(scored[name].is_null()) << name;
    } else {
      ASSERT_TRUE(scored[name].is_number()) << name;
      // summary.json holds 9 significant digits, and score reads the series as written (9 digits): the
      // sensor peak, a difference of velocities, agrees to a few parts in 1e9.
      EXPECT_NEAR(scored[name].get<double>(), value.get<double>(), 2e-8 * std::abs(value.get<double>())) << name;
    }
  }
  EXPECT_GE(compared, 20);  // every metric of runs.csv
  EXPECT_GT(scored["impacts"].get<int>(), 0);
  for (const char* error :
       {"vs_reference_frame1_sensor_peak_relative_error", "vs_reference_contact_duration_relative_error",
        "vs_reference_frame1_displacement_relative_rms_error"})
    EXPECT_EQ(scored[error].get<double>(), 0) << error;  // a run against itself
  fs::remove_all(dir);
}

TEST(ScoreCommand, BadInputExitsWithTwoAndSaysWhy) {
  const fs::path dir = fresh_folder("score_missing");
  Output out = impactbench("score " + dir.string() + " --scenario " + paper("free_vibration"));
  EXPECT_EQ(out.exit_code, 2);
  EXPECT_NE(out.text.find((dir / "series.csv").string()), std::string::npos) << out.text;
  out = impactbench("score " + dir.string());
  EXPECT_EQ(out.exit_code, 2);
  EXPECT_NE(out.text.find("--scenario"), std::string::npos) << out.text;
}

}  // namespace export_score_command_test
