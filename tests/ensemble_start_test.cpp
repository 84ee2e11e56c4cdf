// An ensemble's start K is the scenario run with frame 1's tip displaced by K x the ensemble's step beyond the
// scenario's initial displacement, and nothing else changed; its record says which start it is. And a scoring
// window too short to measure what a run reports is refused before the run.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "harness/jobs/run_job.h"
#include "model/scenario_toml.h"
#include "physics/modal_model.h"
#include "simulators/catalog.h"
#include "suite_test_support.h"

namespace ib {
namespace ensemble_start_test {

struct Start {
  RunRecord record;
  ReferenceData data;
};

Start run_reference(const Scenario& scenario, const EnsembleStart& start) {
  JobSpec job;
  job.scenario_path = scenario.source_path;
  job.engine = "reference";
  job.settings.output_rate_hz = 4096;
  job.start = start;
  Measurement measurement;
  measurement.series = SeriesOutput::all;
  Start s;
  s.record = run_job(scenario, job, measurement, nullptr, nullptr, "", &s.data, simulator_catalog().make);
  return s;
}

// The modal model projects the initial deflection onto its modes, a linear map: the tip it starts from
// scales with the tip displacement asked for, so start K starts at u_0(0) (u0 + offset) / u0.
TEST(EnsembleStart, StartKDisplacesFrameOnesTipByItsOffsetAndRecordsWhichStartItIs) {
  const auto folder = test::fresh_test_folder("ensemble_start_");
  test::write_short_free_vibration(folder);
  const Scenario scenario = load_scenario((folder / "short_free.toml").string());
  const double u0_m = scenario.initial.frame1_tip_displacement_m;
  ASSERT_GT(std::abs(u0_m), 1e-4) << "the free vibration starts displaced";
  const double offset_m = 3e-7;
  const Start unperturbed = run_reference(scenario, {});
  const Start third = run_reference(scenario, {3, 4, offset_m});

  const double tip_0 = unperturbed.data.trajectory.displacement_m[0].front();
  const double tip_3 = third.data.trajectory.displacement_m[0].front();
  EXPECT_NEAR(tip_3, tip_0 * (u0_m + offset_m) / u0_m, 1e-12 * std::abs(tip_0));
  EXPECT_EQ(third.data.trajectory.displacement_m[1].front(), unperturbed.data.trajectory.displacement_m[1].front())
      << "frame 2 starts where the scenario says";
  EXPECT_NE(third.record.metrics->frames[0].peak_displacement_m,
            unperturbed.record.metrics->frames[0].peak_displacement_m);

  EXPECT_EQ(unperturbed.record.job_id, "short_free/reference/hertz") << "start 0 is the single run";
  EXPECT_EQ(third.record.job_id, "short_free/reference/hertz/start=3");
  EXPECT_EQ(third.record.start.index, 3);
  EXPECT_EQ(third.record.start.count, 4);
  EXPECT_EQ(third.record.start.initial_displacement_offset_m, offset_m);
  std::filesystem::remove_all(folder);
}

std::string refusal(const Scenario& scenario, const Measurement& measurement) {
  try {
    check_scoring_window(scenario, measurement);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// With a motor, impacts per cycle need a motor period; without one, the sensor needs one sample.
TEST(EnsembleStart, AWindowShorterThanAMotorPeriodOrASensorSampleIsRefused) {
  Scenario forced = default_rig();
  const double period_s = 1 / motor_frequency_hz(forced);
  Measurement measurement;
  measurement.window_s = 0.9 * period_s;
  const std::string too_short = refusal(forced, measurement);
  EXPECT_EQ(too_short.rfind("--window ", 0), 0u) << too_short;
  EXPECT_NE(too_short.find("allowed: at least one motor period"), std::string::npos) << too_short;
  measurement.window_s = period_s;
  EXPECT_EQ(refusal(forced, measurement), "");

  forced.scoring_window_s = 0.5 * period_s;  // the scenario's own window, no --window: the file's key is named
  const std::string from_file = refusal(forced, Measurement{});
  EXPECT_NE(from_file.find("[scenario] scoring_window_s = "), std::string::npos) << from_file;

  Scenario free = forced;
  free.motor.reset();
  measurement.window_s = 0.5 / measurement.sensor_rate_hz;
  const std::string no_sample = refusal(free, measurement);
  EXPECT_NE(no_sample.find("allowed: at least one sensor sample"), std::string::npos) << no_sample;
  measurement.window_s = 1 / measurement.sensor_rate_hz;
  EXPECT_EQ(refusal(free, measurement), "");
}

}  // namespace ensemble_start_test
}  // namespace ib
