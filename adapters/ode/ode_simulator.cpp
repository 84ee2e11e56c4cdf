#include "adapters/ode/ode_simulator.h"

#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "adapters/common/fixed_step_loop.h"
#include "adapters/common/rig.h"
#include "adapters/ode/ode_contact.h"
#include "adapters/ode/ode_library.h"
#include "adapters/ode/ode_rig.h"
#include "model/simulator_options.h"

namespace ib {
namespace {

using ode::ContactSetup;
using ode::OdeModelSettings;
using ode::OdeRig;
using ode::SpringPath;
using ode::Stepper;

// The step when a run's settings give none (the benchmark's default for fixed-step engines). It resolves
// the structure, but it is not ODE's accurate step for this rig: the implicit hinge springs add
// omega_1 h / 2 = 0.0022 to zeta = 0.003 and the soft contact keeps about half its restitution
// (README.md, "What a user should know"). Its value is descriptor.json's default_time_step_s (adapters/CMakeLists.txt).
constexpr double kDefaultTimeStep_s = IMPACTBENCH_DEFAULT_TIME_STEP_S;
constexpr int kOdeDefaultQuickStepIterations = 20;  // dWorldGetQuickStepNumIterations of a new world

const std::vector<std::pair<std::string, std::string>> kOptions = {
    {"contact",
     "matched (the law in ODE's own terms where it has one, default), injected (the law's force from the tip states, "
     "ODE's collision off), native (ODE's default hard contact)"},
    {"springs",
     "hinge springs: implicit (both hinge stops at the rest angle with StopERP/StopCFM from k, c and the step; "
     "default) or explicit (dJointAddHingeTorque each step; stable only below the step in the diagnostic "
     "explicit_spring_step_limit_s, for K = 8 about 1.65e-4 s with chain_damping=modal, 7.5e-5 s with hinge)"},
    {"stepper", "world (dWorldStep, direct LCP solver; default) or quick (dWorldQuickStep, iterative)"},
    {"iterations", "dWorldQuickStep iterations, 1..100000 (default 20, ODE's own default); only with stepper=quick"},
    {"links", kLinksOptionHelp},
    {kChainDampingOption, kChainDampingOptionHelp},
};

struct RunPlan {
  ContactPath contact = ContactPath::matched;
  OdeModelSettings model;
  int links = 0;
  ChainDamping damping = ChainDamping::modal;
};

RunPlan plan_run(const Scenario& scenario, const RunSettings& settings) {
  const OptionReader options("ode", settings.options, kOptions);
  RunPlan plan;
  plan.contact = options.contact_path();
  plan.model.springs = options.choice("springs", "implicit", {"implicit", "explicit"}) == "explicit"
                           ? SpringPath::explicit_torques
                           : SpringPath::implicit_stops;
  plan.model.stepper =
      options.choice("stepper", "world", {"world", "quick"}) == "quick" ? Stepper::quick : Stepper::world;
  plan.model.quick_step_iterations = options.integer("iterations", kOdeDefaultQuickStepIterations, 1, 100000);
  if (settings.options.count("iterations") && plan.model.stepper != Stepper::quick)
    throw std::invalid_argument("ode option iterations: only with stepper=quick");
  plan.links = links_option(options, settings, scenario);
  plan.damping = chain_damping_option(options);
  plan.model.time_step_s = resolve_time_step_s(settings, kDefaultTimeStep_s, "ode");
  return plan;
}

// The ODE side of the shared fixed-step loop (adapters/common/fixed_step_loop.h): the ODE rig and how its
// tips touch.
class OdeStepper final : public FixedStepEngine {
 public:
  OdeStepper(const Scenario& scenario, const RunSettings& settings, const RunPlan& plan)
      : rig_(build_rig(scenario, settings.law, plan.links, plan.damping)),
        contact_(ode::contact_setup(plan.contact, rig_.law, plan.model.time_step_s)),
        model_(with_spheres(plan.model, contact_.ode_collision)),
        ode_rig_(rig_, model_),
        energy_(rig_),
        newton_(is_instantaneous(rig_.law)),
        step_limit_s_(explicit_hinge_step_limit_s(rig_)),
        angles_(zero_hinge_values(rig_)),
        rates_(zero_hinge_values(rig_)) {}

  const RigSpec& rig() const { return rig_; }
  double time_step_s() const override { return ode_rig_.time_step_s(); }  // what dWorldStep is given
  std::string state_layout() const {
    return "ode bodies[" + std::to_string(ode_rig_.body_count()) +
           "] x (position, quaternion, linear and angular velocity)";
  }

  bool injects_contact() const override { return contact_.force_from_tip_states; }

  std::optional<std::string> read_tips(double t_s, TipState& tips) override {
    for (int f = 0; f < 2; ++f) {
      const ode::TipState tip = ode_rig_.tip(f);
      tips.displacement_m[f] = tip.displacement_m;
      tips.velocity_m_s[f] = tip.velocity_m_s;
      ode_rig_.hinge_state(f, angles_[f], rates_[f]);
    }
    // before ODE would be handed a state it aborts on (non-finite tips: the loop says so itself)
    if (auto why = nonfinite_hinges(t_s, tips, angles_, rates_)) return *why + explain_instability();
    return std::nullopt;
  }

  // the hinge rates read_tips took, for the loop's modal damping torques
  bool read_hinge_rates(std::array<Eigen::VectorXd, 2>& rates_rad_s) override {
    rates_rad_s = rates_;
    return true;
  }

  // Newton's contact stores no energy (RigEnergy takes 0 indentation for it)
  double energy_j(double indentation_m) override { return energy_(angles_, rates_, newton_ ? 0.0 : indentation_m); }

  // The loads of the coming step: the law's force when the adapter applies it (-F on frame 1's tip, +F
  // on frame 2's, along x), the contact joint, the motor, the explicit springs, the modal damping torques.
  void apply_loads(const StepLoads& loads) override {
    if (loads.injected_contact_force_n) {
      ode_rig_.add_tip_force(0, -*loads.injected_contact_force_n);
      ode_rig_.add_tip_force(1, *loads.injected_contact_force_n);
    }
    if (contact_.ode_collision && ode_rig_.make_tip_contact(contact_.surface)) ++contact_joint_steps_;
    if (loads.motor_force_n) ode_rig_.add_tip_force(0, *loads.motor_force_n);
    if (model_.springs == SpringPath::explicit_torques) ode_rig_.add_explicit_spring_torques();
    if (loads.hinge_damping_torques_n_m) ode_rig_.add_hinge_torques(*loads.hinge_damping_torques_n_m);
  }

  std::optional<std::string> step() override {
    ode_rig_.step();
    return std::nullopt;
  }

  double contact_force_n() override { return contact_.ode_collision ? ode_rig_.tip_contact_force() : 0.0; }

  SavedState save_state() override { return {"ode", state_layout(), ode_rig_.body_states()}; }
  void restore_state(const SavedState& state) override {
    check_saved_state(state, "ode", state_layout());
    const std::size_t size = static_cast<std::size_t>(ode_rig_.body_count() * ode::OdeRig::kValuesPerBody);
    if (state.values.size() != size)
      throw std::invalid_argument("a saved ODE state of " + std::to_string(state.values.size()) + " values for " +
                                  state_layout() + " (needs " + std::to_string(size) + ")");
    ode_rig_.set_body_states(state.values);
  }

  // What a person needs to see why a run diverged: the explicit springs' step limit, ODE's own words.
  std::string explain_instability() const override {
    std::ostringstream why;
    why.precision(3);
    if (model_.springs == SpringPath::explicit_torques && model_.time_step_s > step_limit_s_)
      why << "; explicit hinge springs are stable only below a step of " << step_limit_s_
          << " s (the chain's fastest modes), the step is " << model_.time_step_s << " s";
    if (messages_ && !messages_->messages().empty())
      why << "; ODE said (" << messages_->count() << " messages): " << messages_->messages().front();
    return why.str();
  }
  void listen(const ode::MessageLog& messages) { messages_ = &messages; }

  // The mapping's figures, named with units.
  std::vector<std::pair<std::string, double>> diagnostics(const ode::MessageLog& messages) const {
    std::vector<std::pair<std::string, double>> d;
    d.emplace_back("time_step_s", time_step_s());
    d.emplace_back("chain_links", rig_.frames[0].chain.links);
    d.emplace_back("explicit_spring_step_limit_s", step_limit_s_);
    for (int f = 0; f < 2; ++f) {
      add_chain_diagnostics(rig_, f, d);
      const std::string frame = "frame" + std::to_string(f + 1);
      if (model_.springs == SpringPath::implicit_stops) {
        d.emplace_back(frame + "_hinge_stop_erp", ode_rig_.hinge_stop_erp(f));
        d.emplace_back(frame + "_hinge_stop_cfm_rad_per_n_m_s", ode_rig_.hinge_stop_cfm(f));
      }
    }
    if (contact_.ode_collision) {
      const dSurfaceParameters& s = contact_.surface;
      if (s.mode & dContactSoftERP) d.emplace_back("contact_soft_erp", s.soft_erp);
      if (s.mode & dContactSoftCFM) d.emplace_back("contact_soft_cfm_m_per_n_s", s.soft_cfm);
      if (s.mode & dContactBounce) {
        d.emplace_back("contact_bounce", s.bounce);
        d.emplace_back("contact_bounce_threshold_m_s", s.bounce_vel);
      }
      d.emplace_back("contact_joint_steps", static_cast<double>(contact_joint_steps_));
    }
    d.emplace_back("world_erp", ode_rig_.world_erp());
    d.emplace_back("world_cfm", ode_rig_.world_cfm());
    if (model_.stepper == Stepper::quick) d.emplace_back("quick_step_iterations", model_.quick_step_iterations);
    d.emplace_back("ode_messages", static_cast<double>(messages.count()));
    return d;
  }

 private:
  static OdeModelSettings with_spheres(OdeModelSettings model, bool spheres) {
    model.tip_spheres = spheres;  // only what the run needs
    return model;
  }

  const RigSpec rig_;
  const ContactSetup contact_;
  const OdeModelSettings model_;
  OdeRig ode_rig_;
  const RigEnergy energy_;
  const bool newton_;
  const double step_limit_s_;
  std::array<Eigen::VectorXd, 2> angles_, rates_;
  const ode::MessageLog* messages_ = nullptr;
  long long contact_joint_steps_ = 0;
};

class OdeSimulator final : public Simulator {
 public:
  std::string name() const override { return "ode"; }
  std::string version() const override { return ode::version_text(); }
  LibraryBuild library_build() const override {
    return {ode::library_function(), IMPACTBENCH_ENGINE_INSTALL_PREFIX, ode::header_version_text()};
  }
  std::vector<std::pair<std::string, std::string>> option_help() const override { return kOptions; }
  std::optional<int> chain_links(const Scenario& scenario, const RunSettings& settings) const override {
    return plan_run(scenario, settings).links;
  }

  RunResult run(const Scenario& scenario, const RunSettings& settings) override {
    const RunPlan plan = plan_run(scenario, settings);
    ode::ensure_initialised();
    ode::MessageLog messages;  // what ODE warns about during this run (filled by its message handler)
    OdeStepper stepper(scenario, settings, plan);
    stepper.listen(messages);
    RunResult result;
    run_fixed_steps(stepper, stepper.rig(), scenario, settings, result);
    result.diagnostics = stepper.diagnostics(messages);
    return result;
  }
};

}  // namespace

std::unique_ptr<Simulator> make_ode_simulator() { return std::make_unique<OdeSimulator>(); }

}  // namespace ib
