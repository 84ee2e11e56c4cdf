// Out-of-line members of the run records (trajectory.h).
#include "model/trajectory.h"

namespace ib {

// Reserves room for n samples in every per-sample series. The contact events are not per sample and
// are left alone: a run has far fewer of them than samples.
void Trajectory::reserve(std::size_t n) {
  time_s.reserve(n);
  for (int f = 0; f < 2; ++f) {
    displacement_m[f].reserve(n);
    velocity_m_s[f].reserve(n);
    acceleration_m_s2[f].reserve(n);
    peak_abs_acceleration_m_s2[f].reserve(n);
  }
  contact_force_n.reserve(n);
  peak_contact_force_n.reserve(n);
  mechanical_energy_j.reserve(n);
}

const char* to_string(RunStatus status) {
  switch (status) {
    case RunStatus::ok:
      return "ok";
    case RunStatus::unstable:
      return "unstable";
    case RunStatus::failed:
      return "failed";
  }
  return "unknown";
}

}  // namespace ib
