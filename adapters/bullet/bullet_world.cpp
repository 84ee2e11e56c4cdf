#include "adapters/bullet/bullet_world.h"

#include <variant>

#include "adapters/bullet/bullet_contact.h"

namespace ib::bullet {

BulletRig::BulletRig(const RigSpec& rig, Articulation articulation, bool bullet_contact) {
  // Both worlds are Bullet's own defaults for their kind of articulation.
  if (articulation == Articulation::multibody) {
    auto solver = std::make_unique<btMultiBodyConstraintSolver>();
    auto world = std::make_unique<btMultiBodyDynamicsWorld>(&dispatcher_, &broadphase_, solver.get(), &configuration_);
    for (int f = 0; f < 2; ++f)
      chains_[f] = make_multibody_chain(*world, rig.frames[f], rig.sphere_radius_m, bullet_contact);
    solver_ = std::move(solver);
    world_ = std::move(world);
  } else {
    auto solver = std::make_unique<btSequentialImpulseConstraintSolver>();
    auto world = std::make_unique<btDiscreteDynamicsWorld>(&dispatcher_, &broadphase_, solver.get(), &configuration_);
    for (int f = 0; f < 2; ++f)
      chains_[f] = make_constraint_chain(*world, rig.frames[f], rig.sphere_radius_m, bullet_contact);
    solver_ = std::move(solver);
    world_ = std::move(world);
  }
  world_->setGravity(btVector3(0, 0, 0));  // rig.md section 1: gravity is left out
}

BulletRig::~BulletRig() {
  for (auto& chain : chains_) chain.reset();  // out of the world before it goes
}

std::pair<double, int> BulletRig::tip_contact_impulse() {
  double impulse = 0;
  int points = 0;
  const btCollisionObject* a = tip(0);
  const btCollisionObject* b = tip(1);
  for (int m = 0; m < dispatcher_.getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = dispatcher_.getManifoldByIndexInternal(m);
    const bool between_tips = (manifold->getBody0() == a && manifold->getBody1() == b) ||
                              (manifold->getBody0() == b && manifold->getBody1() == a);
    if (!between_tips) continue;
    for (int p = 0; p < manifold->getNumContacts(); ++p) {
      const double applied = manifold->getContactPoint(p).getAppliedImpulse();
      if (applied > 0) {
        impulse += applied;
        ++points;
      }
    }
  }
  return {impulse, points};
}

void configure_tip_contact(BulletRig& bullet, const RigSpec& rig, ContactPath path, double h,
                           std::vector<std::pair<std::string, double>>& d) {
  btCollisionObject& tip1 = *bullet.tip(0);
  btCollisionObject& tip2 = *bullet.tip(1);
  btContactSolverInfo& info = bullet.solver_info();
  if (path == ContactPath::matched) {
    if (const auto* law = std::get_if<ViscoelasticLaw>(&rig.law)) {
      set_spring_dashpot(tip1, tip2, law->stiffness_n_per_m, law->damping_n_s_per_m);
      configure_spring_dashpot_solver(info);
      const double k = combined_contact_stiffness(tip1, tip2), c = combined_contact_damping(tip1, tip2);
      d.emplace_back("contact_stiffness_n_per_m", k);
      d.emplace_back("contact_damping_n_s_per_m", c);
      d.emplace_back("contact_erp", h * k / (h * k + c));
      d.emplace_back("contact_cfm_m_per_n_s", 1 / (h * k + c));
      // Bullet's impulse is never tensile: the published, unclipped law is realised clipped.
      d.emplace_back("contact_tension_clipped", 1);
    } else if (const auto* law = std::get_if<NewtonLaw>(&rig.law)) {
      set_restitution(tip1, tip2, law->restitution);
      set_restitution_processing_threshold(tip1, tip2);
      configure_restitution_solver(info);
    }
  }
  d.emplace_back("contact_restitution", combined_restitution(tip1, tip2));
  d.emplace_back("contact_friction", tip1.getFriction() * tip2.getFriction());
}

}  // namespace ib::bullet
