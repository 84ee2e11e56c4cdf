// The linked-body discretisation every engine builds (rig.md section 4), as plain data, and its
// linearised modes. Adapters build their models from LinkChain so that the physics of the mapping
// stands in one tested place, and the reference can run on exactly the chain an engine simulates.
//
// [0, L] is split into K segments of length l = L/K with a revolute joint at the middle of each,
// x_j = (j - 1/2) l. The piece [0, l/2] is ground; body j spans [x_j, x_{j+1}], the last body spans
// [x_K, L] and carries the tip mass as a point mass at x = L. Each body has mass rho A times its length
// and the rotary inertia of a slender rod; each joint has stiffness EI / l and damping
// (2 zeta / omega_1) EI / l, with omega_1 the chain's own first frequency (mode 1 gets exactly zeta).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "physics/modal_basis.h"
#include "model/scenario.h"

namespace ib {

struct ChainBody {
  double start_m = 0;            // position along the beam of the joint it hangs from [m]
  double length_m = 0;           // [m]
  double mass_kg = 0;            // rho A length [kg]
  double center_m = 0;           // centre of mass along the beam (without the tip mass) [m]
  double inertia_kg_m2 = 0;      // about its centre, slender rod: m length^2 / 12 [kg m^2]
};

struct LinkChain {
  int links = 0;                              // K
  double beam_length_m = 0;                   // L [m]
  double link_length_m = 0;                   // l = L / K [m]
  std::vector<ChainBody> bodies;              // K bodies, body j from joint j
  double tip_mass_kg = 0;                     // point mass at x = L on the last body [kg]
  double joint_stiffness_n_m_per_rad = 0;     // k_theta = EI / l [N m/rad]
  double joint_damping_n_m_s_per_rad = 0;     // c_theta = (2 zeta / omega_1) k_theta [N m s/rad]
  double first_omega_rad_s = 0;               // omega_1 of the chain, used for c_theta [rad/s]
  double damping_ratio = 0;                   // zeta of mode 1 [-]
};

LinkChain build_link_chain(const FrameSpec& frame, int links);

// The chain linearised about the straight rest state in the relative joint angles theta_j:
// T = 1/2 theta'^T M theta', V = 1/2 theta^T K theta, dissipation 1/2 theta'^T C theta', and the tip
// displacement u(L) = tip_lever^T theta.
struct ChainMatrices {
  Eigen::MatrixXd mass;        // [kg m^2]
  Eigen::MatrixXd stiffness;   // [N m/rad]
  Eigen::MatrixXd damping;     // [N m s/rad]
  Eigen::VectorXd tip_lever;   // L - x_j [m]
};
ChainMatrices linearise(const LinkChain& chain);

// The K modes of the chain from the generalised symmetric eigenproblem K v = omega^2 M v (Eigen),
// mass-normalised, with modal damping zeta_n = zeta omega_n / omega_1 (stiffness-proportional).
ModalBasis chain_modes(const LinkChain& chain);

// Joint angles [rad] of the chain's static deflection under a tip force F [N]: theta_j = F (L - x_j) / k.
Eigen::VectorXd static_tip_load_angles(const LinkChain& chain, double tip_force_n);

}  // namespace ib
