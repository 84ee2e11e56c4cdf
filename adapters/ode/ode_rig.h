// The rig of rig.md section 4 as an ODE world: per frame a chain of K rigid bodies joined by hinges
// along y, with rotational springs, the tip mass merged into the last body (RigSpec), and a tip sphere
// for ODE's own contact when the run uses it. No gravity. Owns every ODE object it makes.
//
// Geometry (adapters/common/rig.h): beams along +z from z = 0, bending in x-z; frame 1's clamp at
// x = 0, frame 2's at x = frame_spacing_m. A body's ODE frame has its origin at the centre of mass and,
// in the straight pose, the world's axes. A positive relative hinge angle bends the beam toward +x.
#pragma once

#include <ode/ode.h>

#include <Eigen/Core>
#include <array>
#include <vector>

#include "adapters/common/rig.h"
#include "adapters/ode/soft_constraint.h"

namespace ib::ode {

// How the hinge springs k_theta, c_theta are made.
enum class SpringPath {
  implicit_stops,    // both hinge stops at the rest angle, softened by soft_constraint(k, c, h): backward Euler, stable
  explicit_torques,  // dJointAddHingeTorque(-(k theta + c theta')) each step: ODE's semi-implicit Euler, needs h <
                     // 2/omega_max
};

enum class Stepper {
  world,  // dWorldStep: the direct (Dantzig LCP) solver
  quick,  // dWorldQuickStep: projected Gauss-Seidel with a fixed iteration count
};

struct OdeModelSettings {
  double time_step_s = 1e-4;
  SpringPath springs = SpringPath::implicit_stops;
  Stepper stepper = Stepper::world;
  int quick_step_iterations = 20;  // ODE's own default
  bool tip_spheres = true;         // make the tip spheres (only when ODE's own contact is used)
};

// A frame's tip along x.
struct TipState {
  double displacement_m = 0;  // x of the tip point minus the frame's clamp x
  double velocity_m_s = 0;
};

class OdeRig {
 public:
  OdeRig(const RigSpec& rig, const OdeModelSettings& settings);
  ~OdeRig();
  OdeRig(const OdeRig&) = delete;
  OdeRig& operator=(const OdeRig&) = delete;

  TipState tip(int frame) const;
  // Relative hinge angles [rad] and their rates [rad/s], clamp first (what RigEnergy takes). The
  // vectors must have K entries.
  void hinge_state(int frame, Eigen::VectorXd& angles, Eigen::VectorXd& rates) const;

  // Forces and torques for the coming step (ODE clears them after each step).
  void add_tip_force(int frame, double force_x_n);
  void add_explicit_spring_torques();  // explicit_torques only
  // Torques [N m] about each frame's hinges, K per frame from the clamp: +torque on the body above a
  // hinge, -torque on the one below (the loop's modal damping torques, StepLoads).
  void add_hinge_torques(const std::array<Eigen::VectorXd, 2>& torques_n_m);

  // ODE's own contact for the coming step: collides the tip spheres and, when they overlap, makes one
  // contact joint with this surface and a feedback record. Returns whether a contact joint was made.
  bool make_tip_contact(const dSurfaceParameters& surface);
  // The compressive force the contact joint applied during the last step, along its normal [N]
  // (dJointFeedback; 0 when the step had no contact joint).
  double tip_contact_force() const;

  void step();                                                  // one step of time_step_s()
  double time_step_s() const { return settings_.time_step_s; }  // the step dWorldStep is given [s]

  // ODE's state in maximal coordinates: every body's position, quaternion (w, x, y, z), linear and angular
  // velocity, 13 values a body, frame 1's bodies first (a sweep's continuation, FixedStepEngine::save_state).
  static constexpr int kValuesPerBody = 13;
  int body_count() const { return static_cast<int>(frames_[0].bodies.size() + frames_[1].bodies.size()); }
  std::vector<double> body_states() const;
  void set_body_states(const std::vector<double>& values);  // body_count() x kValuesPerBody values

  // the root hinge's (every hinge has the same ERP; its CFM scales as 1 / k_j); implicit_stops only
  double hinge_stop_erp(int frame) const { return root_stop_softness(frame).erp; }
  double hinge_stop_cfm(int frame) const { return root_stop_softness(frame).cfm; }
  double world_erp() const { return dWorldGetERP(world_); }  // the hinges' own (hard) rows
  double world_cfm() const { return dWorldGetCFM(world_); }

 private:
  struct Frame {
    std::vector<dBodyID> bodies;   // clamp first
    std::vector<dJointID> hinges;  // hinge j joins body j (ODE body 1) to body j-1 or the ground (body 2)
    dGeomID sphere = nullptr;
    double base_x_m = 0;
    double tip_offset_z_m = 0;               // tip point above the last body's centre of mass, in its frame
    std::vector<double> stiffness, damping;  // hinge j's spring [N m/rad] and damper [N m s/rad]
  };
  void build_frame(const FrameRig& spec, double sphere_radius_m, Frame& frame);
  void soften_hinge_stops(int frame);
  SoftConstraint root_stop_softness(int frame) const;
  static void pose_frame(const FrameRig& spec, const Eigen::VectorXd& angles, const Frame& frame);
  double pitch(dBodyID body) const;  // rotation about y [rad]

  OdeModelSettings settings_;
  dWorldID world_ = nullptr;
  dJointGroupID contact_group_ = nullptr;
  std::array<Frame, 2> frames_;
  bool has_contact_ = false;
  dJointFeedback contact_feedback_{};
  dVector3 contact_normal_{};
};

}  // namespace ib::ode
