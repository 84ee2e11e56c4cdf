#include "adapters/bullet/bullet_contact.h"

#include <btBulletCollisionCommon.h>
#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

static_assert(sizeof(btScalar) == 8, "impactbench needs Bullet's double-precision build (pkg-config bullet-float64)");

namespace ib::bullet {

std::array<ContactStiffnessDamping, 2> spring_dashpot_per_tip(double k, double c) {
  if (!(k > 0) || !std::isfinite(k))
    throw std::invalid_argument("contact stiffness must be > 0, got " + std::to_string(k));
  if (!(c >= 0) || !std::isfinite(c))
    throw std::invalid_argument("contact damping must be >= 0, got " + std::to_string(c));
  // Tip 1 carries the law's spring, tip 2 is rigid (infinite stiffness: 1/inf = 0 in the series
  // formula, so nothing is added to 1/k); each carries half the damping (a division by 2 is exact).
  std::array<ContactStiffnessDamping, 2> tips = {
      ContactStiffnessDamping{k, c / 2}, ContactStiffnessDamping{std::numeric_limits<double>::infinity(), c / 2}};
  // Bullet's last operation is a division, 1 / (1/k_1 + 1/k_2), whose results are sparser than the
  // doubles near k: k itself may be out of reach (6.99e6 is: the nearest results are 1 ulp either
  // side). Take the tip-1 value, among k and its neighbours, whose combination lands nearest to k.
  btCollisionObject a, b;
  b.setContactStiffnessAndDamping(tips[1].stiffness_n_per_m, tips[1].damping_n_s_per_m);
  auto miss = [&](double stiffness) {
    a.setContactStiffnessAndDamping(stiffness, tips[0].damping_n_s_per_m);
    return std::abs(combined_contact_stiffness(a, b) - k);
  };
  double best = k, best_miss = miss(k);
  for (double direction : {0.0, std::numeric_limits<double>::infinity()}) {
    double candidate = k;
    for (int ulps = 1; ulps <= 4 && best_miss > 0; ++ulps) {
      candidate = std::nextafter(candidate, direction);
      const double m = miss(candidate);
      if (m < best_miss) best = candidate, best_miss = m;
    }
  }
  tips[0].stiffness_n_per_m = best;
  return tips;
}

double combined_contact_stiffness(const btCollisionObject& a, const btCollisionObject& b) {
  return btManifoldResult::calculateCombinedContactStiffness(&a, &b);
}

double combined_contact_damping(const btCollisionObject& a, const btCollisionObject& b) {
  return btManifoldResult::calculateCombinedContactDamping(&a, &b);
}

double combined_restitution(const btCollisionObject& a, const btCollisionObject& b) {
  return btManifoldResult::calculateCombinedRestitution(&a, &b);
}

void set_spring_dashpot(btCollisionObject& tip1, btCollisionObject& tip2, double k, double c) {
  const auto tips = spring_dashpot_per_tip(k, c);
  tip1.setContactStiffnessAndDamping(tips[0].stiffness_n_per_m, tips[0].damping_n_s_per_m);
  tip2.setContactStiffnessAndDamping(tips[1].stiffness_n_per_m, tips[1].damping_n_s_per_m);
  for (btCollisionObject* tip : {&tip1, &tip2}) {
    tip->setFriction(0);
    tip->setRestitution(0);
  }
}

void configure_spring_dashpot_solver(btContactSolverInfo& info) { info.m_splitImpulse = 0; }

void set_restitution(btCollisionObject& tip1, btCollisionObject& tip2, double restitution) {
  tip1.setRestitution(restitution);
  tip2.setRestitution(1);
  tip1.setFriction(0);
  tip2.setFriction(0);
}

void configure_restitution_solver(btContactSolverInfo& info) {
  info.m_restitutionVelocityThreshold = 0;
  info.m_splitImpulse = 1;
  info.m_splitImpulsePenetrationThreshold = std::numeric_limits<double>::infinity();
  info.m_erp2 = 0;
}

void set_restitution_processing_threshold(btCollisionObject& tip1, btCollisionObject& tip2) {
  tip1.setContactProcessingThreshold(0);
  tip2.setContactProcessingThreshold(0);
}

double spring_dashpot_restitution(double k, double c, double m) {
  const double zeta = c / (2 * std::sqrt(k * m));
  return zeta < 1 ? std::exp(-zeta * M_PI / std::sqrt(1 - zeta * zeta)) : 0.0;
}

}  // namespace ib::bullet
