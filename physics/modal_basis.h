// A set of mass-normalised modes of one frame, as the modal equations of rig.md section 2 use them:
//   q_n'' + 2 zeta_n omega_n q_n' + omega_n^2 q_n = tip_n F_tip(t),   u(L, t) = sum_n tip_n q_n(t).
// The continuous beam, the paper's shapes and the link chain all reduce to this.
#pragma once

#include <Eigen/Core>
#include <string>

namespace ib {

struct ModalBasis {
  Eigen::VectorXd omega_rad_s;  // natural circular frequencies omega_n [rad/s], ascending
  Eigen::VectorXd zeta;         // modal damping ratios zeta_n [-]
  Eigen::VectorXd tip;          // tip values phi_n(L) of the mass-normalised shapes [1/sqrt(kg)]
  std::string origin;           // how it was built, e.g. "beam N=3", "chain K=16"

  int size() const { return static_cast<int>(omega_rad_s.size()); }
  // 1 / sum phi_n(L)^2: the tip's effective mass for an impulse [kg].
  double tip_effective_mass_kg() const { return 1.0 / tip.squaredNorm(); }
  // sum phi_n(L)^2 / omega_n^2: the tip's static compliance to a tip force [m/N].
  double tip_static_compliance_m_per_n() const;
};

}  // namespace ib
