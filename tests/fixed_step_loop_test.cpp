// The one fixed-step loop every engine runs (adapters/common/fixed_step_loop.h), driven by a scripted
// engine whose tips follow a prescribed path: how many steps it takes, the order of an engine's calls
// within a step, the loads it hands over (motor at t, the injected contact force, the modal damping
// torques from the hinge rates it reads), the divergence bound
// taken from the run's settings, and the three ways a run stops early.
#include "adapters/common/fixed_step_loop.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "adapters/common/injected_contact.h"
#include "reference_fixtures.h"

namespace ib {
namespace fixed_step_loop_test {

constexpr double kStep_s = 1e-3;

// Tips at a prescribed state per step index n (t = n h); every call is logged as text.
class ScriptedEngine final : public FixedStepEngine {
 public:
  using Path = std::function<TipState(long long n)>;
  explicit ScriptedEngine(Path path, bool injects = false, double time_step_s = kStep_s)
      : path_(std::move(path)), injects_(injects), time_step_s_(time_step_s) {}

  double time_step_s() const override { return time_step_s_; }
  bool injects_contact() const override { return injects_; }
  std::optional<std::string> read_tips(double t_s, TipState& tips) override {
    calls.push_back("read");
    if (read_trouble_at && n_ == *read_trouble_at) return std::string("engine trouble reading");
    times_read_s.push_back(t_s);
    tips = path_(n_);
    return std::nullopt;
  }
  double energy_j(double) override {
    calls.push_back("energy");
    return 0;
  }
  // Hinge rates per step index when `hinge_rates` is set (the engine then wants the loop's damping torques).
  bool read_hinge_rates(std::array<Eigen::VectorXd, 2>& rates_rad_s) override {
    if (!hinge_rates) return false;
    calls.push_back("rates");
    rates_rad_s = hinge_rates(n_);
    return true;
  }
  void apply_loads(const StepLoads& loads) override {
    calls.push_back("apply");
    applied.push_back(loads);
    // the torques are the loop's buffer, valid during this call: keep a copy
    if (loads.hinge_damping_torques_n_m) damping_torques_n_m.push_back(*loads.hinge_damping_torques_n_m);
    applied.back().hinge_damping_torques_n_m = nullptr;
  }
  std::optional<std::string> step() override {
    calls.push_back("step");
    if (step_trouble_at && n_ == *step_trouble_at) return std::string("engine trouble stepping");
    ++n_;
    return std::nullopt;
  }
  double contact_force_n() override {
    calls.push_back("force");
    return engine_contact_force_n;
  }
  std::string explain_instability() const override { return "; the engine's words"; }
  SavedState save_state() override {
    calls.push_back("save");
    return {"scripted", "step index", {static_cast<double>(n_)}};
  }
  void restore_state(const SavedState& state) override {
    calls.push_back("restore");
    check_saved_state(state, "scripted", "step index");
    n_ = static_cast<long long>(state.values.at(0));
  }

  std::vector<std::string> calls;
  std::vector<double> times_read_s;
  std::vector<StepLoads> applied;
  std::vector<std::array<Eigen::VectorXd, 2>> damping_torques_n_m;
  std::function<std::array<Eigen::VectorXd, 2>(long long n)> hinge_rates;
  std::optional<long long> read_trouble_at, step_trouble_at;
  double engine_contact_force_n = 0;

 private:
  Path path_;
  bool injects_;
  double time_step_s_;
  long long n_ = 0;
};

TipState at_rest(long long) { return {}; }

// Frame `f`'s tip moving away from rest by 1 mm per step (0.5 mm at t = 0).
ScriptedEngine::Path drifting(int f) {
  return [f](long long n) {
    TipState tips;
    tips.displacement_m[f] = 1e-3 * static_cast<double>(n) + 5e-4;
    return tips;
  };
}

struct LoopRun {
  Scenario scenario = testing::paper_scenario("resonance");
  RigSpec rig;
  RunSettings settings;
  RunResult result;
  explicit LoopRun(double duration_s, ChainDamping damping = ChainDamping::modal) {
    scenario.duration_s = duration_s;
    settings.series_start_s = 0;
    settings.time_step_s = kStep_s;
    rig = build_rig(scenario, ContactLaw::hertz, 2, damping);
  }
  void run(ScriptedEngine& engine) { run_fixed_steps(engine, rig, scenario, settings, result); }
};

TEST(FixedStepLoop, StepsFromZeroToTheScenarioEndWithTheRunsStep) {
  LoopRun loop(0.01);
  ScriptedEngine engine(at_rest);
  loop.run(engine);
  EXPECT_EQ(loop.result.status, RunStatus::ok);
  ASSERT_EQ(engine.times_read_s.size(), 11u);  // t = 0, h, ..., 10 h: every state is read and recorded
  for (std::size_t n = 0; n < engine.times_read_s.size(); ++n) EXPECT_EQ(engine.times_read_s[n], n * kStep_s);
  EXPECT_EQ(engine.applied.size(), 10u);
  EXPECT_EQ(loop.result.cost.steps, 10);  // steps taken: the last state recorded is t = 10 h
  EXPECT_GT(loop.result.trajectory.size(), 0u);
}

// The step is the engine's (built with it, resolve_time_step_s): the loop counts time and steps with it
// and hands it on as the run's, whatever the settings held.
TEST(FixedStepLoop, StepsWithTheEnginesStepAndHandsItOn) {
  LoopRun loop(0.01);
  ScriptedEngine engine(at_rest, false, 2.5e-3);
  loop.run(engine);
  ASSERT_EQ(engine.times_read_s.size(), 5u);  // t = 0, 2.5, 5, 7.5, 10 ms
  for (std::size_t n = 0; n < engine.times_read_s.size(); ++n) EXPECT_EQ(engine.times_read_s[n], n * 2.5e-3);
  EXPECT_EQ(loop.result.cost.steps, 4);
  EXPECT_EQ(loop.result.time_step_s, 2.5e-3);
}

TEST(FixedStepLoop, TheStepIsTheAskedOneOrTheEnginesDefault) {
  RunSettings settings;
  EXPECT_EQ(resolve_time_step_s(settings, 5e-5, "engine"), 5e-5);
  settings.time_step_s = 2e-5;
  EXPECT_EQ(resolve_time_step_s(settings, 5e-5, "engine"), 2e-5);
  for (double bad : {-1e-4, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    settings.time_step_s = bad;
    EXPECT_THROW(resolve_time_step_s(settings, 5e-5, "engine"), std::invalid_argument) << bad;
  }
}

TEST(FixedStepLoop, AStepReadsRecordsAppliesStepsThenReadsTheContactForce) {
  LoopRun loop(2 * kStep_s);
  ScriptedEngine engine(at_rest);
  loop.run(engine);
  // the series starts at 0: every state is one the recorder keeps, so its energy is read too
  // and at the end of a run that reached it, the state a later run may continue from
  const std::vector<std::string> expected = {"read",  "energy", "apply", "step", "force",  "read", "energy",
                                             "apply", "step",   "force", "read", "energy", "save"};
  EXPECT_EQ(engine.calls, expected);
}

TEST(FixedStepLoop, AContinuedRunStartsWhereTheSavedStateEndedAndSavesItsOwnEnd) {
  LoopRun first(0.005);
  ScriptedEngine engine(drifting(1));
  first.run(engine);
  ASSERT_EQ(first.result.status, RunStatus::ok);
  ASSERT_TRUE(first.result.final_state);
  EXPECT_EQ(first.result.final_state->values, std::vector<double>{5});  // saved after the last of its 5 steps
  EXPECT_EQ(engine.calls.back(), "save");

  LoopRun second(0.003);
  second.settings.initial_state = first.result.final_state;
  ScriptedEngine continued(drifting(1));
  second.run(continued);
  EXPECT_EQ(continued.calls.front(), "restore");  // before the first state is read
  ASSERT_GT(second.result.trajectory.size(), 0u);
  EXPECT_DOUBLE_EQ(second.result.trajectory.displacement_m[1][0], 1e-3 * 5 + 5e-4);  // where the first run ended
  EXPECT_EQ(second.result.trajectory.time_s[0], 0.0);                                // its own clock starts at 0
  EXPECT_EQ(second.result.final_state->values, std::vector<double>{8});
}

TEST(FixedStepLoop, AStateOfAnotherSimulatorIsRefusedAndARunThatStopsEarlySavesNothing) {
  LoopRun loop(0.005);
  loop.settings.initial_state = SavedState{"reference", "modal q then v", {0, 0}};
  ScriptedEngine engine(at_rest);
  EXPECT_THROW(loop.run(engine), std::invalid_argument);

  LoopRun unstable(0.1);
  ScriptedEngine drifting_away(drifting(0));  // beyond 0.1 L after about 30 steps
  unstable.run(drifting_away);
  EXPECT_EQ(unstable.result.status, RunStatus::unstable);
  EXPECT_FALSE(unstable.result.final_state);
}

TEST(FixedStepLoop, TheMotorForceAtTheStepsStartOnFrameOne) {
  LoopRun loop(0.01);
  ASSERT_TRUE(loop.rig.motor);
  ScriptedEngine engine(at_rest);
  loop.run(engine);
  for (std::size_t n = 0; n < engine.applied.size(); ++n) {
    const StepLoads& loads = engine.applied[n];
    EXPECT_EQ(loads.t_s, n * kStep_s);
    ASSERT_TRUE(loads.motor_force_n);
    EXPECT_EQ(*loads.motor_force_n, loop.rig.motor->at(n * kStep_s));
    EXPECT_FALSE(loads.injected_contact_force_n);  // the engine makes its own contact
  }
}

TEST(FixedStepLoop, TheInjectedContactForceIsTheLawsFromTheTipsAndIsRecorded) {
  LoopRun loop(0.005);
  // the tips pressed 10 um into each other, frame 1 still approaching
  auto pressed = [&](long long) {
    TipState tips;
    tips.displacement_m = {loop.rig.gap_m + 1e-5, 0};
    tips.velocity_m_s = {0.01, 0};
    return tips;
  };
  ScriptedEngine engine(pressed, /*injects=*/true);
  engine.engine_contact_force_n = -1;  // never read on the injected path
  loop.run(engine);
  InjectedContact law(loop.rig);
  const double expected_n = law.force(loop.rig.gap_m + 1e-5, 0.01, 0, 0, kStep_s);
  ASSERT_GT(expected_n, 0);
  for (const StepLoads& loads : engine.applied) {
    ASSERT_TRUE(loads.injected_contact_force_n);
    EXPECT_EQ(*loads.injected_contact_force_n, expected_n);
  }
  for (const std::string& call : engine.calls) EXPECT_NE(call, "force");
  ASSERT_FALSE(loop.result.trajectory.events.empty());
  EXPECT_EQ(loop.result.trajectory.events.front().peak_force_n, expected_n);
}

TEST(FixedStepLoop, TheEnginesOwnContactForceIsRecordedWhenItMakesTheContact) {
  LoopRun loop(0.005);
  auto pressed = [&](long long) {
    TipState tips;
    tips.displacement_m = {loop.rig.gap_m + 1e-5, 0};
    return tips;
  };
  ScriptedEngine engine(pressed);
  engine.engine_contact_force_n = 42;
  loop.run(engine);
  ASSERT_FALSE(loop.result.trajectory.events.empty());
  EXPECT_EQ(loop.result.trajectory.events.front().peak_force_n, 42);
}

// Hinge rates that change with the step, different in the two frames.
std::array<Eigen::VectorXd, 2> rates_at(long long n) {
  const double s = static_cast<double>(n + 1);
  return {Eigen::Vector2d(0.1 * s, -0.2), Eigen::Vector2d(-0.05, 0.3 * s)};
}

// Modal damping: the rates read at the step's start (after the state is recorded, before the loads are
// applied) give the torques -C theta' of each frame's own matrix, handed over with that step's loads.
TEST(FixedStepLoop, ModalDampingTorquesAreMinusCTimesTheRatesAtTheStepsStart) {
  LoopRun loop(3 * kStep_s);
  ASSERT_EQ(loop.rig.frames[0].chain.modal_damping_n_m_s_per_rad.rows(), 2);
  ScriptedEngine engine(at_rest);
  engine.hinge_rates = rates_at;
  loop.run(engine);
  const std::vector<std::string> first_step = {"read", "energy", "rates", "apply", "step", "force"};
  EXPECT_EQ(std::vector<std::string>(engine.calls.begin(), engine.calls.begin() + 6), first_step);
  ASSERT_EQ(engine.damping_torques_n_m.size(), 3u);
  for (long long n = 0; n < 3; ++n)
    for (int f = 0; f < 2; ++f) {
      const Eigen::MatrixXd& c = loop.rig.frames[f].chain.modal_damping_n_m_s_per_rad;
      const Eigen::VectorXd expected = -c * rates_at(n)[f];
      EXPECT_LT((engine.damping_torques_n_m[n][f] - expected).norm(), 1e-15 * expected.norm()) << n << " " << f;
      EXPECT_LT(engine.damping_torques_n_m[n][f].dot(rates_at(n)[f]), 0);  // it dissipates
    }
}

// No torques where the chain's damping is the hinge dampers (the engine's own), nor for an engine that
// applies the damping matrix itself (read_hinge_rates false); the rates are not even asked for the former.
TEST(FixedStepLoop, NoDampingTorquesForHingeDampingOrAnEngineThatAppliesItsOwn) {
  LoopRun hinge(3 * kStep_s, ChainDamping::hinge);
  ScriptedEngine asks(at_rest);
  asks.hinge_rates = rates_at;
  hinge.run(asks);
  EXPECT_TRUE(asks.damping_torques_n_m.empty());
  for (const std::string& call : asks.calls) EXPECT_NE(call, "rates");

  LoopRun modal(3 * kStep_s);
  ScriptedEngine own(at_rest);  // no hinge_rates: read_hinge_rates returns false
  modal.run(own);
  EXPECT_EQ(own.applied.size(), 3u);
  EXPECT_TRUE(own.damping_torques_n_m.empty());
}

TEST(FixedStepLoop, TheDivergenceBoundIsTheRunSettings) {
  // 0.1 L = 30 mm (the default): frame 1's tip passes it at step 30 (30.5 mm)
  LoopRun wide(0.1);
  ScriptedEngine drift_wide(drifting(0));
  wide.run(drift_wide);
  EXPECT_EQ(wide.result.status, RunStatus::unstable);
  EXPECT_EQ(wide.result.cost.steps, 30);  // the state beyond the bound (t = 30 h) is recorded: it happened
  EXPECT_EQ(wide.result.reason,
            "frame 1 tip displacement |u| = 0.0305 m beyond 0.1 L = 0.03 m at t = 0.03 s; the engine's words");

  // 0.05 L = 15 mm: frame 2's tip passes it at step 15
  LoopRun narrow(0.1);
  narrow.settings.stability.displacement_bound_fraction_of_length = 0.05;
  ScriptedEngine drift_narrow(drifting(1));
  narrow.run(drift_narrow);
  EXPECT_EQ(narrow.result.status, RunStatus::unstable);
  EXPECT_EQ(narrow.result.cost.steps, 15);
  EXPECT_EQ(narrow.result.reason,
            "frame 2 tip displacement |u| = 0.0155 m beyond 0.05 L = 0.015 m at t = 0.015 s; the engine's words");
}

TEST(FixedStepLoop, ANonFiniteTipStopsTheRunUnrecorded) {
  LoopRun loop(0.01);
  ScriptedEngine engine([](long long n) {
    TipState tips;
    if (n == 5) tips.velocity_m_s[1] = std::numeric_limits<double>::quiet_NaN();
    return tips;
  });
  loop.run(engine);
  EXPECT_EQ(loop.result.status, RunStatus::unstable);
  EXPECT_EQ(loop.result.cost.steps, 4);  // recorded up to t = 4 h, not the non-finite state at 5 h
  EXPECT_EQ(loop.result.reason.rfind("non-finite state of frame 2 at t = 0.005 s", 0), 0u) << loop.result.reason;
  EXPECT_NE(loop.result.reason.find("; the engine's words"), std::string::npos);
}

TEST(FixedStepLoop, TheEnginesTroubleStopsTheRunWithItsReason) {
  LoopRun reading(0.01);
  ScriptedEngine bad_read(at_rest);
  bad_read.read_trouble_at = 3;
  reading.run(bad_read);
  EXPECT_EQ(reading.result.status, RunStatus::unstable);
  EXPECT_EQ(reading.result.reason, "engine trouble reading");
  EXPECT_EQ(reading.result.cost.steps, 2);  // the state at 3 h was not given

  LoopRun stepping(0.01);
  ScriptedEngine bad_step(at_rest);
  bad_step.step_trouble_at = 3;
  stepping.run(bad_step);
  EXPECT_EQ(stepping.result.status, RunStatus::unstable);
  EXPECT_EQ(stepping.result.reason, "engine trouble stepping");
  EXPECT_EQ(stepping.result.cost.steps, 3);  // the state at 3 h was recorded before its step failed
}

TEST(FixedStepLoop, TheSeriesStartsAtTheRunsSeriesStart) {
  LoopRun loop(0.01);
  loop.settings.series_start_s = 0.005;
  ScriptedEngine engine(at_rest);
  loop.run(engine);
  ASSERT_GT(loop.result.trajectory.size(), 0u);
  EXPECT_NEAR(loop.result.trajectory.time_s.front(), 0.005, 1e-12);
}

}  // namespace fixed_step_loop_test
}  // namespace ib
