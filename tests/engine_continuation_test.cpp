// Every engine continues a run from its saved state (a sweep's continuation, docs/sweeps.md): two runs of
// 1 s joined by the state the first one saved are the run of 2 s they replace. An engine that lost its
// velocities, or a body's orientation, on the way would be millimetres and milliseconds off.
#include <gtest/gtest.h>

#include <cmath>

#include "reference_fixtures.h"
#include "simulators/catalog.h"

namespace ib {
namespace engine_continuation_test {

// The largest differences between a continued run and the second half of the uninterrupted one.
struct Gap {
  double displacement_m = 0, velocity_m_s = 0, onset_s = 0;
  std::size_t events = 0;
};

class EngineContinuation : public ::testing::TestWithParam<std::string> {
 protected:
  // The resonance rig with the motor at 7 Hz (1 s = 7 whole periods: the continued run's motor phase 0 is
  // the long run's at 1 s), frame 1 released from 0.8 mm toward frame 2 (impacts in both halves), Hertz on
  // the engine's matched path at 5e-5 s (1 s = 20 000 steps; every engine is stable there).
  Gap continue_at_one_second() {
    Scenario scenario = testing::paper_scenario("resonance");
    scenario.motor->speed_ratio_to_f1.reset();
    scenario.motor->frequency_hz = 7.0;
    scenario.initial.frame1_tip_displacement_m = 0.8e-3;
    RunSettings settings;
    settings.series_start_s = 0;
    settings.time_step_s = 5e-5;
    settings.options["contact"] = "matched";
    auto engine = make_simulator(GetParam());
    scenario.duration_s = 2;
    const RunResult whole = engine->run(scenario, settings);
    scenario.duration_s = 1;
    const RunResult first = engine->run(scenario, settings);
    EXPECT_EQ(whole.status, RunStatus::ok) << whole.reason;
    EXPECT_TRUE(first.final_state);
    if (!first.final_state) return {};
    EXPECT_EQ(first.final_state->simulator, GetParam());
    settings.initial_state = first.final_state;
    const RunResult second = engine->run(scenario, settings);
    EXPECT_EQ(second.status, RunStatus::ok) << second.reason;
    Gap gap;
    const std::size_t offset = 4096;
    EXPECT_EQ(second.trajectory.size() + offset, whole.trajectory.size());
    for (std::size_t k = 0; k < second.trajectory.size() && k + offset < whole.trajectory.size(); ++k)
      for (int f = 0; f < 2; ++f) {
        gap.displacement_m = std::max(gap.displacement_m, std::abs(second.trajectory.displacement_m[f][k] -
                                                                   whole.trajectory.displacement_m[f][k + offset]));
        gap.velocity_m_s = std::max(gap.velocity_m_s, std::abs(second.trajectory.velocity_m_s[f][k] -
                                                               whole.trajectory.velocity_m_s[f][k + offset]));
      }
    std::vector<double> onsets;
    for (const ContactEvent& e : whole.trajectory.events)
      if (e.onset_time_s >= 1.0) onsets.push_back(e.onset_time_s - 1.0);
    EXPECT_EQ(second.trajectory.events.size(), onsets.size());
    gap.events = std::min(onsets.size(), second.trajectory.events.size());
    for (std::size_t i = 0; i < gap.events; ++i)
      gap.onset_s = std::max(gap.onset_s, std::abs(second.trajectory.events[i].onset_time_s - onsets[i]));
    std::printf("%s continued at 1 s: |du| <= %.3g m, |dv| <= %.3g m/s, onsets within %.3g s (%zu impacts)\n",
                GetParam().c_str(), gap.displacement_m, gap.velocity_m_s, gap.onset_s, gap.events);
    return gap;
  }
};

TEST_P(EngineContinuation, TwoRunsJoinedByTheSavedStateAreTheOneRunTheyReplace) {
  const Gap gap = continue_at_one_second();
  EXPECT_GT(gap.events, 0u);  // the second second has impacts: the contact is continued too
  // of a motion of about 1 mm and 0.05 m/s; a lost velocity or orientation is off by more than 1e-4 m
  EXPECT_LT(gap.displacement_m, 1e-9);
  EXPECT_LT(gap.velocity_m_s, 1e-7);
  EXPECT_LT(gap.onset_s, 1e-6);
}

TEST_P(EngineContinuation, AStateOfAnotherSimulatorOrSizeIsRefused) {
  Scenario scenario = testing::paper_scenario("resonance");
  scenario.duration_s = 0.01;
  RunSettings settings;
  settings.time_step_s = 5e-5;
  auto engine = make_simulator(GetParam());
  settings.initial_state = SavedState{"reference", "modal q then v of 20 modes (beam)", std::vector<double>(40, 0.0)};
  EXPECT_THROW(engine->run(scenario, settings), std::invalid_argument);
  RunSettings plain;  // the same run from the scenario's own start
  plain.time_step_s = 5e-5;
  const RunResult first = engine->run(scenario, plain);
  ASSERT_TRUE(first.final_state);
  SavedState truncated = *first.final_state;
  truncated.values.pop_back();
  settings.initial_state = truncated;
  EXPECT_THROW(engine->run(scenario, settings), std::invalid_argument);
}

std::vector<std::string> engines() {
  std::vector<std::string> names;
  for (const std::string& name : simulator_names())
    if (name != "reference") names.push_back(name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(Engines, EngineContinuation, ::testing::ValuesIn(engines()),
                         [](const auto& info) { return info.param; });

}  // namespace engine_continuation_test
}  // namespace ib
