#include "adapters/dart/dart_simulator.h"

#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include <dart/config.hpp>
#include <dart/simulation/World.hpp>

#include "adapters/common/fixed_step_loop.h"
#include "adapters/common/rig.h"
#include "adapters/dart/dart_contact.h"
#include "adapters/dart/dart_rig.h"
#include "model/simulator_options.h"

namespace ib {
namespace {

using dart_adapter::Collision;
using dart_adapter::ContactSetup;
using dart_adapter::DartRig;
using dart_adapter::DartRigSettings;

// The step when a run's settings give none, as for the other fixed-step engines. DART's joint springs and
// dampers are implicit, so the chain is stable at any step; the modal damping torques the loop holds over a
// step add no limit with implicit springs (explicit_hinge_step_limit_s); the contact is what the step resolves.
// Its value is descriptor.json's default_time_step_s (adapters/CMakeLists.txt).
constexpr double kDefaultTimeStep_s = IMPACTBENCH_DEFAULT_TIME_STEP_S;

const std::vector<std::pair<std::string, std::string>> kOptions = {
    {"contact",
     "matched (Newton: DART's restitution with analytic sphere collision; Hertz and spring-dashpot: the law's force "
     "from the tip states, DART has no compliant rigid contact; default), injected (the law's force from the tip "
     "states, no collision), native (DART's defaults: FCL collision, restitution 0, friction 1)"},
    {"length_unit",
     "the length unit of the DART model: m (default), cm or mm; DART's contact solver has velocity constants in model "
     "units (no bounce when e v <= 0.1 unit/s, bounce capped at 100 unit/s), so cm puts them at 1 mm/s and 1 m/s; the "
     "physics is the same in any unit"},
    {"lcp", "DART's boxed LCP solver: dantzig (default) or pgs"},
    {"links", kLinksOptionHelp},
    {kChainDampingOption, kChainDampingOptionHelp},
};

struct RunPlan {
  ContactPath contact = ContactPath::matched;
  double length_scale = 1;
  std::string length_unit = "m";
  bool pgs = false;
  int links = 0;
  ChainDamping damping = ChainDamping::modal;
  double time_step_s = kDefaultTimeStep_s;
};

RunPlan plan_run(const Scenario& scenario, const RunSettings& settings) {
  const OptionReader options("dart", settings.options, kOptions);
  RunPlan plan;
  plan.contact = options.contact_path();
  plan.length_unit = options.choice("length_unit", "m", {"m", "cm", "mm"});
  plan.length_scale = plan.length_unit == "m" ? 1.0 : plan.length_unit == "cm" ? 100.0 : 1000.0;
  plan.pgs = options.choice("lcp", "dantzig", {"dantzig", "pgs"}) == "pgs";
  plan.links = links_option(options, settings, scenario);
  plan.damping = chain_damping_option(options);
  plan.time_step_s = resolve_time_step_s(settings, kDefaultTimeStep_s, "dart");
  return plan;
}

DartRigSettings rig_settings(const RunPlan& plan, const ContactSetup& contact) {
  DartRigSettings s;
  s.time_step_s = plan.time_step_s;
  s.length_scale = plan.length_scale;
  s.collision = contact.collision;
  s.restitution_per_shape = contact.restitution_per_shape;
  s.friction = contact.friction;
  s.pgs_solver = plan.pgs;
  return s;
}

// The DART side of the shared fixed-step loop (adapters/common/fixed_step_loop.h).
class DartStepper final : public FixedStepEngine {
 public:
  DartStepper(const Scenario& scenario, const RunSettings& settings, const RunPlan& plan)
      : plan_(plan),
        rig_(build_rig(scenario, settings.law, plan.links, plan.damping)),
        contact_(dart_adapter::contact_setup(plan.contact, rig_.law)),
        dart_rig_(rig_, rig_settings(plan, contact_)),
        energy_(rig_) {}

  const RigSpec& rig() const { return rig_; }
  double time_step_s() const override { return dart_rig_.time_step_s(); }  // the world's own

  bool injects_contact() const override { return contact_.force_from_tip_states; }

  std::optional<std::string> read_tips(double t_s, TipState& tips) override {
    for (int f = 0; f < 2; ++f) {
      tips.displacement_m[f] = dart_rig_.tip_displacement_m(f);
      tips.velocity_m_s[f] = dart_rig_.tip_velocity_m_s(f);
    }
    // DART (built with assertions on) aborts on a non-finite force: the loop stops on non-finite tips
    // before any load is applied; a non-finite hinge state with finite tips is caught here.
    for (int f = 0; f < 2; ++f)
      if (!dart_rig_.hinge_angles_rad(f).allFinite() || !dart_rig_.hinge_rates_rad_s(f).allFinite()) {
        std::ostringstream why;
        why << "non-finite hinge angle or rate of frame " << f + 1 << " at t = " << t_s << " s";
        return why.str();
      }
    return std::nullopt;
  }

  // DART's rigid contact stores no energy; the injected law's elastic energy counts where it acts.
  double energy_j(double indentation_m) override {
    const std::array<Eigen::VectorXd, 2> angles{dart_rig_.hinge_angles_rad(0), dart_rig_.hinge_angles_rad(1)};
    const std::array<Eigen::VectorXd, 2> rates{dart_rig_.hinge_rates_rad_s(0), dart_rig_.hinge_rates_rad_s(1)};
    return energy_(angles, rates, contact_.force_from_tip_states ? indentation_m : 0.0);
  }

  bool read_hinge_rates(std::array<Eigen::VectorXd, 2>& rates_rad_s) override {
    for (int f = 0; f < 2; ++f) rates_rad_s[f] = dart_rig_.hinge_rates_rad_s(f);
    return true;
  }

  void apply_loads(const StepLoads& loads) override {
    if (loads.hinge_damping_torques_n_m)
      for (int f = 0; f < 2; ++f) dart_rig_.set_hinge_torques(f, (*loads.hinge_damping_torques_n_m)[f]);
    if (loads.injected_contact_force_n) {
      dart_rig_.add_tip_force(0, -*loads.injected_contact_force_n);
      dart_rig_.add_tip_force(1, *loads.injected_contact_force_n);
    }
    if (loads.motor_force_n) dart_rig_.add_tip_force(0, *loads.motor_force_n);
  }

  std::optional<std::string> step() override {
    dart_rig_.step();
    if (dart_rig_.contact_points() > 0) ++contact_steps_;
    return std::nullopt;
  }

  double contact_force_n() override { return dart_rig_.tip_contact_force_n(); }

  SavedState save_state() override { return {"dart", state_layout(), dart_rig_.joint_state()}; }
  void restore_state(const SavedState& state) override {
    check_saved_state(state, "dart", state_layout());
    if (state.values.size() != dart_rig_.joint_state_size())
      throw std::invalid_argument("a saved DART state of " + std::to_string(state.values.size()) + " values for " +
                                  state_layout() + " (needs " + std::to_string(dart_rig_.joint_state_size()) + ")");
    dart_rig_.set_joint_state(state.values);
  }
  std::string state_layout() const {
    return "dart joint positions then velocities, frame 1 then frame 2 (" +
           std::to_string(dart_rig_.joint_state_size()) + " values)";
  }

  std::vector<std::pair<std::string, double>> diagnostics() const {
    std::vector<std::pair<std::string, double>> d;
    d.emplace_back("time_step_s", time_step_s());
    d.emplace_back("chain_links", rig_.frames[0].chain.links);
    d.emplace_back("length_unit_per_m", plan_.length_scale);
    for (int f = 0; f < 2; ++f) add_chain_diagnostics(rig_, f, d);
    d.emplace_back("contact_force_from_tip_states", contact_.force_from_tip_states ? 1 : 0);
    d.emplace_back("collision_detector_analytic", contact_.collision == Collision::analytic ? 1 : 0);
    d.emplace_back("collision_detector_fcl", contact_.collision == Collision::fcl_default ? 1 : 0);
    if (contact_.collision != Collision::none) {
      // DART's defaults where the adapter leaves them (ShapeNode's DynamicsAspect: restitution 0, friction 1)
      d.emplace_back("restitution_per_shape", contact_.restitution_per_shape.value_or(0.0));
      d.emplace_back("restitution_of_pair", std::pow(contact_.restitution_per_shape.value_or(0.0), 2));
      d.emplace_back("friction_coefficient", contact_.friction.value_or(1.0));
      d.emplace_back("bounce_threshold_m_s", dart_adapter::kBounceThreshold_units_s / plan_.length_scale);
      d.emplace_back("max_bounce_velocity_m_s", dart_adapter::kMaxBounceVelocity_units_s / plan_.length_scale);
      d.emplace_back("contact_steps", static_cast<double>(contact_steps_));
    }
    d.emplace_back("lcp_pgs", plan_.pgs ? 1 : 0);
    return d;
  }

 private:
  const RunPlan plan_;
  const RigSpec rig_;
  const ContactSetup contact_;
  DartRig dart_rig_;
  const RigEnergy energy_;
  long long contact_steps_ = 0;
};

class DartSimulator final : public Simulator {
 public:
  std::string name() const override { return "dart"; }
  std::string version() const override { return std::string("DART ") + DART_VERSION; }
  LibraryBuild library_build() const override {
    // World::create(name) is defined in libdart (the other overload is a header template)
    using CreateWorld = std::shared_ptr<dart::simulation::World> (*)(const std::string&);
    const CreateWorld create_world = &dart::simulation::World::create;
    return {reinterpret_cast<const void*>(create_world), IMPACTBENCH_ENGINE_INSTALL_PREFIX,
            std::string("DART_VERSION ") + DART_VERSION};
  }
  std::vector<std::pair<std::string, std::string>> option_help() const override { return kOptions; }
  std::optional<int> chain_links(const Scenario& scenario, const RunSettings& settings) const override {
    return plan_run(scenario, settings).links;
  }

  RunResult run(const Scenario& scenario, const RunSettings& settings) override {
    const RunPlan plan = plan_run(scenario, settings);
    DartStepper stepper(scenario, settings, plan);
    RunResult result;
    run_fixed_steps(stepper, stepper.rig(), scenario, settings, result);
    result.diagnostics = stepper.diagnostics();
    return result;
  }
};

}  // namespace

std::unique_ptr<Simulator> make_dart_simulator() { return std::make_unique<DartSimulator>(); }

}  // namespace ib
