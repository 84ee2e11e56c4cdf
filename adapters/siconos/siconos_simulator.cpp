// The Siconos side of the shared fixed-step loop (adapters/common/fixed_step_loop.h): the chains of
// siconos_rig.h, the contact paths and the options.
#include "adapters/siconos/siconos_simulator.h"

#include <algorithm>
#include <array>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

#include "adapters/common/fixed_step_loop.h"
#include "adapters/common/rig.h"
#include "adapters/siconos/siconos_rig.h"
#include "model/simulator_options.h"

namespace ib {
namespace {

using siconos::SiconosModelSettings;
using siconos::SiconosRig;
using siconos::SystemContact;

// The step when a run's settings give none: descriptor.json's default_time_step_s (adapters/CMakeLists.txt).
// Moreau-Jean's theta method is unconditionally stable on the linear chain (theta >= 1/2); what bounds the
// step is the contact: Newton's impact is resolved in one step whatever its length, but a smooth law's force
// is held over the step from its start, as on every engine's injected path.
constexpr double kDefaultTimeStep_s = IMPACTBENCH_DEFAULT_TIME_STEP_S;
// The tolerance of Moreau-Jean's Newton loop on a smooth contact force (Siconos's default is 1e-6 on its own
// scaled residual): tight, so that the step's error is the scheme's, not the loop's.
constexpr double kSmoothContactNewtonTolerance = 1e-10;

const std::vector<std::pair<std::string, std::string>> kOptions = {
    {"contact",
     "matched (Newton's law as Siconos's NewtonImpactNSL with the law's restitution, an impact in one step; "
     "Hertz and the spring-dashpot, which Siconos has no nonsmooth law for, as smooth internal forces of the "
     "system, integrated implicitly by Moreau-Jean's Newton loop; default), injected (every law's force from the tip "
     "states, Newton's impulse spread over one step), native "
     "(NewtonImpactNSL as its users leave it: its default restitution, whatever the law)"},
    {"theta", "Moreau-Jean's theta, 0.5..1 (default: MoreauJeanOSI's own, 0.5; 1 is backward Euler)"},
    {"links", kLinksOptionHelp},
    {kChainDampingOption, kChainDampingOptionHelp},
};

struct RunPlan {
  ContactPath contact = ContactPath::matched;
  SiconosModelSettings model;
  int links = 0;
  ChainDamping damping = ChainDamping::modal;
};

RunPlan plan_run(const Scenario& scenario, const RunSettings& settings) {
  const OptionReader options("siconos", settings.options, kOptions);
  RunPlan plan;
  plan.contact = options.contact_path();
  plan.model.theta = options.number("theta", siconos::default_theta(), 0.5, 1.0);
  plan.links = links_option(options, settings, scenario);
  plan.damping = chain_damping_option(options);
  plan.model.time_step_s = resolve_time_step_s(settings, kDefaultTimeStep_s, "siconos");
  // make_contact_model throws, naming the scenario, where it has no parameters for the law
  const ContactModel law = make_contact_model(scenario, settings.law);
  if (plan.contact == ContactPath::native) {
    plan.model.contact = SystemContact::newton_impact;
    plan.model.impact_restitution = siconos::default_impact_restitution();
  } else if (plan.contact == ContactPath::matched && is_instantaneous(law)) {
    plan.model.contact = SystemContact::newton_impact;
    plan.model.impact_restitution = std::get<NewtonLaw>(law).restitution;
  } else if (plan.contact == ContactPath::matched) {
    plan.model.contact = SystemContact::smooth_force;
    plan.model.newton_tolerance = kSmoothContactNewtonTolerance;
  }
  return plan;
}

class SiconosStepper final : public FixedStepEngine {
 public:
  SiconosStepper(const Scenario& scenario, const RunSettings& settings, const RunPlan& plan)
      : rig_(build_rig(scenario, settings.law, plan.links, plan.damping)),
        plan_(plan),
        energy_(rig_),
        newton_(is_instantaneous(rig_.law)),
        angles_(zero_hinge_values(rig_)),
        rates_(zero_hinge_values(rig_)) {
    for (int f = 0; f < 2; ++f) {
      angles_[f] = rig_.frames[f].initial_angles_rad;
      tip_lever_m_[f] = linearise(rig_.frames[f].chain).tip_lever;
    }
  }

  const RigSpec& rig() const { return rig_; }
  // Siconos keeps the step in its time discretisation; before the first step it is the planned one
  double time_step_s() const override { return siconos_ ? siconos_->time_step_s() : plan_.model.time_step_s; }
  bool injects_contact() const override { return plan_.model.contact == SystemContact::external; }

  // the hinges as the last step left them (step() copies them out of Siconos once)
  std::optional<std::string> read_tips(double t_s, TipState& tips) override {
    tips = tip_state();
    return nonfinite_hinges(t_s, tips, angles_, rates_);
  }
  TipState tip_state() const {
    TipState tips;
    for (int f = 0; f < 2; ++f) {
      tips.displacement_m[f] = tip_lever_m_[f].dot(angles_[f]);
      tips.velocity_m_s[f] = tip_lever_m_[f].dot(rates_[f]);
    }
    return tips;
  }

  // Newton's contact stores no energy (RigEnergy takes 0 indentation for it)
  double energy_j(double indentation_m) override { return energy_(angles_, rates_, newton_ ? 0.0 : indentation_m); }

  void apply_loads(const StepLoads& loads) override {
    tip_force_n_ = {0, 0};
    if (loads.injected_contact_force_n)
      tip_force_n_ = {-*loads.injected_contact_force_n, *loads.injected_contact_force_n};
    if (loads.motor_force_n) tip_force_n_[0] += *loads.motor_force_n;
  }

  std::optional<std::string> step() override {
    // built at the first step, so that a restored state (restore_state) is the initial state Siconos keeps
    if (!siconos_) siconos_ = std::make_unique<SiconosRig>(rig_, plan_.model, angles_, rates_, previous_tip_force_n_);
    siconos_->set_tip_forces_n(tip_force_n_[0], tip_force_n_[1]);
    previous_tip_force_n_ = tip_force_n_;
    if (auto trouble = siconos_->step()) return trouble;
    for (int f = 0; f < 2; ++f) siconos_->hinge_state(f, angles_[f], rates_[f]);
    impulse_n_s_ = siconos_->impulse_n_s();
    if (impulse_n_s_ > 0) ++impact_steps_;
    most_newton_iterations_ = std::max(most_newton_iterations_, siconos_->newton_iterations());
    return std::nullopt;
  }

  // Newton: the step's impulse spread over it, as the other engines' rigid contacts report theirs; a smooth
  // force: the law's at the state the step ended in
  double contact_force_n() override {
    if (plan_.model.contact == SystemContact::newton_impact) return impulse_n_s_ / time_step_s();
    if (plan_.model.contact == SystemContact::external || !siconos_) return 0;
    const TipState tips = tip_state();
    const double indentation_m = tips.displacement_m[0] - tips.displacement_m[1] - rig_.gap_m;
    return contact_force(rig_.law, indentation_m, tips.velocity_m_s[0] - tips.velocity_m_s[1]);
  }

  // the tip forces of the last step too: Moreau-Jean's next step weighs them (SiconosRig's constructor)
  std::string state_layout() const {
    return "siconos hinge angles and rates of both frames, then both tip forces of the last step [N]";
  }
  SavedState save_state() override {
    SavedState state{"siconos", state_layout(), {}};
    for (int f = 0; f < 2; ++f) {
      state.values.insert(state.values.end(), angles_[f].data(), angles_[f].data() + angles_[f].size());
      state.values.insert(state.values.end(), rates_[f].data(), rates_[f].data() + rates_[f].size());
    }
    state.values.insert(state.values.end(), previous_tip_force_n_.begin(), previous_tip_force_n_.end());
    return state;
  }
  void restore_state(const SavedState& state) override {
    check_saved_state(state, "siconos", state_layout());
    if (siconos_) throw std::invalid_argument("a Siconos state restored after the first step");
    std::size_t size = previous_tip_force_n_.size();
    for (int f = 0; f < 2; ++f) size += 2 * static_cast<std::size_t>(angles_[f].size());
    if (state.values.size() != size)
      throw std::invalid_argument("a saved Siconos state of " + std::to_string(state.values.size()) + " values for " +
                                  state_layout() + " (needs " + std::to_string(size) + ")");
    const double* value = state.values.data();
    for (int f = 0; f < 2; ++f)
      for (double* x : {angles_[f].data(), rates_[f].data()})
        for (Eigen::Index i = 0; i < angles_[f].size(); ++i) x[i] = *value++;
    for (double& force_n : previous_tip_force_n_) force_n = *value++;
  }

  std::string explain_instability() const override {
    if (!injects_contact()) return {};
    std::ostringstream why;
    why.precision(3);
    why << "; the contact force is held over each step from its start (explicit), at a step of "
        << plan_.model.time_step_s << " s";
    return why.str();
  }

  std::vector<std::pair<std::string, double>> diagnostics() const {
    std::vector<std::pair<std::string, double>> d;
    d.emplace_back("time_step_s", time_step_s());
    d.emplace_back("chain_links", rig_.frames[0].chain.links);
    for (int f = 0; f < 2; ++f) add_chain_diagnostics(rig_, f, d);
    d.emplace_back("moreau_jean_theta", plan_.model.theta);
    d.emplace_back("siconos_contact", static_cast<double>(plan_.model.contact));
    if (plan_.model.contact == SystemContact::newton_impact) {
      d.emplace_back("newton_impact_restitution", plan_.model.impact_restitution);
      d.emplace_back("impact_steps", static_cast<double>(impact_steps_));
    }
    if (plan_.model.contact == SystemContact::smooth_force) {
      d.emplace_back("newton_tolerance", plan_.model.newton_tolerance);
      d.emplace_back("most_newton_iterations", most_newton_iterations_);
    }
    return d;
  }

 private:
  const RigSpec rig_;
  const RunPlan plan_;
  const RigEnergy energy_;
  const bool newton_;
  std::unique_ptr<SiconosRig> siconos_;
  std::array<Eigen::VectorXd, 2> angles_, rates_;
  std::array<Eigen::VectorXd, 2> tip_lever_m_;    // the linearised chain's tip displacement per hinge angle [m/rad]
  std::array<double, 2> tip_force_n_{};           // held over the coming step [N]
  std::array<double, 2> previous_tip_force_n_{};  // held over the step before [N]
  double impulse_n_s_ = 0;
  long long impact_steps_ = 0;
  int most_newton_iterations_ = 0;
};

class SiconosSimulator final : public Simulator {
 public:
  std::string name() const override { return "siconos"; }
  std::string version() const override { return IMPACTBENCH_SICONOS_VERSION; }
  LibraryBuild library_build() const override {
    return {siconos::kernel_library_function(), IMPACTBENCH_ENGINE_INSTALL_PREFIX, "not given by its headers"};
  }
  std::vector<std::pair<std::string, std::string>> option_help() const override { return kOptions; }
  std::optional<int> chain_links(const Scenario& scenario, const RunSettings& settings) const override {
    return plan_run(scenario, settings).links;
  }
  RunResult run(const Scenario& scenario, const RunSettings& settings) override {
    const RunPlan plan = plan_run(scenario, settings);
    SiconosStepper stepper(scenario, settings, plan);
    RunResult result;
    run_fixed_steps(stepper, stepper.rig(), scenario, settings, result);
    result.diagnostics = stepper.diagnostics();
    return result;
  }
};

}  // namespace

std::unique_ptr<Simulator> make_siconos_simulator() { return std::make_unique<SiconosSimulator>(); }

}  // namespace ib
