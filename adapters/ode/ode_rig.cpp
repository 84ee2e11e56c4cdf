#include "adapters/ode/ode_rig.h"

#include <cmath>
#include <stdexcept>

namespace ib::ode {

OdeRig::OdeRig(const RigSpec& rig, const OdeModelSettings& settings) : settings_(settings) {
  world_ = dWorldCreate();
  dWorldSetGravity(world_, 0, 0, 0);  // rig.md section 1: gravity is left out
  // The hinges' own rows stay hard: ODE's defaults (ERP 0.2, CFM 1e-10 in double) only correct drift.
  // ODE's contact defaults, stated so that no other code can have changed them: no surface layer and no
  // cap on the correcting velocity (a cap would clip the spring-dashpot's ERP term, engines.md).
  dWorldSetContactSurfaceLayer(world_, 0);
  dWorldSetContactMaxCorrectingVel(world_, dInfinity);
  dWorldSetQuickStepNumIterations(world_, settings.quick_step_iterations);
  contact_group_ = dJointGroupCreate(0);
  for (int f = 0; f < 2; ++f) {
    build_frame(rig.frames[f], rig.sphere_radius_m, frames_[f]);
    if (settings.springs == SpringPath::implicit_stops) soften_hinge_stops(f);
    pose_frame(rig.frames[f], rig.frames[f].initial_angles_rad, frames_[f]);
  }
}

// Both stops at the rest angle: ODE then keeps the stop row active at every angle and makes it
// two-sided (lo == hi), so with soft_constraint's ERP and CFM it is a spring-dashpot about the straight
// shape, integrated by backward Euler.
void OdeRig::soften_hinge_stops(int f) {
  const Frame& frame = frames_[f];
  for (std::size_t j = 0; j < frame.hinges.size(); ++j) {
    const SoftConstraint soft = soft_constraint(frame.stiffness[j], frame.damping[j], settings_.time_step_s);
    dJointSetHingeParam(frame.hinges[j], dParamLoStop, 0);
    dJointSetHingeParam(frame.hinges[j], dParamHiStop, 0);
    dJointSetHingeParam(frame.hinges[j], dParamStopERP, soft.erp);
    dJointSetHingeParam(frame.hinges[j], dParamStopCFM, soft.cfm);
  }
}

SoftConstraint OdeRig::root_stop_softness(int f) const {
  return soft_constraint(frames_[f].stiffness.at(0), frames_[f].damping.at(0), settings_.time_step_s);
}

OdeRig::~OdeRig() {
  for (Frame& frame : frames_)
    if (frame.sphere) dGeomDestroy(frame.sphere);
  if (contact_group_) dJointGroupDestroy(contact_group_);
  if (world_) dWorldDestroy(world_);  // and its bodies and joints
}

void OdeRig::build_frame(const FrameRig& spec, double sphere_radius_m, Frame& frame) {
  frame.base_x_m = spec.base_x_m;
  frame.stiffness = spec.chain.joint_stiffness_n_m_per_rad;
  frame.damping = spec.chain.joint_damping_n_m_s_per_rad;
  // Bodies in the straight pose first: a hinge takes the bodies' relative orientation when its axis is
  // set as its zero angle, so the straight shape is the springs' rest angle.
  dBodyID parent = nullptr;
  for (const RigBody& b : spec.bodies) {
    dBodyID body = dBodyCreate(world_);
    dMass mass;
    dMassSetParameters(&mass, b.mass_kg, 0, 0, 0, b.inertia_xz_kg_m2, b.inertia_y_kg_m2, b.inertia_xz_kg_m2, 0, 0, 0);
    dBodySetMass(body, &mass);
    dBodySetPosition(body, spec.base_x_m, 0, b.com_z_m);
    dJointID hinge = dJointCreateHinge(world_, nullptr);
    dJointAttach(hinge, body, parent);  // parent nullptr: the ground
    dJointSetHingeAnchor(hinge, spec.base_x_m, 0, b.joint_z_m);
    dJointSetHingeAxis(hinge, 0, 1, 0);
    frame.bodies.push_back(body);
    frame.hinges.push_back(hinge);
    parent = body;
  }
  const RigBody& last = spec.bodies.back();
  frame.tip_offset_z_m = spec.tip_z_m - last.com_z_m;
  if (settings_.tip_spheres) {
    frame.sphere = dCreateSphere(nullptr, sphere_radius_m);  // in no space: collided pairwise with dCollide
    dGeomSetBody(frame.sphere, frame.bodies.back());
    dGeomSetOffsetPosition(frame.sphere, 0, 0, frame.tip_offset_z_m);
  }
}

// Places the bodies of a frame in the shape of the given relative hinge angles, at rest: hinge j turns
// everything above it by angles[j] about y (toward +x for a positive angle).
void OdeRig::pose_frame(const FrameRig& spec, const Eigen::VectorXd& angles, const Frame& frame) {
  double absolute = 0;  // pitch of the current body [rad]
  double hinge_x = spec.base_x_m, hinge_z = spec.bodies.front().joint_z_m;
  for (std::size_t j = 0; j < frame.bodies.size(); ++j) {
    const RigBody& b = spec.bodies[j];
    absolute += angles[static_cast<Eigen::Index>(j)];
    const double s = std::sin(absolute), c = std::cos(absolute);
    const double com_offset = b.com_z_m - b.joint_z_m;  // along the body's axis
    dMatrix3 rotation;
    dRFromAxisAndAngle(rotation, 0, 1, 0, absolute);
    dBodySetRotation(frame.bodies[j], rotation);
    dBodySetPosition(frame.bodies[j], hinge_x + com_offset * s, 0, hinge_z + com_offset * c);
    dBodySetLinearVel(frame.bodies[j], 0, 0, 0);
    dBodySetAngularVel(frame.bodies[j], 0, 0, 0);
    hinge_x += b.length_m * s;
    hinge_z += b.length_m * c;
  }
}

double OdeRig::pitch(dBodyID body) const {
  const dReal* r = dBodyGetRotation(body);  // row-major 3x4; R_y(phi) has R02 = sin phi, R22 = cos phi
  return std::atan2(r[2], r[10]);
}

TipState OdeRig::tip(int f) const {
  const Frame& frame = frames_[f];
  dVector3 position, velocity;
  dBodyGetRelPointPos(frame.bodies.back(), 0, 0, frame.tip_offset_z_m, position);
  dBodyGetRelPointVel(frame.bodies.back(), 0, 0, frame.tip_offset_z_m, velocity);
  return {position[0] - frame.base_x_m, velocity[0]};
}

void OdeRig::hinge_state(int f, Eigen::VectorXd& angles, Eigen::VectorXd& rates) const {
  const Frame& frame = frames_[f];
  double previous_pitch = 0, previous_rate = 0;
  for (std::size_t j = 0; j < frame.bodies.size(); ++j) {
    const double body_pitch = pitch(frame.bodies[j]);
    const double body_rate = dBodyGetAngularVel(frame.bodies[j])[1];
    angles[static_cast<Eigen::Index>(j)] = std::remainder(body_pitch - previous_pitch, 2 * M_PI);
    rates[static_cast<Eigen::Index>(j)] = body_rate - previous_rate;
    previous_pitch = body_pitch;
    previous_rate = body_rate;
  }
}

void OdeRig::add_tip_force(int f, double force_x_n) {
  const Frame& frame = frames_[f];
  dVector3 point;
  dBodyGetRelPointPos(frame.bodies.back(), 0, 0, frame.tip_offset_z_m, point);
  dBodyAddForceAtPos(frame.bodies.back(), force_x_n, 0, 0, point[0], point[1], point[2]);
}

void OdeRig::add_explicit_spring_torques() {
  for (const Frame& frame : frames_) {
    double previous_pitch = 0, previous_rate = 0;
    for (std::size_t j = 0; j < frame.bodies.size(); ++j) {
      const double body_pitch = pitch(frame.bodies[j]);
      const double body_rate = dBodyGetAngularVel(frame.bodies[j])[1];
      const double angle = std::remainder(body_pitch - previous_pitch, 2 * M_PI), rate = body_rate - previous_rate;
      // +torque about the hinge axis (+y) on body j, -torque on its parent
      dJointAddHingeTorque(frame.hinges[j], -(frame.stiffness[j] * angle + frame.damping[j] * rate));
      previous_pitch = body_pitch;
      previous_rate = body_rate;
    }
  }
}

void OdeRig::add_hinge_torques(const std::array<Eigen::VectorXd, 2>& torques_n_m) {
  for (int f = 0; f < 2; ++f)
    for (std::size_t j = 0; j < frames_[f].hinges.size(); ++j)
      dJointAddHingeTorque(frames_[f].hinges[j], torques_n_m[f][static_cast<Eigen::Index>(j)]);
}

bool OdeRig::make_tip_contact(const dSurfaceParameters& surface) {
  dJointGroupEmpty(contact_group_);
  has_contact_ = false;
  dContact contact{};
  contact.surface = surface;
  if (dCollide(frames_[0].sphere, frames_[1].sphere, 1, &contact.geom, sizeof(dContact)) == 0) return false;
  dJointID joint = dJointCreateContact(world_, contact_group_, &contact);
  dJointAttach(joint, dGeomGetBody(contact.geom.g1), dGeomGetBody(contact.geom.g2));
  contact_feedback_ = dJointFeedback{};
  dJointSetFeedback(joint, &contact_feedback_);
  for (int i = 0; i < 3; ++i) contact_normal_[i] = contact.geom.normal[i];
  has_contact_ = true;
  return true;
}

double OdeRig::tip_contact_force() const {
  if (!has_contact_) return 0;
  // The normal points into body 1, so the row's force on body 1 is lambda * normal with lambda >= 0.
  return contact_feedback_.f1[0] * contact_normal_[0] + contact_feedback_.f1[1] * contact_normal_[1] +
         contact_feedback_.f1[2] * contact_normal_[2];
}

void OdeRig::step() {
  if (settings_.stepper == Stepper::quick)
    dWorldQuickStep(world_, settings_.time_step_s);
  else
    dWorldStep(world_, settings_.time_step_s);
}

std::vector<double> OdeRig::body_states() const {
  std::vector<double> values;
  values.reserve(static_cast<std::size_t>(body_count() * kValuesPerBody));
  for (const Frame& frame : frames_)
    for (dBodyID body : frame.bodies) {
      const dReal* p = dBodyGetPosition(body);
      const dReal* q = dBodyGetQuaternion(body);
      const dReal* v = dBodyGetLinearVel(body);
      const dReal* w = dBodyGetAngularVel(body);
      values.insert(values.end(), {p[0], p[1], p[2], q[0], q[1], q[2], q[3], v[0], v[1], v[2], w[0], w[1], w[2]});
    }
  return values;
}

void OdeRig::set_body_states(const std::vector<double>& values) {
  std::size_t i = 0;
  for (const Frame& frame : frames_)
    for (dBodyID body : frame.bodies) {
      const double* x = values.data() + i;
      dBodySetPosition(body, x[0], x[1], x[2]);
      const dQuaternion q = {x[3], x[4], x[5], x[6]};
      dBodySetQuaternion(body, q);
      dBodySetLinearVel(body, x[7], x[8], x[9]);
      dBodySetAngularVel(body, x[10], x[11], x[12]);
      i += kValuesPerBody;
    }
}

}  // namespace ib::ode
