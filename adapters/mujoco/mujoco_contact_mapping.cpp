#include "adapters/mujoco/mujoco_contact_mapping.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace ib {
namespace {

// The largest damping ratio the closed forms cover (below 1/sqrt(2), where the force's zero leaves (pi/2, pi)).
constexpr double kLargestDampingRatio = 0.7;

}  // namespace

SolrefSolimp map_spring_dashpot(double k, double c, double invweight_sum) {
  if (!(k > 0) || !(c >= 0) || !(invweight_sum > 0))
    throw std::invalid_argument("map_spring_dashpot: need k > 0, c >= 0 and an inverse weight > 0");
  const double d = kDirectImpedance;
  SolrefSolimp p;
  p.solref = {-k * invweight_sum * (1 - d), -c * invweight_sum * (1 - d)};
  // dmin = dmax: the impedance does not depend on the indentation, so the width, midpoint and power
  // do nothing; they are MuJoCo's defaults.
  p.solimp = {d, d, 0.001, 0.5, 2};
  return p;
}

SpringDashpot spring_dashpot_of(const SolrefSolimp& p, double invweight_sum) {
  const double scale = invweight_sum * (1 - p.solimp[1]);
  return {-p.solref[0] / scale, -p.solref[1] / scale};
}

double clipped_contact_phase(double zeta) {
  return M_PI - std::atan2(2 * zeta * std::sqrt(1 - zeta * zeta), 1 - 2 * zeta * zeta);
}

double clipped_contact_restitution(double zeta) {
  const double root = std::sqrt(1 - zeta * zeta), phi = clipped_contact_phase(zeta);
  return std::exp(-zeta * phi / root) * (zeta * std::sin(phi) / root - std::cos(phi));
}

SpringDashpot spring_dashpot_for_restitution(double e, double mass, double duration) {
  const double lowest = clipped_contact_restitution(kLargestDampingRatio);
  if (!(e > lowest && e <= 1) || !(mass > 0) || !(duration > 0))
    throw std::invalid_argument("MuJoCo Newton contact: restitution " + std::to_string(e) + " is out of reach (" +
                                std::to_string(lowest) + " < e <= 1) or mass/duration not positive");
  // e(zeta) falls monotonically on [0, 0.7]: bisect.
  double lo = 0, hi = kLargestDampingRatio;
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (clipped_contact_restitution(mid) > e ? lo : hi) = mid;
  }
  const double zeta = 0.5 * (lo + hi);
  const double omega = clipped_contact_phase(zeta) / (duration * std::sqrt(1 - zeta * zeta));
  return {mass * omega * omega, 2 * zeta * mass * omega};
}

}  // namespace ib
