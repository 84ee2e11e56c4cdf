// The Bullet world of one run (the collision pipeline, the solver and the two chains) and the tip
// contact each path and law sets in it. Shared by the simulator and by bench/harness_overhead_benchmark,
// whose bare stepping loop must step exactly the world a run steps.
#pragma once

#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "adapters/bullet/bullet_chain.h"
#include "adapters/common/rig.h"
#include "model/simulator_options.h"

namespace ib::bullet {

class BulletRig {
 public:
  // Both worlds are Bullet's own defaults for their kind of articulation; no gravity (rig.md section 1).
  // With bullet_contact false the tip spheres do not collide (the harness injects the contact force).
  BulletRig(const RigSpec& rig, Articulation articulation, bool bullet_contact);
  ~BulletRig();
  BulletRig(const BulletRig&) = delete;
  BulletRig& operator=(const BulletRig&) = delete;

  btContactSolverInfo& solver_info() { return world_->getSolverInfo(); }
  BulletChain& chain(int frame) { return *chains_[frame]; }
  btCollisionObject* tip(int frame) { return chains_[frame]->tip_collider(); }

  // One step of exactly h: maxSubSteps = 0 makes Bullet take the given step as it is (the default
  // substeps at a fixed 1/60 s and interpolates the state in between).
  void step(double h) { world_->stepSimulation(h, 0); }

  // The impulse the solver applied between the tips in the last step [N s] and the number of contact
  // points that carried it: a point counts when its impulse is positive, not when the spheres are
  // merely within the contact margin.
  std::pair<double, int> tip_contact_impulse();

 private:
  // Declared in construction order; destroyed in reverse, the chains first.
  btDefaultCollisionConfiguration configuration_;
  btCollisionDispatcher dispatcher_{&configuration_};
  btDbvtBroadphase broadphase_;
  std::unique_ptr<btConstraintSolver> solver_;
  std::unique_ptr<btDiscreteDynamicsWorld> world_;
  std::array<std::unique_ptr<BulletChain>, 2> chains_;
};

// Sets Bullet's tip contact for the path and law (matched spring-dashpot: contact stiffness and damping;
// matched Newton: restitution and the solver settings that make it real; native: Bullet's defaults), and
// names what was set in the diagnostics d. For runs whose tips collide in Bullet (not injected).
void configure_tip_contact(BulletRig& bullet, const RigSpec& rig, ContactPath path, double h,
                           std::vector<std::pair<std::string, double>>& d);

}  // namespace ib::bullet
