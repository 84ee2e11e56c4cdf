// `impactbench repro RUN OUT` (cli/command_repro.cpp): one run of a result folder made ready to rerun alone and to
// file with an engine's authors. Its repro.sh reruns the run: the same numbers, for a run of `run` and for a
// suite's ensemble member (a start displaced from the scenario's); a folder that is no run's is refused with
// exit 2, named.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "catalog_engines.h"
#include "command_test_support.h"

namespace repro_command_test {

namespace fs = std::filesystem;
using Output = ib::test::CommandOutput;

Output impactbench(const std::string& arguments) {
  return ib::test::run_impactbench_logged_as(arguments, "impactbench_repro_");
}
fs::path fresh_folder(const std::string& name) { return ib::test::fresh_command_folder("impactbench_repro_", name); }

nlohmann::json summary_of(const fs::path& run) { return nlohmann::json::parse(std::ifstream(run / "summary.json")); }

// The rerun's measured numbers are the run's (a run is deterministic: the same inputs give the same bits).
void expect_same_run(const fs::path& original, const fs::path& rerun) {
  const nlohmann::json a = summary_of(original), b = summary_of(rerun);
  for (const char* key : {"verdict", "impacts", "frame1_sensor_peak_acceleration_g", "frame2_true_peak_acceleration_g",
                          "contact_duration_mean_s", "mean_restitution", "time_step_s", "window_start_s",
                          "window_end_s", "initial_displacement_offset_m"})
    EXPECT_EQ(a[key], b[key]) << key;
}

// `sh OUT/repro.sh`, and the folder it ran into.
fs::path rerun(const fs::path& out) {
  const Output ran = ib::test::run_command("IMPACTBENCH=" + std::string(IMPACTBENCH_EXECUTABLE) + " sh " +
                                           (out / "repro.sh").string() + " 2>&1");
  EXPECT_TRUE(ran.exit_code == 0 || ran.exit_code == 1) << ran.text;  // 1: the run's own verdict was not ok
  return out / "rerun";
}

TEST(ReproCommand, ARunsReproRerunsItToTheSameNumbers) {
  const std::string engine = ib::test::command_engines().front();
  const fs::path dir = fresh_folder("run"), out = fresh_folder("out");
  const Output run = impactbench("run " + ib::test::paper_scenario("free_vibration") + " --engine " + engine +
                                 " --law hertz --dt 5e-5 --duration 0.5 --out " + (dir / "run").string());
  ASSERT_TRUE(run.exit_code == 0 || run.exit_code == 1) << run.text;
  const Output repro = impactbench("repro " + (dir / "run").string() + " " + out.string());
  ASSERT_EQ(repro.exit_code, 0) << repro.text;
  for (const char* file : {"scenario.toml", "repro.sh", "repro.json"}) EXPECT_TRUE(fs::exists(out / file)) << file;
  const nlohmann::json record = nlohmann::json::parse(std::ifstream(out / "repro.json"));
  EXPECT_EQ(record["engine"], engine);
  EXPECT_EQ(record["verdict"], summary_of(dir / "run")["verdict"]);
  if (!record["model_file"].get<std::string>().empty())
    EXPECT_TRUE(fs::exists(out / record["model_file"].get<std::string>()));
  expect_same_run(dir / "run", rerun(out));
  fs::remove_all(dir);
  fs::remove_all(out);
}

TEST(ReproCommand, AnEnsemblesDisplacedStartIsRerunFromItsOwnStart) {
  const std::string engine = ib::test::command_engines().front();
  const fs::path dir = fresh_folder("suite"), out = fresh_folder("member");
  const Output suite =
      impactbench("suite " + ib::test::paper_scenario("free_vibration") + " --engines reference," + engine +
                  " --laws hertz --dt 5e-5 --duration 0.5 --ensemble 2 --jobs 2 --out " + dir.string());
  ASSERT_TRUE(suite.exit_code == 0 || suite.exit_code == 1) << suite.text;
  fs::path member;
  for (const auto& entry : fs::recursive_directory_iterator(dir / "runs"))
    if (entry.path().filename() == "start=1" && entry.path().string().find("/" + engine + "/") != std::string::npos)
      member = entry.path();
  ASSERT_FALSE(member.empty()) << "no start=1 of " << engine << " in " << dir;
  ASSERT_NE(summary_of(member)["initial_displacement_offset_m"], 0.0);
  const Output repro = impactbench("repro " + member.string() + " " + out.string());
  ASSERT_EQ(repro.exit_code, 0) << repro.text;
  expect_same_run(member, rerun(out));
  fs::remove_all(dir);
  fs::remove_all(out);
}

TEST(ReproCommand, AFolderThatIsNoRunsIsRefusedAndNamed) {
  const fs::path dir = fresh_folder("empty"), out = fresh_folder("nothing");
  fs::create_directories(dir);
  const Output empty = impactbench("repro " + dir.string() + " " + out.string());
  EXPECT_EQ(empty.exit_code, 2) << empty.text;
  EXPECT_NE(empty.text.find(dir.string() + ": not a run's folder: it has no summary.json"), std::string::npos)
      << empty.text;
  std::ofstream(dir / "summary.json") << "{ cut";
  const Output damaged = impactbench("repro " + dir.string() + " " + out.string());
  EXPECT_EQ(damaged.exit_code, 2) << damaged.text;
  EXPECT_NE(damaged.text.find((dir / "summary.json").string() + ": not a run's record"), std::string::npos)
      << damaged.text;
  EXPECT_FALSE(fs::exists(out));
  fs::remove_all(dir);
}

}  // namespace repro_command_test
