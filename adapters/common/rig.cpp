#include "adapters/common/rig.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "physics/beam_modes.h"

namespace ib {

int default_links(const Scenario& scenario) {
  for (int links = 2; links <= 64; links *= 2) {
    bool close = true;
    for (const FrameSpec& frame : scenario.frames) {
      const double beam = CantileverModes(frame, 1).omega_rad_s(0);
      // the discretisation's own accuracy, before the joints are tuned to the beam's frequencies
      const double chain = build_link_chain(frame, links).uniform_first_omega_rad_s;
      close = close && std::abs(chain / beam - 1) <= 0.005;
    }
    if (close) return links;
  }
  return 64;
}

int links_option(const OptionReader& options, const RunSettings& settings, const Scenario& scenario) {
  return settings.options.count("links") ? options.integer("links", 0, 1, 64) : default_links(scenario);
}

ChainDamping chain_damping_option(const OptionReader& options) {
  return *chain_damping_from_string(options.choice(kChainDampingOption, to_string(ChainDamping::modal),
                                                   {to_string(ChainDamping::modal), to_string(ChainDamping::hinge)}));
}

std::array<Eigen::VectorXd, 2> zero_hinge_values(const RigSpec& rig) {
  return {Eigen::VectorXd::Zero(rig.frames[0].chain.links), Eigen::VectorXd::Zero(rig.frames[1].chain.links)};
}

void add_chain_diagnostics(const RigSpec& rig, int f, std::vector<std::pair<std::string, double>>& diagnostics) {
  const std::string frame = "frame" + std::to_string(f + 1);
  const LinkChain& chain = rig.frames[f].chain;
  diagnostics.emplace_back(frame + "_chain_first_frequency_hz", chain.first_omega_rad_s / (2 * M_PI));
  diagnostics.emplace_back(frame + "_root_joint_stiffness_n_m_per_rad", chain.joint_stiffness_n_m_per_rad.front());
  diagnostics.emplace_back(frame + "_joint_stiffness_scale", chain.stiffness_scale);
  diagnostics.emplace_back(frame + "_joint_stiffness_taper", chain.stiffness_taper);
  diagnostics.emplace_back(frame + "_root_joint_damping_n_m_s_per_rad", chain.joint_damping_n_m_s_per_rad.front());
}

namespace {

FrameRig build_frame(const FrameSpec& spec, int links, ChainDamping damping, double base_x,
                     double initial_tip_displacement) {
  FrameRig f;
  f.chain = build_link_chain(spec, links, damping);
  f.base_x_m = base_x;
  f.tip_z_m = spec.length_m;
  for (int j = 0; j < links; ++j) {
    const ChainBody& link = f.chain.bodies[j];
    RigBody b;
    b.joint_z_m = link.start_m;
    b.length_m = link.length_m;
    b.mass_kg = link.mass_kg;
    b.com_z_m = link.center_m;
    b.inertia_y_kg_m2 = link.inertia_kg_m2;
    if (j + 1 == links && f.chain.tip_mass_kg > 0) {
      // the tip mass is a point at the tip: merge it (parallel-axis theorem about the new centre)
      const double m = link.mass_kg + f.chain.tip_mass_kg;
      const double com = (link.mass_kg * link.center_m + f.chain.tip_mass_kg * spec.length_m) / m;
      b.inertia_y_kg_m2 = link.inertia_kg_m2 + link.mass_kg * std::pow(link.center_m - com, 2) +
                          f.chain.tip_mass_kg * std::pow(spec.length_m - com, 2);
      b.mass_kg = m;
      b.com_z_m = com;
    }
    b.inertia_xz_kg_m2 = b.inertia_y_kg_m2;
    f.bodies.push_back(b);
  }
  const ChainMatrices m = linearise(f.chain);
  f.tip_effective_mass_kg = 1 / m.tip_lever.dot(m.mass.ldlt().solve(m.tip_lever));
  f.initial_angles_rad = Eigen::VectorXd::Zero(links);
  if (initial_tip_displacement != 0) {
    // u(L) = tip_lever . theta, with theta the static deflection under a unit tip force
    const double compliance = m.tip_lever.dot(static_tip_load_angles(f.chain, 1.0));
    f.initial_angles_rad = static_tip_load_angles(f.chain, initial_tip_displacement / compliance);
  }
  return f;
}

}  // namespace

RigSpec build_rig(const Scenario& scenario, ContactLaw law, int links, ChainDamping damping) {
  if (links < 1) throw std::invalid_argument("links must be >= 1, got " + std::to_string(links));
  RigSpec rig;
  rig.gap_m = scenario.gap_m;
  rig.sphere_radius_m = kTipSphereRadius_m;
  rig.frame_spacing_m = scenario.gap_m + 2 * kTipSphereRadius_m;
  rig.frames[0] = build_frame(scenario.frames[0], links, damping, 0.0, scenario.initial.frame1_tip_displacement_m);
  rig.frames[1] = build_frame(scenario.frames[1], links, damping, rig.frame_spacing_m, 0.0);
  rig.motor = motor_force(scenario);
  rig.law = make_contact_model(scenario, law);
  rig.contact_effective_mass_kg =
      1 / (1 / rig.frames[0].tip_effective_mass_kg + 1 / rig.frames[1].tip_effective_mass_kg);
  rig.duration_s = scenario.duration_s;
  return rig;
}

RigEnergy::RigEnergy(const RigSpec& rig) : law_(rig.law) {
  for (int f = 0; f < 2; ++f) matrices_[f] = linearise(rig.frames[f].chain);
}

double explicit_hinge_step_limit_s(const RigSpec& rig) {
  double limit = std::numeric_limits<double>::infinity();
  for (const FrameRig& frame : rig.frames) {
    const ModalBasis modes = chain_modes(frame.chain);
    for (Eigen::Index n = 0; n < modes.omega_rad_s.size(); ++n) {
      const double omega = modes.omega_rad_s[n], zeta = modes.zeta[n];
      limit = std::min(limit, 2 * (std::sqrt(1 + zeta * zeta) - zeta) / omega);
    }
  }
  return limit;
}

namespace {
// x^T A x for a symmetric A (the chain's mass and stiffness matrices) from its lower triangle,
// sum_j x_j (A_jj x_j + 2 sum_{i>j} A_ij x_i): half the products of the full form, and no temporary
// vector (Eigen's A * x would allocate one per call). The engines call RigEnergy every step.
double symmetric_quadratic_form(const Eigen::MatrixXd& a, const Eigen::VectorXd& x) {
  const Eigen::Index n = a.cols();
  double sum = 0;
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::Index below = n - j - 1;
    sum += x[j] * (a(j, j) * x[j] + 2 * a.col(j).tail(below).dot(x.tail(below)));
  }
  return sum;
}
}  // namespace

double RigEnergy::operator()(const std::array<Eigen::VectorXd, 2>& angles, const std::array<Eigen::VectorXd, 2>& rates,
                             double indentation_m) const {
  double energy = elastic_contact_energy(law_, indentation_m);
  for (int f = 0; f < 2; ++f)
    energy += 0.5 * symmetric_quadratic_form(matrices_[f].mass, rates[f]) +
              0.5 * symmetric_quadratic_form(matrices_[f].stiffness, angles[f]);
  return energy;
}

}  // namespace ib
