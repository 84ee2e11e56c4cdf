// The one function that turns a spring-dashpot k [N/m], c [N s/m] into MuJoCo's solref/solimp, checked
// on a single contact between two free spheres on slide joints: the force MuJoCo applies step by step
// is k delta + c delta' (fitted back from its own contact forces), and the contact lasts and rebounds
// as the exact spring-dashpot that cannot pull. The closed forms used for that are checked against a
// direct integration first, and so is the spring-dashpot chosen for Newton's law.
#include "adapters/mujoco/mujoco_contact_mapping.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "adapters/mujoco/mujoco_engine.h"

namespace ib {
namespace mujoco_contact_mapping_test {

// Two spheres of radius 5 mm on slide joints along x, surfaces 1 mm apart, no gravity. Only the pair
// collides, with the given parameters (none: a model to read body_invweight0 from).
std::string two_spheres(double m1, double m2, double h, const SolrefSolimp* contact) {
  auto n = [](double v) { return std::to_string(v); };
  std::string xml = "<mujoco><option timestep=\"" + n(h) + "\" gravity=\"0 0 0\"/><worldbody>";
  const double x[2] = {0, 0.011}, m[2] = {m1, m2};
  for (int i = 0; i < 2; ++i)
    xml += "<body name=\"b" + std::to_string(i) + "\" pos=\"" + n(x[i]) +
           " 0 0\"><joint type=\"slide\" axis=\"1 0 0\"/>" + "<inertial pos=\"0 0 0\" mass=\"" + n(m[i]) +
           "\" diaginertia=\"1e-5 1e-5 1e-5\"/>" + "<geom name=\"g" + std::to_string(i) +
           "\" type=\"sphere\" size=\"0.005\" contype=\"0\" conaffinity=\"0\"/></body>";
  xml += "</worldbody>";
  if (contact) {
    char pair[512];
    std::snprintf(pair, sizeof pair,
                  "<contact><pair geom1=\"g0\" geom2=\"g1\" condim=\"1\" solref=\"%.17g %.17g\" "
                  "solimp=\"%.17g %.17g %.17g %.17g %.17g\"/></contact>",
                  contact->solref[0], contact->solref[1], contact->solimp[0], contact->solimp[1], contact->solimp[2],
                  contact->solimp[3], contact->solimp[4]);
    xml += pair;
  }
  return xml + "</mujoco>";
}

double invweight_sum(const mjModel* m) { return m->body_invweight0[2 * 1] + m->body_invweight0[2 * 2]; }

struct Impact {
  double stiffness_fit = 0, damping_fit = 0;  // least squares of MuJoCo's force on (delta, delta')
  double force_duration_s = 0;                // steps with a positive force, times h
  double restitution = 0;                     // rebound / approach speed
  double efc_diag_approx = 0;                 // MuJoCo's A for the contact row
};

// Sphere 1 approaches the resting sphere 2 at approach_m_s; steps (forward, then semi-implicit Euler,
// as mj_step) until they are apart again.
Impact collide(double m1, double m2, double k, double c, double h, double approach_m_s) {
  MujocoModelPtr probe = compile_mjcf(two_spheres(m1, m2, h, nullptr));
  const SolrefSolimp contact = map_spring_dashpot(k, c, invweight_sum(probe.get()));
  MujocoModelPtr model = compile_mjcf(two_spheres(m1, m2, h, &contact));
  MujocoDataPtr data = make_data(model.get());
  const mjModel* m = model.get();
  mjData* d = data.get();
  d->qvel[0] = approach_m_s;
  Impact out;
  Eigen::Matrix2d normal = Eigen::Matrix2d::Zero();
  Eigen::Vector2d rhs = Eigen::Vector2d::Zero();
  bool touched = false;
  for (int step = 0; step < 10'000'000; ++step) {
    mj_forward(m, d);
    const double rate = d->qvel[0] - d->qvel[1];
    double force = 0;
    if (d->ncon > 0 && d->contact[0].efc_address >= 0) {
      mjtNum wrench[6];
      mj_contactForce(m, d, 0, wrench);
      force = wrench[0];
      out.efc_diag_approx = d->efc_diagApprox[d->contact[0].efc_address];
      if (force > 0) {
        const Eigen::Vector2d state(-d->contact[0].dist, rate);  // indentation, its rate
        normal += state * state.transpose();
        rhs += state * force;
        out.force_duration_s += h;
        touched = true;
      }
    }
    if (touched && d->ncon == 0) break;  // apart again
    mj_Euler(m, d);
  }
  const Eigen::Vector2d fit = normal.ldlt().solve(rhs);
  out.stiffness_fit = fit[0];
  out.damping_fit = fit[1];
  out.restitution = (d->qvel[1] - d->qvel[0]) / approach_m_s;
  return out;
}

// The no-tension spring-dashpot integrated directly (RK4, 1e5 steps per contact): force duration and e.
std::pair<double, double> integrate_clipped(double zeta) {
  const double omega = 1, h = M_PI / 1e5;
  double x = 0, v = 1, t = 0;
  auto acc = [&](double xs, double vs) { return -(omega * omega * xs + 2 * zeta * omega * vs); };
  while (true) {
    const double k1x = v, k1v = acc(x, v);
    const double k2x = v + h / 2 * k1v, k2v = acc(x + h / 2 * k1x, v + h / 2 * k1v);
    const double k3x = v + h / 2 * k2v, k3v = acc(x + h / 2 * k2x, v + h / 2 * k2v);
    const double k4x = v + h * k3v, k4v = acc(x + h * k3x, v + h * k3v);
    const double xn = x + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x), vn = v + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (acc(xn, vn) >= 0) {  // the force (-m x'') has reached zero: locate it linearly within the step
      const double w = -acc(x, v) / (acc(xn, vn) - acc(x, v));
      return {t + w * h, -(v + w * (vn - v))};
    }
    x = xn, v = vn, t += h;
  }
}

TEST(MujocoContactMapping, ClippedClosedFormsMatchDirectIntegration) {
  for (double zeta : {0.01, 0.056, 0.2, 0.5, 0.69}) {
    const auto [duration, restitution] = integrate_clipped(zeta);
    // omega = 1: the force lasts phi / omega_d
    EXPECT_NEAR(clipped_contact_phase(zeta) / std::sqrt(1 - zeta * zeta), duration, 1e-6) << "zeta " << zeta;
    EXPECT_NEAR(clipped_contact_restitution(zeta), restitution, 1e-6) << "zeta " << zeta;
  }
}

TEST(MujocoContactMapping, NewtonSpringDashpotHasTheRestitutionAndDuration) {
  const double mass = 0.33, duration = 4e-4;
  for (double e : {0.3, 0.8, 0.95}) {
    const SpringDashpot sd = spring_dashpot_for_restitution(e, mass, duration);
    const double omega = std::sqrt(sd.stiffness_n_per_m / mass), zeta = sd.damping_n_s_per_m / (2 * mass * omega);
    EXPECT_NEAR(clipped_contact_restitution(zeta), e, 1e-12);
    EXPECT_NEAR(clipped_contact_phase(zeta) / (omega * std::sqrt(1 - zeta * zeta)), duration, 1e-15);
  }
  EXPECT_THROW(spring_dashpot_for_restitution(0.1, mass, duration), std::invalid_argument);  // needs overdamping
}

TEST(MujocoContactMapping, RoundTrip) {
  const SolrefSolimp p = map_spring_dashpot(6.99e6, 170.07, 1.2);
  EXPECT_LT(p.solref[0], 0);
  EXPECT_LT(p.solref[1], 0);
  EXPECT_EQ(p.solimp[0], p.solimp[1]);  // constant impedance
  const SpringDashpot back = spring_dashpot_of(p, 1.2);
  EXPECT_NEAR(back.stiffness_n_per_m, 6.99e6, 1e-6);
  EXPECT_NEAR(back.damping_n_s_per_m, 170.07, 1e-9);
}

// The rig's viscoelastic law on the two chains' linearised tip effective masses (K = 8: 0.656 and
// 0.426 kg), at the measured mean approach speed. h = 1e-6 s: 600 steps per contact, so the
// time-stepping error (first order in h) stays below 0.1 %.
TEST(MujocoContactMapping, ReproducesStiffnessAndDampingOnASingleContact) {
  const double m1 = 0.656, m2 = 0.426, k = 6.99e6, c = 170.07, h = 1e-6, v0 = 0.1644;
  const Impact impact = collide(m1, m2, k, c, h, v0);
  // MuJoCo's force against the state it was computed from: k and c back within 0.1 % (the mapping's
  // own approximation is of relative size d = 1e-4 times the true / estimated inverse mass, ~3e-4)
  EXPECT_NEAR(impact.stiffness_fit / k, 1, 1e-3) << impact.stiffness_fit;
  EXPECT_NEAR(impact.damping_fit / c, 1, 1e-3) << impact.damping_fit;
  std::printf("fitted k = %.6g N/m (target %.6g), c = %.6g N s/m (target %.6g)\n", impact.stiffness_fit, k,
              impact.damping_fit, c);

  // The exact spring-dashpot that cannot pull on the reduced mass: duration and restitution.
  const double mass = m1 * m2 / (m1 + m2), omega = std::sqrt(k / mass), zeta = c / (2 * std::sqrt(k * mass));
  const double duration = clipped_contact_phase(zeta) / (omega * std::sqrt(1 - zeta * zeta));
  const double restitution = clipped_contact_restitution(zeta);
  std::printf(
      "duration %.6e s (exact %.6e; pi/omega_d = %.6e with tension), e = %.6f (exact %.6f; %.6f with tension)\n",
      impact.force_duration_s, duration, M_PI / (omega * std::sqrt(1 - zeta * zeta)), impact.restitution, restitution,
      std::exp(-zeta * M_PI / std::sqrt(1 - zeta * zeta)));
  EXPECT_NEAR(impact.force_duration_s, duration, 2 * h);  // counted in whole steps
  EXPECT_NEAR(impact.restitution / restitution, 1, 2e-3);
  // what the mapping assumes about MuJoCo: the contact row's A is the body_invweight0 sum
  MujocoModelPtr probe = compile_mjcf(two_spheres(m1, m2, h, nullptr));
  EXPECT_NEAR(impact.efc_diag_approx, invweight_sum(probe.get()), 1e-12);
}

// The Newton contact (4 steps long, the default, at h = 1e-4 s) on the same masses: rebound e within
// 2 %. Four steps per contact leave a stepping error of about 1 % (first order in h omega).
TEST(MujocoContactMapping, NewtonContactReboundsWithTheRestitution) {
  const double m1 = 0.656, m2 = 0.426, h = 1e-4, v0 = 0.1644, e = 0.8;
  const double mass = m1 * m2 / (m1 + m2);
  const SpringDashpot sd = spring_dashpot_for_restitution(e, mass, 4 * h);
  const Impact impact = collide(m1, m2, sd.stiffness_n_per_m, sd.damping_n_s_per_m, h, v0);
  std::printf("Newton e = %.4f (target %.4f) over %.3g s\n", impact.restitution, e, impact.force_duration_s);
  EXPECT_NEAR(impact.restitution, e, 0.02 * e);
}

}  // namespace mujoco_contact_mapping_test
}  // namespace ib
