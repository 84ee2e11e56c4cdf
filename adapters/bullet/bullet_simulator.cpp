#include "adapters/bullet/bullet_simulator.h"

#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "adapters/bullet/bullet_chain.h"
#include "adapters/bullet/bullet_contact.h"
#include "adapters/bullet/bullet_world.h"
#include "adapters/common/fixed_step_loop.h"
#include "adapters/common/rig.h"
#include "model/simulator_options.h"
#include "physics/link_chain.h"

// Bullet's single-precision build would keep a 40 um indentation at 0.3 m from the origin to a few
// hundred float ulps; CMake refuses it too (adapters/bullet/CMakeLists.txt).
static_assert(sizeof(btScalar) == 8, "impactbench needs Bullet's double-precision build (pkg-config bullet-float64)");

namespace ib {
namespace {

using namespace bullet;  // the adapter's own names: chains and contact mapping

// The step when a run does not set one: the largest of 5e-5, 2e-5, 1e-5, 5e-6, ... s within 3/4 of
// the explicit hinge springs' limit (explicit_hinge_step_limit_s, adapters/common/rig.h; hinge damping,
// K = 8: seen 7e-5 s stable, 8e-5 s not): 5e-5 s for the default K = 8 (and fewer links) with either damping.
// Never above 5e-5 s: a sphere contact starts at the first step that begins overlapping, and the
// overlap gained unresisted in that step adds up to (omega h)^2 of an impact's energy to the
// spring-dashpot (omega = 5200 rad/s for the rig): 7 % at 5e-5 s, 27 % at 1e-4 s, enough to make
// energy grow. The ceiling is descriptor.json's default_time_step_s (adapters/CMakeLists.txt compiles it in).
static_assert(IMPACTBENCH_DEFAULT_TIME_STEP_S == 5e-5, "descriptor.json's default_time_step_s is the ladder's ceiling");
double default_time_step(const RigSpec& rig) {
  const double allowed = 0.75 * explicit_hinge_step_limit_s(rig);
  for (double step : {5e-5, 2e-5, 1e-5, 5e-6, 2e-6, 1e-6, 5e-7, 2e-7, 1e-7})
    if (step <= allowed) return step;
  return allowed;
}

const std::vector<std::pair<std::string, std::string>> kOptions = {
    {"contact",
     "matched (Bullet's contact set to the law: spring-dashpot through contact stiffness/damping, Newton through "
     "restitution with the solver settings that make it real; Hertz, which Bullet has no form for, as a force from "
     "the tip states), injected (the harness's force from the tip states for every law, Bullet's tip contact off) or "
     "native (Bullet's default contact and solver settings, as a user leaves them; the law's parameters are not "
     "used) (default matched)"},
    {"articulation",
     "multibody (one btMultiBody per frame, hinge springs as joint torques each step; default) or constraints "
     "(btRigidBody links joined by btGeneric6DofSpring2Constraint springs)"},
    {"links", kLinksOptionHelp},
    {kChainDampingOption, kChainDampingOptionHelp},
};

Articulation articulation_option(const OptionReader& options) {
  return options.choice("articulation", "multibody", {"multibody", "constraints"}) == "multibody"
             ? Articulation::multibody
             : Articulation::constraints;
}

std::string format(double value) {
  std::ostringstream out;
  out.precision(6);
  out << value;
  return out.str();
}

// The Bullet side of the shared fixed-step loop (adapters/common/fixed_step_loop.h).
class BulletStepper final : public FixedStepEngine {
 public:
  // Bullet's world keeps no step of its own (stepSimulation takes it each time): the stepper holds the run's.
  BulletStepper(const RigSpec& rig, BulletRig& bullet, bool injected, double time_step_s)
      : rig_(rig),
        bullet_(bullet),
        injected_(injected),
        time_step_s_(time_step_s),
        energy_(rig),
        instantaneous_(is_instantaneous(rig.law)) {}

  double time_step_s() const override { return time_step_s_; }

  bool injects_contact() const override { return injected_; }

  std::optional<std::string> read_tips(double t_s, TipState& tips) override {
    for (int f = 0; f < 2; ++f) {
      BulletChain& chain = bullet_.chain(f);
      const BulletChain::TipMotion tip = chain.tip_motion();
      tips.displacement_m[f] = tip.x_m - rig_.frames[f].base_x_m;
      tips.velocity_m_s[f] = tip.velocity_x_m_s;
      chain.joint_state(angles_[f], rates_[f]);
    }
    for (int f = 0; f < 2; ++f)  // non-finite tips: the loop says so itself
      if (std::isfinite(tips.displacement_m[f] + tips.velocity_m_s[f]) &&
          !(angles_[f].allFinite() && rates_[f].allFinite()))
        return "Bullet's state became non-finite (frame " + std::to_string(f + 1) + " hinges) at t = " + format(t_s) +
               " s";
    return std::nullopt;
  }

  double energy_j(double indentation_m) override {
    return energy_(angles_, rates_, instantaneous_ ? 0.0 : indentation_m);
  }

  // the hinge rates read_tips took, for the loop's modal damping torques
  bool read_hinge_rates(std::array<Eigen::VectorXd, 2>& rates_rad_s) override {
    rates_rad_s = rates_;
    return true;
  }

  void apply_loads(const StepLoads& loads) override {
    for (int f = 0; f < 2; ++f) bullet_.chain(f).add_joint_spring_torques();
    if (loads.hinge_damping_torques_n_m)
      for (int f = 0; f < 2; ++f) bullet_.chain(f).add_joint_torques((*loads.hinge_damping_torques_n_m)[f]);
    if (loads.motor_force_n) bullet_.chain(0).add_tip_force_x(*loads.motor_force_n);
    injected_force_n_ = loads.injected_contact_force_n.value_or(0.0);
    if (loads.injected_contact_force_n) {
      bullet_.chain(0).add_tip_force_x(-injected_force_n_);
      bullet_.chain(1).add_tip_force_x(injected_force_n_);
    }
  }

  std::optional<std::string> step() override {
    bullet_.step(time_step_s_);
    double force = injected_force_n_;
    if (!injected_) {
      const auto [impulse, points] = bullet_.tip_contact_impulse();
      force = contact_force_n_ = impulse / time_step_s_;
      max_points_ = std::max(max_points_, points);
    }
    // The published spring-dashpot may pull (injected: applied and recorded as computed); Bullet's own
    // contact impulses are never negative.
    contact_steps_ += force != 0;
    return std::nullopt;
  }

  double contact_force_n() override { return contact_force_n_; }

  SavedState save_state() override {
    SavedState state{"bullet", state_layout(), {}};
    for (int f = 0; f < 2; ++f) {
      const std::vector<double> chain = bullet_.chain(f).state();
      state.values.insert(state.values.end(), chain.begin(), chain.end());
    }
    return state;
  }
  void restore_state(const SavedState& state) override {
    check_saved_state(state, "bullet", state_layout());
    const std::size_t size = bullet_.chain(0).state_size() + bullet_.chain(1).state_size();
    if (state.values.size() != size)
      throw std::invalid_argument("a saved Bullet state of " + std::to_string(state.values.size()) + " values for " +
                                  state_layout() + " (needs " + std::to_string(size) + ")");
    bullet_.chain(0).set_state(state.values.data());
    bullet_.chain(1).set_state(state.values.data() + bullet_.chain(0).state_size());
  }

  long long contact_steps() const { return contact_steps_; }
  int max_contact_points() const { return max_points_; }

 private:
  std::string state_layout() {
    return "bullet " + std::to_string(bullet_.chain(0).state_size()) + " + " +
           std::to_string(bullet_.chain(1).state_size()) +
           " values (multibody: hinge angles then rates; constraints: 13 per body)";
  }

  const RigSpec& rig_;
  BulletRig& bullet_;
  const bool injected_;
  const double time_step_s_;
  const RigEnergy energy_;
  const bool instantaneous_;
  std::array<Eigen::VectorXd, 2> angles_, rates_;
  double injected_force_n_ = 0, contact_force_n_ = 0;
  long long contact_steps_ = 0;
  int max_points_ = 0;
};

class BulletSimulator final : public Simulator {
 public:
  std::string name() const override { return "bullet"; }

  std::string version() const override {
    const int v = btGetVersion();
    return "Bullet " + std::to_string(v / 100) + "." + std::to_string(v % 100) +
           (btIsDoublePrecision() ? " (double precision)" : " (single precision)");
  }

  LibraryBuild library_build() const override {
    // btGetVersion is inline (compiled into the adapter); btTypedConstraint::getFixedBody is defined in
    // libBulletDynamics, the library of the dynamics worlds and solvers this adapter steps
    return {reinterpret_cast<const void*>(&btTypedConstraint::getFixedBody), IMPACTBENCH_ENGINE_INSTALL_PREFIX,
            "BT_BULLET_VERSION " + std::to_string(BT_BULLET_VERSION)};
  }

  std::vector<std::pair<std::string, std::string>> option_help() const override { return kOptions; }

  std::optional<int> chain_links(const Scenario& scenario, const RunSettings& settings) const override {
    const OptionReader options(name(), settings.options, kOptions);
    return links_option(options, settings, scenario);
  }

  RunResult run(const Scenario& scenario, const RunSettings& settings) override {
    const OptionReader options(name(), settings.options, kOptions);
    const ContactPath path = options.contact_path();
    const Articulation articulation = articulation_option(options);
    const int links = links_option(options, settings, scenario);
    const RigSpec rig = build_rig(scenario, settings.law, links, chain_damping_option(options));
    const double h = resolve_time_step_s(settings, default_time_step(rig), name());

    // Which contact Bullet makes, and which the harness injects.
    const bool hertz = std::holds_alternative<HertzLaw>(rig.law);
    const bool injected = path == ContactPath::injected || (path == ContactPath::matched && hertz);
    BulletRig bullet(rig, articulation, !injected);
    RunResult result;
    auto& d = result.diagnostics;
    d.emplace_back("time_step_s", h);
    d.emplace_back("hinge_step_limit_s", explicit_hinge_step_limit_s(rig));
    d.emplace_back("chain_links", links);
    d.emplace_back("articulation_multibody", articulation == Articulation::multibody ? 1 : 0);
    d.emplace_back("contact_injected", injected ? 1 : 0);
    for (int f = 0; f < 2; ++f) add_chain_diagnostics(rig, f, d);
    if (!injected) configure_tip_contact(bullet, rig, path, h, d);
    btContactSolverInfo& info = bullet.solver_info();
    d.emplace_back("solver_iterations", info.m_numIterations);
    d.emplace_back("split_impulse", info.m_splitImpulse ? 1 : 0);
    d.emplace_back("warm_starting", info.m_solverMode & SOLVER_USE_WARMSTARTING ? 1 : 0);
    d.emplace_back("restitution_velocity_threshold_m_s", info.m_restitutionVelocityThreshold);
    d.emplace_back("contact_erp2", info.m_erp2);

    BulletStepper stepper(rig, bullet, injected, h);
    run_fixed_steps(stepper, rig, scenario, settings, result);
    d.emplace_back("contact_steps", static_cast<double>(stepper.contact_steps()));
    d.emplace_back("max_contact_points", stepper.max_contact_points());
    return result;
  }
};

}  // namespace

std::unique_ptr<Simulator> make_bullet_simulator() { return std::make_unique<BulletSimulator>(); }

}  // namespace ib
