// The step an engine runs with is the step its run records (runs.csv time_step_s): every engine of this
// build, on frame 1's free vibration, at two asked steps and at its default (its descriptor.json's). The loop's count
// of steps must be the run's length over the recorded step, and the motion must keep its frequency from one step to the
// other: an engine that advanced its bodies by a step other than the one the loop counts (its own default, say) would
// run its physics faster or slower than the recorded time by their ratio.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine_measurements.h"
#include "harness/jobs/run_job.h"
#include "physics/modal_model.h"
#include "simulators/catalog.h"

namespace ib {
namespace engine_time_step_test {

constexpr double kDuration_s = 0.5;
// Two steps every engine runs stably on its default chain (none above the default of the engine whose
// explicit hinge springs bound its step most), a factor 2.5 apart: far more than the step's own effect on
// the frequency, and the factor an engine stepping by another step than the counted one would show.
constexpr double kSteps_s[] = {5e-5, 2e-5};

// Frame 1 released from 0.5 mm toward frame 2 (half the gap): it never reaches frame 2, so the motion
// is the first mode's free decay.
Scenario free_vibration() {
  Scenario s = default_rig();
  s.name = "free_vibration";
  s.motor.reset();
  s.initial.frame1_tip_displacement_m = 5e-4;
  s.duration_s = kDuration_s;
  s.scoring_window_s = kDuration_s;
  return s;
}

struct SteppedRun {
  RunRecord record;
  double frequency_hz = NAN;
};

SteppedRun run_at(const std::string& engine, double time_step_s) {
  const Scenario scenario = free_vibration();
  JobSpec job;
  job.engine = engine;
  job.settings.law = ContactLaw::hertz;
  job.settings.time_step_s = time_step_s;
  Measurement measurement;
  measurement.series = SeriesOutput::none;
  ReferenceData kept;
  SteppedRun run;
  run.record = run_job(scenario, job, measurement, nullptr, nullptr, "", &kept, simulator_catalog().make);
  const testing::Decay decay = testing::measure_decay(kept.trajectory, 0);
  if (decay.peaks >= 3) run.frequency_hz = decay.frequency_hz;
  return run;
}

// The steps a run of kDuration_s takes at the recorded step.
long long steps_at(double time_step_s) { return std::llround(kDuration_s / time_step_s); }

class EngineTimeStep : public ::testing::TestWithParam<std::string> {};

TEST_P(EngineTimeStep, StepsWithTheAskedStepAndRecordsIt) {
  const double beam_hz = frame1_first_frequency_hz(free_vibration());
  std::vector<double> frequencies_hz;
  for (double step_s : kSteps_s) {
    const SteppedRun run = run_at(GetParam(), step_s);
    SCOPED_TRACE("asked step " + std::to_string(step_s) + " s");
    ASSERT_EQ(run.record.verdict, Verdict::ok) << run.record.reason;
    EXPECT_EQ(run.record.time_step_s, step_s);
    EXPECT_EQ(run.record.cost.steps, steps_at(step_s));
    // the chain's first frequency is within 0.5 % of the beam's (the default links): 2 % leaves room
    // for the step's and the damping's effect, and none for a step off by a factor
    EXPECT_NEAR(run.frequency_hz / beam_hz, 1.0, 0.02) << run.frequency_hz << " Hz";
    frequencies_hz.push_back(run.frequency_hz);
  }
  EXPECT_NEAR(frequencies_hz[0] / frequencies_hz[1], 1.0, 0.01);
}

TEST_P(EngineTimeStep, RecordsItsDefaultStepAndStepsWithIt) {
  const SteppedRun run = run_at(GetParam(), 0);
  ASSERT_EQ(run.record.verdict, Verdict::ok) << run.record.reason;
  ASSERT_GT(run.record.time_step_s, 0);
  // the step the adapter took is the one its descriptor.json states (and engines.json shows): on the default
  // rig, Bullet's ladder gives its ceiling
  EXPECT_EQ(run.record.time_step_s, descriptor_of(simulator_catalog(), GetParam()).default_time_step_s);
  EXPECT_EQ(run.record.cost.steps, steps_at(run.record.time_step_s));
  EXPECT_NEAR(run.frequency_hz / frame1_first_frequency_hz(free_vibration()), 1.0, 0.02) << run.frequency_hz << " Hz";
}

// The reference takes no fixed step: its descriptor says so (null, 0 here) and its runs record 0.
TEST(ReferenceTimeStep, ItsDescriptorSaysAdaptive) {
  const SimulatorDescriptor d = descriptor_of(simulator_catalog(), "reference");
  EXPECT_EQ(d.default_time_step_s, 0);
  EXPECT_NE(d.default_time_step_note.find("adaptive"), std::string::npos) << d.default_time_step_note;
}

// Every fixed-step simulator of the catalog: all but the adaptive reference, which takes no step.
std::vector<std::string> fixed_step_simulators() {
  std::vector<std::string> names;
  for (const std::string& name : simulator_catalog().names)
    if (name != "reference") names.push_back(name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(Catalog, EngineTimeStep, ::testing::ValuesIn(fixed_step_simulators()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace engine_time_step_test
}  // namespace ib
