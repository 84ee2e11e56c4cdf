// The command line agrees with itself (issue 48): `--version` says which build this is; an unknown command is named
// as one; --option takes name=value and engine.name=value wherever the engine is known, in every command; `run`
// keeps a folder's run unless --force; the adaptive reference refuses --dt; a study part whose engine list leaves
// no engine is refused. Each refusal is exit 2 with the option or key, the value and what is allowed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "catalog_engines.h"
#include "command_test_support.h"

namespace command_line_test {

namespace fs = std::filesystem;
using Output = ib::test::CommandOutput;

Output impactbench(const std::string& arguments) {
  return ib::test::run_impactbench_logged_as(arguments, "impactbench_command_line_");
}
fs::path fresh_folder(const std::string& name) {
  return ib::test::fresh_command_folder("impactbench_command_line_", name);
}
bool says(const Output& out, const std::string& text) { return out.text.find(text) != std::string::npos; }

TEST(CommandLine, VersionNamesTheBuildAndEveryEnginesLibrary) {
  const Output out = impactbench("--version");
  ASSERT_EQ(out.exit_code, 0) << out.text;
  EXPECT_EQ(out.text.rfind("impactbench ", 0), 0u) << out.text;
  EXPECT_TRUE(says(out, " build\n")) << out.text;
  for (const std::string& engine : ib::test::command_engines())
    EXPECT_TRUE(says(out, "  " + engine + ": ")) << out.text;
}

TEST(CommandLine, AnUnknownCommandIsNamedWithTheCommandsAllowed) {
  const Output out = impactbench("sweeep scenarios/paper/resonance.toml");
  EXPECT_EQ(out.exit_code, 2) << out.text;
  EXPECT_TRUE(says(out, "impactbench: unknown command 'sweeep'; allowed: modes, run, suite,")) << out.text;
  EXPECT_TRUE(says(out, "study, engines")) << out.text;
}

// A short reference run of the free vibration into `out`, with `extra` arguments.
Output reference_run(const fs::path& out, const std::string& extra) {
  return impactbench("run " + ib::test::paper_scenario("free_vibration") + " --engine reference --law hertz " +
                     "--duration 0.3 --out " + out.string() + " " + extra);
}

std::string options_of(const fs::path& run) {
  return nlohmann::json::parse(std::ifstream(run / "summary.json"))["options"].get<std::string>();
}

TEST(CommandLine, RunTakesNameValueAndItsOwnEnginesDottedFormAlike) {
  const fs::path dir = fresh_folder("options");
  const Output plain = reference_run(dir / "plain", "--option n=3");
  ASSERT_EQ(plain.exit_code, 0) << plain.text;
  const Output dotted = reference_run(dir / "dotted", "--option reference.n=3");
  ASSERT_EQ(dotted.exit_code, 0) << dotted.text;
  EXPECT_EQ(options_of(dir / "plain"), "n=3");
  EXPECT_EQ(options_of(dir / "dotted"), "n=3");
  const std::string other = ib::test::command_engines().front();
  const Output wrong = reference_run(dir / "wrong", "--option " + other + ".n=3");
  EXPECT_EQ(wrong.exit_code, 2) << wrong.text;
  EXPECT_TRUE(says(wrong, "--option " + other + ".n=3: names engine '" + other +
                              "', but this runs reference; allowed: name=value or reference.name=value"))
      << wrong.text;
  fs::remove_all(dir);
}

TEST(CommandLine, RunKeepsAnEarlierRunUnlessForced) {
  const fs::path dir = fresh_folder("force");
  ASSERT_EQ(reference_run(dir, "").exit_code, 0);
  const Output again = reference_run(dir, "");
  EXPECT_EQ(again.exit_code, 2) << again.text;
  EXPECT_TRUE(says(again, "--out " + dir.string() +
                              ": holds a run already (summary.json); allowed: a new or empty "
                              "folder, or --force to replace that run"))
      << again.text;
  const Output forced = reference_run(dir, "--force --option n=3");
  EXPECT_EQ(forced.exit_code, 0) << forced.text;
  EXPECT_EQ(options_of(dir), "n=3");
  fs::remove_all(dir);
}

TEST(CommandLine, TheAdaptiveReferenceRefusesAStep) {
  const fs::path dir = fresh_folder("dt");
  const Output out = reference_run(dir, "--dt 1e-4");
  EXPECT_EQ(out.exit_code, 2) << out.text;
  EXPECT_TRUE(says(out, "--dt 0.0001: reference takes no fixed step (adaptive: ")) << out.text;
  EXPECT_TRUE(says(out, "allowed: no --dt with --engine reference, or a fixed-step engine")) << out.text;
  EXPECT_FALSE(fs::exists(dir / "summary.json"));
}

// A suite's --option: name=value where --engines names one engine, engine.name=value always.
TEST(CommandLine, ASuitesNameValueOptionNeedsItsEngineKnown) {
  const std::vector<std::string> engines = ib::test::command_engines();
  const std::string suite = "suite " + ib::test::paper_scenario("free_vibration") + " --laws hertz --duration 0.2 ";
  const fs::path dir = fresh_folder("suite");
  const Output one = impactbench(suite + "--engines reference --option n=3 --out " + (dir / "one").string());
  EXPECT_EQ(one.exit_code, 0) << one.text;
  std::ifstream runs(dir / "one" / "runs.csv");
  const std::string table((std::istreambuf_iterator<char>(runs)), std::istreambuf_iterator<char>());
  EXPECT_NE(table.find("n=3"), std::string::npos) << table;
  if (engines.size() >= 2) {
    const Output two = impactbench(suite + "--engines " + ib::test::engines_option("", engines, 2) +
                                   " --option links=4 --out " + (dir / "two").string());
    EXPECT_EQ(two.exit_code, 2) << two.text;
    EXPECT_TRUE(says(two, "--option links=4: which engine? --engines lists " + engines[0] + "," + engines[1] +
                              "; allowed: engine.name=value, e.g. " + engines[0] + ".links=4"))
        << two.text;
  }
  fs::remove_all(dir);
}

fs::path study_file(const std::string& name, const std::string& engines_keys) {
  const fs::path path = fresh_folder(name + ".toml");
  std::ofstream(path) << "[[suite]]\nname = \"free vibration\"\nscenarios = [\"scenarios/paper/free_vibration.toml\"]\n"
                      << engines_keys << "duration_s = 0.2\n";
  return path;
}

TEST(CommandLine, AStudyPartWithNoEngineLeftIsRefusedAtItsKey) {
  const fs::path empty = study_file("empty", "engines = []\n");
  const Output none = impactbench("study " + empty.string() + " --plan");
  EXPECT_EQ(none.exit_code, 2) << none.text;
  EXPECT_TRUE(says(none, empty.string() + ":4")) << none.text;
  EXPECT_TRUE(says(none, "suite 1.engines: leaves no engine to run")) << none.text;
  std::string every = "reference";
  for (const std::string& engine : ib::test::command_engines()) every += "\", \"" + engine;
  const fs::path skipped = study_file("skipped", "skip_engines = [\"" + every + "\"]\n");
  const Output all_skipped = impactbench("study " + skipped.string() + " --plan");
  EXPECT_EQ(all_skipped.exit_code, 2) << all_skipped.text;
  EXPECT_TRUE(says(all_skipped, "suite 1.skip_engines: leaves no engine to run")) << all_skipped.text;
  fs::remove(empty);
  fs::remove(skipped);
}

}  // namespace command_line_test
