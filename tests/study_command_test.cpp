// `impactbench study FILE`: a study file's parts checked as the commands' options are (one code path, one
// set of ranges), bad keys named with their file and line, and a study's results equal to those of the
// commands it stands for.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "command_test_support.h"
#include "simulators/catalog.h"

namespace study_command_test {

namespace fs = std::filesystem;
using ib::test::run_impactbench_logged_as;

// A study file of this test in the temporary folder.
fs::path study_file(const std::string& name, const std::string& text) {
  return ib::test::temporary_toml_file("impactbench-study-", name, text);
}

ib::test::CommandOutput study(const std::string& arguments) {
  return run_impactbench_logged_as("study " + arguments, "study-test-");
}

// The plan's total line, "total: N runs ..., about X s of CPU, ...": N (-1 when there is no such line) and X (-1).
int planned_runs(const std::string& plan) {
  const std::size_t total = plan.find("\ntotal: ");
  return total == std::string::npos ? -1 : std::stoi(plan.substr(total + 8));
}
double planned_cpu_s(const std::string& plan) {
  const std::size_t total = plan.find("\ntotal: ");
  const std::size_t about = total == std::string::npos ? total : plan.find(", about ", total);
  if (about == std::string::npos) return -1;
  const double value = std::stod(plan.substr(about + 8));
  const std::size_t unit = plan.find_first_of("sm", plan.find(' ', about + 8));
  return plan[unit] == 'm' ? 60 * value : value;  // "12 min" or "3.4 s"
}

const char* kFreeVibration = R"([[suite]]
name = "free vibration"
scenarios = ["scenarios/paper/free_vibration.toml"]
engines = ["reference"]
laws = ["hertz", "newton"]
duration_s = 0.5
)";

// A sweep of the reference over two ratios, short: a study's sweep part.
const char* kCoarseSweep = R"([[sweep]]
name = "coarse"
scenario = "scenarios/paper/resonance.toml"
ratios = "0.95:1.00:0.05"
starts = ["up"]
engines = ["reference"]
rest_duration_s = 2
duration_s = 2
window_s = 1
)";

TEST(StudyFile, TheShippedStudiesAreValidAndAllMeansEveryEngineOfTheBuild) {
  for (const char* name : {"default", "full"}) {
    const auto out = study(std::string(IMPACTBENCH_SOURCE_DIR) + "/studies/" + name + ".toml --plan");
    ASSERT_EQ(out.exit_code, 0) << name << ": " << out.text;
    std::string every_engine;
    for (const std::string& engine : ib::simulator_names()) every_engine += (every_engine.empty() ? "" : ",") + engine;
    EXPECT_NE(out.text.find("engines " + every_engine + ";"), std::string::npos) << name << ": " << out.text;
    EXPECT_NE(out.text.find("laws hertz,viscoelastic,newton;"), std::string::npos) << out.text;
    EXPECT_NE(out.text.find("; starts "), std::string::npos)
        << name << " runs the resonance as an ensemble: " << out.text;
    // under each part its runs and CPU estimate, then the total (every engine of the build has a measured cost)
    EXPECT_NE(out.text.find("\n  suite \"resonance"), std::string::npos) << name << ": " << out.text;
    EXPECT_GT(planned_runs(out.text), 100) << name << ": " << out.text;
    EXPECT_GT(planned_cpu_s(out.text), 60) << name << ": " << out.text;
    EXPECT_EQ(out.text.find("no measured cost"), std::string::npos) << name << ": " << out.text;
  }
  // The cluster's study names its engines (Simbody's sweep first, the costliest): a build without one of them
  // refuses it, as it should.
  if (ib::simulator_names().size() == 7) {
    const auto out = study(std::string(IMPACTBENCH_SOURCE_DIR) + "/studies/cluster.toml --plan");
    ASSERT_EQ(out.exit_code, 0) << out.text;
    EXPECT_NE(out.text.find("search \"stiff and extreme cases, two steps per octave\""), std::string::npos) << out.text;
  }
}

// studies/smoke.toml, the one-minute loop (docs/studies.md, "The smoke study"): every engine of this build on both
// contact paths under every law, and a total line with a positive CPU estimate.
TEST(StudyFile, TheSmokeStudyNamesEveryEngineAndEveryLaw) {
  const auto out = study(std::string(IMPACTBENCH_SOURCE_DIR) + "/studies/smoke.toml --plan");
  ASSERT_EQ(out.exit_code, 0) << out.text;
  std::string every_engine;
  for (const std::string& engine : ib::simulator_names()) every_engine += (every_engine.empty() ? "" : ",") + engine;
  for (const char* part : {"suite \"resonance, ", "suite \"free vibration, "}) {
    const std::size_t line = out.text.find(part);
    ASSERT_NE(line, std::string::npos) << part << " in: " << out.text;
    const std::string text = out.text.substr(line, out.text.find('\n', line) - line);
    EXPECT_NE(text.find("engines " + every_engine + ";"), std::string::npos) << text;
    EXPECT_NE(text.find("laws hertz,viscoelastic,newton;"), std::string::npos) << text;
    EXPECT_NE(text.find("paths matched,native;"), std::string::npos) << text;
  }
  EXPECT_GT(planned_cpu_s(out.text), 0) << out.text;
}

TEST(StudyFile, SkipEnginesLeavesThemOutOfAll) {
  const fs::path file = study_file("skip", R"([[suite]]
scenarios = ["scenarios/paper/resonance.toml"]
engines = "all"
skip_engines = ["reference"]
)");
  const auto out = study(file.string() + " --plan");
  fs::remove(file);
  ASSERT_EQ(out.exit_code, 0) << out.text;
  const std::vector<std::string> names = ib::simulator_names();
  EXPECT_EQ(out.text.find("engines reference"), std::string::npos) << out.text;
  if (names.size() > 1) {
    EXPECT_NE(out.text.find("engines " + names[1]), std::string::npos) << out.text;
  }
}

// [defaults] holds what every part runs unless it says otherwise: a study written with it plans exactly what the
// same study with every value in its parts plans (the plan's lines name every setting that decides a run), and a
// key a part's kind does not have (a suite's reference_chains, for a sweep) is not applied to that part.
TEST(StudyFile, DefaultsApplyWhereAPartIsSilent) {
  const fs::path with = study_file("defaults", R"([defaults]
engines = ["reference"]
duration_s = 12
reference_ensemble_starts = 3
reference_chains = [4]
series = "none"

[[suite]]
name = "takes them all"
scenarios = ["scenarios/paper/free_vibration.toml"]

[[suite]]
name = "overrides two"
scenarios = ["scenarios/paper/free_vibration.toml"]
duration_s = 0.25
reference_ensemble_starts = 1

[[sweep]]
name = "sweep"
scenario = "scenarios/paper/resonance.toml"
ratios = "0.95:1.0:0.05"
starts = ["rest"]
)");
  const fs::path without = study_file("without-defaults", R"([[suite]]
name = "takes them all"
scenarios = ["scenarios/paper/free_vibration.toml"]
engines = ["reference"]
duration_s = 12
reference_ensemble_starts = 3
reference_chains = [4]
series = "none"

[[suite]]
name = "overrides two"
scenarios = ["scenarios/paper/free_vibration.toml"]
engines = ["reference"]
duration_s = 0.25
reference_ensemble_starts = 1
reference_chains = [4]
series = "none"

[[sweep]]
name = "sweep"
scenario = "scenarios/paper/resonance.toml"
ratios = "0.95:1.0:0.05"
starts = ["rest"]
engines = ["reference"]
duration_s = 12
reference_ensemble_starts = 3
series = "none"
)");
  const auto planned_with = study(with.string() + " --plan");
  const auto planned_without = study(without.string() + " --plan");
  fs::remove(with);
  fs::remove(without);
  ASSERT_EQ(planned_with.exit_code, 0) << planned_with.text;
  ASSERT_EQ(planned_without.exit_code, 0) << planned_without.text;
  EXPECT_EQ(planned_with.text, planned_without.text);
  EXPECT_NE(planned_with.text.find("cut to 12 s"), std::string::npos) << planned_with.text;
  EXPECT_NE(planned_with.text.find("cut to 0.25 s"), std::string::npos) << planned_with.text;
  EXPECT_NE(planned_with.text.find("continued 12 s"), std::string::npos) << planned_with.text;
}

TEST(StudyFile, AnArrayItemKeepsItsComma) {
  // A scenario file whose name holds a comma: one item of the array, not two.
  const fs::path folder = fs::temp_directory_path() / ("impactbench-study-comma-" + std::to_string(::getpid()));
  fs::create_directories(folder);
  fs::copy_file(std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/paper/free_vibration.toml",
                folder / "free,vibration.toml", fs::copy_options::overwrite_existing);
  const fs::path file = study_file("comma", "[[suite]]\nscenarios = [\"" + (folder / "free,vibration.toml").string() +
                                                "\"]\nengines = [\"reference\"]\n");
  const auto out = study(file.string() + " --plan");
  fs::remove(file);
  fs::remove_all(folder);
  ASSERT_EQ(out.exit_code, 0) << out.text;
  EXPECT_NE(out.text.find("free,vibration.toml; engines reference"), std::string::npos) << out.text;
}

struct BadStudy {
  const char* name;
  const char* text;
  std::vector<std::string> said;  // every piece must be in the message
};
void PrintTo(const BadStudy& bad, std::ostream* out) { *out << bad.name; }

class StudyFileErrors : public ::testing::TestWithParam<BadStudy> {};

TEST_P(StudyFileErrors, ExitTwoNamingTheFileTheLineTheKeyTheValueAndWhatIsAllowed) {
  const BadStudy& bad = GetParam();
  const fs::path file = study_file(bad.name, bad.text);
  const auto out =
      study(file.string() + " --out " + (fs::temp_directory_path() / "impactbench-study-never-written").string());
  fs::remove(file);
  EXPECT_EQ(out.exit_code, 2) << out.text;
  EXPECT_NE(out.text.find(file.string()), std::string::npos) << out.text;
  for (const std::string& piece : bad.said)
    EXPECT_NE(out.text.find(piece), std::string::npos) << piece << " in: " << out.text;
  EXPECT_FALSE(fs::exists(fs::temp_directory_path() / "impactbench-study-never-written"));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, StudyFileErrors,
    ::testing::Values(
        BadStudy{"unknown_key",
                 "[[suite]]\nscenarios = [\"scenarios/paper\"]\ntime_step = 1e-4\n",
                 {":3:", "time_step", "unknown key", "dt_s"}},
        BadStudy{"unknown_table", "[[suites]]\nscenarios = [\"scenarios/paper\"]\n", {":1:", "suites", "[[suite]]"}},
        BadStudy{"wrong_type",
                 "[[suite]]\nscenarios = \"scenarios/paper\"\n",
                 {":2:", "scenarios", "wrong type", "an array of strings"}},
        BadStudy{"zero_step",
                 "[[suite]]\nscenarios = [\"scenarios/paper\"]\n\ndt_s = [0]\n",
                 {":4:", "dt_s", "--dt 0", "allowed"}},
        BadStudy{"negative_duration",
                 "[[search]]\nscenarios = [\"scenarios/stiff\"]\nduration_s = -1\n",
                 {":3:", "duration_s", "-1", "allowed"}},
        BadStudy{"unknown_engine",
                 "[[suite]]\nscenarios = [\"scenarios/paper\"]\nengines = [\"reference\", \"havok\"]\n",
                 {":3:", "engines", "havok"}},
        BadStudy{"missing_scenarios", "[[suite]]\nengines = \"all\"\n", {":1:", "scenarios", "missing required key"}},
        BadStudy{"all_misspelt",
                 "[[suite]]\nscenarios = [\"scenarios/paper\"]\nlaws = \"every\"\n",
                 {":3:", "laws", "\"all\" or an array of strings"}},
        BadStudy{"sweep_without_name", "[[sweep]]\nscenario = \"scenarios/paper/resonance.toml\"\n", {":1:", "name"}},
        BadStudy{"two_sweeps_one_folder",
                 "[[sweep]]\nname = \"a\"\nscenario = \"scenarios/paper/resonance.toml\"\n"
                 "[[sweep]]\nname = \"a\"\nscenario = \"scenarios/paper/resonance.toml\"\n",
                 {":4:", "already the name of the sweep at line 1"}},
        BadStudy{"reference_ensemble_below_the_engines",
                 "[[suite]]\nscenarios = [\"scenarios/paper\"]\nensemble_starts = 4\nreference_ensemble_starts = 2\n",
                 {":4:", "reference_ensemble_starts", "--reference-ensemble 2", "allowed: 0 (--ensemble's), or 4"}},
        BadStudy{"ensemble_spread_beyond_a_hundredth_of_the_gap",
                 "[[suite]]\nscenarios = [\"scenarios/paper\"]\nensemble_starts = 200\nensemble_step_m = 1e-6\n",
                 {":4:", "ensemble_step_m", "--ensemble-step 1e-06", "allowed"}},
        BadStudy{"recommended_beside_a_step",
                 "[[suite]]\nscenarios = [\"scenarios/paper\"]\ndt_s = [1e-4]\nrecommended = true\n",
                 {":4:", "recommended", "--recommended cannot be combined with --paths, --dt or --find-steps"}},
        BadStudy{"reference_chains_beyond_the_engines_links",
                 "[[suite]]\nscenarios = [\"scenarios/paper\"]\nreference_chains = [8, 65]\n",
                 {":3:", "reference_chains", "--reference-chains", "65 is not allowed", "1 <= K <= 64"}},
        BadStudy{"reference_chains_out_of_order",
                 "[[suite]]\nscenarios = [\"scenarios/paper\"]\nreference_chains = [16, 8]\n",
                 {":3:", "reference_chains", "8 is not allowed", "increasing"}},
        BadStudy{"reference_chains_not_integers",
                 "[[suite]]\nscenarios = [\"scenarios/paper\"]\nreference_chains = [8.5]\n",
                 {":3:", "reference_chains", "8.5 is not allowed"}},
        BadStudy{"defaults_wrong_type",
                 "[defaults]\nduration_s = \"long\"\n[[suite]]\nscenarios = [\"scenarios/paper\"]\n",
                 {":2:", "defaults.duration_s", "wrong type", "a number"}},
        BadStudy{"defaults_naming_a_parts_own_key",
                 "[defaults]\nscenarios = [\"scenarios/paper\"]\n[[suite]]\nscenarios = [\"scenarios/paper\"]\n",
                 {":2:", "scenarios", "unknown key", "allowed keys in [defaults]", "a part's name and scenarios"}},
        BadStudy{"defaults_out_of_range",  // checked by the part that takes it, named at its line in [defaults]
                 "[defaults]\n\nduration_s = -1\n[[suite]]\nscenarios = [\"scenarios/paper\"]\n",
                 {":3:", "duration_s", "-1", "allowed"}},
        BadStudy{"syntax", "[[suite]\nscenarios = [\"scenarios/paper\"]\n", {":1:", "TOML syntax error"}}),
    [](const ::testing::TestParamInfo<BadStudy>& info) { return std::string(info.param.name); });

// A study's suite part records exactly what the `suite` command with the same options records: the same
// settings record (suite.jsonl) and the same metrics, run by run.
TEST(StudyCommand, APartGivesTheResultsOfTheCommandItStandsFor) {
  const fs::path folder = fs::temp_directory_path() / ("impactbench-study-equal-" + std::to_string(::getpid()));
  fs::remove_all(folder);
  const fs::path file = study_file("equal", kFreeVibration);
  const auto by_study = study(file.string() + " --jobs 2 --no-report --out " + (folder / "study").string());
  fs::remove(file);
  ASSERT_EQ(by_study.exit_code, 0) << by_study.text;
  const auto by_suite = run_impactbench_logged_as(
      "suite " + ib::test::paper_scenario("free_vibration") +
          " --engines reference --laws hertz,newton --duration 0.5 --jobs 2 --out " + (folder / "suite").string(),
      "study-test-suite-");
  ASSERT_EQ(by_suite.exit_code, 0) << by_suite.text;
  const auto read = [](const fs::path& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  // runs.csv's rows arrive in the order the jobs end: compare them sorted, without the timing columns
  const auto metrics = [&](const fs::path& csv) {
    const auto out = ib::test::run_command(
        "/usr/bin/python3 -c \"import csv,sys; rows=list(csv.DictReader(open(sys.argv[1]))); "
        "keep=lambda r: {k: v for k, v in r.items() if 'time' not in k and 'per_s' not in k "
        "and k not in ('scenario_file', 'steps_per_cpu_second', 'load_average')}; "
        "print(sorted(str(sorted(keep(r).items())) for r in rows))\" " +
        csv.string());
    return out.text;
  };
  EXPECT_EQ(metrics(folder / "study" / "runs.csv"), metrics(folder / "suite" / "runs.csv"));
  EXPECT_FALSE(metrics(folder / "suite" / "runs.csv").empty());
  // the settings record and the jobs; the command that wrote them differs
  const auto record = [&](const fs::path& path) {
    nlohmann::json line = nlohmann::json::parse(read(path));
    line.erase("command");
    return line;
  };
  EXPECT_EQ(record(folder / "study" / "suite.jsonl"), record(folder / "suite" / "suite.jsonl"));
  fs::remove_all(folder);
}

// The plan's count is what the study records: a suite part and a second one that shares its references (counted
// once, in the first) and adds a law, an engine's native run answering for two laws (two rows, one run), and a
// sweep's rows; the CPU estimate is there and positive.
TEST(StudyCommand, ThePlansCountIsTheRunsItRecords) {
  const std::vector<std::string> names = ib::simulator_names();
  const std::string engine = names.size() > 1 ? names[1] : names[0];
  const fs::path folder = fs::temp_directory_path() / ("impactbench-study-count-" + std::to_string(::getpid()));
  fs::remove_all(folder);
  const fs::path file = study_file("count", R"([defaults]
series = "none"

[[suite]]
name = "first"
scenarios = ["scenarios/paper/free_vibration.toml"]
duration_s = 0.2
engines = ["reference", ")" + engine + R"("]
laws = ["hertz", "newton"]
paths = ["matched", "native"]

[[suite]]
name = "shares the first's references"
scenarios = ["scenarios/paper/free_vibration.toml"]
duration_s = 0.2
engines = ["reference"]
laws = ["hertz", "viscoelastic"]
)" + kCoarseSweep);
  const auto plan = study(file.string() + " --plan --jobs 2");
  ASSERT_EQ(plan.exit_code, 0) << plan.text;
  EXPECT_NE(plan.text.find("1 more planned by an earlier part"), std::string::npos) << plan.text;
  EXPECT_GT(planned_cpu_s(plan.text), 0) << plan.text;
  const auto ran = study(file.string() + " --jobs 2 --no-report --out " + folder.string());
  fs::remove(file);
  ASSERT_LE(ran.exit_code, 1) << ran.text;  // 1: a run unstable or inaccurate, a finding
  const auto rows = [](const fs::path& csv) {
    std::ifstream in(csv);
    int lines = 0;
    for (std::string line; std::getline(in, line);) lines += !line.empty();
    return lines - 1;  // the header
  };
  EXPECT_EQ(planned_runs(plan.text), rows(folder / "runs.csv") + rows(folder / "sweeps" / "coarse" / "sweep.csv"))
      << plan.text;
  fs::remove_all(folder);
}

TEST(StudyCommand, SweepsGoIntoTheirOwnFoldersAndResumeRunsNothingTwice) {
  const fs::path folder = fs::temp_directory_path() / ("impactbench-study-sweep-" + std::to_string(::getpid()));
  fs::remove_all(folder);
  const fs::path file = study_file("sweep", std::string(kFreeVibration) + "\n" + kCoarseSweep);
  const auto first = study(file.string() + " --no-report --out " + folder.string());
  ASSERT_EQ(first.exit_code, 0) << first.text;
  EXPECT_TRUE(fs::exists(folder / "runs.csv"));
  EXPECT_TRUE(fs::exists(folder / "sweeps" / "coarse" / "sweep.csv"));
  const auto again = study(file.string() + " --no-report --resume --out " + folder.string());
  fs::remove(file);
  ASSERT_EQ(again.exit_code, 0) << again.text;
  EXPECT_NE(again.text.find("suite: 0 runs recorded"), std::string::npos) << again.text;
  EXPECT_NE(again.text.find("(0 run now, 2 already recorded)"), std::string::npos) << again.text;
  fs::remove_all(folder);
}

}  // namespace study_command_test
