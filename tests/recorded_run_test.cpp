// A run's record read back as a struct (harness/records/recorded_run.h): what a job's process wrote into runs.jsonl
// is what the suite and the step search read, field by field, with the verdict as an enum and "timed out"
// as a field of its own (not a prefix of the reason); a line a kill cut short reads as not readable.
#include <gtest/gtest.h>

#include <cmath>

#include "harness/records/recorded_run.h"
#include "harness/records/reporters.h"
#include "harness/records/run_record.h"

namespace ib {
namespace recorded_run_test {

RunRecord engine_record() {
  RunRecord r;
  r.job_id = "resonance/engine_a/hertz/dt=1e-4";
  r.engine = "engine_a";  // the record reads no engine's name
  r.verdict = Verdict::inaccurate;
  r.reason = "vs own chain: frame 1 sensor peak +28.8 % (tolerance 10 %)";
  r.cost.steps = 200000;
  r.cost.wall_time_s = 1.25;
  Metrics m;
  m.frames[0].sensor_peak_acceleration_g = 12.5;
  m.contact_duration_mean_s = 4.5e-4;
  m.impacts_per_cycle = 0.75;
  r.metrics = m;
  MetricErrors beam, chain;
  beam.sensor_peak_relative_error = {0.2, -0.1};
  beam.contact_duration_relative_error = 0.05;
  beam.impacts_per_cycle_difference = -0.25;
  chain.sensor_peak_relative_error = {0.288, 0.01};
  chain.contact_duration_relative_error = -0.02;
  chain.impacts_per_cycle_difference = 0;
  r.errors_vs_reference = beam;
  r.errors_vs_chain_reference = chain;
  return r;
}

TEST(RecordedRun, AWrittenRecordReadsBackFieldByField) {
  const RecordedRun r = read_recorded_run(json_line(engine_record()));
  ASSERT_TRUE(r.readable);
  EXPECT_EQ(r.job_id, "resonance/engine_a/hertz/dt=1e-4");
  EXPECT_EQ(r.verdict, Verdict::inaccurate);
  EXPECT_EQ(r.reason, "vs own chain: frame 1 sensor peak +28.8 % (tolerance 10 %)");
  EXPECT_FALSE(r.timed_out);
  EXPECT_EQ(r.steps, 200000);
  EXPECT_DOUBLE_EQ(r.wall_time_s, 1.25);
  EXPECT_DOUBLE_EQ(r.frame1_sensor_peak_g, 12.5);
  EXPECT_DOUBLE_EQ(r.contact_duration_mean_s, 4.5e-4);
  EXPECT_DOUBLE_EQ(r.impacts_per_cycle, 0.75);
  EXPECT_DOUBLE_EQ(r.vs_reference.frame1_sensor_peak_relative, 0.2);
  EXPECT_DOUBLE_EQ(r.vs_reference.contact_duration_relative, 0.05);
  EXPECT_DOUBLE_EQ(r.vs_reference.impacts_per_cycle_difference, -0.25);
  EXPECT_DOUBLE_EQ(r.vs_chain_reference.frame1_sensor_peak_relative, 0.288);
  EXPECT_DOUBLE_EQ(r.vs_chain_reference.contact_duration_relative, -0.02);
  EXPECT_DOUBLE_EQ(r.vs_chain_reference.impacts_per_cycle_difference, 0);
}

TEST(RecordedRun, TimedOutIsAFieldNotAPrefixOfTheReason) {
  RunRecord stopped = engine_record();
  stopped.verdict = Verdict::failed;
  stopped.metrics.reset();
  stopped.reason = "stopped after the time limit of 600 s";
  stopped.timed_out = true;
  EXPECT_TRUE(read_recorded_run(json_line(stopped)).timed_out);
  // a failed run whose reason merely reads like one is not timed out
  stopped.timed_out = false;
  const RecordedRun crashed = read_recorded_run(json_line(stopped));
  EXPECT_FALSE(crashed.timed_out);
  EXPECT_EQ(crashed.verdict, Verdict::failed);
  EXPECT_TRUE(std::isnan(crashed.frame1_sensor_peak_g));
}

TEST(RecordedRun, ALineCutShortOrAForeignVerdictIsNotARecord) {
  const std::string line = json_line(engine_record());
  EXPECT_FALSE(read_recorded_run(line.substr(0, line.size() / 2)).readable);
  EXPECT_FALSE(read_recorded_run(R"({"job_id": "x", "verdict": "fine"})").readable);
  EXPECT_FALSE(read_recorded_run("[1, 2]").readable);
  EXPECT_TRUE(read_recorded_run(R"({"job_id": "x", "verdict": "unstable"})").readable);
}

}  // namespace recorded_run_test
}  // namespace ib
