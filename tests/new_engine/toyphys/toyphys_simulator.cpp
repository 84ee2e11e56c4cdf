// The toy engine: each frame's linearised link chain (physics/link_chain.h: M w' = tau - C w - K q) stepped
// by semi-implicit Euler, the tip displacement the tip lever times the hinge angles, and the contact law's
// force injected by the shared loop (its only contact path). Small enough to read as the template of an
// adapter; not an engine to benchmark.
#include "adapters/toyphys/toyphys_simulator.h"

#include <Eigen/Cholesky>
#include <array>
#include <stdexcept>
#include <string>

#include "adapters/common/fixed_step_loop.h"
#include "adapters/common/rig.h"
#include "model/simulator_options.h"

namespace ib {
namespace {

// Below the explicit springs' limit of the default chain; descriptor.json's default_time_step_s, which the
// engine's target is compiled with (adapters/CMakeLists.txt), as engines.json shows it.
constexpr double kDefaultTimeStep_s = IMPACTBENCH_DEFAULT_TIME_STEP_S;

const std::vector<std::pair<std::string, std::string>> kOptions = {
    {"contact", "injected (the law's force from the tip states; the only path of this toy)"},
    {"links", kLinksOptionHelp},
};

class ToyStepper final : public FixedStepEngine {
 public:
  ToyStepper(const Scenario& scenario, const RunSettings& settings, int links)
      : rig_(build_rig(scenario, settings.law, links)),
        energy_(rig_),
        time_step_s_(resolve_time_step_s(settings, kDefaultTimeStep_s, "toyphys")),
        angles_(zero_hinge_values(rig_)),
        rates_(zero_hinge_values(rig_)) {
    for (int f = 0; f < 2; ++f) {
      matrices_[f] = linearise(rig_.frames[f].chain);
      mass_[f].compute(matrices_[f].mass);
      angles_[f] = rig_.frames[f].initial_angles_rad;
    }
  }

  const RigSpec& rig() const { return rig_; }
  bool injects_contact() const override { return true; }
  double time_step_s() const override { return time_step_s_; }

  std::optional<std::string> read_tips(double t_s, TipState& tips) override {
    for (int f = 0; f < 2; ++f) {
      tips.displacement_m[f] = matrices_[f].tip_lever.dot(angles_[f]);
      tips.velocity_m_s[f] = matrices_[f].tip_lever.dot(rates_[f]);
    }
    return nonfinite_hinges(t_s, tips, angles_, rates_);
  }

  double energy_j(double indentation_m) override {
    return energy_(angles_, rates_, is_instantaneous(rig_.law) ? 0.0 : indentation_m);
  }

  void apply_loads(const StepLoads& loads) override {
    tip_force_n_ = {0, 0};
    if (loads.injected_contact_force_n)
      tip_force_n_ = {-*loads.injected_contact_force_n, *loads.injected_contact_force_n};
    if (loads.motor_force_n) tip_force_n_[0] += *loads.motor_force_n;
  }

  std::optional<std::string> step() override {
    for (int f = 0; f < 2; ++f) {
      const ChainMatrices& m = matrices_[f];
      const Eigen::VectorXd torque = m.tip_lever * tip_force_n_[f] - m.damping * rates_[f] - m.stiffness * angles_[f];
      rates_[f] += time_step_s_ * mass_[f].solve(torque);
      angles_[f] += time_step_s_ * rates_[f];
    }
    return std::nullopt;
  }

  double contact_force_n() override { return 0; }  // no contact of its own

  std::string layout() const { return "toyphys hinge angles and rates of both frames"; }
  SavedState save_state() override {
    SavedState state{"toyphys", layout(), {}};
    for (int f = 0; f < 2; ++f) {
      state.values.insert(state.values.end(), angles_[f].data(), angles_[f].data() + angles_[f].size());
      state.values.insert(state.values.end(), rates_[f].data(), rates_[f].data() + rates_[f].size());
    }
    return state;
  }
  void restore_state(const SavedState& state) override {
    check_saved_state(state, "toyphys", layout());
    std::size_t size = 0;
    for (int f = 0; f < 2; ++f) size += 2 * static_cast<std::size_t>(angles_[f].size());
    if (state.values.size() != size) throw std::invalid_argument("a saved toyphys state of the wrong size");
    const double* value = state.values.data();
    for (int f = 0; f < 2; ++f) {
      for (double* x : {angles_[f].data(), rates_[f].data()})
        for (Eigen::Index i = 0; i < angles_[f].size(); ++i) x[i] = *value++;
    }
  }

 private:
  const RigSpec rig_;
  const RigEnergy energy_;
  const double time_step_s_;
  std::array<ChainMatrices, 2> matrices_;
  std::array<Eigen::LDLT<Eigen::MatrixXd>, 2> mass_;
  std::array<Eigen::VectorXd, 2> angles_, rates_;
  std::array<double, 2> tip_force_n_{};
};

class ToySimulator final : public Simulator {
 public:
  std::string name() const override { return "toyphys"; }
  std::string version() const override { return "toy"; }
  std::vector<std::pair<std::string, std::string>> option_help() const override { return kOptions; }

  RunResult run(const Scenario& scenario, const RunSettings& settings) override {
    const OptionReader options("toyphys", settings.options, kOptions);
    options.choice("contact", "injected", {"injected"});
    ToyStepper stepper(scenario, settings, links_option(options, settings, scenario));
    RunResult result;
    run_fixed_steps(stepper, stepper.rig(), scenario, settings, result);
    result.diagnostics = {{"time_step_s", stepper.time_step_s()},
                          {"explicit_spring_step_limit_s", explicit_hinge_step_limit_s(stepper.rig())}};
    return result;
  }
};

}  // namespace

std::unique_ptr<Simulator> make_toyphys_simulator() { return std::make_unique<ToySimulator>(); }

}  // namespace ib
