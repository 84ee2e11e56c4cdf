// How the Simbody rig is advanced through one of the loop's steps (adapters/common/fixed_step_loop.h):
//  - fixed step: a Simbody integrator with setFixedStepSize(h) (every step accepted), stepTo(t + h);
//  - error control: a Simbody integrator with setAccuracy(a) choosing its own steps; the loop's step is
//    then only the interval at which the state is read and recorded (dense output in between, unless
//    forces are set between steps: then every interval ends an integrator step);
//  - rigid Newton contact: SemiExplicitEulerTimeStepper (its own stepping loop, one step per stepTo).
// Simbody reports trouble by throwing SimTK::Exception; every call that advances catches it and returns
// its message.
#pragma once

#include <Simbody.h>

#include <memory>
#include <optional>
#include <string>

namespace ib::simbody {

enum class IntegratorKind { semi_explicit_euler, rk2, rk3, rkm, verlet, cpodes };
const char* to_string(IntegratorKind kind);

struct SteppingSettings {
  IntegratorKind integrator = IntegratorKind::semi_explicit_euler;
  bool error_control = false;            // false: fixed step = the loop's step
  double accuracy = 0;                   // error control only: Integrator::setAccuracy [-]
  double step_s = 0;                     // the loop's step [s]
  bool rigid_contact = false;            // SemiExplicitEulerTimeStepper instead of an integrator
  double constraint_tolerance_m = 1e-6;  // rigid contact: how close the spheres must be to be "in contact" [m]
};

class SimbodyStepping {
 public:
  SimbodyStepping(const SimTK::MultibodySystem& system, const SimTK::State& initial, const SteppingSettings& settings);
  // The current state, realised to Stage::Velocity.
  const SimTK::State& state() const;
  // Advances by the loop's step (to the next multiple of it); the reason when Simbody threw.
  std::optional<std::string> advance();
  double step_s() const { return settings_.step_s; }  // what advance() advances by [s]
  // Starts again from `state` (a continued run's: a saved state set into a copy of state()), as the
  // constructor started from the initial one.
  void restart(const SimTK::State& state);
  // Forces read from outside the state were changed between steps: the integrator must not reuse what it
  // computed from the old ones (Integrator::reinitialize at Stage::Dynamics).
  void loads_changed();
  long long internal_steps() const;   // the integrator's own steps taken (rigid: one per advance)
  long long attempted_steps() const;  // including rejected ones (error control)
  double smallest_step_s() const;     // error control: over the run so far (0 when none)
  double largest_step_s() const;
  double constraint_tolerance_in_use_m() const;
  double impact_capture_speed_m_s() const;  // rigid contact: below this closing speed an impact is plastic

 private:
  const SimTK::MultibodySystem& system_;
  const SteppingSettings settings_;
  std::unique_ptr<SimTK::Integrator> integrator_;
  std::unique_ptr<SimTK::SemiExplicitEulerTimeStepper> rigid_;
  long long advances_ = 0;
  double smallest_step_s_ = 0, largest_step_s_ = 0;
};

}  // namespace ib::simbody
