// The one fixed-step loop every engine runs (docs/adding-an-engine.md): it steps an engine from t = 0 to
// the scenario's end with the run's step, applies the motor force and, on the injected path, the
// harness's contact force at the tips, stops the run at the divergence bound of the run's settings
// (RunSettings::stability, the record the verdict reads too), records every state through the
// StepRecorder from the run's series start on, and times the stepping with the one RunClock. An engine
// supplies only what is its own, through FixedStepEngine.
//
// Within a step, in this order: read the tips at t (the state the last step ended in, or the initial one)
// -> stop when the engine reported trouble (nothing recorded) or a tip is not finite (nothing recorded)
// -> record the state, with the contact force of the step that led to it -> stop when a tip is beyond
// the bound (its state is recorded: it happened) -> at the end, stop -> the loads of the coming step from
// the state at its start (motor at t, the injected contact force, the chains' modal damping torques
// -C theta' from the hinge rates the engine reads, read_hinge_rates) -> step -> the contact force of that
// step (the injected one, or the engine's own).
//
// What stays the engine's, in its Simulator::run around run_fixed_steps: its options, the rig
// (build_rig, adapters/common/rig.h) translated into its own bodies and joints, its contact set up for
// the law and path, and its diagnostics, written into the result. The step has one owner: the engine
// is built with it (resolve_time_step_s: the asked step, or the engine's default; explicit hinge springs
// bound it, explicit_hinge_step_limit_s) and advances by it at every step() (many engines bake it into
// their model: contact softness, a world's own step); the loop reads it from the engine
// (FixedStepEngine::time_step_s), counts time and steps with it, and hands it on as RunResult::time_step_s,
// the step the run records. Accelerations are not asked for: the recorder takes a step's velocity change.
// tests/fixed_step_loop_test.cpp pins this contract with a scripted engine.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "adapters/common/rig.h"
#include "model/simulator.h"

namespace ib {

// The two tips as an engine reads them, along x from rest, positive toward frame 2.
struct TipState {
  std::array<double, 2> displacement_m{};
  std::array<double, 2> velocity_m_s{};
};

// The loads of the coming step, held over it, computed by the loop from the state at the step's start.
struct StepLoads {
  double t_s = 0;                                  // the step's start [s]
  std::optional<double> motor_force_n;             // on frame 1's tip along +x; absent without a motor
  std::optional<double> injected_contact_force_n;  // the harness's law: -F on frame 1's tip, +F on
                                                   // frame 2's; absent when the engine makes the contact
  // The chains' modal damping (physics/link_chain.h, ChainDamping::modal) as hinge torques, K per frame in
  // hinge order from the clamp: tau = -C theta' from the rates at the step's start, each torque acting on
  // the body above its hinge and its reaction on the body below [N m]. Null when the loop applies none
  // (hinge damping, or an engine that applies the chain's damping matrix itself: read_hinge_rates).
  const std::array<Eigen::VectorXd, 2>* hinge_damping_torques_n_m = nullptr;
};

// What an engine implements for the loop (its rig built, its contact configured, beforehand).
class FixedStepEngine {
 public:
  virtual ~FixedStepEngine() = default;
  // True when the harness's contact law is applied as tip forces (the injected path, or a law the engine
  // has no form for); the engine then makes no contact of its own.
  virtual bool injects_contact() const = 0;
  // The tips now into `tips`. A reason instead when the engine cannot give a state to trust (its own
  // checks failed, an internal state is not finite): the run stops without recording it.
  virtual std::optional<std::string> read_tips(double t_s, TipState& tips) = 0;
  // The mechanical energy of the state just read [J], with the contact's elastic energy at this
  // indentation where the engine's contact stores one (RigEnergy); called only where the recorder reads it.
  virtual double energy_j(double indentation_m) = 0;
  // The hinge rates of the state just read [rad/s], K per frame in hinge order from the clamp, for the
  // modal damping torques of the coming step (StepLoads::hinge_damping_torques_n_m); called only when the
  // rig's chains have modal damping. False (the default) when the engine applies the chains' damping
  // matrix itself (a linearised-chain engine with the full C): the loop then adds no torques.
  virtual bool read_hinge_rates(std::array<Eigen::VectorXd, 2>& rates_rad_s) {
    (void)rates_rad_s;
    return false;
  }
  // Applies the loads of the coming step, in the engine's own order, plus whatever the engine adds
  // itself (explicit hinge springs, a contact joint).
  virtual void apply_loads(const StepLoads& loads) = 0;
  // The step the engine was built with and advances by at every step() [s]: read from the engine's own
  // model where it keeps one, so that the step counted and recorded is the step taken.
  virtual double time_step_s() const = 0;
  // One step of time_step_s(). A reason instead when the engine reported trouble during it (the run stops there).
  virtual std::optional<std::string> step() = 0;
  // The force between the tips during the last step [N], > 0 compressive (when it makes the contact).
  virtual double contact_force_n() = 0;
  // The engine's own state, for a later run to continue from (RunSettings::initial_state): what it needs
  // to continue its bodies exactly (its joints' positions and velocities, or its bodies' poses and
  // velocities), in SI units, with a layout that names what the values are and for which rig.
  virtual SavedState save_state() = 0;
  // Puts the engine into a state save_state wrote, before the first step (the loop calls it when the run
  // continues). Throws std::invalid_argument for a state of another simulator, layout or size.
  virtual void restore_state(const SavedState& state) = 0;
  // Appended to the reason of a run that left the bound (e.g. a step limit, the engine's own messages).
  virtual std::string explain_instability() const { return {}; }
};

// The step a fixed-step engine is built with: settings.time_step_s when given (> 0), else the engine's
// default (default_step_s). The one place of this rule. Throws std::invalid_argument, naming the engine,
// for a negative or non-finite step.
double resolve_time_step_s(const RunSettings& settings, double default_step_s, const std::string& engine);

// A reason read_tips gives for a hinge angle or rate that is not finite while the tips are (non-finite tips
// the loop reports itself): "non-finite hinge angle or rate at t = T s"; nullopt when every value is finite.
std::optional<std::string> nonfinite_hinges(double t_s, const TipState& tips,
                                            const std::array<Eigen::VectorXd, 2>& angles,
                                            const std::array<Eigen::VectorXd, 2>& rates);

// Runs the engine over the scenario with its fixed step (engine.time_step_s()): fills the result's
// trajectory, impact zoom, status and reason (unstable, with the time and the bound), cost, time step and,
// for a run that reached its end, final state. Starts from settings.initial_state when set. The
// diagnostics are the engine's.
void run_fixed_steps(FixedStepEngine& engine, const RigSpec& rig, const Scenario& scenario, const RunSettings& settings,
                     RunResult& result);

}  // namespace ib
