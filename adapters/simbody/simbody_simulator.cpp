#include "adapters/simbody/simbody_simulator.h"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>

#include "adapters/common/fixed_step_loop.h"
#include "adapters/common/rig.h"
#include "adapters/simbody/simbody_chain.h"
#include "adapters/simbody/simbody_contact.h"
#include "adapters/simbody/simbody_quiet_stdout.h"
#include "adapters/simbody/simbody_stepping.h"
#include "model/simulator_options.h"

namespace ib {
namespace {

using simbody::ContactKind;
using simbody::IntegratorKind;

// The step when a run's settings give none. The hinge springs and the damping (hinge dampers, or the modal
// damping matrix as a force element, simbody_chain.h) are forces integrated explicitly, so the step must stay
// below the chain's explicit limit (explicit_hinge_step_limit_s for K = 8 with semi-explicit Euler: 7.5e-5 s
// with hinge damping, about twice that with modal); 5e-5 s also resolves the spring-dashpot contact
// (omega h = 0.26). Its value is descriptor.json's default_time_step_s (adapters/CMakeLists.txt).
constexpr double kDefaultTimeStep_s = IMPACTBENCH_DEFAULT_TIME_STEP_S;
constexpr double kDefaultConstraintTolerance_m = 1e-6;

const std::vector<std::pair<std::string, std::string>> kOptions = {
    {"contact",
     "matched (the law in Simbody's own terms: Hunt-Crossley for Hertz n = 1.5, a force element for the "
     "spring-dashpot, rigid contact for Newton; default), injected (the law's force from the tip states), native "
     "(Hunt-Crossley contact with steel: E = 200 GPa, nu = 0.3, dissipation 0.2 s/m)"},
    {"integrator",
     "euler (semi-explicit Euler, default), rk2, rk3, rkm (Runge-Kutta-Merson), verlet: fixed step = the run's step; "
     "with accuracy also cpodes (BDF); not with the rigid Newton contact (its own stepper)"},
    {"accuracy",
     "error-controlled integration with this relative accuracy, 1e-10..0.1 (integrator rk3, rkm, verlet or cpodes; "
     "default rkm); the run's step is then only the recording interval"},
    {"constraint_tolerance",
     "rigid Newton contact: the distance at which the spheres count as touching [m], 1e-9..1e-3 (default 1e-6; "
     "Simbody's own 1e-3 fires the impact 0.5 mm early)"},
    {"links", kLinksOptionHelp},
    {kChainDampingOption, kChainDampingOptionHelp},
};

struct RunPlan {
  ContactPath contact = ContactPath::matched;
  simbody::SteppingSettings stepping;
  int links = 0;
  ChainDamping damping = ChainDamping::modal;
};

RunPlan plan_run(const Scenario& scenario, const RunSettings& settings) {
  const OptionReader options("simbody", settings.options, kOptions);
  RunPlan plan;
  plan.contact = options.contact_path();
  const bool error_control = settings.options.count("accuracy") > 0;
  const std::string integrator =
      options.choice("integrator", error_control ? "rkm" : "euler",
                     error_control ? std::vector<std::string>{"rk3", "rkm", "verlet", "cpodes"}
                                   : std::vector<std::string>{"euler", "rk2", "rk3", "rkm", "verlet"});
  for (IntegratorKind kind : {IntegratorKind::semi_explicit_euler, IntegratorKind::rk2, IntegratorKind::rk3,
                              IntegratorKind::rkm, IntegratorKind::verlet, IntegratorKind::cpodes})
    if (integrator == simbody::to_string(kind)) plan.stepping.integrator = kind;
  plan.stepping.error_control = error_control;
  plan.stepping.accuracy = options.number("accuracy", 1e-3, 1e-10, 0.1);
  plan.stepping.constraint_tolerance_m =
      options.number("constraint_tolerance", kDefaultConstraintTolerance_m, 1e-9, 1e-3);
  plan.stepping.rigid_contact = plan.contact == ContactPath::matched && settings.law == ContactLaw::newton;
  if (plan.stepping.rigid_contact && (settings.options.count("integrator") || error_control))
    throw std::invalid_argument(
        "simbody option integrator/accuracy: the rigid Newton contact (law newton, contact matched) steps with its "
        "own SemiExplicitEulerTimeStepper; allowed only with contact=injected or another law");
  if (settings.options.count("constraint_tolerance") && !plan.stepping.rigid_contact)
    throw std::invalid_argument(
        "simbody option constraint_tolerance: only with the rigid Newton contact (law newton, contact matched)");
  plan.links = links_option(options, settings, scenario);
  plan.damping = chain_damping_option(options);
  plan.stepping.step_s = resolve_time_step_s(settings, kDefaultTimeStep_s, "simbody");
  return plan;
}

// The Simbody side of the shared fixed-step loop: the rig, its contact and how it is advanced.
class SimbodyStepper final : public FixedStepEngine {
 public:
  SimbodyStepper(const Scenario& scenario, const RunSettings& settings, const RunPlan& plan)
      : plan_(plan),
        rig_(build_rig(scenario, settings.law, plan.links, plan.damping)),
        setup_(simbody::contact_setup(plan.contact, rig_.law)),
        chain_(rig_),
        contact_(chain_, setup_, rig_),
        stepping_(chain_.system(), chain_.initial_state(), plan.stepping),
        energy_(rig_),
        newton_(is_instantaneous(rig_.law)),
        step_limit_s_(explicit_hinge_step_limit_s(rig_)),
        angles_(zero_hinge_values(rig_)),
        rates_(zero_hinge_values(rig_)) {}

  const RigSpec& rig() const { return rig_; }
  double time_step_s() const override { return stepping_.step_s(); }  // what advance() advances by
  std::size_t state_size() const {
    return 2 * static_cast<std::size_t>(rig_.frames[0].chain.links + rig_.frames[1].chain.links);
  }
  std::string state_layout() const {
    return "simbody hinge angles then rates of " + std::to_string(rig_.frames[0].chain.links) + " + " +
           std::to_string(rig_.frames[1].chain.links) + " links";
  }

  bool injects_contact() const override { return setup_.kind == ContactKind::injected; }

  std::optional<std::string> read_tips(double t_s, TipState& tips) override {
    const SimTK::State& state = stepping_.state();
    for (int f = 0; f < 2; ++f) {
      const simbody::TipReading tip = chain_.tip(state, f);
      tips.displacement_m[f] = tip.displacement_m;
      tips.velocity_m_s[f] = tip.velocity_m_s;
      chain_.hinge_state(state, f, angles_[f], rates_[f]);
    }
    if (auto why = nonfinite_hinges(t_s, tips, angles_, rates_)) return *why + explain_instability();
    closing_m_s_ = tips.velocity_m_s[0] - tips.velocity_m_s[1];
    separation_m_ = rig_.gap_m - (tips.displacement_m[0] - tips.displacement_m[1]);
    return std::nullopt;
  }

  // The chains' hinge angles then rates [rad, rad/s], frame 1 first (the State's q and u), read and set
  // through the chain's mobilisers; restored into a fresh initial State, from which the stepping restarts.
  SavedState save_state() override {
    const SimTK::State& s = stepping_.state();
    SavedState state{"simbody", state_layout(), {}};
    for (int f = 0; f < 2; ++f) {
      Eigen::VectorXd angles(rig_.frames[f].chain.links),
          rates(rig_.frames[f].chain.links);  // hinge_state fills K entries
      chain_.hinge_state(s, f, angles, rates);
      state.values.insert(state.values.end(), angles.data(), angles.data() + angles.size());
      state.values.insert(state.values.end(), rates.data(), rates.data() + rates.size());
    }
    return state;
  }
  void restore_state(const SavedState& saved) override {
    check_saved_state(saved, "simbody", state_layout());
    if (saved.values.size() != state_size())
      throw std::invalid_argument("a saved Simbody state of " + std::to_string(saved.values.size()) + " values for " +
                                  state_layout() + " (needs " + std::to_string(state_size()) + ")");
    SimTK::State s = chain_.initial_state();
    std::size_t k = 0;
    for (int f = 0; f < 2; ++f) {
      const int links = rig_.frames[f].chain.links;
      for (int j = 0; j < links; ++j) chain_.set_hinge(s, f, j, saved.values[k + j], saved.values[k + links + j]);
      k += 2 * static_cast<std::size_t>(links);
    }
    stepping_.restart(s);
  }

  // the rigid contact stores no energy (RigEnergy takes 0 indentation for it)
  double energy_j(double indentation_m) override { return energy_(angles_, rates_, newton_ ? 0.0 : indentation_m); }

  // The motor is not taken from the loop: the chain's Force::Custom evaluates the same MotorForce at every
  // stage time (the loop's value at the step's start for semi-explicit Euler; exact inside Runge-Kutta
  // stages and error-controlled steps). The injected force is held over the step: the integrator is told.
  void apply_loads(const StepLoads& loads) override {
    if (loads.injected_contact_force_n) {
      chain_.loads().set_tip_forces_n(-*loads.injected_contact_force_n, *loads.injected_contact_force_n);
      stepping_.loads_changed();
    }
  }

  std::optional<std::string> step() override {
    const double step_s = time_step_s();
    const double closing_before_m_s = closing_m_s_;
    if (auto trouble = stepping_.advance()) return *trouble + explain_instability();
    last_step_impulse_force_n_ = 0;
    if (setup_.kind == ContactKind::rigid_newton) {
      // Simbody keeps the impact impulse to itself: the force the recorder needs is estimated from the
      // reversal of the closing speed over the step, m_eff (v_before - v_after) / h (rig.h's tip
      // effective mass), on the steps that reversed it with the spheres within reach of each other (a
      // closing speed also turns at every free oscillation's extreme)
      const SimTK::State& state = stepping_.state();
      const double closing_after_m_s = chain_.tip(state, 0).velocity_m_s - chain_.tip(state, 1).velocity_m_s;
      const double reach_m = closing_before_m_s * step_s + 10 * plan_.stepping.constraint_tolerance_m;
      if (closing_before_m_s > 0 && closing_after_m_s < 0 && separation_m_ <= reach_m) {
        last_step_impulse_force_n_ = rig_.contact_effective_mass_kg * (closing_before_m_s - closing_after_m_s) / step_s;
        ++impacts_;
      }
    }
    return std::nullopt;
  }

  double contact_force_n() override {
    if (setup_.kind == ContactKind::rigid_newton) return last_step_impulse_force_n_;
    return contact_.force_n(stepping_.state());
  }

  std::string explain_instability() const override {
    std::ostringstream why;
    why.precision(3);
    if (!plan_.stepping.error_control && plan_.stepping.integrator == IntegratorKind::semi_explicit_euler &&
        plan_.stepping.step_s > step_limit_s_)
      why << "; the hinge springs are explicit forces in Simbody, stable with semi-explicit Euler only below a step of "
          << step_limit_s_ << " s (the chain's fastest modes), the step is " << plan_.stepping.step_s << " s";
    return why.str();
  }

  std::vector<std::pair<std::string, double>> diagnostics() const;

 private:
  const RunPlan plan_;
  const RigSpec rig_;
  const simbody::ContactSetup setup_;
  simbody::SimbodyChain chain_;
  simbody::SimbodyContact contact_;
  simbody::SimbodyStepping stepping_;
  const RigEnergy energy_;
  const bool newton_;
  const double step_limit_s_;
  std::array<Eigen::VectorXd, 2> angles_, rates_;
  double closing_m_s_ = 0;   // tip 1 - tip 2 velocity at the last read [m/s]
  double separation_m_ = 0;  // surface gap at the last read [m]
  double last_step_impulse_force_n_ = 0;
  long long impacts_ = 0;
};

// Every setting the run used, named with units (the report states them per configuration).
std::vector<std::pair<std::string, double>> SimbodyStepper::diagnostics() const {
  std::vector<std::pair<std::string, double>> d;
  const simbody::SteppingSettings& s = plan_.stepping;
  d.emplace_back(s.error_control ? "recording_interval_s" : "time_step_s", s.step_s);
  d.emplace_back("chain_links", rig_.frames[0].chain.links);
  d.emplace_back("explicit_spring_step_limit_s", step_limit_s_);
  d.emplace_back("error_controlled", s.error_control ? 1 : 0);
  if (!s.rigid_contact) d.emplace_back("integrator_" + std::string(simbody::to_string(s.integrator)), 1);
  if (s.error_control) {
    d.emplace_back("accuracy", s.accuracy);
    d.emplace_back("smallest_step_s", stepping_.smallest_step_s());
    d.emplace_back("largest_step_s", stepping_.largest_step_s());
  }
  d.emplace_back("integrator_steps", static_cast<double>(stepping_.internal_steps()));
  d.emplace_back("integrator_steps_attempted", static_cast<double>(stepping_.attempted_steps()));
  for (int f = 0; f < 2; ++f) add_chain_diagnostics(rig_, f, d);
  d.emplace_back("contact_injected", setup_.kind == ContactKind::injected ? 1 : 0);
  if (!setup_.note.empty()) d.emplace_back("hertz_exponent_not_representable_injected", 1);
  if (setup_.kind == ContactKind::hunt_crossley) {
    d.emplace_back("hunt_crossley_material_stiffness_pa", setup_.material.stiffness_pa);
    d.emplace_back("hunt_crossley_dissipation_s_per_m", setup_.material.dissipation_s_per_m);
  }
  if (setup_.kind == ContactKind::spring_dashpot) d.emplace_back("spring_dashpot_force_element", 1);
  if (s.rigid_contact) {
    d.emplace_back("rigid_contact_newton_restitution", std::get<NewtonLaw>(rig_.law).restitution);
    d.emplace_back("rigid_constraint_tolerance_m", stepping_.constraint_tolerance_in_use_m());
    d.emplace_back("rigid_impact_capture_speed_m_s", stepping_.impact_capture_speed_m_s());
    d.emplace_back("rigid_impacts", static_cast<double>(impacts_));
  }
  return d;
}

std::string simbody_version() {
  int major = 0, minor = 0, build = 0;
  SimTK_version_simbody(&major, &minor, &build);
  return "Simbody " + std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(build);
}

class SimbodySimulator final : public Simulator {
 public:
  std::string name() const override { return "simbody"; }
  std::string version() const override { return simbody_version(); }
  LibraryBuild library_build() const override {
    // Simbody's headers define no version macro: its version is the library's answer (version()) alone
    return {reinterpret_cast<const void*>(&SimTK_version_simbody), IMPACTBENCH_ENGINE_INSTALL_PREFIX,
            "not given by its headers"};
  }
  std::vector<std::pair<std::string, std::string>> option_help() const override { return kOptions; }
  std::optional<int> chain_links(const Scenario& scenario, const RunSettings& settings) const override {
    return plan_run(scenario, settings).links;
  }
  void check_settings(const RunSettings& settings) const override {
    const OptionReader options("simbody", settings.options, kOptions);  // names and ranges; the rest needs a scenario
    (void)options;
  }

  RunResult run(const Scenario& scenario, const RunSettings& settings) override {
    const RunPlan plan = plan_run(scenario, settings);
    RunResult result;
    try {
      // the rigid stepper of the Debian build prints every step: kept off `impactbench run`'s stdout
      std::optional<simbody::QuietStdout> quiet;
      if (plan.stepping.rigid_contact) quiet.emplace();
      SimbodyStepper stepper(scenario, settings, plan);
      run_fixed_steps(stepper, stepper.rig(), scenario, settings, result);
      result.diagnostics = stepper.diagnostics();
    } catch (const std::invalid_argument&) {  // a saved state of another rig: bad input, nothing run
      throw;
    } catch (const std::exception& e) {  // Simbody's own errors while building (SimTK::Exception)
      result.status = RunStatus::failed;
      result.reason = std::string("Simbody: ") + e.what();
    }
    return result;
  }
};

}  // namespace

std::unique_ptr<Simulator> make_simbody_simulator() { return std::make_unique<SimbodySimulator>(); }

}  // namespace ib
