// The options several commands share go through one table (cli/option_rules.h): every command that takes
// one refuses the same bad values with exit 2 and the same message, naming the option, the value, the
// range with its unit and meaning. Before it, `run --dt 0` ran silently at the engine's default step while
// `suite --dt 0` was refused, `run --dt -1` got an engine's own message, and `--rate`, `--time-limit`,
// `--duration` had other ranges in `sweep` than in `suite`. And `run --duration S` runs S seconds as a
// suite's --duration does, keeping the scoring window.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "command_test_support.h"

namespace cli_option_ranges_test {

namespace fs = std::filesystem;
using Output = ib::test::CommandOutput;

Output impactbench(const std::string& arguments) {
  return ib::test::run_impactbench_logged_as(arguments, "impactbench_option_ranges_");
}
std::string paper(const std::string& name) { return ib::test::paper_scenario(name); }

// The line of the output that starts with "impactbench: OPTION " ("" when there is none).
std::string message_line(const std::string& text, const std::string& option) {
  std::stringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("impactbench: " + option + " ", 0) == 0) return line;
  return "";
}

// Two texts that read as the same number (nan never is).
bool same_number(const std::string& a, const std::string& b) {
  try {
    return std::stod(a) == std::stod(b);
  } catch (const std::exception&) {
    return false;
  }
}

// Each command as a user types it, up to the option under test: nothing in it is wrong, so a refusal is
// the option's. The folders are never made (the options are checked before anything runs).
std::map<std::string, std::string> commands(const fs::path& dir) {
  const std::string out = " --out " + (dir / "out").string();
  return {{"run", "run " + paper("resonance") + " --engine reference" + out},
          {"suite", "suite " + paper("resonance") + out},
          {"sweep", "sweep " + paper("resonance") + out},
          {"export", "export " + paper("resonance") + " --engine reference --out " + (dir / "model.json").string()},
          {"score", "score " + (dir / "run").string() + " --scenario " + paper("resonance")}};
}

struct SharedOption {
  std::string name;
  std::vector<std::string> commands;  // every command that takes it
  std::string allowed;                // the range, its unit and meaning: one decision (cli/option_rules.cpp)
  std::vector<std::string> bad;       // values outside it: zero or below, above, not a number
};

const std::vector<SharedOption> kShared = {
    {"--dt",
     {"run", "suite", "sweep", "export"},
     "1e-09 <= x <= 0.01 s (the time step of fixed-step engines)",
     {"0", "-1", "1e-12", "0.5", "abc", "nan"}},
    {"--rate",
     {"run", "suite", "sweep", "export"},
     "256 <= x <= 1e+06 Hz (the output series' sample rate)",
     {"0", "-4096", "100", "1e12", "fast", "inf"}},
    {"--sensor-rate",
     {"run", "suite", "sweep", "score"},
     "256 <= x <= 1e+06 Hz (the accelerometer's sample rate)",
     {"0", "-2048", "1e9", "2k"}},
    {"--time-limit",
     {"run", "suite", "sweep"},
     "0 < x <= 604800 s (the wall time of one run before it is stopped)",
     {"0", "-1", "1e6", "10min"}},
    {"--duration",
     {"run", "suite", "sweep"},
     "0 < x <= 3600 s (the simulated time of a run)",
     {"0", "-5", "1e4", "nan", "long"}},
    {"--window",
     {"run", "suite", "sweep", "score"},
     "0 < x <= 3600 s (the scored last part of a run)",
     {"0", "-1", "4000", "nan", "all"}},
    {"--merge-window",
     {"run", "suite", "score"},
     "0 <= x <= 1 s (onsets closer than this are one impact)",
     {"-0.001", "2", "x"}},
    {"--jobs",
     {"suite", "sweep"},
     "1 <= x <= 1024, a whole number (worker processes)",
     {"0", "-2", "5000", "1.5", "all"}},
    {"--repeat",
     {"run", "suite"},
     "0 <= x <= 100, a whole number (timed runs after the logged one)",
     {"-1", "1000", "2.5", "some"}},
    {"--series-start", {"run"}, "0 <= x <= 3600 s (the time of the first output sample)", {"-1", "1e4", "start"}},
};

TEST(CliOptionRanges, EveryCommandRefusesABadValueOfASharedOptionWithTheSameMessage) {
  const fs::path dir = ib::test::fresh_command_folder("impactbench_option_ranges_", "bad");
  const auto typed = commands(dir);
  for (const SharedOption& option : kShared) {
    for (const std::string& value : option.bad) {
      std::string first;  // the message of the first command: every other says the same
      for (const std::string& command : option.commands) {
        const std::string arguments = typed.at(command) + " " + option.name + " " + value;
        const Output out = impactbench(arguments);
        EXPECT_EQ(out.exit_code, 2) << arguments << "\n" << out.text;
        const std::string line = message_line(out.text, option.name);
        // the value as typed, or (a number) as it reads back: 1e12 is 1e+12
        EXPECT_NE(line.find(": allowed: " + option.allowed), std::string::npos) << arguments << "\n" << out.text;
        const std::string shown = line.substr(0, line.find(": allowed: "));
        EXPECT_TRUE(shown == "impactbench: " + option.name + " " + value ||
                    same_number(shown.substr(shown.rfind(' ') + 1), value))
            << arguments << "\n"
            << out.text;
        if (first.empty()) first = line;
        EXPECT_EQ(line, first) << option.name << " " << value << ": " << command << " says otherwise than "
                               << option.commands[0];
      }
    }
  }
  EXPECT_FALSE(fs::exists(dir));  // nothing ran
}

TEST(CliOptionRanges, AListOfStepsIsCheckedItemByItemAsOneStepIs) {
  const fs::path dir = ib::test::fresh_command_folder("impactbench_option_ranges_", "list");
  const auto typed = commands(dir);
  const std::string expected =
      "impactbench: --dt 0: allowed: 1e-09 <= x <= 0.01 s (the time step of fixed-step engines)";
  for (const char* command : {"suite", "sweep"}) {
    const Output out = impactbench(typed.at(command) + " --dt 1e-4,0");
    EXPECT_EQ(out.exit_code, 2) << out.text;
    EXPECT_EQ(message_line(out.text, "--dt"), expected) << out.text;
  }
  const Output single = impactbench(typed.at("run") + " --dt 0");
  EXPECT_EQ(message_line(single.text, "--dt"), expected) << single.text;
  EXPECT_FALSE(fs::exists(dir));
}

// Where the rule needs another option's value: the series must be at least as fine as the sensor, which
// reads it, and the window inside the run.
TEST(CliOptionRanges, TheSeriesIsNoCoarserThanTheSensorAndTheWindowInsideTheRun) {
  const fs::path dir = ib::test::fresh_command_folder("impactbench_option_ranges_", "cross");
  const auto typed = commands(dir);
  std::string first;
  for (const char* command : {"run", "suite", "sweep"}) {
    const Output out = impactbench(typed.at(command) + " --rate 1024");  // the sensor's default: 2048 Hz
    EXPECT_EQ(out.exit_code, 2) << command << "\n" << out.text;
    const std::string line = message_line(out.text, "--rate");
    EXPECT_NE(line.find("--rate 1024: allowed: at least --sensor-rate (2048 Hz"), std::string::npos) << command << "\n"
                                                                                                     << out.text;
    if (first.empty()) first = line;
    EXPECT_EQ(line, first) << command;
  }
  // the same series with a sensor it resolves passes, up to a fault each command finds after that rule
  const std::map<std::string, std::string> later_fault = {
      {"run", "--window 3000"}, {"suite", "--shard 0/0"}, {"sweep", "--shard 0/0"}};
  for (const auto& [command, fault] : later_fault) {
    const Output out = impactbench(typed.at(command) + " --rate 1024 --sensor-rate 1024 " + fault);
    EXPECT_EQ(out.exit_code, 2) << command << "\n" << out.text;
    EXPECT_EQ(message_line(out.text, "--rate"), "") << command << "\n" << out.text;
    EXPECT_NE(out.text.find("impactbench: " + fault.substr(0, fault.find(' ')) + " "), std::string::npos)
        << command << "\n"
        << out.text;
  }
  const Output run = impactbench(typed.at("run") + " --duration 2 --window 3");
  EXPECT_EQ(run.exit_code, 2) << run.text;
  EXPECT_EQ(message_line(run.text, "--window"), "impactbench: --window 3: allowed: at most the run (--duration 2 s)")
      << run.text;
  const Output start =
      impactbench(typed.at("run") + " --duration 2 --series-start 2.5");  // the cut run's end, not the file's
  EXPECT_EQ(start.exit_code, 2) << start.text;
  EXPECT_EQ(message_line(start.text, "--series-start"),
            "impactbench: --series-start 2.5: allowed: before the run's end (--duration 2 s)")
      << start.text;
  const Output sweep = impactbench(typed.at("sweep") + " --duration 2 --window 3");
  EXPECT_EQ(message_line(sweep.text, "--window"), message_line(run.text, "--window")) << sweep.text;
  EXPECT_FALSE(fs::exists(dir));
}

// A scenario file's value of KEY (a number at the start of its line: "duration_s = 100.0").
double scenario_value(const std::string& file, const std::string& key) {
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(key + " = ", 0) == 0) return std::stod(line.substr(key.size() + 3));
  ADD_FAILURE() << file << " has no " << key;
  return NAN;
}

// `run --duration S` runs S seconds of a longer scenario and keeps its scoring window, the last part of the
// run, as a suite's --duration does (shortened to the run when longer); --window scores the last part.
TEST(CliOptionRanges, RunDurationRunsThatLongAndKeepsTheScoringWindow) {
  const fs::path dir = ib::test::fresh_command_folder("impactbench_option_ranges_", "duration");
  const auto summary_of = [](const fs::path& folder) {
    return nlohmann::json::parse(std::ifstream(folder / "summary.json"));
  };
  const auto last_sample_s = [](const fs::path& folder) {
    const Output series = ib::test::run_command("zcat " + (folder / "series.csv.gz").string() + " | tail -1");
    return std::stod(series.text.substr(0, series.text.find(',')));
  };
  // the published resonance: 100 s with a window of its last 14 s; cut to 20 s, the window is [6, 20] s
  const std::string resonance = paper("resonance");
  ASSERT_GT(scenario_value(resonance, "duration_s"), 20);
  const double window_s = scenario_value(resonance, "scoring_window_s");
  Output out = impactbench("run " + resonance + " --engine reference --law hertz --duration 20 --out " +
                           (dir / "resonance").string());
  ASSERT_EQ(out.exit_code, 0) << out.text;
  const auto kept = summary_of(dir / "resonance");
  EXPECT_DOUBLE_EQ(kept["duration_s"].get<double>(), 20.0) << kept.dump(2);
  EXPECT_DOUBLE_EQ(kept["window_start_s"].get<double>(), 20.0 - window_s) << kept.dump(2);
  EXPECT_DOUBLE_EQ(kept["window_end_s"].get<double>(), 20.0) << kept.dump(2);
  EXPECT_NE(out.text.find("before the start-up transient's end"), std::string::npos) << out.text;  // as a suite warns
  // the published free vibration, scored whole: cut to 2 s, the 2 s are scored, and its series ends there
  const std::string free =
      "run " + paper("free_vibration") + " --engine reference --law hertz --series all --duration 2";
  out = impactbench(free + " --out " + (dir / "cut").string());
  ASSERT_EQ(out.exit_code, 0) << out.text;
  const auto cut = summary_of(dir / "cut");
  EXPECT_DOUBLE_EQ(cut["duration_s"].get<double>(), 2.0) << cut.dump(2);
  EXPECT_DOUBLE_EQ(cut["window_start_s"].get<double>(), 0.0) << cut.dump(2);
  EXPECT_DOUBLE_EQ(cut["window_end_s"].get<double>(), 2.0) << cut.dump(2);
  EXPECT_NEAR(last_sample_s(dir / "cut"), 2.0, 1e-9);
  out = impactbench(free + " --window 0.5 --out " + (dir / "window").string());
  ASSERT_EQ(out.exit_code, 0) << out.text;
  const auto windowed = summary_of(dir / "window");
  EXPECT_DOUBLE_EQ(windowed["window_start_s"].get<double>(), 1.5) << windowed.dump(2);
  EXPECT_DOUBLE_EQ(windowed["window_end_s"].get<double>(), 2.0) << windowed.dump(2);
  EXPECT_LT(windowed["impacts"].get<int>(), cut["impacts"].get<int>()) << windowed.dump(2) << cut.dump(2);
  fs::remove_all(dir);
}

}  // namespace cli_option_ranges_test
