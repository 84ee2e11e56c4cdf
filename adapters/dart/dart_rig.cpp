#include "adapters/dart/dart_rig.h"

#include <cmath>

#include <dart/collision/dart/DARTCollisionDetector.hpp>
#include <dart/constraint/BoxedLcpConstraintSolver.hpp>
#include <dart/constraint/PgsBoxedLcpSolver.hpp>
#include <dart/dynamics/RevoluteJoint.hpp>
#include <dart/dynamics/ShapeNode.hpp>
#include <dart/dynamics/SphereShape.hpp>

namespace ib::dart_adapter {

using dart::dynamics::BodyNode;
using dart::dynamics::RevoluteJoint;

DartRig::DartRig(const RigSpec& rig, const DartRigSettings& settings) : settings_(settings) {
  world_ = dart::simulation::World::create("impactbench");
  world_->setGravity(Eigen::Vector3d::Zero());  // rig.md section 1: gravity is left out
  world_->setTimeStep(settings.time_step_s);
  if (settings.pgs_solver) {
    auto* solver = dynamic_cast<dart::constraint::BoxedLcpConstraintSolver*>(world_->getConstraintSolver());
    if (solver) solver->setBoxedLcpSolver(std::make_shared<dart::constraint::PgsBoxedLcpSolver>());
  }
  if (settings.collision == Collision::analytic)
    world_->getConstraintSolver()->setCollisionDetector(dart::collision::DARTCollisionDetector::create());
  for (int f = 0; f < 2; ++f) {
    build_frame(rig.frames[f], rig.sphere_radius_m, f);
    world_->addSkeleton(frames_[f].skeleton);
  }
}

// Body j's frame sits at its hinge, the joint rotates about y (a positive angle turns the body above it
// toward +x), and the hinge's spring about the straight shape and its damper are DART's own joint
// properties, which its integrator treats implicitly.
void DartRig::build_frame(const FrameRig& spec, double sphere_radius_m, int f) {
  const double s = settings_.length_scale, s2 = s * s;
  Frame& frame = frames_[f];
  frame.skeleton = dart::dynamics::Skeleton::create("frame" + std::to_string(f + 1));
  frame.base_x = spec.base_x_m * s;
  frame.rest_tip_x = frame.base_x;
  BodyNode* parent = nullptr;
  double parent_joint_z_m = 0;
  int j = 0;
  for (const RigBody& b : spec.bodies) {
    // unique names, or DART renames them and says so for every body
    const std::string link = "frame" + std::to_string(f + 1) + "_link" + std::to_string(++j);
    RevoluteJoint::Properties joint;
    joint.mName = link + "_hinge";
    joint.mAxis = Eigen::Vector3d::UnitY();
    joint.mT_ParentBodyToJoint = Eigen::Isometry3d::Identity();
    joint.mT_ParentBodyToJoint.translation() = parent ? Eigen::Vector3d(0, 0, (b.joint_z_m - parent_joint_z_m) * s)
                                                      : Eigen::Vector3d(frame.base_x, 0, b.joint_z_m * s);
    joint.mRestPositions[0] = 0;
    joint.mSpringStiffnesses[0] = spec.chain.joint_stiffness_n_m_per_rad[j - 1] * s2;
    joint.mDampingCoefficients[0] = spec.chain.joint_damping_n_m_s_per_rad[j - 1] * s2;
    BodyNode::Properties body;
    body.mName = link;
    body.mInertia.setMass(b.mass_kg);
    body.mInertia.setMoment(b.inertia_xz_kg_m2 * s2, b.inertia_y_kg_m2 * s2, b.inertia_xz_kg_m2 * s2, 0, 0, 0);
    body.mInertia.setLocalCOM(Eigen::Vector3d(0, 0, (b.com_z_m - b.joint_z_m) * s));
    parent = frame.skeleton->createJointAndBodyNodePair<RevoluteJoint>(parent, joint, body).second;
    parent_joint_z_m = b.joint_z_m;
  }
  frame.tip_body = parent;
  frame.tip_offset = Eigen::Vector3d(0, 0, (spec.tip_z_m - spec.bodies.back().joint_z_m) * s);
  if (settings_.collision != Collision::none) {
    auto sphere = std::make_shared<dart::dynamics::SphereShape>(sphere_radius_m * s);
    auto* node =
        frame.tip_body->createShapeNodeWith<dart::dynamics::CollisionAspect, dart::dynamics::DynamicsAspect>(sphere);
    node->setRelativeTranslation(frame.tip_offset);
    auto* dynamics = node->getDynamicsAspect();
    if (settings_.restitution_per_shape) dynamics->setRestitutionCoeff(*settings_.restitution_per_shape);
    if (settings_.friction) dynamics->setFrictionCoeff(*settings_.friction);
  }
  frame.skeleton->setPositions(spec.initial_angles_rad);
  frame.skeleton->setVelocities(Eigen::VectorXd::Zero(spec.chain.links));
  frame.angles = Eigen::VectorXd::Zero(spec.chain.links);
  frame.rates = Eigen::VectorXd::Zero(spec.chain.links);
}

double DartRig::tip_displacement_m(int f) const {
  const Frame& frame = frames_[f];
  return ((frame.tip_body->getWorldTransform() * frame.tip_offset).x() - frame.rest_tip_x) / settings_.length_scale;
}

double DartRig::tip_velocity_m_s(int f) const {
  const Frame& frame = frames_[f];
  return frame.tip_body->getLinearVelocity(frame.tip_offset).x() / settings_.length_scale;
}

const Eigen::VectorXd& DartRig::hinge_angles_rad(int f) const {
  frames_[f].angles = frames_[f].skeleton->getPositions();
  return frames_[f].angles;
}

const Eigen::VectorXd& DartRig::hinge_rates_rad_s(int f) const {
  frames_[f].rates = frames_[f].skeleton->getVelocities();
  return frames_[f].rates;
}

void DartRig::add_tip_force(int f, double force_x_n) {
  const Frame& frame = frames_[f];
  // the force in world coordinates (not local), at the tip point given in the body's frame (local)
  frame.tip_body->addExtForce(Eigen::Vector3d(force_x_n * settings_.length_scale, 0, 0), frame.tip_offset,
                              /*isForceLocal=*/false, /*isOffsetLocal=*/true);
}

void DartRig::set_hinge_torques(int f, const Eigen::VectorXd& torques_n_m) {
  // a torque is a force times a length: model units scale it by length_scale^2, as the hinge stiffness
  frames_[f].skeleton->setForces(torques_n_m * (settings_.length_scale * settings_.length_scale));
}

double DartRig::time_step_s() const { return world_->getTimeStep(); }

void DartRig::step() { world_->step(); }

double DartRig::tip_contact_force_n() const {
  if (settings_.collision == Collision::none) return 0;
  // Each contact constraint stores its impulse over the step as a force on its first body, along the
  // normal; the tips touch along x, so the compressive magnitude is |F_x|.
  double force = 0;
  for (const auto& contact : world_->getLastCollisionResult().getContacts()) force += std::abs(contact.force.x());
  return force / settings_.length_scale;
}

std::size_t DartRig::contact_points() const { return world_->getLastCollisionResult().getNumContacts(); }

std::vector<double> DartRig::joint_state() const {
  std::vector<double> values;
  for (const Frame& frame : frames_) {
    const Eigen::VectorXd q = frame.skeleton->getPositions(), v = frame.skeleton->getVelocities();
    values.insert(values.end(), q.data(), q.data() + q.size());
    values.insert(values.end(), v.data(), v.data() + v.size());
  }
  return values;
}

void DartRig::set_joint_state(const std::vector<double>& values) {
  std::size_t i = 0;
  for (Frame& frame : frames_) {
    const auto dofs = static_cast<Eigen::Index>(frame.skeleton->getNumDofs());
    frame.skeleton->setPositions(Eigen::Map<const Eigen::VectorXd>(values.data() + i, dofs));
    frame.skeleton->setVelocities(Eigen::Map<const Eigen::VectorXd>(values.data() + i + dofs, dofs));
    i += 2 * static_cast<std::size_t>(dofs);
  }
}

std::size_t DartRig::joint_state_size() const {
  return 2 * (frames_[0].skeleton->getNumDofs() + frames_[1].skeleton->getNumDofs());
}

}  // namespace ib::dart_adapter
