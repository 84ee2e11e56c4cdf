#include "adapters/mujoco/mujoco_simulator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "adapters/common/fixed_step_loop.h"
#include "adapters/mujoco/mujoco_engine.h"
#include "adapters/mujoco/mujoco_model.h"
#include "physics/link_chain.h"

namespace ib {
namespace {

std::string at_time(double t) {
  std::ostringstream out;
  out.precision(9);
  out << "t = " << t << " s";
  return out.str();
}

// The compiled rig and its state, with the handles the stepping loop needs.
class MujocoRig {
 public:
  explicit MujocoRig(const MujocoRunPlan& plan)
      : plan_(plan), model_(compile_mjcf(write_mjcf(plan))), data_(make_data(model_.get())) {
    const mjModel* m = model_.get();
    for (int f = 0; f < 2; ++f) {
      tip_site_[f] = lookup(mjOBJ_SITE, mujoco_tip_site_name(f));
      tip_body_[f] = lookup(mjOBJ_BODY, mujoco_body_name(f, plan.links - 1));
      angles_[f].resize(plan.links);
      rates_[f].resize(plan.links);
      for (int j = 0; j < plan.links; ++j) {
        const int joint = lookup(mjOBJ_JOINT, mujoco_joint_name(f, j));
        qpos_address_[f].push_back(m->jnt_qposadr[joint]);
        dof_address_[f].push_back(m->jnt_dofadr[joint]);
      }
    }
    // the keyframe holds the initial hinge angles when they are not all zero
    if (m->nkey > 0) mj_resetDataKeyframe(m, data_.get(), 0);
  }

  const mjModel* model() const { return model_.get(); }
  mjData* data() { return data_.get(); }

  // Position and velocity stages for the current state (kinematics, collisions, constraint rows).
  void compute_state() {
    mj_fwdPosition(model_.get(), data_.get());
    mj_fwdVelocity(model_.get(), data_.get());
  }

  // Tip displacement along x from rest [m] and tip velocity along x [m/s] (after compute_state()).
  double tip_displacement(int f) const { return data_->site_xpos[3 * tip_site_[f]] - plan_.rig.frames[f].base_x_m; }
  double tip_velocity(int f) const {
    mjtNum velocity[6];  // rotation, then translation, in world axes at the site
    mj_objectVelocity(model_.get(), data_.get(), mjOBJ_SITE, tip_site_[f], velocity, 0);
    return velocity[3];
  }

  // Hinge angles and rates of both chains, for RigEnergy.
  const std::array<Eigen::VectorXd, 2>& angles() {
    for (int f = 0; f < 2; ++f)
      for (int j = 0; j < plan_.links; ++j) angles_[f][j] = data_->qpos[qpos_address_[f][j]];
    return angles_;
  }
  const std::array<Eigen::VectorXd, 2>& rates() {
    for (int f = 0; f < 2; ++f)
      for (int j = 0; j < plan_.links; ++j) rates_[f][j] = data_->qvel[dof_address_[f][j]];
    return rates_;
  }

  // A force along +x [N] at a tip point, added to qfrc_applied (uses the current kinematics).
  void apply_tip_force(int f, double force_x) {
    const mjtNum force[3] = {force_x, 0, 0}, torque[3] = {0, 0, 0};
    mj_applyFT(model_.get(), data_.get(), force, torque, data_->site_xpos + 3 * tip_site_[f], tip_body_[f],
               data_->qfrc_applied);
  }
  void clear_applied_forces() { mju_zero(data_->qfrc_applied, model_->nv); }
  // Torques [N m] about the hinges (a hinge's generalised force), added to qfrc_applied.
  void apply_hinge_torques(const std::array<Eigen::VectorXd, 2>& torques_n_m) {
    for (int f = 0; f < 2; ++f)
      for (int j = 0; j < plan_.links; ++j) data_->qfrc_applied[dof_address_[f][j]] += torques_n_m[f][j];
  }

  // The normal force [N] of MuJoCo's active contacts (>= 0; only the tip spheres can collide).
  double contact_normal_force() const {
    double force = 0;
    for (int i = 0; i < data_->ncon; ++i) {
      if (data_->contact[i].efc_address < 0) continue;  // detected within a margin, not in the solver
      mjtNum wrench[6];                                 // in the contact frame: normal first
      mj_contactForce(model_.get(), data_.get(), i, wrench);
      force += std::max(0.0, static_cast<double>(wrench[0]));
    }
    return force;
  }

  // The first warning MuJoCo raised since the last call ("" when none).
  std::string new_warning(double t) { return warnings_.new_warning(t); }

 private:
  int lookup(mjtObj type, const std::string& name) const {
    const int id = mj_name2id(model_.get(), type, name.c_str());
    if (id < 0) throw std::logic_error("MuJoCo model has no " + name);
    return id;
  }

  const MujocoRunPlan& plan_;
  MujocoModelPtr model_;
  MujocoDataPtr data_;
  std::array<int, 2> tip_site_{}, tip_body_{};
  std::array<std::vector<int>, 2> qpos_address_, dof_address_;
  std::array<Eigen::VectorXd, 2> angles_, rates_;
  MujocoWarningWatch warnings_{data_.get()};
};

std::vector<std::pair<std::string, double>> plan_diagnostics(const MujocoRunPlan& plan, const mjModel* m) {
  std::vector<std::pair<std::string, double>> out = {
      {"time_step_s", plan.time_step_s},
      {"chain_links", plan.links},
      {"integrator_rk4", plan.integrator == MujocoIntegrator::rk4 ? 1.0 : 0.0},
  };
  double omega_max = 0;
  for (int f = 0; f < 2; ++f) {
    const LinkChain& chain = plan.rig.frames[f].chain;
    add_chain_diagnostics(plan.rig, f, out);
    omega_max = std::max(omega_max, chain_modes(chain).omega_rad_s.maxCoeff());
  }
  // explicit hinge springs: the semi-implicit Euler step is stable below about 2 / omega_max
  out.push_back({"chain_fastest_mode_rad_s", omega_max});
  if (plan.tip_pair) {
    const TipPairContact& pair = *plan.tip_pair;
    out.push_back({"contact_stiffness_n_per_m", pair.spring_dashpot.stiffness_n_per_m});
    out.push_back({"contact_damping_n_s_per_m", pair.spring_dashpot.damping_n_s_per_m});
    out.push_back({"contact_invweight_sum_per_kg", pair.invweight_sum_per_kg});
    out.push_back({"solref_stiffness_per_s2", pair.parameters.solref[0]});
    out.push_back({"solref_damping_per_s", pair.parameters.solref[1]});
    out.push_back({"solimp_impedance", pair.parameters.solimp[0]});
    if (plan.law == ContactLaw::newton) {
      out.push_back({"newton_contact_duration_s", pair.newton_duration_s});
      out.push_back({"newton_contact_damping_ratio", pair.newton_damping_ratio});
    }
  }
  if (plan.native_contact && m) {
    // what a user's default MuJoCo contact is: solref (timeconst, dampratio) and solimp of the tip spheres
    const int geom = mj_name2id(m, mjOBJ_GEOM, mujoco_tip_geom_name(0).c_str());
    out.push_back({"native_solref_timeconst_s", m->geom_solref[mjNREF * geom]});
    out.push_back({"native_solref_dampratio", m->geom_solref[mjNREF * geom + 1]});
    out.push_back({"native_solimp_dmin", m->geom_solimp[mjNIMP * geom]});
    out.push_back({"native_solimp_dmax", m->geom_solimp[mjNIMP * geom + 1]});
    out.push_back({"native_condim", m->geom_condim[geom]});
  }
  return out;
}

// The MuJoCo side of the shared fixed-step loop (adapters/common/fixed_step_loop.h).
class MujocoStepper final : public FixedStepEngine {
 public:
  MujocoStepper(const MujocoRunPlan& plan, MujocoRig& rig)
      : plan_(plan),
        rig_(rig),
        energy_(plan.rig),
        // a contact law's elastic energy belongs in the balance only where MuJoCo applies that law
        law_energy_(plan.law != ContactLaw::newton && !plan.native_contact) {}

  // the model's own step (its <option timestep>, written from the plan's): what mj_Euler and
  // mj_RungeKutta advance by
  double time_step_s() const override { return rig_.model()->opt.timestep; }

  bool injects_contact() const override { return plan_.harness_contact_force; }

  std::optional<std::string> read_tips(double t_s, TipState& tips) override {
    try {
      // MuJoCo's own checks (mj_step runs them too): a bad qpos/qvel resets the data and warns
      mj_checkPos(rig_.model(), rig_.data());
      mj_checkVel(rig_.model(), rig_.data());
      if (std::string warning = rig_.new_warning(t_s); !warning.empty()) return warning;
      rig_.compute_state();
    } catch (const MujocoError& error) {
      return std::string(error.what()) + " (at " + at_time(t_s) + ")";
    }
    for (int f = 0; f < 2; ++f) {
      tips.displacement_m[f] = rig_.tip_displacement(f);
      tips.velocity_m_s[f] = rig_.tip_velocity(f);
    }
    t_s_ = t_s;
    return std::nullopt;
  }

  double energy_j(double indentation_m) override {
    return energy_(rig_.angles(), rig_.rates(), law_energy_ ? indentation_m : 0.0);
  }

  // forces held over the step, from the state at its start
  // the hinge rates of the state read_tips computed, for the loop's modal damping torques
  bool read_hinge_rates(std::array<Eigen::VectorXd, 2>& rates_rad_s) override {
    rates_rad_s = rig_.rates();
    return true;
  }

  void apply_loads(const StepLoads& loads) override {
    rig_.clear_applied_forces();
    if (loads.hinge_damping_torques_n_m) rig_.apply_hinge_torques(*loads.hinge_damping_torques_n_m);
    if (loads.motor_force_n) rig_.apply_tip_force(0, *loads.motor_force_n);
    if (loads.injected_contact_force_n) {
      rig_.apply_tip_force(0, -*loads.injected_contact_force_n);
      rig_.apply_tip_force(1, *loads.injected_contact_force_n);
    }
  }

  std::optional<std::string> step() override {
    const mjModel* m = rig_.model();
    mjData* d = rig_.data();
    try {
      mj_forwardSkip(m, d, mjSTAGE_VEL, 1);  // actuation, acceleration, constraint solve
      mj_checkAcc(m, d);
      if (std::string warning = rig_.new_warning(t_s_); !warning.empty()) return warning;
      if (!plan_.harness_contact_force) contact_force_n_ = rig_.contact_normal_force();
      if (plan_.integrator == MujocoIntegrator::rk4)
        mj_RungeKutta(m, d, 4);
      else
        mj_Euler(m, d);
    } catch (const MujocoError& error) {
      return std::string(error.what()) + " (at " + at_time(t_s_) + ")";
    }
    return std::nullopt;
  }

  double contact_force_n() override { return contact_force_n_; }

  // mjData's evolving state: joint positions and velocities, actuator activations, and the constraint
  // solver's warm start (without it a continued run's first contact solve starts cold and differs in
  // the solver's last digits).
  SavedState save_state() override {
    const mjModel* m = rig_.model();
    const mjData* d = rig_.data();
    SavedState state{"mujoco", state_layout(m), {}};
    auto& v = state.values;
    v.insert(v.end(), d->qpos, d->qpos + m->nq);
    v.insert(v.end(), d->qvel, d->qvel + m->nv);
    v.insert(v.end(), d->act, d->act + m->na);
    v.insert(v.end(), d->qacc_warmstart, d->qacc_warmstart + m->nv);
    return state;
  }

  void restore_state(const SavedState& state) override {
    const mjModel* m = rig_.model();
    mjData* d = rig_.data();
    check_saved_state(state, "mujoco", state_layout(m));
    const std::size_t size = static_cast<std::size_t>(m->nq + 2 * m->nv + m->na);
    if (state.values.size() != size)
      throw std::invalid_argument("a saved MuJoCo state of " + std::to_string(state.values.size()) + " values for " +
                                  state_layout(m) + " (needs " + std::to_string(size) + ")");
    const double* v = state.values.data();
    std::copy(v, v + m->nq, d->qpos);
    v += m->nq;
    std::copy(v, v + m->nv, d->qvel);
    v += m->nv;
    std::copy(v, v + m->na, d->act);
    v += m->na;
    std::copy(v, v + m->nv, d->qacc_warmstart);
  }

 private:
  static std::string state_layout(const mjModel* m) {
    return "mujoco qpos[" + std::to_string(m->nq) + "] qvel[" + std::to_string(m->nv) + "] act[" +
           std::to_string(m->na) + "] qacc_warmstart[" + std::to_string(m->nv) + "]";
  }

  const MujocoRunPlan& plan_;
  MujocoRig& rig_;
  const RigEnergy energy_;
  const bool law_energy_;
  double t_s_ = 0;  // the time of the state last read: the step's start
  double contact_force_n_ = 0;
};

class MujocoSimulator final : public Simulator {
 public:
  MujocoSimulator() { install_mujoco_handlers(); }
  std::string name() const override { return "mujoco"; }
  std::string version() const override { return mujoco_version(); }
  LibraryBuild library_build() const override {
    // mj_version is defined in libmujoco itself (not inline): its address lies in the file loaded at run time
    return {reinterpret_cast<const void*>(&mj_version), IMPACTBENCH_ENGINE_INSTALL_PREFIX,
            "mjVERSION_HEADER " + std::to_string(mjVERSION_HEADER)};
  }
  std::vector<std::pair<std::string, std::string>> option_help() const override { return mujoco_options(); }
  std::string export_model(const Scenario& scenario, const RunSettings& settings) const override {
    return mujoco_model_xml(scenario, settings);
  }
  std::optional<int> chain_links(const Scenario& scenario, const RunSettings& settings) const override {
    return mujoco_chain_links(scenario, settings);
  }

  // A bad option or law propagates as std::invalid_argument (nothing was run); a model MuJoCo cannot
  // compile is a failed run with MuJoCo's message.
  RunResult run(const Scenario& scenario, const RunSettings& settings) override {
    RunResult result;
    std::optional<MujocoRunPlan> plan;
    std::unique_ptr<MujocoRig> rig;
    try {
      plan = plan_mujoco_run(scenario, settings);
      rig = std::make_unique<MujocoRig>(*plan);
    } catch (const std::runtime_error& error) {
      result.status = RunStatus::failed;
      result.reason = error.what();
      return result;
    }
    result.diagnostics = plan_diagnostics(*plan, rig->model());
    MujocoStepper stepper(*plan, *rig);
    run_fixed_steps(stepper, plan->rig, scenario, settings, result);
    return result;
  }
};

}  // namespace

std::unique_ptr<Simulator> make_mujoco_simulator() { return std::make_unique<MujocoSimulator>(); }

std::string mujoco_model_xml(const Scenario& scenario, const RunSettings& settings) {
  return write_mjcf(plan_mujoco_run(scenario, settings));
}

}  // namespace ib
