// The tip state the Bullet adapter reads every step (BulletChain::tip_motion), against the planar
// chain's kinematics worked out here from the rig's geometry and the hinge angles and rates Bullet
// reports: the tip point p = clamp + sum of the links turned by their absolute angles, and its x
// velocity sum_j theta'_j (p_z - h_jz) about each hinge h_j. Also against Bullet's own general
// localPosToWorld (tip_x_m). After a hard push, so that the angles are far from small. The multibody
// chain only: its reduced coordinates make the joints exact, whereas the constraint chain's joints
// drift (by about 1e-6 m at the tip after this push) and its tip is read from the tip body itself.
#include <gtest/gtest.h>

#include <cmath>

#include "adapters/bullet/bullet_world.h"
#include "adapters/common/rig.h"
#include "reference_fixtures.h"

namespace ib::bullet {
namespace bullet_tip_kinematics_test {

struct PlanarTip {
  double x_m = 0, velocity_x_m_s = 0;
};

// Bodies hang from hinges at joint_z_m along the undeformed beam; a positive hinge angle turns the
// rest of the chain toward +x (right-handed about y).
PlanarTip planar_tip(const FrameRig& frame, const Eigen::VectorXd& angles, const Eigen::VectorXd& rates) {
  const std::size_t links = frame.bodies.size();
  std::vector<double> hinge_z(links);
  double x = frame.base_x_m, z = frame.bodies[0].joint_z_m, absolute = 0;
  for (std::size_t j = 0; j < links; ++j) {
    hinge_z[j] = z;
    absolute += angles[static_cast<Eigen::Index>(j)];
    const double to_next = (j + 1 < links ? frame.bodies[j + 1].joint_z_m : frame.tip_z_m) - frame.bodies[j].joint_z_m;
    x += std::sin(absolute) * to_next;
    z += std::cos(absolute) * to_next;
  }
  double velocity = 0;
  for (std::size_t j = 0; j < links; ++j) velocity += rates[static_cast<Eigen::Index>(j)] * (z - hinge_z[j]);
  return {x, velocity};
}

TEST(BulletTipKinematics, TipMotionIsThePlanarChainsKinematics) {
  const RigSpec rig = build_rig(testing::paper_scenario("resonance"), ContactLaw::hertz, 8);
  BulletRig bullet(rig, Articulation::multibody, false);
  const double h = 5e-5;
  double largest_angle = 0;
  for (int n = 0; n < 400; ++n) {
    for (int f = 0; f < 2; ++f) bullet.chain(f).add_joint_spring_torques();
    bullet.chain(0).add_tip_force_x(n < 200 ? 2000.0 : 0.0);  // a push, then free motion
    bullet.chain(1).add_tip_force_x(n < 200 ? -1500.0 : 0.0);
    bullet.step(h);
    if (n % 40 != 39) continue;
    for (int f = 0; f < 2; ++f) {
      SCOPED_TRACE("frame " + std::to_string(f + 1) + ", step " + std::to_string(n + 1));
      Eigen::VectorXd angles, rates;
      bullet.chain(f).joint_state(angles, rates);
      largest_angle = std::max(largest_angle, angles.cwiseAbs().maxCoeff());
      const PlanarTip expected = planar_tip(rig.frames[f], angles, rates);
      const BulletChain::TipMotion tip = bullet.chain(f).tip_motion();
      const double length = rig.frames[f].tip_z_m;
      EXPECT_NEAR(tip.x_m, expected.x_m, 1e-12 * length);
      EXPECT_NEAR(tip.x_m, bullet.chain(f).tip_x_m(), 1e-12 * length);
      EXPECT_NEAR(tip.velocity_x_m_s, expected.velocity_x_m_s,
                  1e-12 * std::max(1.0, std::abs(expected.velocity_x_m_s)));
    }
  }
  // the check means something only with angles far from small (sin x = x to 1e-12 below 2e-6 rad)
  EXPECT_GT(largest_angle, 1e-2);
}

}  // namespace bullet_tip_kinematics_test
}  // namespace ib::bullet
