// The linked-body discretisation every engine builds (rig.md section 4), as plain data, and its
// linearised modes. Adapters build their models from LinkChain so that the physics of the mapping
// stands in one tested place, and the reference can run on exactly the chain an engine simulates.
//
// [0, L] is split into K segments of length l = L/K with a revolute joint at the middle of each,
// x_j = (j - 1/2) l. The piece [0, l/2] is ground; body j spans [x_j, x_{j+1}], the last body spans
// [x_K, L] and carries the tip mass as a point mass at x = L. Each body has mass rho A times its length
// and the rotary inertia of a slender rod. Joint j has stiffness (EI / l) a (1 + b x_j / L), with the scale a and
// the taper b solved so that the chain's first two frequencies equal the beam's (a uniform EI / l leaves the
// second 1 % high, enough to move it off the impacts' harmonic it rings on). The chain's damping is one of
// two (ChainDamping): modal, the joint damping matrix C = M Phi diag(2 zeta omega_n) Phi^T M that gives
// every mode the beam's zeta (the measured beam rings in every mode with about the same zeta); or hinge,
// a damper (2 zeta / omega_1) k_j in every joint, with omega_1 the chain's own first frequency (mode 1
// gets exactly zeta, mode n zeta omega_n / omega_1).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "model/scenario.h"
#include "physics/modal_basis.h"

namespace ib {

// How the chain's joints dissipate (rig.md section 4):
//  modal - every mode gets the beam's zeta: a full joint damping matrix (modal_damping_matrix), no dampers
//          in the hinges; an engine applies it as joint torques -C theta' (the shared fixed-step loop);
//  hinge - a damper c_theta = (2 zeta / omega_1) k_theta in every hinge (stiffness-proportional: mode n
//          gets zeta omega_n / omega_1), the engines' own joint damping.
enum class ChainDamping { modal, hinge };
const char* to_string(ChainDamping damping);
std::optional<ChainDamping> chain_damping_from_string(const std::string& name);
// The option that chooses it, the same name, values and default for every engine and the chain reference.
constexpr const char* kChainDampingOption = "chain_damping";
constexpr const char* kChainDampingOptionHelp =
    "the chain's damping: modal (every mode gets the beam's zeta: joint damping matrix M Phi diag(2 zeta omega_n) "
    "Phi^T M, default) or hinge (a damper (2 zeta / omega_1) k_theta in every hinge: mode n gets zeta omega_n / "
    "omega_1)";
constexpr const char* kChainDampingValues = "modal, hinge";

struct ChainBody {
  double start_m = 0;        // position along the beam of the joint it hangs from [m]
  double length_m = 0;       // [m]
  double mass_kg = 0;        // rho A length [kg]
  double center_m = 0;       // centre of mass along the beam (without the tip mass) [m]
  double inertia_kg_m2 = 0;  // about its centre, slender rod: m length^2 / 12 [kg m^2]
};

struct LinkChain {
  int links = 0;                  // K
  double beam_length_m = 0;       // L [m]
  double link_length_m = 0;       // l = L / K [m]
  std::vector<ChainBody> bodies;  // K bodies, body j from joint j
  double tip_mass_kg = 0;         // point mass at x = L on the last body [kg]
  // k_j = (EI / l) a (1 + b x_j / L) per joint [N m/rad]; a and b (stiffness_scale, stiffness_taper) give the
  // chain the beam's first two frequencies (one hinge: a alone, the first)
  std::vector<double> joint_stiffness_n_m_per_rad;
  double stiffness_scale = 1;                       // a [-]
  double stiffness_taper = 0;                       // b [-]
  double uniform_first_omega_rad_s = 0;             // omega_1 of the same chain with every k_j = EI / l (a = 1, b = 0):
                                                    // how well K links discretise the beam, before any tuning [rad/s]
  ChainDamping damping = ChainDamping::modal;       // which of the two dampings below the chain has
  std::vector<double> joint_damping_n_m_s_per_rad;  // hinge: c_j = (2 zeta / omega_1) k_j; modal: 0 [N m s/rad]
  Eigen::MatrixXd modal_damping_n_m_s_per_rad;  // modal: C = M Phi diag(2 zeta omega_n) Phi^T M (K x K); hinge: empty
  double first_omega_rad_s = 0;                 // omega_1 of the chain, used for c_theta [rad/s]
  double damping_ratio = 0;                     // the beam's zeta: of every mode (modal), of mode 1 (hinge) [-]
};

LinkChain build_link_chain(const FrameSpec& frame, int links, ChainDamping damping = ChainDamping::modal);

// The chain linearised about the straight rest state in the relative joint angles theta_j:
// T = 1/2 theta'^T M theta', V = 1/2 theta^T K theta, dissipation 1/2 theta'^T C theta', and the tip
// displacement u(L) = tip_lever^T theta.
struct ChainMatrices {
  Eigen::MatrixXd mass;       // [kg m^2]
  Eigen::MatrixXd stiffness;  // [N m/rad]
  Eigen::MatrixXd damping;    // [N m s/rad]
  Eigen::VectorXd tip_lever;  // L - x_j [m]
};
// C = diag(c_theta) (hinge) or the modal damping matrix (modal).
ChainMatrices linearise(const LinkChain& chain);

// The damping matrix that gives every mode of (M, K) the damping ratio zeta: with Phi the mass-normalised
// modes (Phi^T M Phi = I, Phi^T K Phi = diag(omega_n^2)), C = M Phi diag(2 zeta omega_n) Phi^T M, so that
// Phi^T C Phi = diag(2 zeta omega_n) and each mode obeys q'' + 2 zeta omega_n q' + omega_n^2 q = 0.
Eigen::MatrixXd modal_damping_matrix(const Eigen::MatrixXd& mass, const Eigen::MatrixXd& stiffness, double zeta);

// The K modes of the chain from the generalised symmetric eigenproblem K v = omega^2 M v (Eigen),
// mass-normalised, with damping ratios zeta_n = zeta (modal) or zeta omega_n / omega_1 (hinge).
ModalBasis chain_modes(const LinkChain& chain);

// Joint angles [rad] of the chain's static deflection under a tip force F [N]: theta_j = F (L - x_j) / k_j.
Eigen::VectorXd static_tip_load_angles(const LinkChain& chain, double tip_force_n);

}  // namespace ib
