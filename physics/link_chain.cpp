#include "physics/link_chain.h"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>
#include <string>

#include "physics/beam_modes.h"

namespace ib {
namespace {

// Eigen-decomposition shared by build_link_chain (for omega_1) and chain_modes.
Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solve_chain(const ChainMatrices& m) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(m.stiffness, m.mass);
  if (solver.info() != Eigen::Success) throw std::runtime_error("chain eigenproblem did not converge");
  return solver;
}

// k_j = (EI / l) a (1 + b x_j / L)
void set_joint_stiffnesses(LinkChain& chain, double uniform_n_m_per_rad, double scale, double taper) {
  chain.stiffness_scale = scale;
  chain.stiffness_taper = taper;
  chain.joint_stiffness_n_m_per_rad.resize(chain.links);
  for (int j = 0; j < chain.links; ++j)
    chain.joint_stiffness_n_m_per_rad[j] =
        uniform_n_m_per_rad * scale * (1 + taper * chain.bodies[j].start_m / chain.beam_length_m);
}

// The chain's squared frequencies over the beam's, less one, for its first min(K, 2) modes.
Eigen::Vector2d frequency_mismatch(const LinkChain& chain, const Eigen::Vector2d& beam_omega_squared) {
  const auto solver = solve_chain(linearise(chain));
  Eigen::Vector2d mismatch = Eigen::Vector2d::Zero();
  for (int n = 0; n < std::min(chain.links, 2); ++n) mismatch[n] = solver.eigenvalues()[n] / beam_omega_squared[n] - 1;
  return mismatch;
}

// Solves for a and b (Newton, finite-difference Jacobian) so that the chain's first two frequencies are the
// beam's; a single hinge has only a, solved for the first. The uniform chain (a = 1, b = 0) is within a few
// per cent, so a few iterations reach the eigensolver's rounding (which grows with K: 1e-11 at K = 64).
void tune_joint_stiffnesses(LinkChain& chain, const FrameSpec& frame) {
  const CantileverModes beam(frame, 2);
  const Eigen::Vector2d beam_omega_squared(beam.omega_rad_s(0) * beam.omega_rad_s(0),
                                           beam.omega_rad_s(1) * beam.omega_rad_s(1));
  const double uniform = frame.bending_stiffness_n_m2() / chain.link_length_m;
  set_joint_stiffnesses(chain, uniform, 1, 0);
  chain.uniform_first_omega_rad_s = std::sqrt(solve_chain(linearise(chain)).eigenvalues()[0]);
  Eigen::Vector2d p(1, 0), best = p;  // (a, b)
  double best_mismatch = 1;
  for (int iteration = 0; iteration < 30; ++iteration) {
    set_joint_stiffnesses(chain, uniform, p[0], p[1]);
    const Eigen::Vector2d r = frequency_mismatch(chain, beam_omega_squared);
    if (r.cwiseAbs().maxCoeff() < best_mismatch) {
      best_mismatch = r.cwiseAbs().maxCoeff();
      best = p;
    }
    if (best_mismatch < 1e-14) break;
    Eigen::Vector2d step(r[0] * p[0] / (1 + r[0]), 0);  // one hinge: omega^2 is proportional to a
    if (chain.links > 1) {
      Eigen::Matrix2d jacobian;
      const double h = 1e-6;
      for (int c = 0; c < 2; ++c) {
        Eigen::Vector2d q = p;
        q[c] += h;
        set_joint_stiffnesses(chain, uniform, q[0], q[1]);
        jacobian.col(c) = (frequency_mismatch(chain, beam_omega_squared) - r) / h;
      }
      step = jacobian.partialPivLu().solve(r);
    }
    p -= step;
  }
  set_joint_stiffnesses(chain, uniform, best[0], best[1]);  // the iterates end in the eigensolver's rounding
  const double mismatch = frequency_mismatch(chain, beam_omega_squared).cwiseAbs().maxCoeff();
  if (!(mismatch < 1e-9))
    throw std::runtime_error("the chain's joint stiffnesses did not reach the beam's first two frequencies (K = " +
                             std::to_string(chain.links) + ", omega^2 off by " + std::to_string(mismatch) + ")");
}

}  // namespace

const char* to_string(ChainDamping damping) { return damping == ChainDamping::modal ? "modal" : "hinge"; }

std::optional<ChainDamping> chain_damping_from_string(const std::string& name) {
  for (ChainDamping d : {ChainDamping::modal, ChainDamping::hinge})
    if (name == to_string(d)) return d;
  return std::nullopt;
}

LinkChain build_link_chain(const FrameSpec& frame, int links, ChainDamping damping) {
  if (links < 1 || links > 1000)
    throw std::invalid_argument("chain links must be 1..1000, got " + std::to_string(links));
  LinkChain chain;
  chain.links = links;
  chain.beam_length_m = frame.length_m;
  chain.link_length_m = frame.length_m / links;
  chain.tip_mass_kg = frame.tip_mass_kg;
  chain.damping_ratio = frame.damping_ratio;
  chain.damping = damping;
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
  chain.joint_damping_n_m_s_per_rad.assign(links, 0.0);
  tune_joint_stiffnesses(chain, frame);
  // the undamped chain (no damping set yet) fixes omega_1 and, for modal damping, the modes
  const ChainMatrices undamped = linearise(chain);
  const auto solver = solve_chain(undamped);
  chain.first_omega_rad_s = std::sqrt(solver.eigenvalues()[0]);
  if (damping == ChainDamping::hinge)
    for (int j = 0; j < links; ++j)
      chain.joint_damping_n_m_s_per_rad[j] =
          2 * frame.damping_ratio / chain.first_omega_rad_s * chain.joint_stiffness_n_m_per_rad[j];
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
  m.stiffness = Eigen::Map<const Eigen::VectorXd>(chain.joint_stiffness_n_m_per_rad.data(), k).asDiagonal();
  m.damping = Eigen::MatrixXd::Zero(k, k);
  if (static_cast<int>(chain.joint_damping_n_m_s_per_rad.size()) == k)
    m.damping.diagonal() = Eigen::Map<const Eigen::VectorXd>(chain.joint_damping_n_m_s_per_rad.data(), k);
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
    theta[i] = tip_force_n * (chain.beam_length_m - chain.bodies[i].start_m) / chain.joint_stiffness_n_m_per_rad[i];
  return theta;
}

}  // namespace ib
