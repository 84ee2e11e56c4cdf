#include "physics/link_chain.h"

#include <Eigen/Eigenvalues>
#include <stdexcept>
#include <string>

namespace ib {
namespace {

// Eigen-decomposition shared by build_link_chain (for omega_1) and chain_modes.
Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solve_chain(const ChainMatrices& m) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(m.stiffness, m.mass);
  if (solver.info() != Eigen::Success) throw std::runtime_error("chain eigenproblem did not converge");
  return solver;
}

}  // namespace

const char* to_string(ChainDamping damping) {
  return damping == ChainDamping::modal ? "modal" : "hinge";
}

std::optional<ChainDamping> chain_damping_from_string(const std::string& name) {
  for (ChainDamping d : {ChainDamping::modal, ChainDamping::hinge})
    if (name == to_string(d)) return d;
  return std::nullopt;
}

LinkChain build_link_chain(const FrameSpec& frame, int links, ChainDamping damping) {
  if (links < 1 || links > 1000) throw std::invalid_argument("chain links must be 1..1000, got " + std::to_string(links));
  LinkChain chain;
  chain.links = links;
  chain.beam_length_m = frame.length_m;
  chain.link_length_m = frame.length_m / links;
  chain.tip_mass_kg = frame.tip_mass_kg;
  chain.damping_ratio = frame.damping_ratio;
  chain.damping = damping;
  chain.joint_stiffness_n_m_per_rad = frame.bending_stiffness_n_m2() / chain.link_length_m;
  const double rho_a = frame.mass_per_length_kg_m();
  for (int j = 0; j < links; ++j) {
    ChainBody body;
    body.start_m = (j + 0.5) * chain.link_length_m;
    const double end = (j + 1 < links) ? (j + 1.5) * chain.link_length_m : frame.length_m;
    body.length_m = end - body.start_m;
    body.mass_kg = rho_a * body.length_m;
    body.center_m = 0.5 * (body.start_m + end);
    body.inertia_kg_m2 = body.mass_kg * body.length_m * body.length_m / 12;
    chain.bodies.push_back(body);
  }
  // the undamped chain (no damping set yet) fixes omega_1 and, for modal damping, the modes
  const ChainMatrices undamped = linearise(chain);
  const auto solver = solve_chain(undamped);
  chain.first_omega_rad_s = std::sqrt(solver.eigenvalues()[0]);
  if (damping == ChainDamping::hinge)
    chain.joint_damping_n_m_s_per_rad =
        2 * frame.damping_ratio / chain.first_omega_rad_s * chain.joint_stiffness_n_m_per_rad;
  else
    chain.modal_damping_n_m_s_per_rad = modal_damping_matrix(undamped.mass, undamped.stiffness, frame.damping_ratio);
  return chain;
}

ChainMatrices linearise(const LinkChain& chain) {
  const int k = chain.links;
  ChainMatrices m;
  m.mass.setZero(k, k);
  // A point at x on body j moves by sum_{i <= j} theta_i (x - x_i) and body j turns by sum_{i <= j} theta_i.
  for (int j = 0; j < k; ++j) {
    const ChainBody& body = chain.bodies[j];
    Eigen::VectorXd lever = Eigen::VectorXd::Zero(k), turn = Eigen::VectorXd::Zero(k);
    for (int i = 0; i <= j; ++i) {
      lever[i] = body.center_m - chain.bodies[i].start_m;
      turn[i] = 1;
    }
    m.mass += body.mass_kg * lever * lever.transpose() + body.inertia_kg_m2 * turn * turn.transpose();
  }
  m.tip_lever.resize(k);
  for (int i = 0; i < k; ++i) m.tip_lever[i] = chain.beam_length_m - chain.bodies[i].start_m;
  m.mass += chain.tip_mass_kg * m.tip_lever * m.tip_lever.transpose();
  m.stiffness = chain.joint_stiffness_n_m_per_rad * Eigen::MatrixXd::Identity(k, k);
  m.damping = chain.joint_damping_n_m_s_per_rad * Eigen::MatrixXd::Identity(k, k);
  if (chain.modal_damping_n_m_s_per_rad.size() > 0) m.damping += chain.modal_damping_n_m_s_per_rad;
  return m;
}

Eigen::MatrixXd modal_damping_matrix(const Eigen::MatrixXd& mass, const Eigen::MatrixXd& stiffness, double zeta) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(stiffness, mass);
  if (solver.info() != Eigen::Success) throw std::runtime_error("chain eigenproblem did not converge");
  const Eigen::MatrixXd m_phi = mass * solver.eigenvectors();
  const Eigen::VectorXd two_zeta_omega = 2 * zeta * solver.eigenvalues().cwiseMax(0).cwiseSqrt();
  Eigen::MatrixXd c = m_phi * two_zeta_omega.asDiagonal() * m_phi.transpose();
  return 0.5 * (c + c.transpose());  // symmetric to rounding, so that -C theta' never does work
}

ModalBasis chain_modes(const LinkChain& chain) {
  const ChainMatrices m = linearise(chain);
  const auto solver = solve_chain(m);
  const int k = chain.links;
  ModalBasis basis;
  basis.omega_rad_s = solver.eigenvalues().cwiseSqrt();
  // Eigen returns M-normalised eigenvectors; fix the sign so that every tip value is positive.
  basis.tip = solver.eigenvectors().transpose() * m.tip_lever;
  for (int n = 0; n < k; ++n)
    if (basis.tip[n] < 0) basis.tip[n] = -basis.tip[n];
  if (chain.damping == ChainDamping::modal)
    basis.zeta = Eigen::VectorXd::Constant(k, chain.damping_ratio);
  else
    basis.zeta = chain.damping_ratio * basis.omega_rad_s / chain.first_omega_rad_s;
  basis.origin = "chain K=" + std::to_string(k);
  return basis;
}

Eigen::VectorXd static_tip_load_angles(const LinkChain& chain, double tip_force_n) {
  Eigen::VectorXd theta(chain.links);
  for (int i = 0; i < chain.links; ++i)
    theta[i] = tip_force_n * (chain.beam_length_m - chain.bodies[i].start_m) / chain.joint_stiffness_n_m_per_rad;
  return theta;
}

}  // namespace ib
