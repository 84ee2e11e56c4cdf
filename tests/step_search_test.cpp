// The search for the largest stable and accurate time steps (suite --find-steps): on synthetic
// outcomes with known boundaries it finds each boundary to one grid step, one probe updates every
// bracket, outcomes that are not monotone in the step are noted, a probe at the time limit decides
// nothing; through the suite runner with a simulator that is unstable and inaccurate above known
// steps, it writes one row per group, and --resume re-runs no probe and duplicates no row.
#include "harness/suite/step_search.h"
#include "simulators/catalog.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "harness/suite/suite.h"
#include "reference/reference_simulator.h"
#include "suite_test_support.h"

namespace ib {
namespace step_search_test {

namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The known boundaries of the synthetic engine [s].
constexpr double kUnstableAbove_s = 2e-4;
constexpr double kSensorPeakOffAbove_s = 5e-5;  // frame 1's sensor peak 20 % high above this
constexpr double kDurationOffAbove_s = 1e-5;    // contact durations 30 % long above this

ProbeResult synthetic(double dt) {
  ProbeResult r;
  r.verdict = dt > kUnstableAbove_s ? Verdict::unstable : Verdict::ok;
  r.error[HeadlineMetric::frame1_sensor_peak] = dt > kSensorPeakOffAbove_s ? 0.2 : 0.01;
  r.error[HeadlineMetric::contact_duration] = dt > kDurationOffAbove_s ? 0.3 : 0.02;
  r.error[HeadlineMetric::impacts_per_cycle] = 0;
  r.beam_error = r.error;
  r.wall_time_s = 1e-3 / dt;
  return r;
}

ReferenceFacts forced_reference() { return ReferenceFacts{true, 20.0, 1e-3, 0.5}; }

// Runs a search to its end with the given outcomes; returns the grid indices probed, in order.
std::vector<int> run(StepSearch& search, const std::function<ProbeResult(double)>& outcome) {
  std::vector<int> probed;
  while (const auto k = search.next_probe()) {
    EXPECT_FALSE(search.probed(*k)) << "probed twice: " << *k;
    if (search.probed(*k)) break;
    search.add(*k, outcome(search.grid()[*k]));
    probed.push_back(*k);
  }
  return probed;
}

// The largest grid step <= bound and the grid step just above it.
std::pair<double, double> grid_neighbours(const std::vector<double>& grid, double bound) {
  for (std::size_t k = 1; k < grid.size(); ++k)
    if (grid[k] <= bound) return {grid[k], grid[k - 1]};
  return {kNaN, kNaN};
}

TEST(StepGrid, IsGeometricFromTheLargestStepDownToTheSmallest) {
  StepSearchSettings s;
  const auto grid = step_grid(s);
  ASSERT_EQ(grid.size(), 40u);  // 1e-3 * 2^(-k/4) >= 1e-6 for k <= 39 (4 log2(1000) = 39.9)
  EXPECT_DOUBLE_EQ(grid.front(), 1e-3);
  for (std::size_t k = 1; k < grid.size(); ++k) EXPECT_NEAR(grid[k - 1] / grid[k], std::pow(2.0, 0.25), 1e-12);
  EXPECT_GE(grid.back(), 1e-6);
  EXPECT_LT(grid.back() / std::pow(2.0, 0.25), 1e-6);
  s.min_step_s = 2e-3;
  EXPECT_THROW(step_grid(s), std::invalid_argument);
}

TEST(StepSearchLogic, FindsEachBoundaryToOneGridStep) {
  StepSearch search(StepSearchSettings{}, forced_reference(), "reference");
  const auto probed = run(search, synthetic);
  const auto& grid = search.grid();
  const auto [stable, unstable] = grid_neighbours(grid, kUnstableAbove_s);
  EXPECT_EQ(search.stability().largest_pass_step_s, stable);
  EXPECT_EQ(search.stability().smallest_fail_step_s, unstable);
  EXPECT_EQ(search.stability().status, "bracketed to one grid step");
  const auto [peak_ok, peak_off] = grid_neighbours(grid, kSensorPeakOffAbove_s);
  EXPECT_EQ(search.accuracy(HeadlineMetric::frame1_sensor_peak).largest_pass_step_s, peak_ok);
  EXPECT_EQ(search.accuracy(HeadlineMetric::frame1_sensor_peak).smallest_fail_step_s, peak_off);
  EXPECT_DOUBLE_EQ(search.accuracy(HeadlineMetric::frame1_sensor_peak).error_at_largest_pass, 0.01);
  const auto [duration_ok, duration_off] = grid_neighbours(grid, kDurationOffAbove_s);
  EXPECT_EQ(search.accuracy(HeadlineMetric::contact_duration).largest_pass_step_s, duration_ok);
  EXPECT_EQ(search.accuracy(HeadlineMetric::contact_duration).smallest_fail_step_s, duration_off);
  // impacts per cycle is exact wherever the run is stable: its boundary is the stability boundary
  EXPECT_EQ(search.accuracy(HeadlineMetric::impacts_per_cycle).largest_pass_step_s, stable);
  EXPECT_TRUE(search.notes().empty());
  // bisection: far fewer probes than grid points (three distinct boundaries, about log2(40) each)
  EXPECT_LE(probed.size(), 3 * 7u);
  EXPECT_LT(probed.size(), grid.size() / 2);
}

TEST(StepSearchLogic, OneProbeUpdatesEveryBracket) {
  StepSearch search(StepSearchSettings{}, forced_reference(), "reference");
  const int first = *search.next_probe();
  EXPECT_EQ(first, 19);  // the middle of the whole grid (indices 0 .. 39, with -1 and 40 as open ends)
  ProbeResult good;
  good.verdict = Verdict::ok;
  for (HeadlineMetric m : kHeadlineMetrics) good.error[m] = 0;
  search.add(first, good);
  EXPECT_EQ(search.stability().largest_pass_step_s, search.grid()[first]);
  for (HeadlineMetric m : kHeadlineMetrics) EXPECT_EQ(search.accuracy(m).largest_pass_step_s, search.grid()[first]);
  // every bracket is now [none, first]: the next probe halves it
  EXPECT_EQ(*search.next_probe(), 9);
  // an unstable probe fails every predicate at once
  ProbeResult bad;
  bad.verdict = Verdict::unstable;
  search.add(10, bad);
  EXPECT_EQ(search.stability().smallest_fail_step_s, search.grid()[10]);
  for (HeadlineMetric m : kHeadlineMetrics) EXPECT_EQ(search.accuracy(m).smallest_fail_step_s, search.grid()[10]);
}

TEST(StepSearchLogic, NonMonotoneOutcomesAreNoted) {
  StepSearch search(StepSearchSettings{}, forced_reference(), "reference");
  // unstable at one small step (index 30, a probe the bisection would not make itself, put in by hand)
  // below steps that are stable: the result is a step below which every probe was stable, and the
  // stable probes at larger steps are reported
  const auto glitch = [&](double dt) {
    ProbeResult r = synthetic(dt);
    if (std::abs(dt / search.grid()[30] - 1) < 1e-9) r.verdict = Verdict::unstable;
    return r;
  };
  for (int k : {5, 30, 19}) search.add(k, glitch(search.grid()[k]));
  run(search, glitch);
  EXPECT_EQ(search.stability().largest_pass_step_s, search.grid()[31]);
  EXPECT_EQ(search.stability().smallest_fail_step_s, search.grid()[30]);
  bool noted = false;
  for (const auto& note : search.notes()) noted |= note.find("non-monotone: stable at the larger") != std::string::npos;
  EXPECT_TRUE(noted) << (search.notes().empty() ? "no notes" : search.notes().front());
  // without the glitch the same probes give the stability boundary and no note
  StepSearch clean(StepSearchSettings{}, forced_reference(), "reference");
  for (int k : {5, 19}) clean.add(k, synthetic(clean.grid()[k]));
  run(clean, synthetic);
  EXPECT_EQ(clean.stability().largest_pass_step_s, grid_neighbours(clean.grid(), kUnstableAbove_s).first);
  EXPECT_TRUE(clean.notes().empty());
}

TEST(StepSearchLogic, AProbeAtTheTimeLimitDecidesNothing) {
  StepSearch search(StepSearchSettings{}, forced_reference(), "reference");
  // below 3e-5 s every probe reaches the time limit
  const auto slow = [](double dt) {
    ProbeResult r = synthetic(dt);
    if (dt < 3e-5) {
      r = ProbeResult{};
      r.verdict = Verdict::failed;
      r.reason = std::string(kTimeLimitReason) + " of 600 s";
      r.timed_out = true;
    }
    return r;
  };
  const auto probed = run(search, slow);
  // a smaller step than one that reached the time limit is never tried
  int smallest_timed_out = static_cast<int>(search.grid().size());
  for (int k : probed) {
    EXPECT_LT(k, smallest_timed_out) << search.grid()[k];
    if (search.grid()[k] < 3e-5) smallest_timed_out = k;
  }
  EXPECT_LT(smallest_timed_out, static_cast<int>(search.grid().size()));
  // the stability and sensor-peak boundaries lie above 3e-5 s and are found; the duration's is not
  EXPECT_EQ(search.stability().status, "bracketed to one grid step");
  EXPECT_EQ(search.stability().largest_pass_step_s, grid_neighbours(search.grid(), kUnstableAbove_s).first);
  EXPECT_EQ(search.accuracy(HeadlineMetric::frame1_sensor_peak).status, "bracketed to one grid step");
  const auto duration = search.accuracy(HeadlineMetric::contact_duration);
  EXPECT_EQ(duration.status, "not decided: probes reached the time limit");
  EXPECT_TRUE(std::isnan(duration.largest_pass_step_s));
  bool noted = false;
  for (const auto& note : search.notes()) noted |= note.find("reached the time limit") != std::string::npos;
  EXPECT_TRUE(noted);
  EXPECT_NE(search.probe_list().find(":timed_out"), std::string::npos);
}

TEST(StepSearchLogic, MetricsTheReferenceLacksAreNotApplicable) {
  ReferenceFacts free{true, 20.0, 1e-3, kNaN};  // no excitation
  StepSearch search(StepSearchSettings{}, free, "reference on the 4-link chain");
  run(search, synthetic);
  EXPECT_EQ(search.accuracy(HeadlineMetric::impacts_per_cycle).status,
            "not applicable: the scenario has no excitation");
  EXPECT_TRUE(std::isnan(search.accuracy(HeadlineMetric::impacts_per_cycle).largest_pass_step_s));
  ReferenceFacts no_impacts{true, 20.0, kNaN, 0.0};
  StepSearch quiet(StepSearchSettings{}, no_impacts, "beam reference");
  EXPECT_EQ(quiet.accuracy(HeadlineMetric::contact_duration).status,
            "not applicable: the beam reference has no impacts in the window");
  StepSearch orphan(StepSearchSettings{}, ReferenceFacts{}, "beam reference");
  EXPECT_EQ(orphan.accuracy(HeadlineMetric::frame1_sensor_peak).status,
            "not applicable: the beam reference did not finish");
}

// ---- through the suite runner ------------------------------------------------------------------------

// The reference on a 4-link chain under another name, made unstable and inaccurate above the known
// steps: its frame 1 velocities scaled by 1.2 (the sensor peak 20 % high), its contact episodes made
// 30 % longer. Optionally never returns below a step (a probe that reaches the time limit).
class SteppedMirror final : public Simulator {
 public:
  explicit SteppedMirror(double hang_below_s = 0) : hang_below_s_(hang_below_s) {}
  std::string name() const override { return "stepped"; }
  std::string version() const override { return "test"; }
  std::vector<std::pair<std::string, std::string>> option_help() const override { return {}; }
  RunResult run(const Scenario& s, const RunSettings& settings) override {
    const double dt = settings.time_step_s;
    if (dt < hang_below_s_)
      for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
    RunSettings chain = settings;
    chain.options = chain_reference_options(4);
    RunResult result = make_reference_simulator()->run(s, chain);
    if (dt > kUnstableAbove_s) {
      result.status = RunStatus::unstable;
      result.reason = "synthetic instability above 2e-4 s";
    }
    if (dt > kSensorPeakOffAbove_s)
      for (double& v : result.trajectory.velocity_m_s[0]) v *= 1.2;
    if (dt > kDurationOffAbove_s)
      for (ContactEvent& e : result.trajectory.events) e.end_time_s += 0.3 * (e.end_time_s - e.onset_time_s);
    return result;
  }
  std::optional<int> chain_links(const Scenario&, const RunSettings&) const override { return 4; }

 private:
  double hang_below_s_;
};

class StepSearchSuite : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = test::fresh_test_folder("impactbench_steps_");
    test::write_short_free_vibration(root_ / "scenarios");
    settings_.inputs = {(root_ / "scenarios").string()};
    settings_.out = (root_ / "out").string();
    settings_.laws = {ContactLaw::viscoelastic};
    settings_.engines = {"stepped"};
    settings_.jobs = 2;
    settings_.time_limit_s = 60;
    settings_.step_search = StepSearchSettings{};
    settings_.simulators = simulator_catalog();
    settings_.simulators.make = [](const std::string& name) -> std::unique_ptr<Simulator> {
      return name == "stepped" ? std::make_unique<SteppedMirror>() : make_simulator(name);
    };
  }
  void TearDown() override { fs::remove_all(root_); }
  fs::path root_;
  SuiteSettings settings_;
};

TEST_F(StepSearchSuite, FindsTheKnownStepsAndResumesWithoutRepeating) {
  const SuiteOutcome first = run_suite(settings_);
  EXPECT_EQ(first.step_searches, 1);
  const auto rows = test::json_lines(settings_.out + "/steps.jsonl");
  ASSERT_EQ(rows.size(), 1u);
  const auto& row = rows[0];
  const auto grid = step_grid(StepSearchSettings{});
  EXPECT_EQ(row["group_id"], "short_free/stepped/viscoelastic");
  EXPECT_EQ(row["chain_links"].get<double>(), 4);
  EXPECT_EQ(row["accuracy_reference"], "reference on the 4-link chain");
  EXPECT_EQ(row["largest_stable_step_s"].get<double>(), grid_neighbours(grid, kUnstableAbove_s).first);
  EXPECT_EQ(row["smallest_unstable_step_s"].get<double>(), grid_neighbours(grid, kUnstableAbove_s).second);
  EXPECT_EQ(row["frame1_sensor_peak_largest_step_within_tolerance_s"].get<double>(),
            grid_neighbours(grid, kSensorPeakOffAbove_s).first);
  EXPECT_EQ(row["contact_duration_largest_step_within_tolerance_s"].get<double>(),
            grid_neighbours(grid, kDurationOffAbove_s).first);
  // below its boundaries the synthetic engine is the reference on its chain: no error there but the
  // 9 digits of the reference's saved series (the suite reads a reference back from its files)
  EXPECT_LT(std::abs(row["frame1_sensor_peak_relative_error_at_largest_step"].get<double>()), 1e-8);
  EXPECT_NE(row["frame1_sensor_peak_relative_error_vs_beam_reference_at_largest_step"].get<double>(), 0.0);
  EXPECT_TRUE(row["impacts_per_cycle_largest_step_within_tolerance_s"].is_null());
  EXPECT_EQ(row["impacts_per_cycle_status"], "not applicable: the scenario has no excitation");
  // every probe is an ordinary run: beam reference + chain reference + the probes
  const auto runs = test::json_lines(settings_.out + "/runs.jsonl");
  EXPECT_EQ(runs.size(), 2 + row["probes"].get<std::size_t>());
  EXPECT_EQ(first.jobs_run, static_cast<int>(runs.size()));
  std::ifstream csv(settings_.out + "/steps.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header + "\n", steps_csv_header());

  // --resume: nothing runs again, no row is added
  settings_.resume = true;
  const SuiteOutcome again = run_suite(settings_);
  EXPECT_EQ(again.jobs_run, 0);
  EXPECT_EQ(again.step_searches, 0);
  EXPECT_EQ(test::json_lines(settings_.out + "/steps.jsonl").size(), 1u);
  // a kill before the row was written: the row is recomputed from the recorded probes, none re-run
  fs::remove(settings_.out + "/steps.jsonl");
  fs::remove(settings_.out + "/steps.csv");
  const SuiteOutcome recomputed = run_suite(settings_);
  EXPECT_EQ(recomputed.jobs_run, 0);
  EXPECT_EQ(recomputed.step_searches, 1);
  const auto after = test::json_lines(settings_.out + "/steps.jsonl");
  ASSERT_EQ(after.size(), 1u);
  EXPECT_EQ(after[0], row);
  EXPECT_EQ(test::json_lines(settings_.out + "/runs.jsonl").size(), runs.size());
  // other tolerances are another search: a second row, reusing the probes it shares with the first
  settings_.measurement.verdicts.accuracy.sensor_peak_relative = 0.3;  // the one tolerance record
  EXPECT_THROW(run_suite(settings_), std::invalid_argument);           // another suite in this folder: said, not mixed
  settings_.extend = true;
  const SuiteOutcome looser = run_suite(settings_);
  const auto both = test::json_lines(settings_.out + "/steps.jsonl");
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(both[1]["frame1_sensor_peak_largest_step_within_tolerance_s"].get<double>(),
            grid_neighbours(grid, kUnstableAbove_s).first);
  EXPECT_LT(looser.jobs_run, row["probes"].get<int>());
}

TEST_F(StepSearchSuite, AProbeAtTheTimeLimitIsNotDecidedNotUnstable) {
  settings_.time_limit_s = 3;
  settings_.step_search->min_step_s = 1e-5;
  settings_.step_search->max_step_s = 1e-3;
  settings_.simulators = simulator_catalog();
  settings_.simulators.make = [](const std::string& name) -> std::unique_ptr<Simulator> {
    return name == "stepped" ? std::make_unique<SteppedMirror>(1e-4) : make_simulator(name);
  };
  run_suite(settings_);
  const auto rows = test::json_lines(settings_.out + "/steps.jsonl");
  ASSERT_EQ(rows.size(), 1u);
  const auto grid = step_grid(*settings_.step_search);
  EXPECT_EQ(rows[0]["largest_stable_step_s"].get<double>(), grid_neighbours(grid, kUnstableAbove_s).first);
  EXPECT_EQ(rows[0]["frame1_sensor_peak_status"], "not decided: probes reached the time limit");
  const std::string notes = rows[0]["notes"];
  EXPECT_NE(notes.find("reached the time limit"), std::string::npos) << notes;
  EXPECT_EQ(notes.find("non-monotone"), std::string::npos) << notes;
}

// ---- the command line -----------------------------------------------------------------------------

struct Command {
  int exit_code;
  std::string output;
};

Command run_command(const std::string& arguments) {
  const std::string command = std::string(IMPACTBENCH_EXECUTABLE) + " " + arguments + " 2>&1";
  std::FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  char buffer[4096];
  while (pipe && std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
  const int status = pipe ? pclose(pipe) : -1;
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

TEST(StepSearchCommand, BadSearchOptionsAreClearErrors) {
  const std::string suite = "suite --engines reference --out /nonexistent/never_written ";
  const Command range = run_command(suite + "--find-steps --step-range 1e-3,1e-6");
  EXPECT_EQ(range.exit_code, 2) << range.output;
  EXPECT_NE(range.output.find("--step-range 1e-3,1e-6: allowed: MIN <= MAX"), std::string::npos) << range.output;
  const Command tolerance = run_command(suite + "--find-steps --tolerance sensor=0.1");
  EXPECT_EQ(tolerance.exit_code, 2) << tolerance.output;
  EXPECT_NE(tolerance.output.find("--tolerance sensor=0.1: expected metric=value with metric frame1_sensor_peak"),
            std::string::npos)
      << tolerance.output;
  const Command negative = run_command(suite + "--find-steps --tolerance contact_duration=-1");
  EXPECT_EQ(negative.exit_code, 2) << negative.output;
  EXPECT_NE(negative.output.find("-1: allowed: a number > 0"), std::string::npos) << negative.output;
  const Command both = run_command(suite + "--find-steps --dt 1e-4");
  EXPECT_EQ(both.exit_code, 2) << both.output;
  EXPECT_NE(both.output.find("--dt cannot be combined with --find-steps"), std::string::npos) << both.output;
  const Command alone = run_command(suite + "--step-range 1e-5,1e-4");
  EXPECT_EQ(alone.exit_code, 2) << alone.output;
  EXPECT_NE(alone.output.find("need --find-steps"), std::string::npos) << alone.output;
}

}  // namespace step_search_test
}  // namespace ib
