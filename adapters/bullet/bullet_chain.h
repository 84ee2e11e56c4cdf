// A frame's link chain (rig.md section 4) in Bullet, built the two ways Bullet users build
// articulations:
//  - multibody: one btMultiBody (Featherstone's reduced coordinates) with K revolute joints. Bullet's
//    btMultiBody has no joint springs (its joint damping field is unused), so the hinge springs and
//    dampers are joint torques added before every step: -k theta - c theta' from the state at the start
//    of the step (explicit).
//  - constraints: K btRigidBody joined by btGeneric6DofSpring2Constraint with only the rotation about y
//    free and a spring (k) and damper (c) on it, limitIfNeeded = false: otherwise Bullet silently caps
//    the stiffness at m / (16 h^2) and the damping at m / h. The constraint solver's iterations hold the
//    locked axes (joints are not exact) and apply the spring as an explicit impulse.
// Both: bodies with the masses, centres of mass and inertias of RigBody, no velocity damping, never
// deactivated (a sleeping body would freeze the chain), and a sphere at the tip point as the only
// colliding geometry.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "adapters/common/rig.h"

class btCollisionObject;
class btDiscreteDynamicsWorld;
class btMultiBodyDynamicsWorld;

namespace ib::bullet {

enum class Articulation { multibody, constraints };
const char* to_string(Articulation articulation);

// Collision filter groups: the two tip spheres collide with each other and nothing else.
constexpr int kTipCollisionGroup = 1 << 6;
constexpr int kLinkCollisionGroup = 1 << 7;

class BulletChain {
 public:
  virtual ~BulletChain() = default;
  // The hinge spring and damper torques of the coming step (multibody); nothing for the constraint
  // chain, whose springs live in its constraints.
  virtual void add_joint_spring_torques() = 0;
  // Torques [N m] about the hinges for the coming step, in hinge order from the clamp: +torque on the link
  // above a hinge, -torque on the one below (the loop's modal damping torques, StepLoads).
  virtual void add_joint_torques(const Eigen::VectorXd& torques_n_m) = 0;
  // A force along +x [N] at the tip point for the coming step.
  virtual void add_tip_force_x(double force_n) = 0;
  virtual double tip_x_m() const = 0;
  virtual double tip_velocity_x_m_s() const = 0;
  // Both at once (what the stepping loops read every step): one pass through the chain where the
  // articulation allows it.
  struct TipMotion {
    double x_m = 0, velocity_x_m_s = 0;
  };
  virtual TipMotion tip_motion() const { return {tip_x_m(), tip_velocity_x_m_s()}; }
  // Relative hinge angles [rad] and their rates [rad/s], in hinge order from the clamp.
  virtual void joint_state(Eigen::VectorXd& angles_rad, Eigen::VectorXd& rates_rad_s) const = 0;
  // The chain's own state, to continue a run from (FixedStepEngine::save_state): the multibody's hinge
  // angles then rates [rad, rad/s]; the constraint chain's bodies, each its centre of mass [m], orientation
  // quaternion (x, y, z, w), linear [m/s] and angular [rad/s] velocity. set_state takes state_size() values.
  virtual std::vector<double> state() const = 0;
  virtual void set_state(const double* values) = 0;
  virtual std::size_t state_size() const = 0;
  // The tip sphere's collision object; nullptr when the chain was built without tip contact.
  virtual btCollisionObject* tip_collider() = 0;
};

// Builds the frame in the world at the frame's initial angles, at rest. With tip_contact false the tip
// sphere is left out of collision detection (injected contact).
std::unique_ptr<BulletChain> make_multibody_chain(btMultiBodyDynamicsWorld& world, const FrameRig& frame,
                                                  double sphere_radius_m, bool tip_contact);
std::unique_ptr<BulletChain> make_constraint_chain(btDiscreteDynamicsWorld& world, const FrameRig& frame,
                                                   double sphere_radius_m, bool tip_contact);

}  // namespace ib::bullet
