// The rig every engine builds, derived in one place: masses, inertias, geometry, initial shape,
// default discretisation and the energy measure.
#include "adapters/common/rig.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "physics/beam_modes.h"
#include "reference_fixtures.h"

namespace ib {
namespace rig_test {

TEST(Rig, DefaultLinksIsTheSmallestWithinHalfAPercent) {
  const Scenario s = testing::paper_scenario("resonance");
  EXPECT_EQ(default_links(s), 8);  // K = 4 is 0.9 % off, K = 8 0.22 %
}

TEST(Rig, BodiesCarryTheBeamAndTheTipMass) {
  const Scenario s = testing::paper_scenario("resonance");
  const RigSpec rig = build_rig(s, ContactLaw::hertz, 8);
  for (int f = 0; f < 2; ++f) {
    const FrameSpec& frame = s.frames[f];
    double mass = 0, moment = 0;
    for (const RigBody& b : rig.frames[f].bodies) {
      mass += b.mass_kg;
      moment += b.mass_kg * b.com_z_m;
    }
    const double l = frame.length_m / 8;
    const double beam = frame.mass_per_length_kg_m() * (frame.length_m - l / 2);
    EXPECT_NEAR(mass, beam + frame.tip_mass_kg, 1e-12);
    // first moment: the chain's beam pieces about their centres plus the tip mass at L
    double expected = frame.tip_mass_kg * frame.length_m;
    for (const ChainBody& c : rig.frames[f].chain.bodies) expected += c.mass_kg * c.center_m;
    EXPECT_NEAR(moment, expected, 1e-12);
    // the last body's inertia about its centre: rod + point mass by the parallel-axis theorem
    const RigBody& last = rig.frames[f].bodies.back();
    const ChainBody& link = rig.frames[f].chain.bodies.back();
    const double expected_inertia = link.inertia_kg_m2 + link.mass_kg * std::pow(link.center_m - last.com_z_m, 2) +
                                    frame.tip_mass_kg * std::pow(frame.length_m - last.com_z_m, 2);
    EXPECT_NEAR(last.inertia_y_kg_m2, expected_inertia, 1e-15);
  }
  EXPECT_DOUBLE_EQ(rig.frame_spacing_m, s.gap_m + 2 * rig.sphere_radius_m);
  ASSERT_TRUE(rig.motor.has_value());
  EXPECT_NEAR(rig.motor->omega_rad_s, 2 * M_PI * 6.9498, 2e-3);
}

TEST(Rig, ExplicitHingeStepLimitIsSetByTheFastestChainMode) {
  Scenario s = testing::paper_scenario("resonance");
  const double hinge_s = explicit_hinge_step_limit_s(build_rig(s, ContactLaw::hertz, 8, ChainDamping::hinge));
  EXPECT_NEAR(hinge_s, 7.5e-5, 0.3e-5);  // the fastest mode: 1966 Hz, zeta 0.85
  // modal damping: zeta in every mode, 2 (sqrt(1 + zeta^2) - zeta) / omega_max
  const RigSpec modal = build_rig(s, ContactLaw::hertz, 8, ChainDamping::modal);
  double omega_max = 0;
  for (const FrameRig& frame : modal.frames)
    omega_max = std::max(omega_max, chain_modes(frame.chain).omega_rad_s.maxCoeff());
  const double zeta = s.frames[0].damping_ratio;
  ASSERT_EQ(zeta, s.frames[1].damping_ratio);
  EXPECT_NEAR(explicit_hinge_step_limit_s(modal), 2 * (std::sqrt(1 + zeta * zeta) - zeta) / omega_max, 1e-15);
  // without damping the limit is 2 / omega_max, which the damping only lowers
  for (FrameSpec& frame : s.frames) frame.damping_ratio = 0;
  const RigSpec undamped = build_rig(s, ContactLaw::hertz, 8);
  EXPECT_NEAR(explicit_hinge_step_limit_s(undamped), 2 / omega_max, 1e-15);
  EXPECT_LT(hinge_s, explicit_hinge_step_limit_s(modal));
  EXPECT_LT(explicit_hinge_step_limit_s(modal), 2 / omega_max);
}

// Frame 1's linearised chain stepped as the engines step it, the damping torques -C theta' held over a step
// from the rates at its start: with explicit springs (semi-implicit Euler) the motion decays just below
// explicit_hinge_step_limit_s and grows just above it; with implicit springs (backward Euler) it decays
// at 100 times that step. The energy 1/2 w^T M w + 1/2 q^T K q after 400 steps from the static tip-load shape
// with every mode in it, against its start. About 10 ms.
double energy_ratio_after_steps(const FrameRig& frame, double step_s, bool implicit_springs) {
  const ChainMatrices m = linearise(frame.chain);
  Eigen::VectorXd q = static_tip_load_angles(frame.chain, 1.0), w = Eigen::VectorXd::Zero(q.size());
  auto energy = [&] { return 0.5 * w.dot(m.mass * w) + 0.5 * q.dot(m.stiffness * q); };
  const double start = energy();
  const Eigen::LDLT<Eigen::MatrixXd> lhs(implicit_springs ? Eigen::MatrixXd(m.mass + step_s * step_s * m.stiffness)
                                                          : m.mass);
  for (int n = 0; n < 400; ++n) {
    const Eigen::VectorXd held_damping = -m.damping * w;
    // (M + h^2 K) w' = M w + h (-C w - K q) with the spring at the step's end (q' = q + h w'); M w' = ... without
    w = lhs.solve(m.mass * w + step_s * (held_damping - m.stiffness * q));
    q += step_s * w;
  }
  return energy() / start;
}

TEST(Rig, ModalDampingHeldOverAStepIsStableBelowTheStatedLimit) {
  const Scenario s = testing::paper_scenario("resonance");
  for (ChainDamping damping : {ChainDamping::modal, ChainDamping::hinge}) {
    const RigSpec rig = build_rig(s, ContactLaw::hertz, 8, damping);
    const double limit_s = explicit_hinge_step_limit_s(rig);
    EXPECT_LT(energy_ratio_after_steps(rig.frames[0], 0.98 * limit_s, false), 1.0) << to_string(damping);
    EXPECT_GT(energy_ratio_after_steps(rig.frames[0], 1.02 * limit_s, false), 1e3) << to_string(damping);
    EXPECT_LT(energy_ratio_after_steps(rig.frames[0], 100 * limit_s, true), 1.0) << to_string(damping);
  }
}

TEST(Rig, OnlyWhatTheScenarioNeeds) {
  const Scenario s = testing::paper_scenario("free_vibration");
  const RigSpec rig = build_rig(s, ContactLaw::newton, 4);
  EXPECT_FALSE(rig.motor.has_value());
  EXPECT_TRUE(std::holds_alternative<NewtonLaw>(rig.law));
  // frame 1 starts in its static tip-load shape with the tip 2 mm back; frame 2 straight
  const ChainMatrices m = linearise(rig.frames[0].chain);
  EXPECT_NEAR(m.tip_lever.dot(rig.frames[0].initial_angles_rad), -2e-3, 1e-15);
  EXPECT_EQ(rig.frames[1].initial_angles_rad.norm(), 0.0);
}

// A static tip load P deflecting the tip by u stores the energy P u / 2; tip effective masses are
// close to the beam's tip mass plus a fraction of the beam.
TEST(Rig, EnergyAndEffectiveMassesAreThoseOfTheChain) {
  const Scenario s = testing::paper_scenario("free_vibration");
  const RigSpec rig = build_rig(s, ContactLaw::viscoelastic, 16);
  const RigEnergy energy(rig);
  const ChainMatrices m = linearise(rig.frames[0].chain);
  const double u = m.tip_lever.dot(rig.frames[0].initial_angles_rad);
  const double force = u / m.tip_lever.dot(m.stiffness.ldlt().solve(m.tip_lever));  // u / (lever^T K^-1 lever)
  const std::array<Eigen::VectorXd, 2> angles = {rig.frames[0].initial_angles_rad, rig.frames[1].initial_angles_rad};
  const std::array<Eigen::VectorXd, 2> rates = {Eigen::VectorXd::Zero(16), Eigen::VectorXd::Zero(16)};
  EXPECT_NEAR(energy(angles, rates, -1e-3) / (0.5 * force * u), 1.0, 1e-12);
  // the viscoelastic spring's energy joins when the tips overlap
  EXPECT_NEAR(energy(angles, rates, 1e-6) - energy(angles, rates, -1e-3), 0.5 * 6.99e6 * 1e-12, 1e-15);
  // the kinetic energy 1/2 w^T M w of any hinge rates, M full (every link moves with the hinges below it)
  const std::array<Eigen::VectorXd, 2> moving = {Eigen::VectorXd::LinSpaced(16, -0.3, 0.5),
                                                 Eigen::VectorXd::LinSpaced(16, 0.2, -0.1)};
  const std::array<Eigen::VectorXd, 2> straight = {Eigen::VectorXd::Zero(16), Eigen::VectorXd::Zero(16)};
  double kinetic = 0;
  for (int f = 0; f < 2; ++f) kinetic += 0.5 * moving[f].dot(linearise(rig.frames[f].chain).mass * moving[f]);
  EXPECT_NEAR(energy(straight, moving, -1e-3) / kinetic, 1.0, 1e-14);
  for (int f = 0; f < 2; ++f) {
    EXPECT_GT(rig.frames[f].tip_effective_mass_kg, s.frames[f].tip_mass_kg);
    EXPECT_LT(rig.frames[f].tip_effective_mass_kg, s.frames[f].tip_mass_kg + s.frames[f].beam_mass_kg());
  }
}

}  // namespace rig_test
}  // namespace ib
