// The linked-body chain of rig.md section 4: its modes converge to the beam's; its damping gives every
// mode the beam's zeta (modal) or is stiffness-proportional with exactly zeta on mode 1 (hinge), as the
// eigenvalues of the linearised damped chain say.
#include "physics/link_chain.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

#include "physics/beam_modes.h"
#include "physics/modal_model.h"

namespace ib {
namespace link_chain_test {

// The chain with every joint EI / l, before tuning (LinkChain::uniform_first_omega_rad_s).
LinkChain uniform_chain(const FrameSpec& frame, int links) {
  LinkChain chain = build_link_chain(frame, links);
  chain.joint_stiffness_n_m_per_rad.assign(links, frame.bending_stiffness_n_m2() / chain.link_length_m);
  return chain;
}

TEST(LinkChain, UniformChainsFirstFrequencyConvergesToTheBeamsAsLinksGrow) {
  const FrameSpec frame = default_rig().frames[0];
  const double beam = CantileverModes(frame, 1).omega_rad_s(0);
  double previous_error = 1;
  for (int links : {2, 4, 8, 16, 32}) {
    const double uniform = chain_modes(uniform_chain(frame, links)).omega_rad_s[0];
    EXPECT_NEAR(build_link_chain(frame, links).uniform_first_omega_rad_s / uniform, 1.0, 1e-14) << "K = " << links;
    const double error = std::abs(uniform / beam - 1);
    EXPECT_LT(error, previous_error) << "K = " << links;
    previous_error = error;
  }
  EXPECT_LT(previous_error, 1e-3);  // K = 32: within 0.1 %
  // rig.md section 4 quotes about 4 %, 1 %, 0.2 %, 0.06 % for K = 2, 4, 8, 16 (this rig: 3.8, 0.91, 0.22, 0.056)
  const std::pair<int, double> quoted[] = {{2, 0.04}, {4, 0.01}, {8, 0.002}, {16, 0.0006}};
  for (const auto& [links, error] : quoted)
    EXPECT_NEAR(chain_modes(uniform_chain(frame, links)).omega_rad_s[0] / beam - 1, error, 0.25 * error)
        << "K = " << links;
}

// The tuned joints k_j = (EI / l) a (1 + b x_j / L) give the chain the beam's first two frequencies to rounding
// at every K, both frames; the tuning shrinks as K grows (the uniform chain converges), and the third mode,
// which is not tuned, comes out nearer the beam's than the uniform chain's (K = 8: 1.8 % high uniform).
TEST(LinkChain, TunedJointsGiveTheBeamsFirstTwoFrequencies) {
  for (const FrameSpec& frame : default_rig().frames) {
    const ModalBasis beam = CantileverModes(frame, 3).basis();
    double previous_tuning = 1;
    for (int links : {2, 4, 8, 16, 32}) {
      const LinkChain chain = build_link_chain(frame, links);
      const ModalBasis tuned = chain_modes(chain);
      for (int n = 0; n < 2; ++n)
        EXPECT_NEAR(tuned.omega_rad_s[n] / beam.omega_rad_s[n], 1.0, 1e-10) << "K = " << links << ", mode " << n + 1;
      const double l = frame.length_m / links;
      for (int j = 0; j < links; ++j)
        EXPECT_NEAR(chain.joint_stiffness_n_m_per_rad[j],
                    frame.bending_stiffness_n_m2() / l * chain.stiffness_scale *
                        (1 + chain.stiffness_taper * (j + 0.5) * l / frame.length_m),
                    1e-12 * chain.joint_stiffness_n_m_per_rad[j]);
      const double tuning = std::abs(chain.stiffness_scale - 1) + std::abs(chain.stiffness_taper);
      EXPECT_LT(tuning, previous_tuning) << "K = " << links;
      previous_tuning = tuning;
      if (links >= 4) {
        const double uniform = chain_modes(uniform_chain(frame, links)).omega_rad_s[2];
        EXPECT_LT(std::abs(tuned.omega_rad_s[2] / beam.omega_rad_s[2] - 1), std::abs(uniform / beam.omega_rad_s[2] - 1))
            << "K = " << links;
      }
    }
    EXPECT_LT(previous_tuning, 0.01);  // K = 32
  }
}

TEST(LinkChain, HigherModesAndTipValuesConvergeToo) {
  const FrameSpec frame = default_rig().frames[1];
  const ModalBasis beam = CantileverModes(frame, 3).basis();
  const ModalBasis chain = chain_modes(build_link_chain(frame, 64));
  for (int n = 0; n < 3; ++n) {
    EXPECT_NEAR(chain.omega_rad_s[n] / beam.omega_rad_s[n], 1.0, 5e-3) << "mode " << n + 1;
    EXPECT_NEAR(std::abs(chain.tip[n]) / std::abs(beam.tip[n]), 1.0, 5e-3) << "mode " << n + 1;
  }
}

// The damped chain's free motion theta' = A theta with A = [[0, I], [-M^-1 K, -M^-1 C]]: each mode is a pair
// lambda = -zeta omega +- i omega sqrt(1 - zeta^2), so omega = |lambda| and zeta = -Re lambda / |lambda|.
// The underdamped pairs' (omega, zeta), ascending in omega.
std::vector<std::pair<double, double>> damped_modes(const LinkChain& chain) {
  const ChainMatrices m = linearise(chain);
  const int k = chain.links;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * k, 2 * k);
  a.topRightCorner(k, k).setIdentity();
  a.bottomLeftCorner(k, k) = -m.mass.ldlt().solve(m.stiffness);
  a.bottomRightCorner(k, k) = -m.mass.ldlt().solve(m.damping);
  const Eigen::VectorXcd lambda = Eigen::EigenSolver<Eigen::MatrixXd>(a, false).eigenvalues();
  std::vector<std::pair<double, double>> modes;
  for (const auto& l : lambda)
    if (l.imag() > 0) modes.emplace_back(std::abs(l), -l.real() / std::abs(l));
  std::sort(modes.begin(), modes.end());
  return modes;
}

// Modal damping, C = M Phi diag(2 zeta omega_n) Phi^T M: every mode of the damped chain has the beam's zeta
// and its undamped frequency (classical damping leaves |lambda| = omega_n); tolerances: the nonsymmetric
// eigensolver's rounding on a matrix whose entries span about 1e8 (seen up to 1.4e-8 relative at K = 16).
TEST(LinkChain, ModalDampingGivesEveryModeTheBeamsZeta) {
  for (int links : {2, 8, 16}) {
    const FrameSpec frame = default_rig().frames[0];
    const LinkChain chain = build_link_chain(frame, links, ChainDamping::modal);
    for (double c : chain.joint_damping_n_m_s_per_rad) EXPECT_EQ(c, 0);  // no hinge dampers
    const ModalBasis modes = chain_modes(chain);
    const auto damped = damped_modes(chain);
    ASSERT_EQ(static_cast<int>(damped.size()), links);
    for (int n = 0; n < links; ++n) {
      EXPECT_NEAR(damped[n].second, frame.damping_ratio, 1e-9) << "K = " << links << ", mode " << n + 1;
      EXPECT_NEAR(damped[n].first / modes.omega_rad_s[n], 1.0, 1e-7) << "K = " << links << ", mode " << n + 1;
      EXPECT_EQ(modes.zeta[n], frame.damping_ratio);
    }
    // Phi^T C Phi = diag(2 zeta omega_n) in closed form: C is symmetric and positive definite
    const Eigen::MatrixXd& c = chain.modal_damping_n_m_s_per_rad;
    EXPECT_EQ((c - c.transpose()).norm(), 0);
    EXPECT_GT(c.ldlt().vectorD().minCoeff(), 0);
  }
}

// Hinge damping, c_theta in every hinge: the damped chain's modes have zeta omega_n / omega_1.
TEST(LinkChain, HingeDampingGivesModeNZetaOmegaNOverOmegaOne) {
  const FrameSpec frame = default_rig().frames[0];
  const LinkChain chain = build_link_chain(frame, 8, ChainDamping::hinge);
  EXPECT_EQ(chain.modal_damping_n_m_s_per_rad.size(), 0);
  const ModalBasis modes = chain_modes(chain);
  const auto damped = damped_modes(chain);
  ASSERT_EQ(damped.size(), 8u);  // all underdamped at K = 8 (the fastest: zeta 0.85)
  for (int n = 0; n < 8; ++n) {
    const double expected = frame.damping_ratio * modes.omega_rad_s[n] / modes.omega_rad_s[0];
    EXPECT_NEAR(damped[n].second / expected, 1.0, 1e-7) << "mode " << n + 1;  // the eigensolver's rounding
    EXPECT_NEAR(modes.zeta[n] / expected, 1.0, 1e-12) << "mode " << n + 1;
  }
  EXPECT_NEAR(damped[1].second / frame.damping_ratio, modes.omega_rad_s[1] / modes.omega_rad_s[0], 1e-6);
  EXPECT_GT(damped[1].second, 9 * frame.damping_ratio);  // mode 2 (about 74 Hz against 7 Hz): ten times zeta
}

TEST(LinkChain, DampingIsStiffnessProportionalWithZetaOnModeOne) {
  const FrameSpec frame = default_rig().frames[0];
  const LinkChain chain = build_link_chain(frame, 8, ChainDamping::hinge);
  const ModalBasis modes = chain_modes(chain);
  EXPECT_NEAR(modes.zeta[0], frame.damping_ratio, 1e-15);
  EXPECT_NEAR(chain.first_omega_rad_s, modes.omega_rad_s[0], 1e-12 * modes.omega_rad_s[0]);
  for (int j = 0; j < 8; ++j)
    EXPECT_NEAR(chain.joint_damping_n_m_s_per_rad[j],
                2 * frame.damping_ratio / modes.omega_rad_s[0] * chain.joint_stiffness_n_m_per_rad[j], 1e-15);
  // modal damping from the matrices: v^T C v / (2 omega) for mass-normalised v
  const ChainMatrices m = linearise(chain);
  for (int n = 1; n < 8; ++n)
    EXPECT_NEAR(modes.zeta[n], frame.damping_ratio * modes.omega_rad_s[n] / modes.omega_rad_s[0], 1e-12);
  EXPECT_EQ(m.damping.diagonal(), Eigen::Map<const Eigen::VectorXd>(chain.joint_damping_n_m_s_per_rad.data(), 8));
  EXPECT_EQ(m.damping.norm(), m.damping.diagonal().norm());
}

TEST(LinkChain, GeometryFollowsTheSpecification) {
  const FrameSpec frame = default_rig().frames[0];
  const LinkChain chain = build_link_chain(frame, 4);
  const double l = frame.length_m / 4;
  ASSERT_EQ(chain.bodies.size(), 4u);
  double mass = 0;
  for (int j = 0; j < 4; ++j) {
    EXPECT_DOUBLE_EQ(chain.bodies[j].start_m, (j + 0.5) * l);
    mass += chain.bodies[j].mass_kg;
  }
  EXPECT_DOUBLE_EQ(chain.bodies[3].length_m, l / 2);
  // the ground keeps [0, l/2]: the chain carries the rest of the beam's mass
  EXPECT_NEAR(mass, frame.mass_per_length_kg_m() * (frame.length_m - l / 2), 1e-15);
}

// The chain's static tip compliance from its modes equals sum (L - x_j)^2 / k_j, and both approach the
// beam's L^3 / (3 EI).
TEST(LinkChain, StaticTipComplianceMatchesTheJointSum) {
  const FrameSpec frame = default_rig().frames[0];
  const LinkChain chain = build_link_chain(frame, 32);
  double joint_sum = 0;
  for (int j = 0; j < 32; ++j)
    joint_sum += std::pow(frame.length_m - chain.bodies[j].start_m, 2) / chain.joint_stiffness_n_m_per_rad[j];
  EXPECT_NEAR(chain_modes(chain).tip_static_compliance_m_per_n() / joint_sum, 1.0, 1e-8);  // eigensolver accuracy
  const double beam = std::pow(frame.length_m, 3) / (3 * frame.bending_stiffness_n_m2());
  EXPECT_NEAR(joint_sum / beam, 1.0, 1e-3);
  const Eigen::VectorXd angles = static_tip_load_angles(chain, 1.0);
  EXPECT_NEAR(linearise(chain).tip_lever.dot(angles) / joint_sum, 1.0, 1e-12);
}

}  // namespace link_chain_test
}  // namespace ib
