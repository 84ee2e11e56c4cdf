#include "adapters/simbody/simbody_stepping.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ib::simbody {

using namespace SimTK;

const char* to_string(IntegratorKind kind) {
  switch (kind) {
    case IntegratorKind::semi_explicit_euler:
      return "euler";
    case IntegratorKind::rk2:
      return "rk2";
    case IntegratorKind::rk3:
      return "rk3";
    case IntegratorKind::rkm:
      return "rkm";
    case IntegratorKind::verlet:
      return "verlet";
    case IntegratorKind::cpodes:
      return "cpodes";
  }
  return "?";
}

namespace {
// A run stops when Simbody returns this many times in a row without advancing: after reinitialize() the
// first stepTo() returns at the start of the interval (engines.md); more than a few is a stuck integrator.
constexpr int kMaxCallsWithoutProgress = 8;

std::unique_ptr<Integrator> make_integrator(const MultibodySystem& system, const SteppingSettings& s) {
  switch (s.integrator) {
    case IntegratorKind::semi_explicit_euler:
      // error control for this method is SemiExplicitEuler2Integrator (the option refuses the pairing)
      return std::make_unique<SemiExplicitEulerIntegrator>(system, s.step_s);
    case IntegratorKind::rk2:
      return std::make_unique<RungeKutta2Integrator>(system);
    case IntegratorKind::rk3:
      return std::make_unique<RungeKutta3Integrator>(system);
    case IntegratorKind::rkm:
      return std::make_unique<RungeKuttaMersonIntegrator>(system);
    case IntegratorKind::verlet:
      return std::make_unique<VerletIntegrator>(system);
    case IntegratorKind::cpodes:
      return std::make_unique<CPodesIntegrator>(system, CPodes::BDF, CPodes::Newton);
  }
  throw std::logic_error("unknown integrator");
}
}  // namespace

SimbodyStepping::SimbodyStepping(const MultibodySystem& system, const State& initial, const SteppingSettings& settings)
    : system_(system), settings_(settings) {
  if (settings.rigid_contact) {
    rigid_ = std::make_unique<SemiExplicitEulerTimeStepper>(system);
    rigid_->setRestitutionModel(SemiExplicitEulerTimeStepper::Newton);
    // the default tolerance (accuracy 1e-2 / 10 = 1e-3 m) treats the spheres as touching 1 mm early and
    // fires the impact about 0.5 mm before contact (engines.md); the capture and min-COR speeds follow
    // it (2 x tolerance per second), so impacts above 2e-6 m/s get the full e
    rigid_->setConstraintTolerance(settings.constraint_tolerance_m);
    rigid_->initialize(initial);
    return;
  }
  integrator_ = make_integrator(system, settings);
  if (settings.error_control) {
    integrator_->setAccuracy(settings.accuracy);
    integrator_->setReturnEveryInternalStep(true);  // to count and size every step
  } else {
    integrator_->setFixedStepSize(settings.step_s);
    // land on every step's end exactly instead of stepping past it and interpolating back
    integrator_->setAllowInterpolation(false);
  }
  integrator_->initialize(initial);
}

const State& SimbodyStepping::state() const {
  const State& s = rigid_ ? rigid_->getState() : integrator_->getState();
  system_.realize(s, Stage::Velocity);
  return s;
}

void SimbodyStepping::restart(const State& state) {
  if (rigid_)
    rigid_->initialize(state);
  else
    integrator_->initialize(state);
}

void SimbodyStepping::loads_changed() {
  if (integrator_) {
    integrator_->reinitialize(Stage::Dynamics, false);
    // with interpolation a reinitialised integrator would restart from its advanced state, past the
    // state the loads were computed from: every interval ends a step instead
    integrator_->setAllowInterpolation(false);
  }
}

std::optional<std::string> SimbodyStepping::advance() {
  // the loop's time is a count of steps: the same multiple here, no accumulated sum
  const double target_s = static_cast<double>(advances_ + 1) * settings_.step_s;
  try {
    if (rigid_) {
      rigid_->stepTo(target_s);
    } else {
      int stuck = 0;
      while (integrator_->getTime() < target_s * (1 - 1e-14)) {
        const double before_s = integrator_->getTime();
        const Integrator::SuccessfulStepStatus status = integrator_->stepTo(target_s);
        if (status == Integrator::EndOfSimulation)
          return "Simbody's integrator ended the simulation at t = " + std::to_string(before_s) + " s";
        if (integrator_->getAdvancedTime() <= before_s && integrator_->getTime() <= before_s) {
          if (++stuck > kMaxCallsWithoutProgress)
            return "Simbody's integrator does not advance from t = " + std::to_string(before_s) + " s";
          continue;
        }
        stuck = 0;
        if (settings_.error_control && status == Integrator::TimeHasAdvanced) {
          const double h = integrator_->getPreviousStepSizeTaken();
          smallest_step_s_ = smallest_step_s_ > 0 ? std::min(smallest_step_s_, h) : h;
          largest_step_s_ = std::max(largest_step_s_, h);
        }
      }
    }
  } catch (const std::exception& e) {
    return std::string("Simbody threw: ") + e.what();
  }
  ++advances_;
  return std::nullopt;
}

long long SimbodyStepping::internal_steps() const { return rigid_ ? advances_ : integrator_->getNumStepsTaken(); }
long long SimbodyStepping::attempted_steps() const { return rigid_ ? advances_ : integrator_->getNumStepsAttempted(); }
double SimbodyStepping::smallest_step_s() const { return smallest_step_s_; }
double SimbodyStepping::largest_step_s() const { return largest_step_s_; }

double SimbodyStepping::constraint_tolerance_in_use_m() const {
  return rigid_ ? rigid_->getConstraintToleranceInUse() : integrator_->getConstraintToleranceInUse();
}

double SimbodyStepping::impact_capture_speed_m_s() const {
  return rigid_ ? rigid_->getDefaultImpactCaptureVelocityInUse() : 0.0;
}

}  // namespace ib::simbody
