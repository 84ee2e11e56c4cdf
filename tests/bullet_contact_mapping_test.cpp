// The mapping of the contact laws to Bullet's knobs (adapters/bullet/bullet_contact.h), checked on
// Bullet itself with one contact between two free spheres, where the contact is a one-degree-of-
// freedom problem with the reduced mass:
//  - the per-tip stiffness and damping combine to the law's k (to Bullet's last rounding) and c
//    (exactly), in Bullet's own formula and in the contact points its solver uses;
//  - the spring-dashpot Bullet then integrates is the implicit (backward-Euler) one, step for step;
//  - Newton's restitution is realised exactly with the solver settings of the mapping, and not with
//    Bullet's defaults;
//  - what the adapter relies on to read the contact force: the applied impulse is written back to the
//    contact points only with warm starting on.
#include <btBulletDynamicsCommon.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "adapters/bullet/bullet_contact.h"

namespace ib::bullet {
namespace bullet_contact_mapping_test {

constexpr double kRadius = 5e-3;                // the rig's tip spheres [m]
constexpr double kM1 = 0.65628, kM2 = 0.42569;  // the K = 8 chains' tip effective masses [kg]
const double kReducedMass = kM1 * kM2 / (kM1 + kM2);
constexpr double kK = 6.99e6, kC = 170.07;  // the paper's spring-dashpot
constexpr double kApproach = 0.1644;        // the measured mean approach velocity [m/s]

// Two free spheres on the x axis, sphere 1 moving toward sphere 2 across a small gap.
class TwoSpheres {
 public:
  explicit TwoSpheres(double gap_m) {
    world_.setGravity(btVector3(0, 0, 0));
    a_ = add(kM1, 0.0);
    b_ = add(kM2, 2 * kRadius + gap_m);
    a_->setLinearVelocity(btVector3(kApproach, 0, 0));
  }
  ~TwoSpheres() {
    world_.removeRigidBody(a_.get());
    world_.removeRigidBody(b_.get());
  }
  btRigidBody& a() { return *a_; }
  btRigidBody& b() { return *b_; }
  btContactSolverInfo& solver_info() { return world_.getSolverInfo(); }
  void step(double h) { world_.stepSimulation(h, 0); }
  double indentation() const {
    return a_->getCenterOfMassPosition().x() + 2 * kRadius - b_->getCenterOfMassPosition().x();
  }
  double indentation_rate() const { return a_->getLinearVelocity().x() - b_->getLinearVelocity().x(); }
  // The contact points between the spheres after the last step.
  std::vector<const btManifoldPoint*> points() {
    std::vector<const btManifoldPoint*> out;
    for (int m = 0; m < dispatcher_.getNumManifolds(); ++m) {
      const btPersistentManifold* manifold = dispatcher_.getManifoldByIndexInternal(m);
      for (int p = 0; p < manifold->getNumContacts(); ++p) out.push_back(&manifold->getContactPoint(p));
    }
    return out;
  }
  double applied_impulse() {
    double sum = 0;
    for (const btManifoldPoint* p : points()) sum += p->getAppliedImpulse();
    return sum;
  }

 private:
  std::unique_ptr<btRigidBody> add(double mass, double x) {
    btVector3 inertia;
    shape_.calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, &shape_, inertia);
    info.m_startWorldTransform.setOrigin(btVector3(x, 0, 0.3));
    auto body = std::make_unique<btRigidBody>(info);
    body->setActivationState(DISABLE_DEACTIVATION);
    world_.addRigidBody(body.get());
    return body;
  }

  btDefaultCollisionConfiguration configuration_;
  btCollisionDispatcher dispatcher_{&configuration_};
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  btDiscreteDynamicsWorld world_{&dispatcher_, &broadphase_, &solver_, &configuration_};
  btSphereShape shape_{kRadius};
  std::unique_ptr<btRigidBody> a_, b_;
};

double ulp(double x) { return std::nextafter(x, INFINITY) - x; }

// How close to k any result of Bullet's 1 / y can come, y ranging over the doubles near 1/k.
double nearest_reachable_miss(double k) {
  double y = 1 / k, miss = INFINITY;
  for (int i = 0; i < 8; ++i) y = std::nextafter(y, 0.0);
  for (int i = 0; i < 16; ++i, y = std::nextafter(y, INFINITY)) miss = std::min(miss, std::abs(1 / y - k));
  return miss;
}

TEST(BulletContactMapping, PerTipValuesCombineToTheLaw) {
  for (double k : {6.99e6, 1e3, 2.31e10, 3.3e5, 7.77e7, 1.2345678e9})
    for (double c : {170.07, 0.0, 0.1, 1e-3, 4.2e4}) {
      const auto tips = spring_dashpot_per_tip(k, c);
      btCollisionObject a, b;
      a.setContactStiffnessAndDamping(tips[0].stiffness_n_per_m, tips[0].damping_n_s_per_m);
      b.setContactStiffnessAndDamping(tips[1].stiffness_n_per_m, tips[1].damping_n_s_per_m);
      // the stiffness to Bullet's last rounding: within one ulp of k, and no farther than any
      // value Bullet's final division 1 / (1/k_1 + 1/k_2) can produce near k
      const double combined = combined_contact_stiffness(a, b);
      EXPECT_LE(std::abs(combined - k), ulp(k)) << "k = " << k << ", c = " << c;
      EXPECT_LE(std::abs(combined - k), nearest_reachable_miss(k)) << "k = " << k << ", c = " << c;
      EXPECT_EQ(combined_contact_stiffness(b, a), combined) << "k = " << k << ", c = " << c;
      EXPECT_EQ(combined_contact_damping(a, b), c) << "k = " << k << ", c = " << c;
    }
  // what the mapping avoids: the law on one tip only adds Bullet's default damping of the other
  btCollisionObject a, b;
  a.setContactStiffnessAndDamping(kK, kC);
  EXPECT_EQ(combined_contact_damping(a, b), kC + 0.1);
  EXPECT_THROW(spring_dashpot_per_tip(0, 1), std::invalid_argument);
  EXPECT_THROW(spring_dashpot_per_tip(1, -1), std::invalid_argument);
}

TEST(BulletContactMapping, TheSolverSeesTheLaw) {
  TwoSpheres spheres(1e-6);
  set_spring_dashpot(spheres.a(), spheres.b(), kK, kC);
  configure_spring_dashpot_solver(spheres.solver_info());
  for (int n = 0; n < 10 && spheres.points().empty(); ++n) spheres.step(1e-5);
  const auto points = spheres.points();
  ASSERT_EQ(points.size(), 1u);
  EXPECT_TRUE(points[0]->m_contactPointFlags & BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING);
  EXPECT_LE(std::abs(points[0]->m_combinedContactStiffness1 - kK), ulp(kK));
  EXPECT_EQ(points[0]->m_combinedContactDamping1, kC);
  EXPECT_EQ(points[0]->m_combinedFriction, 0.0);
  EXPECT_EQ(points[0]->m_combinedRestitution, 0.0);
}

// The indentation delta = x1 + 2r - x2 and its rate, one step at a time.
struct Indentation {
  double delta = 0, rate = 0;
};

// Implicit (backward Euler): the force of the step is the law at the end of the step,
// F = k delta_{n+1} + c delta'_{n+1} with delta_{n+1} = delta_n + h delta'_{n+1}, clipped at zero.
Indentation implicit_step(Indentation s, double h) {
  double rate = s.rate;
  if (s.delta > 0) {
    rate = (kReducedMass * s.rate - h * kK * s.delta) / (kReducedMass + h * h * kK + h * kC);
    if (kK * (s.delta + h * rate) + kC * rate < 0) rate = s.rate;  // no tension: no force this step
  }
  return {s.delta + h * rate, rate};
}

// Explicit (symplectic Euler): the force of the step is the law at its start, clipped at zero.
Indentation explicit_step(Indentation s, double h) {
  const double force = s.delta > 0 ? std::max(0.0, kK * s.delta + kC * s.rate) : 0.0;
  const double rate = s.rate - h * force / kReducedMass;
  return {s.delta + h * rate, rate};
}

struct Rebound {
  double restitution = 0;
  int contact_steps = 0;
  double largest_deviation_m = 0;  // from Bullet's indentation, over the contact
};

// Steps the recurrence from Bullet's initial state alongside Bullet until the spheres part.
template <class Step>
Rebound follow(Step&& step, double h, const std::vector<Indentation>& bullet) {
  Rebound r;
  Indentation s = bullet.front();
  for (std::size_t n = 1; n < bullet.size(); ++n) {
    const Indentation before = s;
    s = step(s, h);
    r.largest_deviation_m = std::max(r.largest_deviation_m, std::abs(s.delta - bullet[n].delta));
    r.contact_steps += s.rate != before.rate;
  }
  r.restitution = -s.rate / kApproach;
  return r;
}

TEST(BulletContactMapping, TheSpringDashpotIsTheImplicitOneStepForStep) {
  // h = 1e-5 s: omega h = 0.05 for omega = sqrt(k / m) = 5200 rad/s, 60 steps per contact; the
  // implicit and explicit schemes then differ by about 8 % in restitution, so the test can tell.
  const double h = 1e-5;
  TwoSpheres spheres(0.3e-6);
  set_spring_dashpot(spheres.a(), spheres.b(), kK, kC);
  configure_spring_dashpot_solver(spheres.solver_info());
  std::vector<Indentation> bullet = {{spheres.indentation(), spheres.indentation_rate()}};
  int contact_steps = 0;
  for (int n = 0; n < 200; ++n) {
    spheres.step(h);
    bullet.push_back({spheres.indentation(), spheres.indentation_rate()});
    contact_steps += spheres.applied_impulse() > 0;
  }
  const double peak = 4e-5;  // about v sqrt(m / k)
  const Rebound implicit = follow(implicit_step, h, bullet);
  const Rebound explicit_ = follow(explicit_step, h, bullet);
  // Bullet is the implicit scheme to rounding: 1e-9 of the peak indentation at every step
  EXPECT_LT(implicit.largest_deviation_m, 1e-9 * peak);
  EXPECT_EQ(implicit.contact_steps, contact_steps);
  EXPECT_NEAR(-bullet.back().rate / kApproach, implicit.restitution, 1e-9);
  // and not the explicit one
  EXPECT_GT(explicit_.largest_deviation_m, 1e-2 * peak);
  EXPECT_GT(explicit_.restitution - implicit.restitution, 0.05);
  // The implicit scheme loses energy: below the exact clipped law's restitution (closed form of the
  // continuous contact: the unclipped e = exp(-zeta pi / sqrt(1 - zeta^2)) is a lower bound of it)
  const double e_unclipped = spring_dashpot_restitution(kK, kC, kReducedMass);
  std::printf(
      "[ measured ] h = %g s: Bullet e = %.6f, implicit %.6f, explicit %.6f, continuous unclipped %.6f; %d contact "
      "steps; largest deviation from the implicit scheme %.2g m, from the explicit %.2g m\n",
      h, -bullet.back().rate / kApproach, implicit.restitution, explicit_.restitution, e_unclipped, contact_steps,
      implicit.largest_deviation_m, explicit_.largest_deviation_m);
  EXPECT_LT(implicit.restitution, e_unclipped);
}

TEST(BulletContactMapping, NewtonRestitutionIsExactWithTheMappingsSolverSettings) {
  for (double h : {1e-6, 1e-4}) {
    for (double e : {0.8, 0.5, 0.3}) {
      TwoSpheres spheres(0.5 * kApproach * h);  // touching half-way through the first step
      set_restitution(spheres.a(), spheres.b(), e);
      set_restitution_processing_threshold(spheres.a(), spheres.b());
      configure_restitution_solver(spheres.solver_info());
      EXPECT_EQ(combined_restitution(spheres.a(), spheres.b()), e);
      double impulse = 0;
      for (int n = 0; n < 10; ++n) {
        spheres.step(h);
        impulse += spheres.applied_impulse();
      }
      EXPECT_NEAR(-spheres.indentation_rate() / kApproach, e, 1e-12) << "h = " << h << ", e = " << e;
      // the impulse read from the contact points: (1 + e) m v
      EXPECT_NEAR(impulse / ((1 + e) * kReducedMass * kApproach), 1.0, 1e-12) << "h = " << h << ", e = " << e;
    }
  }
}

// Engine facts the mapping is built on (engines.md), so that a Bullet that changes them fails here.
TEST(BulletContactMapping, BulletsDefaultsDoNotRealiseTheRestitution) {
  const double h = 1e-4, e = 0.8;
  // Defaults: no bounce below the 0.2 m/s restitution threshold, and Baumgarte's push-out (ERP 0.2)
  // instead: a rebound that depends on how deep the step ended, never e.
  {
    TwoSpheres spheres(0.5 * kApproach * h);
    set_restitution(spheres.a(), spheres.b(), e);
    EXPECT_EQ(spheres.solver_info().m_restitutionVelocityThreshold, btScalar(0.2f));
    for (int n = 0; n < 10; ++n) spheres.step(h);
    const double realised = -spheres.indentation_rate() / kApproach;
    std::printf("[ measured ] Bullet's default solver settings: e = %.4f for a target of %.1f at %.4f m/s\n", realised,
                e, kApproach);
    EXPECT_GT(std::abs(realised - e), 0.1);
  }
  // Restitution threshold 0 but no split impulse: the push-out adds to the rebound.
  {
    TwoSpheres spheres(0.5 * kApproach * h);
    set_restitution(spheres.a(), spheres.b(), e);
    spheres.solver_info().m_restitutionVelocityThreshold = 0;
    spheres.solver_info().m_splitImpulse = 0;
    for (int n = 0; n < 10; ++n) spheres.step(h);
    EXPECT_GT(-spheres.indentation_rate() / kApproach, e + 0.01);
  }
}

TEST(BulletContactMapping, AppliedImpulsesAreWrittenBackOnlyWithWarmStarting) {
  for (bool warm_starting : {true, false}) {
    TwoSpheres spheres(0.5e-6);
    set_restitution(spheres.a(), spheres.b(), 0.8);
    configure_restitution_solver(spheres.solver_info());
    if (!warm_starting) spheres.solver_info().m_solverMode &= ~SOLVER_USE_WARMSTARTING;
    double impulse = 0;
    for (int n = 0; n < 10; ++n) {
      spheres.step(1e-5);
      impulse += spheres.applied_impulse();
    }
    // the bounce happens either way ...
    EXPECT_NEAR(-spheres.indentation_rate() / kApproach, 0.8, 1e-12);
    // ... but only warm starting lets the contact points report its impulse
    if (warm_starting)
      EXPECT_NEAR(impulse / (1.8 * kReducedMass * kApproach), 1.0, 1e-12);
    else
      EXPECT_EQ(impulse, 0.0);
  }
}

}  // namespace bullet_contact_mapping_test
}  // namespace ib::bullet
