// The frequency sweep: its ratios and plan, the reference continued exactly from a saved state, and a
// sweep's results the same whether it ran whole, was resumed or ran in shards that were merged.
#include "harness/sweep/sweep.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "harness/records/reporters.h"
#include "harness/study/merge.h"
#include "reference_fixtures.h"
#include "simulators/catalog.h"

namespace ib {
namespace sweep_test {

namespace fs = std::filesystem;

TEST(SweepRatios, FromToStepIncludesBothEndsOnAClean1e9Grid) {
  const auto ratios = parse_ratios("0.85:1.20:0.01");
  ASSERT_EQ(ratios.size(), 36u);
  EXPECT_EQ(ratios.front(), 0.85);
  EXPECT_EQ(ratios[15], 1.0);
  EXPECT_EQ(ratios.back(), 1.2);
  EXPECT_EQ(parse_ratios("1:1:0").size(), 1u);
}

TEST(SweepRatios, BadRangesNameTheOptionTheValueAndWhatIsAllowed) {
  for (const char* bad :
       {"1.2:0.85:0.01", "a:1:0.1", "0.85:1.2", "0.01:1:0.1", "0.9:1:0", "0.9:1:-0.1", "0.9:1:1e-9", "nan:1:0.1"}) {
    try {
      parse_ratios(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("--ratios ") + bad), std::string::npos) << e.what();
    }
  }
}

SweepSettings small_sweep(const std::string& out) {
  SweepSettings s;
  s.scenario_path = std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/paper/resonance.toml";
  s.ratios = {0.98, 0.99, 1.0};
  s.starts = {SweepStart::up, SweepStart::down, SweepStart::rest};
  s.continuation_duration_s = 3;
  s.rest_duration_s = 4;
  s.window_s = 2;
  s.jobs = 2;
  s.out = out;
  s.measurement.series = SeriesOutput::none;
  s.simulators = simulator_catalog();
  return s;
}

TEST(SweepPlan, ContinuationsRunInOrderUpAndDownAndEveryStartFromRestIsAChainOfItsOwn) {
  const auto chains = plan_sweep(small_sweep("unused"), "resonance");
  ASSERT_EQ(chains.size(), 2u + 3u);
  EXPECT_EQ(chains[0].id, "resonance/reference/hertz/up");
  ASSERT_EQ(chains[0].rows.size(), 3u);
  EXPECT_EQ(chains[0].rows[0].ratio, 0.98);
  EXPECT_TRUE(chains[0].rows[0].first_of_chain);
  EXPECT_FALSE(chains[0].rows[1].first_of_chain);
  EXPECT_EQ(chains[1].rows[0].ratio, 1.0);  // down: from the top
  EXPECT_EQ(chains[1].rows[2].id, "resonance/reference/hertz/down/r=0.98");
  EXPECT_EQ(chains[2].rows.size(), 1u);
  EXPECT_EQ(chains[4].id, "resonance/reference/hertz/rest/r=1");
}

// The reference's ensemble (SweepSettings::ensemble): its other starts from rest at the ensemble's ratios, each a
// chain of its own right after the ratio's row from rest (start 0), frame 1's tip displaced K x the step.
TEST(SweepPlan, TheReferencesEnsembleAddsItsOtherStartsFromRestAtTheEnsembleRatiosOnly) {
  SweepSettings s = small_sweep("unused");
  s.starts = {SweepStart::up, SweepStart::rest};
  s.ensemble = {3, 2e-7, {0.99}};
  const auto chains = plan_sweep(s, "resonance");
  ASSERT_EQ(chains.size(), 1u + 3u + 2u);  // up; rest at 0.98, 0.99 (and its starts 1 and 2), 1.0
  EXPECT_EQ(chains[0].rows.size(), 3u);
  EXPECT_EQ(chains[0].rows[1].job.start.count, 1);  // a continuation runs once
  EXPECT_EQ(chains[1].id, "resonance/reference/hertz/rest/r=0.98");
  EXPECT_EQ(chains[1].rows[0].job.start.count, 1);
  EXPECT_EQ(chains[2].id, "resonance/reference/hertz/rest/r=0.99");
  EXPECT_EQ(chains[2].rows[0].job.start.count, 3);
  EXPECT_EQ(chains[2].rows[0].job.start.initial_displacement_offset_m, 0.0);
  for (int k = 1; k <= 2; ++k) {
    const SweepRow& member = chains[2 + k].rows.at(0);
    EXPECT_EQ(member.id, "resonance/reference/hertz/rest/r=0.99/start=" + std::to_string(k));
    EXPECT_EQ(member.chain, member.id);
    EXPECT_EQ(member.start, SweepStart::rest);
    EXPECT_EQ(member.job.start.index, k);
    EXPECT_DOUBLE_EQ(member.job.start.initial_displacement_offset_m, k * 2e-7);
  }
  EXPECT_EQ(chains[5].id, "resonance/reference/hertz/rest/r=1");
  s.ensemble.ratios.clear();  // every ratio
  EXPECT_EQ(plan_sweep(s, "resonance").size(), 1u + 3u * 3u);
  s.engines = {"an_engine"};  // engines run from one start: the ensemble is the reference's
  EXPECT_EQ(plan_sweep(s, "resonance").size(), 1u + 3u);
}

TEST(SweepRatios, EnsembleRatiosAreRangesOrSingleRatiosOfTheSweep) {
  const std::vector<double> sweep = parse_ratios("0.90:1.20:0.01");
  EXPECT_EQ(parse_ensemble_ratios("1.1,0.93:0.95:0.01", sweep), (std::vector<double>{0.93, 0.94, 0.95, 1.1}));
  for (const char* bad : {"0.935", "1.19:1.21:0.01", "x"}) {
    try {
      parse_ensemble_ratios(bad, sweep);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("--"), std::string::npos) << e.what();
    }
  }
}

// Continuing from a saved state is the same physics as not stopping: 2 x 3 s against 6 s at once, the motor
// at 7 Hz (3 s = 21 whole periods, so the continued run's motor phase 0 is the one the long run has at 3 s).
TEST(ReferenceContinuation, TwoRunsJoinedByTheSavedStateAreTheOneRunTheyReplace) {
  Scenario scenario = testing::paper_scenario("resonance");
  scenario.motor->speed_ratio_to_f1.reset();
  scenario.motor->frequency_hz = 7.0;
  scenario.initial.frame1_tip_displacement_m = 0.8e-3;  // contact within the first 3 s and after
  RunSettings settings;
  settings.series_start_s = 0;
  auto reference = make_simulator("reference");
  scenario.duration_s = 6;
  const RunResult whole = reference->run(scenario, settings);
  scenario.duration_s = 3;
  const RunResult first = reference->run(scenario, settings);
  ASSERT_TRUE(first.final_state);
  EXPECT_EQ(first.final_state->simulator, "reference");
  settings.initial_state = first.final_state;
  const RunResult second = reference->run(scenario, settings);
  ASSERT_EQ(second.status, RunStatus::ok);
  const std::size_t offset = 3 * 4096;
  ASSERT_EQ(second.trajectory.size() + offset, whole.trajectory.size());
  double largest_difference_m = 0;
  for (std::size_t k = 0; k < second.trajectory.size(); ++k)
    for (int f = 0; f < 2; ++f)
      largest_difference_m = std::max(largest_difference_m, std::abs(second.trajectory.displacement_m[f][k] -
                                                                     whole.trajectory.displacement_m[f][k + offset]));
  EXPECT_LT(largest_difference_m, 1e-9);  // of a 1 mm motion
  // the same impacts, at the same times
  std::vector<double> onsets_whole;
  for (const ContactEvent& e : whole.trajectory.events)
    if (e.onset_time_s >= 3.0) onsets_whole.push_back(e.onset_time_s - 3.0);
  ASSERT_EQ(second.trajectory.events.size(), onsets_whole.size());
  ASSERT_GT(onsets_whole.size(), 0u);
  // measured: up to 3.0e-9 s apart (the free-flight grid restarts at the continued run's t = 0, and the
  // contact integrator's tolerance is 1e-9); a continuation that lost the velocities is off by milliseconds
  for (std::size_t i = 0; i < onsets_whole.size(); ++i)
    EXPECT_NEAR(second.trajectory.events[i].onset_time_s, onsets_whole[i], 1e-8);
}

std::string read_all(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// sweep.csv without the machine's measurements (its last three columns: cpu and wall time, load)
std::string without_timing(const std::string& csv) {
  std::istringstream lines(csv);
  std::string out;
  for (std::string line; std::getline(lines, line);) {
    for (int cut = 0; cut < 3; ++cut) line = line.substr(0, line.rfind(','));
    out += line + "\n";
  }
  return out;
}

TEST(SweepResults, TheSameWholeResumedAndShardedThenMerged) {
  const std::string root = ::testing::TempDir() + "/sweep_results";
  fs::remove_all(root);
  const SweepOutcome whole = run_sweep(small_sweep(root + "/whole"));
  EXPECT_EQ(whole.rows_run, 9);
  EXPECT_EQ(whole.not_ok, 0);
  const std::string expected = without_timing(read_all(root + "/whole/sweep.csv"));
  ASSERT_EQ(std::count(expected.begin(), expected.end(), '\n'), 10);
  EXPECT_NE(expected.find("resonance/reference/hertz/down/r=0.99"), std::string::npos);

  // interrupted after some rows: the up chain's last ratio and one start from rest lost
  fs::copy(root + "/whole", root + "/resumed", fs::copy_options::recursive);
  fs::remove_all(root + "/resumed/runs/resonance/reference/hertz/up/r=1");
  fs::remove_all(root + "/resumed/runs/resonance/reference/hertz/rest/r=0.99");
  fs::remove(root + "/resumed/sweep.csv");
  SweepSettings resume = small_sweep(root + "/resumed");
  resume.resume = true;
  const SweepOutcome resumed = run_sweep(resume);
  EXPECT_EQ(resumed.rows_run, 2);
  EXPECT_EQ(resumed.rows_skipped, 7);
  EXPECT_EQ(without_timing(read_all(root + "/resumed/sweep.csv")), expected);
  EXPECT_EQ(read_all(root + "/resumed/poincare.csv"), read_all(root + "/whole/poincare.csv"));

  std::vector<std::string> shards;
  for (int k = 1; k <= 2; ++k) {
    SweepSettings shard = small_sweep(root + "/shard-" + std::to_string(k));
    shard.shard = Shard{k, 2};
    run_sweep(shard);
    shards.push_back(shard.out);
  }
  // a shard's folder holds that shard alone, a whole sweep's none (campaign_folder.h), as a suite's
  SweepSettings other_shard = small_sweep(root + "/shard-1");
  other_shard.shard = Shard{2, 2};
  other_shard.resume = true;
  try {
    run_sweep(other_shard);
    ADD_FAILURE() << "shard 2/2 was run into shard 1/2's folder";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("holds shard 1/2 of a sweep (shard.jsonl), not --shard 2/2"),
              std::string::npos)
        << e.what();
  }
  SweepSettings shard_of_whole = small_sweep(root + "/whole");
  shard_of_whole.shard = Shard{1, 2};
  shard_of_whole.resume = true;
  EXPECT_THROW(run_sweep(shard_of_whole), std::invalid_argument) << "a shard into a whole sweep's folder";
  const MergeOutcome merged = merge_suites(MergeSettings{shards, root + "/merged"});
  EXPECT_TRUE(merged.complete());
  EXPECT_EQ(merged.runs, 9);
  EXPECT_EQ(without_timing(read_all(root + "/merged/sweep.csv")), expected);
  EXPECT_EQ(read_all(root + "/merged/poincare.csv"), read_all(root + "/whole/poincare.csv"));
}

std::vector<std::string> csv_columns(const std::string& header_line) {
  std::vector<std::string> columns;
  std::istringstream cells(header_line);
  for (std::string cell; std::getline(cells, cell, ',');) columns.push_back(cell);
  return columns;
}

// One vocabulary: a quantity sweep.csv shares with runs.csv has runs.csv's name and unit (the sensor peak in
// g, not m/s^2), with the run record's own value (summary.json, written by the code that writes runs.csv); the contact
// path has its column; a start from rest whose window lies in the start-up transient carries the warning in its records
// (row.json, summary.json).
TEST(SweepResults, SharedQuantitiesHaveTheRunsCsvNamesUnitsAndValues) {
  const std::string root = ::testing::TempDir() + "/sweep_vocabulary";
  fs::remove_all(root);
  const std::vector<std::string> names = simulator_names();
  if (names.size() < 2) GTEST_SKIP() << "no engine in this build";
  const std::string engine_name = names[1];  // any engine: its native path ignores the law
  SweepSettings s = small_sweep(root);
  s.ratios = {1.0};
  s.starts = {SweepStart::rest};
  s.engines = {"reference", engine_name};
  s.contact_paths = {"native"};
  ASSERT_EQ(run_sweep(s).rows_run, 2);
  std::ifstream table(root + "/sweep.csv");
  std::string header;
  std::getline(table, header);
  const std::vector<std::string> runs =
      csv_columns(csv_header(RunRecord{}).substr(0, csv_header(RunRecord{}).size() - 1));
  const std::set<std::string> runs_columns(runs.begin(), runs.end());
  // the sweep's own: what a run of a suite does not have (its place in the sweep, the regime, the samples)
  const std::set<std::string> sweep_only = {
      "id",        "start",  "ratio",    "motor_frequency_hz", "window_s",
      "timed_out", "regime", "period_n", "impacts_per_period", "poincare_samples"};
  for (const std::string& column : csv_columns(header))
    EXPECT_TRUE(runs_columns.count(column) || sweep_only.count(column)) << column << " is not a runs.csv column";
  for (const char* shared :
       {"frame1_sensor_peak_acceleration_g", "frame2_sensor_peak_acceleration_g", "frame1_peak_displacement_m",
        "frame2_peak_displacement_m", "contact_duration_mean_s", "mean_approach_velocity_m_s", "impacts",
        "impacts_per_cycle", "contact_path", "law_simulated"})
    EXPECT_NE(("," + header + ",").find(std::string(",") + shared + ","), std::string::npos) << shared;

  for (const std::string& engine : {std::string("reference"), engine_name}) {
    const std::string folder =
        root + "/runs/resonance/" + engine + "/hertz" + (engine == engine_name ? "/contact=native" : "") + "/rest/r=1";
    const auto row = nlohmann::json::parse(read_all(folder + "/row.json"));
    const auto summary = nlohmann::json::parse(read_all(folder + "/summary.json"));
    ASSERT_EQ(row["verdict"], "ok") << folder << ": " << row["reason"];
    for (const char* same : {"frame1_sensor_peak_acceleration_g", "frame2_peak_displacement_m",
                             "contact_duration_mean_s", "impacts", "contact_path", "law_simulated"})
      EXPECT_EQ(row[same], summary[same]) << engine << " " << same;
    EXPECT_EQ(row["contact_path"], engine == engine_name ? "native" : "");
    EXPECT_EQ(row["law_simulated"], engine == engine_name ? "no" : "yes");
    EXPECT_EQ(row["timed_out"], false);
    // 4 s from rest scored from 2 s: inside the 22.9 s transient
    ASSERT_EQ(row["warnings"].size(), 1u) << row.dump();
    EXPECT_NE(row["warnings"][0].get<std::string>().find("before the start-up transient's end (22.9 s"),
              std::string::npos);
    EXPECT_EQ(summary["warnings"], row["warnings"]);
  }
  EXPECT_EQ(header.find("warnings"), std::string::npos);  // a list: sweep.jsonl's alone
  EXPECT_NE(read_all(root + "/sweep.jsonl").find("start-up transient"), std::string::npos);
}

// Each start of the reference's ensemble is a row of sweep.csv with runs.csv's ensemble columns, and runs displaced.
TEST(SweepResults, TheReferencesEnsembleStartsAreRowsWithTheirStartAndDisplacement) {
  const std::string root = ::testing::TempDir() + "/sweep_ensemble";
  fs::remove_all(root);
  SweepSettings s = small_sweep(root);
  s.ratios = {1.0};
  s.starts = {SweepStart::rest};
  s.ensemble = {3, 1e-6, {}};
  ASSERT_EQ(run_sweep(s).rows_run, 3);
  std::istringstream lines(read_all(root + "/sweep.jsonl"));
  int k = 0;
  std::set<double> displacements;
  for (std::string line; std::getline(lines, line); ++k) {
    const auto row = nlohmann::json::parse(line);
    EXPECT_EQ(row["id"], "resonance/reference/hertz/rest/r=1" + (k ? "/start=" + std::to_string(k) : std::string()));
    EXPECT_EQ(row["ensemble_start"], k);
    EXPECT_EQ(row["ensemble_starts"], 3);
    EXPECT_DOUBLE_EQ(row["initial_displacement_offset_m"].get<double>(), k * 1e-6);
    displacements.insert(row["frame1_peak_displacement_m"].get<double>());
  }
  EXPECT_EQ(k, 3);
  EXPECT_EQ(displacements.size(), 3u);  // three runs, not one run recorded three times
  const auto settings = nlohmann::json::parse(read_all(root + "/sweep.json"));
  EXPECT_EQ(settings["reference_ensemble_starts"], 3);
}

TEST(SweepResults, AResumeWithOtherSettingsOrAScenarioWithoutAMotorIsRefusedBeforeAnyRun) {
  const std::string root = ::testing::TempDir() + "/sweep_refusals";
  fs::remove_all(root);
  SweepSettings s = small_sweep(root + "/a");
  s.ratios = {1.0};
  s.starts = {SweepStart::rest};
  run_sweep(s);
  s.resume = true;
  s.window_s = 1;
  try {
    run_sweep(s);
    ADD_FAILURE() << "a resume with another window was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("window_s"), std::string::npos) << e.what();
  }
  s.resume = false;
  EXPECT_THROW(run_sweep(s), std::invalid_argument);  // the folder holds a sweep: --resume or another --out
  SweepSettings free_vibration = small_sweep(root + "/b");
  free_vibration.scenario_path = std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/paper/free_vibration.toml";
  EXPECT_THROW(run_sweep(free_vibration), std::invalid_argument);
  EXPECT_FALSE(fs::exists(root + "/b/sweep.json"));
}

}  // namespace sweep_test
}  // namespace ib
