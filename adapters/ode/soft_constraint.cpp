#include "adapters/ode/soft_constraint.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace ib::ode {

SoftConstraint soft_constraint(double stiffness, double damping, double time_step_s) {
  if (!(stiffness >= 0) || !(damping >= 0) || !(time_step_s > 0) || !std::isfinite(stiffness) ||
      !std::isfinite(damping) || !std::isfinite(time_step_s) || stiffness + damping <= 0)
    throw std::invalid_argument(
        "ODE soft constraint: needs stiffness >= 0, damping >= 0 (not both 0) and a step > 0; got k = " +
        std::to_string(stiffness) + ", c = " + std::to_string(damping) + ", h = " + std::to_string(time_step_s));
  const double hk = time_step_s * stiffness;
  return {hk / (hk + damping), 1 / (hk + damping)};
}

}  // namespace ib::ode
