// Input that is accepted by its type but not by physics or by the machine, through the command as a user
// types it: every case ends with exit 2 before anything runs, and its message names the option or the file
// and key, the value and what is allowed; nothing runs forever (a FIFO, /dev/zero), nothing is silently
// ignored (--window -1, --duration nan, --engines ''), and `score` refuses data it cannot measure (times
// out of order, uneven samples, contacts that end before they begin, a window past the data). `run` stops
// at its --time-limit as a suite's job does. Each of these once passed with exit 0, NaN, a hang, exit 1
// or 3, or a traceback.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cctype>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "catalog_engines.h"
#include "command_test_support.h"

namespace implausible_input_test {

namespace fs = std::filesystem;
using Output = ib::test::CommandOutput;

Output impactbench(const std::string& arguments) {
  return ib::test::run_impactbench_logged_as(arguments, "impactbench_implausible_");
}
std::string paper(const std::string& name) { return ib::test::paper_scenario(name); }
fs::path fresh(const std::string& name) { return ib::test::fresh_command_folder("impactbench_implausible_", name); }

// The first engine of the binary under test (catalog_engines.h), or "" when it was built with none: a rule
// of the harness needs one engine, never a particular one.
std::string first_engine() {
  const std::vector<std::string> engines = ib::test::command_engines();
  return engines.empty() ? "" : engines.front();
}

// The command ends with exit 2 and says each fragment.
void refused(const std::string& arguments, const std::vector<std::string>& fragments) {
  const auto started = std::chrono::steady_clock::now();
  const Output out = impactbench(arguments);
  EXPECT_EQ(out.exit_code, 2) << arguments << "\n" << out.text;
  for (const std::string& fragment : fragments)
    EXPECT_NE(out.text.find(fragment), std::string::npos) << arguments << "\n" << out.text;
  EXPECT_EQ(out.text.find("Traceback"), std::string::npos) << out.text;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), 30) << arguments;
}

TEST(ImplausibleInput, RunOptionsOutsideTheirRangesAreRefused) {
  const std::string out = " --out " + fresh("run").string();
  const std::string run = "run " + paper("free_vibration") + " --engine reference";
  refused(run + " --rate 1e12" + out, {"--rate 1e+12: allowed: 256 <= x <= 1e+06 Hz"});
  refused(run + " --sensor-rate 1e9" + out, {"--sensor-rate 1e+09: allowed: 256 <= x <= 1e+06 Hz"});
  refused(run + " --series-start 100" + out,
          {"--series-start 100: allowed: before the run's end", "duration_s = 14 s"});
  refused(run + " --window -1" + out, {"--window -1: allowed: 0 < x <= 3600 s"});
  refused(run + " --window nan" + out, {"--window nan: allowed: 0 < x <= 3600 s"});
  refused(run + " --window 20" + out, {"--window 20", "allowed: at most the run"});
  refused(run + " --time-limit 0" + out, {"--time-limit 0: allowed: 0 < x <= 604800 s"});
  refused("run " + paper("free_vibration") + " --engine reference --out ''", {"--out '': allowed: a folder path"});
}

TEST(ImplausibleInput, AStepThatTakesNoStepOrForeverIsRefused) {
  const std::string out = " --out " + fresh("dt").string();
  const std::string engine = first_engine();
  if (engine.empty()) GTEST_SKIP() << "no engine in this build";
  // one engine shows the rule (it is the harness's, not the engine's)
  const std::string run = std::string("run ") + paper("free_vibration") + " --engine " + engine;
  refused(run + " --dt 1e300" + out, {"--dt 1e+300: allowed: 1e-09 <= x <= 0.01 s"});
  refused(run + " --dt 1e-12" + out, {"--dt 1e-12: allowed: 1e-09 <= x <= 0.01 s"});
}

TEST(ImplausibleInput, ScenarioFilesThatNeverEndOrAreNotFilesAreRefused) {
  const fs::path dir = fresh("files");
  fs::create_directories(dir);
  const fs::path fifo = dir / "fifo.toml";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0644), 0);
  refused("run " + fifo.string() + " --out " + (dir / "a").string(), {"fifo.toml", "not a regular file"});
  refused("run /dev/zero --out " + (dir / "b").string(), {"/dev/zero", "not a regular file"});
  // a scenario whose values are each within range but whose frame is no beam, or rings at 10^-17 Hz
  std::ifstream in(paper("resonance"));
  std::stringstream text;
  text << in.rdbuf();
  const auto with = [&](const std::string& from, const std::string& to, const std::string& name) {
    std::string t = text.str();
    t.replace(t.find(from), from.size(), to);
    std::ofstream(dir / name) << t;
    return (dir / name).string();
  };
  refused("run " + with("column_thickness_m = 1.75e-3", "column_thickness_m = 0.1", "thick.toml") + " --out " +
              (dir / "c").string(),
          {"thick.toml:", "frame1.column_thickness_m = 0.1: out of range; allowed: x <= frame1.length_m / 10 = 0.03"});
  refused("run " + with("youngs_modulus_pa = 200e9", "youngs_modulus_pa = 1e300", "stiff.toml") + " --out " +
              (dir / "d").string(),
          {"stiff.toml:", "frame1.youngs_modulus_pa = 1e300: out of range; allowed: 100000 <= x <= 1.5e+12"});
  refused(
      "run " + with("tip_mass_kg = 0.64439", "tip_mass_kg = 1e300", "heavy.toml") + " --out " + (dir / "e").string(),
      {"heavy.toml:", "frame1.tip_mass_kg = 1e300: out of range; allowed: 0 <= x <= 10000"});
  refused("run " + with("duration_s = 100.0", "duration_s = 1e300", "long.toml") + " --out " + (dir / "f").string(),
          {"long.toml:", "scenario.duration_s = 1e300: out of range; allowed: 0 < x <= 3600"});
  refused("run " + with("speed_ratio_to_f1 = 1.00", "speed_ratio_to_f1 = 1e6", "fast.toml") + " --out " +
              (dir / "g").string(),
          {"fast.toml:", "motor.speed_ratio_to_f1 = 1e6: out of range; allowed: 0 < x <= 100"});
  refused("run " + with("density_kg_m3 = 7850.0", "density_kg_m3 = 1e-300", "light.toml") + " --out " +
              (dir / "h").string(),
          {"light.toml:", "frame1.density_kg_m3 = 1e-300: out of range; allowed: 10 <= x <= 25000"});
  refused("run " + with("youngs_modulus_pa = 200e9", "youngs_modulus_pa = 1e5", "soft.toml") + " --out " +
              (dir / "i").string(),
          {"soft.toml:", "frame1: its first natural frequency would be about 0.0049", "allowed: 0.05 to 5000 Hz"});
  fs::remove_all(dir);
}

TEST(ImplausibleInput, SuiteListsAndFoldersThatSayNothingAreRefused) {
  const fs::path dir = fresh("suite");
  const std::string suite = "suite " + paper("free_vibration") + " --out " + (dir / "out").string();
  refused(suite + " --engines ''", {"--engines '': empty; allowed: reference"});
  const std::string with_empty = "reference,," + first_engine();
  refused(suite + " --engines " + with_empty, {"--engines '" + with_empty + "': an empty item"});
  refused(suite + " --laws hertz,", {"--laws 'hertz,': an empty item"});
  refused(suite + " --paths matched,,native", {"--paths 'matched,,native': an empty item"});
  refused(suite + " --duration 0", {"--duration 0: allowed: 0 < x <= 3600 s"});
  refused(suite + " --duration nan", {"--duration nan: allowed: 0 < x <= 3600 s"});
  refused(suite + " --window -1", {"--window -1: allowed: 0 < x <= 3600 s"});
  refused(suite + " --rate 1e12", {"--rate 1e+12: allowed: 256 <= x <= 1e+06 Hz"});
  refused(suite + " --dt 1e-12", {"--dt 1e-12: allowed: 1e-09 <= x <= 0.01 s"});
  refused("suite " + (dir / "nowhere").string() + " --out " + (dir / "out").string(),
          {"nowhere: no such file or folder"});
  fs::create_directories(dir / "empty");
  refused("suite " + (dir / "empty").string() + " --out " + (dir / "out").string(), {"empty: holds no scenario file"});
  refused("suite " + paper("free_vibration") + " --out ''", {"--out '': allowed: a folder path"});
  EXPECT_FALSE(fs::exists(dir / "out" / "runs.csv"));
  fs::remove_all(dir);
}

TEST(ImplausibleInput, RunStopsAtItsTimeLimitAndRecordsWhy) {
  const fs::path dir = fresh("limit");
  // the published resonance (100 s of rig time, its 14 s window written at 4096 Hz with the peaks between samples)
  // takes ten times longer than 0.02 s of wall time
  const Output out =
      impactbench("run " + paper("resonance") + " --engine reference --time-limit 0.02 --out " + dir.string());
  EXPECT_EQ(out.exit_code, 1) << out.text;
  EXPECT_NE(out.text.find("failed: stopped at the time limit of 0.02 s (--time-limit)"), std::string::npos) << out.text;
  const auto summary = nlohmann::json::parse(std::ifstream(dir / "summary.json"));
  EXPECT_EQ(summary["verdict"], "failed");
  EXPECT_EQ(summary["timed_out"], true);
  fs::remove_all(dir);
}

// A run folder of another solver for `score`: series.csv and events.csv with one fault each.
TEST(ImplausibleInput, ScoreRefusesDataItCannotMeasure) {
  const fs::path dir = fresh("score");
  const std::string scenario = paper("free_vibration");
  ASSERT_EQ(
      impactbench("run " + scenario + " --engine reference --law hertz --series all --out " + (dir / "good").string())
          .exit_code,
      0);
  // the series as plain CSV, and the events
  const Output plain = ib::test::run_command("zcat " + (dir / "good" / "series.csv.gz").string());
  ASSERT_EQ(plain.exit_code, 0);
  std::ifstream events_in(dir / "good" / "events.csv");
  std::stringstream events;
  events << events_in.rdbuf();
  const auto folder_with = [&](const std::string& name, std::string series, std::string event_text) {
    fs::create_directories(dir / name);
    std::ofstream(dir / name / "series.csv") << series;
    std::ofstream(dir / name / "events.csv") << event_text;
    return (dir / name).string();
  };
  std::vector<std::string> lines;
  std::stringstream in(plain.text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  const auto joined = [](const std::vector<std::string>& l) {
    std::string t;
    for (const std::string& s : l) t += s + "\n";
    return t;
  };
  auto swapped = lines;
  std::swap(swapped[100], swapped[101]);
  refused("score " + folder_with("order", joined(swapped), events.str()) + " --scenario " + scenario,
          {"series.csv:102: time_s = ", "allowed: increasing times"});
  auto gap = lines;
  gap.erase(gap.begin() + 200);
  refused("score " + folder_with("uneven", joined(gap), events.str()) + " --scenario " + scenario,
          {"series.csv:", "allowed: samples evenly spaced"});
  auto nan_time = lines;
  nan_time[50] = "nan" + nan_time[50].substr(nan_time[50].find(','));
  refused("score " + folder_with("nan", joined(nan_time), events.str()) + " --scenario " + scenario,
          {"series.csv:51: time_s = ", "allowed: a finite time"});
  // a contact that ends before it begins
  std::string backwards = events.str();
  const auto second_line = backwards.find('\n') + 1;
  const auto comma = backwards.find(',', second_line);
  backwards.replace(comma + 1, backwards.find(',', comma + 1) - comma - 1, "0");
  refused("score " + folder_with("backwards", joined(lines), backwards) + " --scenario " + scenario,
          {"events.csv:2: the contact ends (0 s) before it begins", "allowed: end_time_s >= onset_time_s"});
  // a window past the data: the series' second half only, the scenario's window the whole run
  auto second_half = lines;
  second_half.erase(second_half.begin() + 1, second_half.begin() + static_cast<long>(lines.size() / 2));
  refused("score " + folder_with("window", joined(second_half), events.str()) + " --scenario " + scenario,
          {"but the scoring window is", "allowed: a window inside the series"});
  fs::remove_all(dir);
}

TEST(ImplausibleInput, TheReportOfADamagedFolderSaysWhatIsWrongWithoutATraceback) {
  const fs::path dir = fresh("report");
  const std::string engine = first_engine();
  if (engine.empty()) GTEST_SKIP() << "no engine in this build";
  ASSERT_LE(impactbench("suite " + paper("free_vibration") + " --engines reference," + engine +
                        " --dt 1e-4 --laws viscoelastic --duration 1 --out " + dir.string())
                .exit_code,
            1);
  // the engine run's series emptied (the report draws it)
  const fs::path engine_series =
      dir / "runs" / "free_vibration" / engine / "viscoelastic" / "dt=0.0001" / "series.csv.gz";
  ASSERT_TRUE(fs::exists(engine_series)) << engine_series;
  std::ofstream(engine_series, std::ios::trunc);
  Output out = impactbench("report " + dir.string());
  EXPECT_EQ(out.exit_code, 2) << out.text;
  EXPECT_EQ(out.text.find("Traceback"), std::string::npos) << out.text;
  EXPECT_NE(out.text.find("make_report: cannot make the report of"), std::string::npos) << out.text;
  // runs.jsonl a folder
  fs::rename(dir / "runs.jsonl", dir / "kept.jsonl");
  fs::create_directories(dir / "runs.jsonl");
  out = impactbench("report " + dir.string());
  EXPECT_EQ(out.exit_code, 2) << out.text;
  EXPECT_NE(out.text.find("runs.jsonl: not a file"), std::string::npos) << out.text;
  // a job recorded twice
  fs::remove_all(dir / "runs.jsonl");
  fs::rename(dir / "kept.jsonl", dir / "runs.jsonl");
  std::ifstream first(dir / "runs.jsonl");
  std::string line;
  std::getline(first, line);
  first.close();
  std::ofstream(dir / "runs.jsonl", std::ios::app) << line << "\n";
  out = impactbench("report " + dir.string());
  EXPECT_EQ(out.exit_code, 2) << out.text;
  EXPECT_NE(out.text.find("recorded again, the same"), std::string::npos) << out.text;
  refused("report " + (dir / "nowhere").string(), {"nowhere: no such folder"});
  fs::remove_all(dir);
}

}  // namespace implausible_input_test
