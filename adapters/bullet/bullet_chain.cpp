#include "adapters/bullet/bullet_chain.h"

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <vector>

static_assert(sizeof(btScalar) == 8, "impactbench needs Bullet's double-precision build (pkg-config bullet-float64)");

namespace ib::bullet {

const char* to_string(Articulation articulation) {
  return articulation == Articulation::multibody ? "multibody" : "constraints";
}

namespace {

const btVector3 kHingeAxis(0, 1, 0);  // beams bend in the x-z plane

// A joint velocity limit far above anything the rig reaches: Bullet's default (100 rad/s) would clamp
// a diverging run and hide its instability.
constexpr double kMaxJointRate_rad_s = 1e9;

// The tip sphere, carried by the last body whose frame sits at its centre of mass: a compound shape
// places the sphere at the tip point.
struct TipShape {
  TipShape(const FrameRig& frame, double radius) : sphere(radius) {
    btTransform at_tip = btTransform::getIdentity();
    at_tip.setOrigin(btVector3(0, 0, frame.tip_z_m - frame.bodies.back().com_z_m));
    compound.addChildShape(at_tip, &sphere);
  }
  btSphereShape sphere;
  btCompoundShape compound{false};
};

btVector3 principal_inertia(const RigBody& body) {
  return btVector3(body.inertia_xz_kg_m2, body.inertia_y_kg_m2, body.inertia_xz_kg_m2);
}

// ---- btMultiBody ------------------------------------------------------------------------------------

class MultiBodyChain final : public BulletChain {
 public:
  MultiBodyChain(btMultiBodyDynamicsWorld& world, const FrameRig& frame, double radius, bool tip_contact)
      : world_(world), frame_(frame), tip_shape_(frame, radius) {
    const int links = static_cast<int>(frame.bodies.size());
    // A fixed base at the clamp: the ground piece [0, l/2] has no dynamics.
    body_ = std::make_unique<btMultiBody>(links, 0.0, btVector3(0, 0, 0), true, false);
    body_->setBasePos(btVector3(frame.base_x_m, 0, 0));
    body_->setWorldToBaseRot(btQuaternion::getIdentity());
    for (int j = 0; j < links; ++j) {
      const RigBody& b = frame.bodies[j];
      const double parent_com_z = j == 0 ? 0.0 : frame.bodies[j - 1].com_z_m;
      body_->setupRevolute(j, b.mass_kg, principal_inertia(b), j - 1, btQuaternion::getIdentity(), kHingeAxis,
                           btVector3(0, 0, b.joint_z_m - parent_com_z), btVector3(0, 0, b.com_z_m - b.joint_z_m), true);
    }
    body_->finalizeMultiDof();
    // Bullet's default velocity damping (0.04, linear and quadratic) is not part of the rig.
    body_->setLinearDamping(0);
    body_->setAngularDamping(0);
    body_->setMaxCoordinateVelocity(kMaxJointRate_rad_s);
    body_->setHasSelfCollision(false);
    body_->setCanSleep(false);
    for (int j = 0; j < links; ++j) {
      body_->setJointPos(j, frame.initial_angles_rad[j]);
      body_->setJointVel(j, 0);
    }
    world_.addMultiBody(body_.get());
    if (tip_contact) {
      collider_ = std::make_unique<btMultiBodyLinkCollider>(body_.get(), links - 1);
      collider_->setCollisionShape(&tip_shape_.compound);
      collider_->setActivationState(DISABLE_DEACTIVATION);
      body_->getLink(links - 1).m_collider = collider_.get();
      world_.addCollisionObject(collider_.get(), kTipCollisionGroup, kTipCollisionGroup);
    }
    // Place the links (and the collider) at the initial angles before the first collision detection.
    btAlignedObjectArray<btQuaternion> world_to_local;
    btAlignedObjectArray<btVector3> local_origin;
    body_->forwardKinematics(world_to_local, local_origin);
    body_->updateCollisionObjectWorldTransforms(world_to_local, local_origin);
    const RigBody& last = frame.bodies.back();
    tip_in_last_ = btVector3(0, 0, frame.tip_z_m - last.com_z_m);
    for (const RigBody& b : frame.bodies) hinge_in_link_.emplace_back(0, 0, b.joint_z_m - b.com_z_m);
  }

  ~MultiBodyChain() override {
    if (collider_) {
      world_.removeCollisionObject(collider_.get());
      body_->getLink(body_->getNumLinks() - 1).m_collider = nullptr;
    }
    world_.removeMultiBody(body_.get());
  }

  void add_joint_spring_torques() override {
    const std::vector<double>& k = frame_.chain.joint_stiffness_n_m_per_rad;
    const std::vector<double>& c = frame_.chain.joint_damping_n_m_s_per_rad;
    for (int j = 0; j < body_->getNumLinks(); ++j)
      body_->addJointTorque(j, -k[j] * body_->getJointPos(j) - c[j] * body_->getJointVel(j));
  }

  void add_joint_torques(const Eigen::VectorXd& torques_n_m) override {
    for (int j = 0; j < body_->getNumLinks(); ++j) body_->addJointTorque(j, torques_n_m[j]);
  }

  void add_tip_force_x(double force_n) override {
    const int last = body_->getNumLinks() - 1;
    const btVector3 force(force_n, 0, 0);
    const btVector3 lever = body_->localDirToWorld(last, tip_in_last_);  // from the link's centre of mass
    body_->addLinkForce(last, force);
    body_->addLinkTorque(last, lever.cross(force));
  }

  double tip_x_m() const override { return body_->localPosToWorld(body_->getNumLinks() - 1, tip_in_last_).x(); }

  double tip_velocity_x_m_s() const override { return tip_motion().velocity_x_m_s; }

  // The tip moves with every hinge rate about its hinge: v = sum_j theta'_j y x (p - h_j), whose
  // x component is sum_j theta'_j (p_z - h_jz) (exact for the planar chain). The hinge points come from
  // one pass from the base out (each link's frame from its parent's, as localPosToWorld composes them),
  // not from localPosToWorld per hinge, which walks back to the base every time: O(K) instead of O(K^2)
  // per step; the tip point falls out of the same pass.
  // Every rotation in the chain is about y (identity base and zero rotations, hinges about kHingeAxis),
  // a quaternion (0, s, 0, c) of the half angle: composing two is a product of complex numbers, and
  // turning a vector in the x-z plane takes cos = c^2 - s^2 and sin = 2 s c. This runs every step, so
  // it is a few products per link instead of Bullet's general quaternion algebra.
  TipMotion tip_motion() const override {
    const int links = body_->getNumLinks();
    double s = 0, c = 1;  // link frame -> world, about y (the base: identity)
    double x = body_->getBasePos().x(), z = body_->getBasePos().z();  // link frame origin in the world
    double cos_turn = 1, sin_turn = 0;
    double sum_rate = 0, sum_rate_hinge_z = 0;  // sum theta'_j, sum theta'_j h_jz
    for (int j = 0; j < links; ++j) {           // a serial chain: link j's parent is link j - 1 (the base for j = 0)
      // to_world * parent_to_local^-1, with parent_to_local = (0, ps, 0, pc)
      const btQuaternion& parent_to_local = body_->getParentToLocalRot(j);
      const double ps = parent_to_local.y(), pc = parent_to_local.w();
      const double s_next = s * pc - c * ps, c_next = c * pc + s * ps;
      s = s_next;
      c = c_next;
      cos_turn = c * c - s * s;
      sin_turn = 2 * s * c;
      const btVector3& r = body_->getRVector(j);  // parent's origin -> this origin, in this frame
      x += cos_turn * r.x() + sin_turn * r.z();
      z += cos_turn * r.z() - sin_turn * r.x();
      const double rate = body_->getJointVel(j);
      sum_rate += rate;
      sum_rate_hinge_z += rate * (z + cos_turn * hinge_in_link_[j].z() - sin_turn * hinge_in_link_[j].x());
    }
    const double tip_x = x + cos_turn * tip_in_last_.x() + sin_turn * tip_in_last_.z();
    const double tip_z = z + cos_turn * tip_in_last_.z() - sin_turn * tip_in_last_.x();
    return {tip_x, sum_rate * tip_z - sum_rate_hinge_z};
  }

  void joint_state(Eigen::VectorXd& angles, Eigen::VectorXd& rates) const override {
    const int links = body_->getNumLinks();
    angles.resize(links);
    rates.resize(links);
    for (int j = 0; j < links; ++j) {
      angles[j] = body_->getJointPos(j);
      rates[j] = body_->getJointVel(j);
    }
  }

  std::vector<double> state() const override {
    std::vector<double> values;
    for (int j = 0; j < body_->getNumLinks(); ++j) values.push_back(body_->getJointPos(j));
    for (int j = 0; j < body_->getNumLinks(); ++j) values.push_back(body_->getJointVel(j));
    return values;
  }
  void set_state(const double* values) override {
    const int links = body_->getNumLinks();
    for (int j = 0; j < links; ++j) {
      body_->setJointPos(j, values[j]);
      body_->setJointVel(j, values[links + j]);
    }
    // the links and the collider where the angles put them, before the next collision detection
    btAlignedObjectArray<btQuaternion> world_to_local;
    btAlignedObjectArray<btVector3> local_origin;
    body_->forwardKinematics(world_to_local, local_origin);
    body_->updateCollisionObjectWorldTransforms(world_to_local, local_origin);
  }
  std::size_t state_size() const override { return static_cast<std::size_t>(2 * body_->getNumLinks()); }

  btCollisionObject* tip_collider() override { return collider_.get(); }

 private:
  btMultiBodyDynamicsWorld& world_;
  const FrameRig& frame_;
  TipShape tip_shape_;
  std::unique_ptr<btMultiBody> body_;
  std::unique_ptr<btMultiBodyLinkCollider> collider_;
  btVector3 tip_in_last_;
  std::vector<btVector3> hinge_in_link_;
};

// ---- btRigidBody + btGeneric6DofSpring2Constraint ---------------------------------------------------

// The rotation about y of a body that turns in the x-z plane: R = [[c 0 s] [0 1 0] [-s 0 c]].
double pitch(const btRigidBody& body) {
  const btMatrix3x3& r = body.getCenterOfMassTransform().getBasis();
  return std::atan2(r[0][2], r[2][2]);
}

class ConstraintChain final : public BulletChain {
 public:
  ConstraintChain(btDiscreteDynamicsWorld& world, const FrameRig& frame, double radius, bool tip_contact)
      : world_(world), frame_(frame), tip_shape_(frame, radius), link_shape_(radius), tip_contact_(tip_contact) {
    const int links = static_cast<int>(frame.bodies.size());
    // Built straight, where every constraint frame is aligned (zero hinge angle), then posed.
    for (int j = 0; j < links; ++j) {
      const RigBody& b = frame.bodies[j];
      const bool tip = j + 1 == links;
      btRigidBody::btRigidBodyConstructionInfo info(
          b.mass_kg, nullptr, tip ? static_cast<btCollisionShape*>(&tip_shape_.compound) : &link_shape_,
          principal_inertia(b));
      info.m_startWorldTransform.setOrigin(btVector3(frame.base_x_m, 0, b.com_z_m));
      info.m_friction = 0.5;  // Bullet's default; the contact paths set their own on the tip
      auto body = std::make_unique<btRigidBody>(info);
      body->setActivationState(DISABLE_DEACTIVATION);
      body->setDamping(0, 0);
      body->setSleepingThresholds(0, 0);
      // Only the tip spheres collide, and only with each other.
      const bool collides = tip && tip_contact;
      world_.addRigidBody(body.get(), collides ? kTipCollisionGroup : kLinkCollisionGroup,
                          collides ? kTipCollisionGroup : 0);
      bodies_.push_back(std::move(body));
    }
    for (int j = 0; j < links; ++j) {
      const RigBody& b = frame.bodies[j];
      btTransform in_this = btTransform::getIdentity();
      in_this.setOrigin(btVector3(0, 0, b.joint_z_m - b.com_z_m));
      std::unique_ptr<btGeneric6DofSpring2Constraint> joint;
      if (j == 0) {
        joint = std::make_unique<btGeneric6DofSpring2Constraint>(*bodies_[0], in_this);  // to the fixed world
      } else {
        btTransform in_parent = btTransform::getIdentity();
        in_parent.setOrigin(btVector3(0, 0, b.joint_z_m - frame.bodies[j - 1].com_z_m));
        joint = std::make_unique<btGeneric6DofSpring2Constraint>(*bodies_[j - 1], *bodies_[j], in_parent, in_this);
      }
      joint->setLinearLowerLimit(btVector3(0, 0, 0));
      joint->setLinearUpperLimit(btVector3(0, 0, 0));
      // rotation about y free (lower > upper), about x and z locked
      joint->setAngularLowerLimit(btVector3(0, 1, 0));
      joint->setAngularUpperLimit(btVector3(0, -1, 0));
      const int about_y = 4;  // 0-2 linear, 3-5 angular
      joint->enableSpring(about_y, true);
      joint->setStiffness(about_y, frame.chain.joint_stiffness_n_m_per_rad[j], false);
      joint->setDamping(about_y, frame.chain.joint_damping_n_m_s_per_rad[j], false);
      joint->setEquilibriumPoint(about_y, 0);
      world_.addConstraint(joint.get(), true);
      joints_.push_back(std::move(joint));
    }
    pose(frame.initial_angles_rad);
  }

  ~ConstraintChain() override {
    for (auto& joint : joints_) world_.removeConstraint(joint.get());
    for (auto& body : bodies_) world_.removeRigidBody(body.get());
  }

  void add_joint_spring_torques() override {}

  void add_joint_torques(const Eigen::VectorXd& torques_n_m) override {
    for (std::size_t j = 0; j < bodies_.size(); ++j) {
      const btVector3 torque(0, torques_n_m[static_cast<Eigen::Index>(j)], 0);  // about the hinge axis y
      bodies_[j]->applyTorque(torque);
      if (j > 0) bodies_[j - 1]->applyTorque(-torque);
    }
  }

  void add_tip_force_x(double force_n) override {
    btRigidBody& tip = *bodies_.back();
    tip.applyForce(btVector3(force_n, 0, 0), tip_point() - tip.getCenterOfMassPosition());
  }

  double tip_x_m() const override { return tip_point().x(); }

  double tip_velocity_x_m_s() const override {
    const btRigidBody& tip = *bodies_.back();
    return tip.getVelocityInLocalPoint(tip_point() - tip.getCenterOfMassPosition()).x();
  }

  void joint_state(Eigen::VectorXd& angles, Eigen::VectorXd& rates) const override {
    const int links = static_cast<int>(bodies_.size());
    angles.resize(links);
    rates.resize(links);
    double parent_angle = 0, parent_rate = 0;
    for (int j = 0; j < links; ++j) {
      const double angle = pitch(*bodies_[j]), rate = bodies_[j]->getAngularVelocity().y();
      angles[j] = angle - parent_angle;
      rates[j] = rate - parent_rate;
      parent_angle = angle;
      parent_rate = rate;
    }
  }

  std::vector<double> state() const override {
    std::vector<double> values;
    for (const auto& body : bodies_) {
      const btTransform& pose = body->getCenterOfMassTransform();
      const btVector3 p = pose.getOrigin(), v = body->getLinearVelocity(), w = body->getAngularVelocity();
      const btQuaternion q = pose.getRotation();
      values.insert(values.end(),
                    {p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w(), v.x(), v.y(), v.z(), w.x(), w.y(), w.z()});
    }
    return values;
  }
  void set_state(const double* values) override {
    for (const auto& body : bodies_) {
      const double* x = values;
      const btTransform pose(btQuaternion(x[3], x[4], x[5], x[6]), btVector3(x[0], x[1], x[2]));
      body->setCenterOfMassTransform(pose);
      body->setInterpolationWorldTransform(pose);
      body->setLinearVelocity(btVector3(x[7], x[8], x[9]));
      body->setAngularVelocity(btVector3(x[10], x[11], x[12]));
      values += 13;
    }
  }
  std::size_t state_size() const override { return 13 * bodies_.size(); }

  btCollisionObject* tip_collider() override { return tip_contact_ ? bodies_.back().get() : nullptr; }

 private:
  btVector3 tip_point() const {
    const btRigidBody& tip = *bodies_.back();
    return tip.getCenterOfMassTransform() * btVector3(0, 0, frame_.tip_z_m - frame_.bodies.back().com_z_m);
  }

  // Places every body at the relative hinge angles, at rest.
  void pose(const Eigen::VectorXd& angles) {
    btVector3 hinge(frame_.base_x_m, 0, frame_.bodies[0].joint_z_m);
    double absolute = 0;
    for (std::size_t j = 0; j < bodies_.size(); ++j) {
      const RigBody& b = frame_.bodies[j];
      absolute += angles[static_cast<Eigen::Index>(j)];
      const btQuaternion turn(kHingeAxis, absolute);
      const btMatrix3x3 basis(turn);
      btTransform pose(turn, hinge + basis * btVector3(0, 0, b.com_z_m - b.joint_z_m));
      bodies_[j]->setCenterOfMassTransform(pose);
      bodies_[j]->setLinearVelocity(btVector3(0, 0, 0));
      bodies_[j]->setAngularVelocity(btVector3(0, 0, 0));
      hinge += basis * btVector3(0, 0, b.length_m);
    }
  }

  btDiscreteDynamicsWorld& world_;
  const FrameRig& frame_;
  TipShape tip_shape_;
  btSphereShape link_shape_;  // never collides (filter mask 0); Bullet needs a shape for the broadphase
  bool tip_contact_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
  std::vector<std::unique_ptr<btGeneric6DofSpring2Constraint>> joints_;
};

}  // namespace

std::unique_ptr<BulletChain> make_multibody_chain(btMultiBodyDynamicsWorld& world, const FrameRig& frame,
                                                  double sphere_radius_m, bool tip_contact) {
  return std::make_unique<MultiBodyChain>(world, frame, sphere_radius_m, tip_contact);
}

std::unique_ptr<BulletChain> make_constraint_chain(btDiscreteDynamicsWorld& world, const FrameRig& frame,
                                                   double sphere_radius_m, bool tip_contact) {
  return std::make_unique<ConstraintChain>(world, frame, sphere_radius_m, tip_contact);
}

}  // namespace ib::bullet
