// ODE's restitution knob as the adapter's Newton path uses it (ode_contact.h): dContactBounce with
// bounce = e reverses the closing speed of two free spheres with factor e within the one step in which
// they are found overlapping; a closing speed below bounce_vel is plastic; and a negative bounce_vel
// silently disables the bounce (engines.md), which is why the adapter's threshold is >= 0.
#include <gtest/gtest.h>
#include <ode/ode.h>

#include <array>
#include <cstdio>

#include "adapters/ode/ode_contact.h"
#include "adapters/ode/ode_library.h"

namespace ib {
namespace ode_bounce_test {

struct Bounce {
  double restitution = 0;  // opening speed after the contact / closing speed before it
  int contact_steps = 0;   // steps with a contact joint
};

// Two free spheres (the rig's tip effective masses), the first closing on the second at approach_m_s,
// with the Newton surface of the adapter but the given restitution and threshold.
Bounce collide(double restitution, double threshold_m_s, double approach_m_s, double h = 1e-4) {
  ode::ensure_initialised();
  dWorldID world = dWorldCreate();
  dWorldSetGravity(world, 0, 0, 0);
  dJointGroupID group = dJointGroupCreate(0);
  const double radius = 5e-3;
  std::array<dBodyID, 2> bodies{};
  std::array<dGeomID, 2> spheres{};
  for (int i = 0; i < 2; ++i) {
    bodies[i] = dBodyCreate(world);
    dMass mass;
    dMassSetSphereTotal(&mass, i == 0 ? 0.6563 : 0.4257, radius);
    dBodySetMass(bodies[i], &mass);
    spheres[i] = dCreateSphere(nullptr, radius);
    dGeomSetBody(spheres[i], bodies[i]);
  }
  dBodySetPosition(bodies[1], 2 * radius + 0.5 * approach_m_s * h, 0, 0);
  dBodySetLinearVel(bodies[0], approach_m_s, 0, 0);
  ode::ContactSetup setup = ode::contact_setup(ContactPath::matched, NewtonLaw{restitution}, h);
  setup.surface.bounce_vel = threshold_m_s;
  Bounce out;
  for (int n = 0; n < 50; ++n) {
    dJointGroupEmpty(group);
    dContact contact{};
    contact.surface = setup.surface;
    if (dCollide(spheres[0], spheres[1], 1, &contact.geom, sizeof(dContact)) > 0) {
      dJointID joint = dJointCreateContact(world, group, &contact);
      dJointAttach(joint, dGeomGetBody(contact.geom.g1), dGeomGetBody(contact.geom.g2));
      ++out.contact_steps;
    }
    dWorldStep(world, h);
  }
  out.restitution = (dBodyGetLinearVel(bodies[1])[0] - dBodyGetLinearVel(bodies[0])[0]) / approach_m_s;
  for (dGeomID g : spheres) dGeomDestroy(g);
  dJointGroupDestroy(group);
  dWorldDestroy(world);
  return out;
}

TEST(OdeBounce, ReversesTheClosingSpeedWithFactorE) {
  for (double e : {0.8, 0.5}) {
    const Bounce b = collide(e, ode::kBounceThreshold_m_s, 0.075);
    std::printf("bounce = %.2f: restitution %.6f after %d contact step(s)\n", e, b.restitution, b.contact_steps);
    EXPECT_NEAR(b.restitution, e, 1e-6);
    EXPECT_LE(b.contact_steps, 2);  // the overlap step, and the step after if the spheres still overlap
  }
}

TEST(OdeBounce, BelowTheThresholdTheImpactIsPlastic) {
  const Bounce slow = collide(0.8, 0.1, 0.075);  // closing at 0.075 m/s under a 0.1 m/s threshold
  EXPECT_NEAR(slow.restitution, 0, 1e-6);
}

TEST(OdeBounce, ANegativeThresholdSilentlyDisablesTheBounce) {
  const Bounce disabled = collide(0.8, -1e-4, 0.075);
  std::printf("bounce_vel = -1e-4 m/s: restitution %.6f\n", disabled.restitution);
  EXPECT_NEAR(disabled.restitution, 0, 1e-6);
  EXPECT_GE(ode::kBounceThreshold_m_s, 0.0);
}

}  // namespace ode_bounce_test
}  // namespace ib
