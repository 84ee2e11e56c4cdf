#include "adapters/mujoco/mujoco_model.h"

#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "adapters/common/fixed_step_loop.h"
#include "adapters/mujoco/mujoco_engine.h"

namespace ib {

const double kDefaultMujocoTimeStep_s = IMPACTBENCH_DEFAULT_TIME_STEP_S;

namespace {

const std::vector<std::pair<std::string, std::string>> kOptions = {
    {"contact",
     "matched (MuJoCo's contact set to the law; Hertz, which MuJoCo has no form for, applied as a force from the tip "
     "states), injected (the harness applies the law's force, MuJoCo's contact off) or native (MuJoCo's default "
     "contact settings) (default matched)"},
    {"integrator", "euler (MuJoCo's default: semi-implicit, joint damping implicit) or rk4 (default euler)"},
    {"links", kLinksOptionHelp},
    {kChainDampingOption, kChainDampingOptionHelp},
    {"newton_contact_steps",
     "Newton law, matched path: time steps the contact force lasts, 2..1000 (default 4); see "
     "adapters/mujoco/README.md"},
};

// Shortest text that reads back to the same double.
std::string num(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string frame_name(int frame) { return "frame" + std::to_string(frame + 1); }

// body_invweight0 of the two tip bodies, summed: what MuJoCo scales the contact's solref by. It depends
// only on masses and geometry, so a copy of the plan without the pair gives it.
double tip_invweight_sum(const MujocoRunPlan& plan) {
  MujocoRunPlan probe = plan;
  probe.tip_pair.reset();
  const MujocoModelPtr model = compile_mjcf(write_mjcf(probe));
  double sum = 0;
  for (int f = 0; f < 2; ++f) {
    const int body = mj_name2id(model.get(), mjOBJ_BODY, mujoco_body_name(f, plan.links - 1).c_str());
    if (body < 0) throw std::logic_error("MuJoCo model without tip body");
    sum += model->body_invweight0[2 * body];  // [2 b]: translation, [2 b + 1]: rotation
  }
  return sum;
}

void write_frame(std::ostringstream& out, const MujocoRunPlan& plan, int f) {
  const FrameRig& frame = plan.rig.frames[f];
  const LinkChain& chain = frame.chain;
  const std::string name = frame_name(f);
  const bool last_collides = plan.native_contact;
  out << "    <!-- " << (f == 0 ? "Frame 1" : "Frame 2") << ": clamp at x = " << num(frame.base_x_m)
      << " m; beam length L = " << num(chain.beam_length_m) << " m as " << chain.links
      << " links of l = " << num(chain.link_length_m) << " m (hinges at segment middles, the piece below the first is "
      << "ground);\n         tip mass " << num(chain.tip_mass_kg) << " kg merged into the last link; hinge stiffness "
      << "k_j = (EI / l) a (1 + b x_j / L) with a = " << num(chain.stiffness_scale)
      << ", b = " << num(chain.stiffness_taper) << "\n         (the beam's first two frequencies), ";
  if (chain.damping == ChainDamping::hinge)
    out << "damping c_j = (2 zeta / omega_1) k_j\n         (zeta = " << num(chain.damping_ratio)
        << ", chain omega_1 = " << num(chain.first_omega_rad_s) << " rad/s). -->\n";
  else
    out << "no hinge dampers:\n         modal damping (zeta = " << num(chain.damping_ratio)
        << " in every mode), the harness applies the torques -C theta' each step (MJCF has no damping matrix). -->\n";
  std::string indent = "    ";
  for (int j = 0; j < chain.links; ++j) {
    const RigBody& body = frame.bodies[j];
    const double x = j == 0 ? frame.base_x_m : 0.0;
    const double z = j == 0 ? body.joint_z_m : body.joint_z_m - frame.bodies[j - 1].joint_z_m;
    out << indent << "<body name=\"" << mujoco_body_name(f, j) << "\" pos=\"" << num(x) << " 0 " << num(z) << "\">\n";
    indent += "  ";
    out << indent << "<!-- link " << j + 1 << ": from its hinge at z = " << num(body.joint_z_m) << " m, length "
        << num(body.length_m) << " m, mass " << num(body.mass_kg) << " kg"
        << (j + 1 == chain.links ? " (beam piece + tip mass)" : "") << ", centre of mass at z = " << num(body.com_z_m)
        << " m, inertia about it " << num(body.inertia_y_kg_m2) << " kg m^2 -->\n";
    out << indent << "<joint name=\"" << mujoco_joint_name(f, j) << "\" type=\"hinge\" axis=\"0 1 0\" stiffness=\""
        << num(chain.joint_stiffness_n_m_per_rad[j]) << "\" damping=\"" << num(chain.joint_damping_n_m_s_per_rad[j])
        << "\" springref=\"0\"/>\n";
    out << indent << "<inertial pos=\"0 0 " << num(body.com_z_m - body.joint_z_m) << "\" mass=\"" << num(body.mass_kg)
        << "\" diaginertia=\"" << num(body.inertia_xz_kg_m2) << " " << num(body.inertia_y_kg_m2) << " "
        << num(body.inertia_xz_kg_m2) << "\"/>\n";
    out << indent << "<geom type=\"capsule\" fromto=\"0 0 0 0 0 " << num(body.length_m)
        << "\" size=\"0.002\" contype=\"0\" conaffinity=\"0\" group=\"1\" rgba=\"0.6 0.6 0.7 1\"/>\n";
    if (j + 1 == chain.links) {
      const double tip = frame.tip_z_m - body.joint_z_m;
      out << indent << "<site name=\"" << mujoco_tip_site_name(f) << "\" pos=\"0 0 " << num(tip)
          << "\" size=\"0.001\"/>\n";
      out << indent << "<!-- tip sphere, radius " << num(plan.rig.sphere_radius_m) << " m, centred at the tip point"
          << (plan.native_contact || plan.tip_pair ? ""
                                                   : "; it does not collide (the harness applies the contact force)")
          << " -->\n";
      out << indent << "<geom name=\"" << mujoco_tip_geom_name(f) << "\" type=\"sphere\" size=\""
          << num(plan.rig.sphere_radius_m) << "\" pos=\"0 0 " << num(tip) << "\""
          << (last_collides ? "" : " contype=\"0\" conaffinity=\"0\"") << " rgba=\"0.8 0.3 0.2 1\"/>\n";
    }
  }
  for (int j = chain.links; j > 0; --j) {
    indent.resize(indent.size() - 2);
    out << indent << "</body>\n";
  }
}

const char* path_text(const MujocoRunPlan& plan) {
  if (plan.native_contact)
    return "native: MuJoCo's default contact settings between the tip spheres (the law's parameters are not used)";
  if (plan.tip_pair && plan.law == ContactLaw::newton)
    return "matched: MuJoCo's contact as a short no-tension spring-dashpot with the law's restitution (MuJoCo has "
           "none)";
  if (plan.tip_pair) return "matched: MuJoCo's contact as the law's spring-dashpot (direct solref)";
  if (plan.path == ContactPath::matched)
    return "matched: MuJoCo has no Hertz contact; the harness applies the law's force from the tip states each step";
  return "injected: the harness applies the law's force from the tip states each step; MuJoCo's contact is off";
}

}  // namespace

const std::vector<std::pair<std::string, std::string>>& mujoco_options() { return kOptions; }

std::string mujoco_body_name(int frame, int link) { return frame_name(frame) + "_link" + std::to_string(link + 1); }
std::string mujoco_joint_name(int frame, int link) { return frame_name(frame) + "_hinge" + std::to_string(link + 1); }
std::string mujoco_tip_site_name(int frame) { return frame_name(frame) + "_tip"; }
std::string mujoco_tip_geom_name(int frame) { return frame_name(frame) + "_tip_sphere"; }

int mujoco_chain_links(const Scenario& scenario, const RunSettings& settings) {
  return links_option(OptionReader("mujoco", settings.options, kOptions), settings, scenario);
}

MujocoRunPlan plan_mujoco_run(const Scenario& scenario, const RunSettings& settings) {
  const OptionReader options("mujoco", settings.options, kOptions);
  MujocoRunPlan plan;
  plan.scenario_name = scenario.name;
  plan.law = settings.law;
  plan.links = mujoco_chain_links(scenario, settings);
  plan.path = options.contact_path();
  plan.integrator = options.choice("integrator", "euler", {"euler", "rk4"}) == "rk4" ? MujocoIntegrator::rk4
                                                                                     : MujocoIntegrator::euler;
  const int newton_steps = options.integer("newton_contact_steps", kDefaultNewtonContactSteps, 2, 1000);
  plan.time_step_s = resolve_time_step_s(settings, kDefaultMujocoTimeStep_s, "mujoco");
  plan.rig = build_rig(scenario, settings.law, plan.links, chain_damping_option(options));

  plan.native_contact = plan.path == ContactPath::native;
  const bool matched = plan.path == ContactPath::matched;
  plan.harness_contact_force = plan.path == ContactPath::injected || (matched && settings.law == ContactLaw::hertz);
  if (matched && settings.law != ContactLaw::hertz) {
    TipPairContact pair;
    pair.invweight_sum_per_kg = tip_invweight_sum(plan);
    if (const auto* law = std::get_if<ViscoelasticLaw>(&plan.rig.law)) {
      pair.spring_dashpot = {law->stiffness_n_per_m, law->damping_n_s_per_m};
    } else {
      const double e = std::get<NewtonLaw>(plan.rig.law).restitution;
      pair.newton_duration_s = newton_steps * plan.time_step_s;
      pair.spring_dashpot =
          spring_dashpot_for_restitution(e, plan.rig.contact_effective_mass_kg, pair.newton_duration_s);
      pair.newton_damping_ratio =
          pair.spring_dashpot.damping_n_s_per_m /
          (2 * std::sqrt(pair.spring_dashpot.stiffness_n_per_m * plan.rig.contact_effective_mass_kg));
    }
    pair.parameters = map_spring_dashpot(pair.spring_dashpot.stiffness_n_per_m, pair.spring_dashpot.damping_n_s_per_m,
                                         pair.invweight_sum_per_kg);
    plan.tip_pair = pair;
  }
  return plan;
}

std::string write_mjcf(const MujocoRunPlan& plan) {
  const RigSpec& rig = plan.rig;
  std::ostringstream out;
  out << "<mujoco model=\"impactbench " << plan.scenario_name << "\">\n";
  out << "  <!-- impactbench rig (rig.md section 4), scenario '" << plan.scenario_name << "', contact law "
      << to_string(plan.law) << ".\n       Contact path " << path_text(plan) << ".\n"
      << "       SI units, angles in radians. The beams stand along +z and bend in the x-z plane (hinge axes along "
         "y);\n"
      << "       a tip displacement along +x is toward frame 2. Surface gap between the tip spheres at rest: "
      << num(rig.gap_m) << " m. -->\n";
  out << "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n";
  out << "  <!-- time step h = " << num(plan.time_step_s) << " s; no gravity (rig.md leaves it out) -->\n";
  out << "  <option timestep=\"" << num(plan.time_step_s) << "\" integrator=\""
      << (plan.integrator == MujocoIntegrator::rk4 ? "RK4" : "Euler") << "\" gravity=\"0 0 0\"/>\n";
  out << "  <worldbody>\n";
  for (int f = 0; f < 2; ++f) write_frame(out, plan, f);
  out << "  </worldbody>\n";
  if (plan.tip_pair) {
    const TipPairContact& pair = *plan.tip_pair;
    const SolrefSolimp& p = pair.parameters;
    out << "  <contact>\n";
    if (plan.law == ContactLaw::newton)
      out << "    <!-- Newton's law with e = " << num(std::get<NewtonLaw>(rig.law).restitution)
          << ": MuJoCo has no restitution, so the tips get a no-tension spring-dashpot whose rebound on their "
             "effective\n"
          << "         mass " << num(rig.contact_effective_mass_kg) << " kg is e (damping ratio "
          << num(pair.newton_damping_ratio) << ") and whose force lasts " << num(pair.newton_duration_s) << " s. -->\n";
    out << "    <!-- spring-dashpot k = " << num(pair.spring_dashpot.stiffness_n_per_m)
        << " N/m, c = " << num(pair.spring_dashpot.damping_n_s_per_m)
        << " N s/m (the solver never pulls: clipped at zero).\n"
        << "         solref = (-k A (1 - d), -c A (1 - d)) with A = " << num(pair.invweight_sum_per_kg)
        << " 1/kg (body_invweight0 of the two tip bodies) and d = " << num(p.solimp[0])
        << " (solimp dmin = dmax). -->\n";
    out << "    <pair geom1=\"" << mujoco_tip_geom_name(0) << "\" geom2=\"" << mujoco_tip_geom_name(1)
        << "\" condim=\"1\" solref=\"" << num(p.solref[0]) << " " << num(p.solref[1]) << "\" solimp=\""
        << num(p.solimp[0]) << " " << num(p.solimp[1]) << " " << num(p.solimp[2]) << " " << num(p.solimp[3]) << " "
        << num(p.solimp[4]) << "\"/>\n";
    out << "  </contact>\n";
  }
  const Eigen::VectorXd& initial = rig.frames[0].initial_angles_rad;
  if (initial.cwiseAbs().maxCoeff() > 0 || rig.frames[1].initial_angles_rad.cwiseAbs().maxCoeff() > 0) {
    out << "  <keyframe>\n    <!-- the initial state (t = 0, at rest): frame 1 in its static tip-load shape -->\n"
        << "    <key name=\"initial\" qpos=\"";
    for (int f = 0; f < 2; ++f)
      for (Eigen::Index j = 0; j < rig.frames[f].initial_angles_rad.size(); ++j)
        out << (f + j > 0 ? " " : "") << num(rig.frames[f].initial_angles_rad[j]);
    out << "\"/>\n  </keyframe>\n";
  }
  if (rig.motor)
    out << "  <!-- Motor: each step the harness applies F(t) = " << num(rig.motor->amplitude_n) << " N cos("
        << num(rig.motor->omega_rad_s) << " rad/s t) along +x at site " << mujoco_tip_site_name(0)
        << " (MJCF has no time-varying force). -->\n";
  if (plan.harness_contact_force)
    out << "  <!-- Contact: each step the harness applies -F at " << mujoco_tip_site_name(0) << " and +F at "
        << mujoco_tip_site_name(1) << " along x, F = the " << to_string(plan.law)
        << " law at the tips' indentation and its rate. -->\n";
  out << "</mujoco>\n";
  return out.str();
}

}  // namespace ib
