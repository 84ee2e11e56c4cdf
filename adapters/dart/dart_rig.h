// The rig of rig.md section 4 as DART 6.12 skeletons (adapters/common/rig.h gives the physics; this file
// only translates it): per frame one Skeleton, a chain of RevoluteJoint bodies about y whose joint springs
// and dampers DART integrates implicitly, the tip mass merged into the last body, a tip sphere only when
// DART makes the contact. DART models are unit-free: `length_scale` (1 for metres, 100 for centimetres,
// 1000 for millimetres) multiplies every length handed to DART, so that the hard-coded velocity constants
// of its contact solver (a bounce threshold of 0.1 and a bounce cap of 100 model units per second) sit
// elsewhere in m/s; masses stay kilograms and time seconds, so forces scale like lengths and moments of
// inertia, hinge stiffness and damping like its square. The angles, and so the dynamics, are unchanged.
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <optional>
#include <vector>

#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/simulation/World.hpp>

#include "adapters/common/rig.h"

namespace ib::dart_adapter {

// How DART detects the tips' contact.
enum class Collision {
  none,         // no tip shapes: the contact force comes from the harness (injected) or nowhere
  analytic,     // DARTCollisionDetector: exact sphere-sphere
  fcl_default,  // DART's default detector (FCL), spheres approximated by meshes (dart#59)
};

struct DartRigSettings {
  double time_step_s = 1e-4;
  double length_scale = 1;  // model units per metre
  Collision collision = Collision::none;
  std::optional<double> restitution_per_shape;  // set on both tip shapes (a pair uses the product); DART's default 0
  std::optional<double> friction;               // both tip shapes; DART's default 1
  bool pgs_solver = false;                      // the boxed LCP solver: Dantzig (DART's default) or PGS
};

class DartRig {
 public:
  DartRig(const RigSpec& rig, const DartRigSettings& settings);

  // Tip f's displacement along x from rest [m] and velocity [m/s].
  double tip_displacement_m(int f) const;
  double tip_velocity_m_s(int f) const;
  // Relative hinge angles [rad] and rates [rad/s] of frame f, from the clamp.
  const Eigen::VectorXd& hinge_angles_rad(int f) const;
  const Eigen::VectorXd& hinge_rates_rad_s(int f) const;
  // Adds a force along x [N] at tip f for the coming step (DART clears it after each step).
  void add_tip_force(int f, double force_x_n);
  // Sets the torques [N m] about frame f's hinges for the coming step, from the clamp (DART's joint forces,
  // cleared after each step): the loop's modal damping torques (StepLoads).
  void set_hinge_torques(int f, const Eigen::VectorXd& torques_n_m);
  void step();                 // one step of the world's own step, time_step_s()
  double time_step_s() const;  // the world's step (World::getTimeStep) [s]
  // The force between the tips during the last step [N], > 0 compressive, from DART's contact constraints
  // (impulse / step); 0 without contact or without collision.
  double tip_contact_force_n() const;
  // How many contact points DART's last collision check found.
  std::size_t contact_points() const;

  const DartRigSettings& settings() const { return settings_; }

  // Both skeletons' joint positions then velocities [rad, rad/s], frame 1 first: the state a run continues
  // from (FixedStepEngine::save_state). set_joint_state takes joint_state_size() values.
  std::vector<double> joint_state() const;
  void set_joint_state(const std::vector<double>& values);
  std::size_t joint_state_size() const;

 private:
  struct Frame {
    dart::dynamics::SkeletonPtr skeleton;
    dart::dynamics::BodyNode* tip_body = nullptr;
    Eigen::Vector3d tip_offset;  // the tip point in the last body's frame [model units]
    double base_x = 0;           // the clamp along x [model units]
    double rest_tip_x = 0;       // the tip's x at rest (straight) [model units]
    mutable Eigen::VectorXd angles, rates;
  };
  void build_frame(const FrameRig& spec, double sphere_radius_m, int f);

  DartRigSettings settings_;
  dart::simulation::WorldPtr world_;
  std::array<Frame, 2> frames_;
};

}  // namespace ib::dart_adapter
