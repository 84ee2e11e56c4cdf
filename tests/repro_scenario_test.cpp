// `impactbench repro RUN OUT` (cli/command_repro.cpp) reproduces the run it was given or says why not: another
// scenario, or the same file changed since the run, is refused with exit 2, named; it works from any folder (the
// run's scenario path was relative to where it ran); and repro.sh finds impactbench on PATH or next to itself.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "command_test_support.h"

namespace repro_scenario_test {

namespace fs = std::filesystem;
using Output = ib::test::CommandOutput;

// A short reference run of the free vibration, its scenario named by a path relative to `from`.
struct RunFolder {
  fs::path root, run;
};

RunFolder reference_run(const std::string& name) {
  RunFolder folder;
  folder.root = ib::test::fresh_command_folder("impactbench_repro_scenario_", name);
  fs::create_directories(folder.root / "scenarios");
  fs::copy_file(ib::test::paper_scenario("free_vibration"), folder.root / "scenarios" / "free_vibration.toml");
  folder.run = folder.root / "run";
  const Output ran = ib::test::run_command("cd " + folder.root.string() + " && " + IMPACTBENCH_EXECUTABLE +
                                           " run scenarios/free_vibration.toml --engine reference --law hertz "
                                           "--duration 0.3 --out run 2>&1");
  EXPECT_EQ(ran.exit_code, 0) << ran.text;
  return folder;
}

// `impactbench ARGUMENTS` run from the folder `cwd`.
Output impactbench_in(const fs::path& cwd, const std::string& arguments) {
  return ib::test::run_command("cd " + cwd.string() + " && " + IMPACTBENCH_EXECUTABLE + " " + arguments + " 2>&1");
}

TEST(ReproScenario, AnotherScenarioIsRefusedAndNamed) {
  const RunFolder folder = reference_run("other");
  const std::string resonance = ib::test::paper_scenario("resonance");
  const Output repro = impactbench_in(folder.root, "repro run out --scenario " + resonance);
  EXPECT_EQ(repro.exit_code, 2) << repro.text;
  EXPECT_NE(repro.text.find(resonance + ": scenario 'resonance', but run ran 'free_vibration'"), std::string::npos)
      << repro.text;
  EXPECT_FALSE(fs::exists(folder.root / "out"));
  fs::remove_all(folder.root);
}

TEST(ReproScenario, TheSameFileChangedSinceTheRunIsRefusedByItsDigest) {
  const RunFolder folder = reference_run("changed");
  std::ofstream(folder.root / "scenarios" / "free_vibration.toml", std::ios::app) << "\n# edited after the run\n";
  const Output repro = impactbench_in(folder.root, "repro run out");
  EXPECT_EQ(repro.exit_code, 2) << repro.text;
  EXPECT_NE(repro.text.find("scenarios/free_vibration.toml: its content (digest "), std::string::npos) << repro.text;
  EXPECT_NE(repro.text.find("is not the file run ran (summary.json scenario_digest "), std::string::npos) << repro.text;
  fs::remove_all(folder.root);
}

TEST(ReproScenario, WorksFromAnyFolderAndItsScriptFindsImpactbenchNextToItselfOrOnPath) {
  const RunFolder folder = reference_run("anywhere");
  const fs::path elsewhere = folder.root / "elsewhere";
  fs::create_directories(elsewhere);
  // from another folder the recorded relative path names nothing: the run's absolute path does
  const Output repro = impactbench_in(elsewhere, "repro " + folder.run.string() + " out");
  ASSERT_EQ(repro.exit_code, 0) << repro.text;
  const fs::path script = elsewhere / "out" / "repro.sh";
  std::ifstream in(script);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.find(IMPACTBENCH_EXECUTABLE), std::string::npos) << "repro.sh holds this build's path:\n" << text;

  const std::string no_impactbench = "env -u IMPACTBENCH PATH=/usr/bin:/bin ";
  const Output missing = ib::test::run_command(no_impactbench + "sh " + script.string() + " 2>&1");
  EXPECT_EQ(missing.exit_code, 127) << missing.text;
  EXPECT_NE(missing.text.find("repro.sh: impactbench not found: put it on PATH or next to this script"),
            std::string::npos)
      << missing.text;

  fs::create_directories(folder.root / "bin");
  fs::create_symlink(IMPACTBENCH_EXECUTABLE, folder.root / "bin" / "impactbench");
  const Output on_path = ib::test::run_command("env -u IMPACTBENCH PATH=" + (folder.root / "bin").string() +
                                               ":/usr/bin:/bin sh " + script.string() + " 2>&1");
  EXPECT_EQ(on_path.exit_code, 0) << on_path.text;
  EXPECT_TRUE(fs::exists(elsewhere / "out" / "rerun" / "summary.json"));

  // $IMPACTBENCH as a path relative to where the script is run from (it changes to its own folder after)
  const std::string relative = fs::relative(IMPACTBENCH_EXECUTABLE, folder.root).string();
  const Output relative_path = ib::test::run_command("cd " + folder.root.string() + " && env IMPACTBENCH=" + relative +
                                                     " PATH=/usr/bin:/bin sh " + script.string() + " 2>&1");
  EXPECT_EQ(relative_path.exit_code, 0) << relative << ": " << relative_path.text;

  fs::create_symlink(IMPACTBENCH_EXECUTABLE, elsewhere / "out" / "impactbench");
  const Output next_to_it = ib::test::run_command(no_impactbench + "sh " + script.string() + " 2>&1");
  EXPECT_EQ(next_to_it.exit_code, 0) << next_to_it.text;  // and the earlier rerun replaced, not refused
  fs::remove_all(folder.root);
}

}  // namespace repro_scenario_test
