// The one mapping from a spring-damper (k, c) and the step h to ODE's ERP/CFM, and what ODE does with
// it: on a single contact between two free spheres, and on a single hinge, ODE reproduces the
// backward-Euler spring-dashpot step for step; against the exact spring-dashpot it loses energy at first
// order in the step, about as exp(-pi omega h / 2). Also: the ODE this build links is the double-precision 0.16
// library.
#include "adapters/ode/soft_constraint.h"

#include <gtest/gtest.h>
#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "adapters/ode/ode_library.h"
#include "adapters/ode/ode_simulator.h"

namespace ib {
namespace ode_soft_constraint_test {

TEST(OdeLibrary, IsTheDoublePrecisionBuild) {
  ode::ensure_initialised();
  EXPECT_EQ(sizeof(dReal), sizeof(double));
  EXPECT_TRUE(dCheckConfiguration("ODE_double_precision")) << dGetConfiguration();
  EXPECT_EQ(make_ode_simulator()->version().rfind("ODE 0.16", 0), 0u) << make_ode_simulator()->version();
}

TEST(OdeSoftConstraint, IsTheUserGuidesSpringDamperMapping) {
  const double k = 6.99e6, c = 170.07, h = 1e-5;
  const ode::SoftConstraint s = ode::soft_constraint(k, c, h);
  EXPECT_DOUBLE_EQ(s.erp, h * k / (h * k + c));
  EXPECT_DOUBLE_EQ(s.cfm, 1 / (h * k + c));
  // the row's spring and damper read back: k = ERP / (h CFM), c = (1 - ERP) / CFM
  EXPECT_NEAR(s.erp / (h * s.cfm), k, 1e-9 * k);
  EXPECT_NEAR((1 - s.erp) / s.cfm, c, 1e-9 * c);
  // a pure damper never corrects the error, a pure spring has ERP 1
  EXPECT_EQ(ode::soft_constraint(0, c, h).erp, 0.0);
  EXPECT_EQ(ode::soft_constraint(k, 0, h).erp, 1.0);
  EXPECT_THROW(ode::soft_constraint(0, 0, h), std::invalid_argument);
  EXPECT_THROW(ode::soft_constraint(-k, c, h), std::invalid_argument);
  EXPECT_THROW(ode::soft_constraint(k, c, 0), std::invalid_argument);
  EXPECT_THROW(ode::soft_constraint(k, NAN, h), std::invalid_argument);
}

// Two free spheres on the x axis (no gravity), the first moving toward the second. The relative motion
// is a one-degree-of-freedom contact with the reduced mass m = m1 m2 / (m1 + m2).
struct TwoSpheres {
  double m1 = 0.6563, m2 = 0.4257;  // the rig's tip effective masses for K = 8 [kg]
  double radius = 5e-3;
  double stiffness = 6.99e6, damping = 170.07;  // rig.md's spring-dashpot
  double approach = 0.075;                      // [m/s], the free vibration case's first impact
  double reduced_mass() const { return m1 * m2 / (m1 + m2); }
};

// Per step: depth at the step's start (ODE's collision), closing speed after the step, the contact
// force ODE reports for the step.
struct ContactStep {
  double depth_m, closing_speed_m_s, force_n;
};

std::vector<ContactStep> run_ode_contact(const TwoSpheres& p, double h) {
  ode::ensure_initialised();
  dWorldID world = dWorldCreate();
  dWorldSetGravity(world, 0, 0, 0);
  dWorldSetContactSurfaceLayer(world, 0);
  dWorldSetContactMaxCorrectingVel(world, dInfinity);
  dJointGroupID group = dJointGroupCreate(0);
  std::array<dBodyID, 2> bodies{};
  std::array<dGeomID, 2> spheres{};
  for (int i = 0; i < 2; ++i) {
    bodies[i] = dBodyCreate(world);
    dMass mass;
    dMassSetSphereTotal(&mass, i == 0 ? p.m1 : p.m2, p.radius);
    dBodySetMass(bodies[i], &mass);
    spheres[i] = dCreateSphere(nullptr, p.radius);
    dGeomSetBody(spheres[i], bodies[i]);
  }
  // the spheres touch after a quarter of a step's travel: the first overlap is not aligned with a step
  dBodySetPosition(bodies[0], 0, 0, 0);
  dBodySetPosition(bodies[1], 2 * p.radius + 0.25 * p.approach * h, 0, 0);
  dBodySetLinearVel(bodies[0], p.approach, 0, 0);
  const ode::SoftConstraint soft = ode::soft_constraint(p.stiffness, p.damping, h);
  std::vector<ContactStep> steps;
  dJointFeedback feedback{};
  for (int n = 0; n < 100000; ++n) {
    dJointGroupEmpty(group);
    dContact contact{};
    contact.surface.mode = dContactSoftERP | dContactSoftCFM;
    contact.surface.mu = 0;
    contact.surface.soft_erp = soft.erp;
    contact.surface.soft_cfm = soft.cfm;
    const double depth = 2 * p.radius - (dBodyGetPosition(bodies[1])[0] - dBodyGetPosition(bodies[0])[0]);
    const bool touching = dCollide(spheres[0], spheres[1], 1, &contact.geom, sizeof(dContact)) > 0;
    if (touching) {
      dJointID joint = dJointCreateContact(world, group, &contact);
      dJointAttach(joint, dGeomGetBody(contact.geom.g1), dGeomGetBody(contact.geom.g2));
      feedback = dJointFeedback{};
      dJointSetFeedback(joint, &feedback);
    }
    dWorldStep(world, h);
    const double closing = dBodyGetLinearVel(bodies[0])[0] - dBodyGetLinearVel(bodies[1])[0];
    steps.push_back({depth, closing, touching ? -feedback.f1[0] : 0.0});
    if (n > 0 && !touching && steps[n - 1].depth_m > 0) break;  // separated
  }
  for (dGeomID g : spheres) dGeomDestroy(g);
  dJointGroupDestroy(group);
  dWorldDestroy(world);
  return steps;
}

// The backward-Euler spring-dashpot of the same contact, compressive only (ODE's contact row has
// lambda >= 0), switched on when the depth at the start of a step is positive:
//   f = k d_{n+1} + c d'_{n+1},  d_{n+1} = d_n + h d'_{n+1},  m d'_{n+1} = m d'_n - h f.
std::vector<ContactStep> backward_euler_contact(const TwoSpheres& p, double h, std::size_t steps) {
  std::vector<ContactStep> out;
  const double m = p.reduced_mass();
  double depth = -0.25 * p.approach * h, rate = p.approach;
  for (std::size_t n = 0; n < steps; ++n) {
    double force = 0;
    if (depth > 0) {
      force =
          (p.stiffness * depth + (h * p.stiffness + p.damping) * rate) / (1 + h * (h * p.stiffness + p.damping) / m);
      force = std::max(0.0, force);
    }
    const double start_depth = depth;
    rate -= h * force / m;
    depth += h * rate;
    out.push_back({start_depth, rate, force});
  }
  return out;
}

// The exact spring-dashpot, compressive only: d = v0/w_d e^(-zeta w t) sin(w_d t) until the force
// k d + c d' reaches zero; the tips then part at the speed they have there.
double exact_restitution(const TwoSpheres& p) {
  const double m = p.reduced_mass(), omega = std::sqrt(p.stiffness / m);
  const double zeta = p.damping / (2 * std::sqrt(p.stiffness * m)), omega_d = omega * std::sqrt(1 - zeta * zeta);
  const auto depth = [&](double t) {
    return p.approach / omega_d * std::exp(-zeta * omega * t) * std::sin(omega_d * t);
  };
  const auto rate = [&](double t) {
    return p.approach * std::exp(-zeta * omega * t) *
           (std::cos(omega_d * t) - zeta * omega / omega_d * std::sin(omega_d * t));
  };
  double low = 0.25 * M_PI / omega_d, high = M_PI / omega_d;  // force > 0 at low, < 0 at high
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (low + high);
    (p.stiffness * depth(mid) + p.damping * rate(mid) > 0 ? low : high) = mid;
  }
  return -rate(low) / p.approach;
}

TEST(OdeSoftConstraint, OdeContactIsTheBackwardEulerSpringDashpotStepForStep) {
  const TwoSpheres p;
  for (double h : {1e-4, 1e-5}) {
    const auto ode_steps = run_ode_contact(p, h);
    const auto expected = backward_euler_contact(p, h, ode_steps.size());
    double peak = 0, worst_speed = 0, worst_force = 0;
    for (const ContactStep& s : expected) peak = std::max(peak, s.force_n);
    for (std::size_t n = 0; n < ode_steps.size(); ++n) {
      worst_speed = std::max(worst_speed, std::abs(ode_steps[n].closing_speed_m_s - expected[n].closing_speed_m_s));
      worst_force = std::max(worst_force, std::abs(ode_steps[n].force_n - expected[n].force_n));
    }
    std::printf("h = %g s: %zu steps, largest differences from backward Euler: %.3g m/s (of %.3g), %.3g N (of %.3g)\n",
                h, ode_steps.size(), worst_speed, p.approach, worst_force, peak);
    for (std::size_t n = 0; n < ode_steps.size(); ++n) {
      // ODE's own sphere depth and dWorldStep's LCP solve: agreement to rounding (1e-9 of the scales)
      EXPECT_NEAR(ode_steps[n].depth_m, expected[n].depth_m, 1e-9 * p.approach * h * 100)
          << "h = " << h << ", step " << n;
      EXPECT_NEAR(ode_steps[n].closing_speed_m_s, expected[n].closing_speed_m_s, 1e-9 * p.approach)
          << "h = " << h << ", step " << n;
      EXPECT_NEAR(ode_steps[n].force_n, expected[n].force_n, 1e-9 * peak) << "h = " << h << ", step " << n;
    }
  }
}

// How far that is from the exact spring-dashpot (compressive only): the rebound loses energy at first
// order in the step. Backward Euler damps an oscillation at the rate omega^2 h / 2, so over a half
// period pi / omega the restitution shrinks by about exp(-pi omega h / 2) (engines.md); the damped,
// clipped contact ends a little before the half period, so the loss is somewhat smaller.
TEST(OdeSoftConstraint, OdeContactLosesEnergyAtFirstOrderInTheStep) {
  const TwoSpheres p;
  const double e_exact = exact_restitution(p);
  const double omega = std::sqrt(p.stiffness / p.reduced_mass());
  std::vector<double> loss;  // 1 - e / e_exact
  for (double h : {1e-4, 1e-5, 2e-6}) {
    const auto steps = run_ode_contact(p, h);
    const double e = -steps.back().closing_speed_m_s / p.approach;
    const double ratio = e / e_exact;
    loss.push_back(1 - ratio);
    std::printf("h = %g s: omega h = %.4f, e = %.4f against the exact %.4f: ratio %.4f, exp(-pi omega h / 2) = %.4f\n",
                h, omega * h, e, e_exact, ratio, std::exp(-M_PI * omega * h / 2));
    EXPECT_LT(ratio, 1.0) << "backward Euler never gains energy; h = " << h;
    if (omega * h < 0.1) {
      // -ln(ratio) / (omega h) is the loss coefficient: pi / 2 for a full undamped half period
      const double coefficient = -std::log(ratio) / (omega * h);
      EXPECT_LE(coefficient, M_PI / 2) << "h = " << h;
      EXPECT_GE(coefficient, 0.8 * M_PI / 2) << "h = " << h;
    }
  }
  // first order: a step 5 times shorter loses about 5 times less
  EXPECT_NEAR(loss[1] / loss[2], 5.0, 0.5);
  // and the rig's default step is far too long for this contact (omega h = 0.52): 40 % of e is lost
  EXPECT_GT(loss[0], 0.3);
}

// A single body on a hinge to the ground, its spring made by both stops at zero with the same mapping,
// released from an angle: the hinge angle follows the backward-Euler rotational spring-dashpot with
// the body's inertia about the hinge.
TEST(OdeSoftConstraint, HingeStopsAreTheSameBackwardEulerSpring) {
  ode::ensure_initialised();
  const double mass = 0.7, length = 0.0375, inertia_c = mass * length * length / 12;  // a link with its tip mass
  const double k = 363.0, c = 0.05, h = 1e-4, theta0 = -5e-3;
  dWorldID world = dWorldCreate();
  dWorldSetGravity(world, 0, 0, 0);
  dBodyID body = dBodyCreate(world);
  dMass m;
  dMassSetParameters(&m, mass, 0, 0, 0, inertia_c, inertia_c, inertia_c, 0, 0, 0);
  dBodySetMass(body, &m);
  dBodySetPosition(body, 0, 0, length / 2);
  dJointID hinge = dJointCreateHinge(world, nullptr);
  dJointAttach(hinge, body, nullptr);
  dJointSetHingeAnchor(hinge, 0, 0, 0);
  dJointSetHingeAxis(hinge, 0, 1, 0);
  const ode::SoftConstraint soft = ode::soft_constraint(k, c, h);
  dJointSetHingeParam(hinge, dParamLoStop, 0);
  dJointSetHingeParam(hinge, dParamHiStop, 0);
  dJointSetHingeParam(hinge, dParamStopERP, soft.erp);
  dJointSetHingeParam(hinge, dParamStopCFM, soft.cfm);
  // released from theta0 about y (toward -x)
  dMatrix3 r;
  dRFromAxisAndAngle(r, 0, 1, 0, theta0);
  dBodySetRotation(body, r);
  dBodySetPosition(body, length / 2 * std::sin(theta0), 0, length / 2 * std::cos(theta0));
  const double inertia = inertia_c + mass * length * length / 4;
  double theta = theta0, rate = 0, worst = 0;
  for (int n = 0; n < 2000; ++n) {
    dWorldStep(world, h);
    rate = (rate - h * (k * theta) / inertia) / (1 + h * (h * k + c) / inertia);
    theta += h * rate;
    const dReal* rot = dBodyGetRotation(body);
    worst = std::max(worst, std::abs(std::atan2(rot[2], rot[10]) - theta));
  }
  dWorldDestroy(world);
  std::printf("hinge: largest angle difference from backward Euler %.3g rad of %.3g rad\n", worst, std::abs(theta0));
  // exact but for ODE's linear position update of the centre of mass along the tangent (corrected by
  // the hinge's ERP): second order in the angle
  EXPECT_LT(worst, 1e-6 * std::abs(theta0)) << "largest angle difference " << worst << " rad";
}

}  // namespace ode_soft_constraint_test
}  // namespace ib
