// The rig of rig.md section 4 in Siconos's own terms (adapters/siconos/README.md): both frames' chains as one
// Lagrangian system in their hinge angles (M q'' + C q' + K q = f_ext, each chain linearised about the straight
// rest state as physics/link_chain.h does), stepped by Moreau-Jean time stepping (MoreauJeanOSI, the theta
// method). The contact is one of: Newton's impact law (NewtonImpactNSL) on the gap between the tips (a
// LagrangianLinearTIR), an LCP at every step; the law's force as a smooth internal force of the system,
// integrated implicitly by Moreau-Jean's Newton loop; or none (the harness's force through f_ext). Siconos's headers
// stay in the .cpp: they take seconds to parse, and nothing else needs them.
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <optional>
#include <string>

#include "adapters/common/rig.h"

namespace ib::siconos {

enum class SystemContact {
  newton_impact,  // NewtonImpactNSL on the gap, with impact_restitution
  smooth_force,   // the rig's law (Hertz, the spring-dashpot) as an internal force of the system
  external,       // none of Siconos's: the harness's force through the tips' external forces
};

struct SiconosModelSettings {
  double time_step_s = 0;
  double theta = 0.5;  // MoreauJeanOSI's theta: 0.5 its default (trapezoidal), 1 backward Euler
  SystemContact contact = SystemContact::external;
  double impact_restitution = 0;  // newton_impact's e [-]
  double newton_tolerance = 0;    // smooth_force: the tolerance of Moreau-Jean's Newton loop
};

class SiconosRig {
 public:
  // Builds both chains from the rig with the hinge angles `angles_rad` and rates `rates_rad_s` as the
  // initial state; nothing is stepped yet. Moreau-Jean's first step weighs the forces at its start by
  // 1 - theta, and Siconos evaluates them when it initialises: with `previous_tip_forces_n`, the tip forces
  // held over the step that led to the initial state (zero at a run's start), so that a continued run steps
  // as the run it continues would have.
  SiconosRig(const RigSpec& rig, const SiconosModelSettings& settings, const std::array<Eigen::VectorXd, 2>& angles_rad,
             const std::array<Eigen::VectorXd, 2>& rates_rad_s, const std::array<double, 2>& previous_tip_forces_n);
  ~SiconosRig();
  SiconosRig(const SiconosRig&) = delete;
  SiconosRig& operator=(const SiconosRig&) = delete;

  // The external forces along x on both tips for the coming step [N] (frame 1, frame 2), held over it.
  void set_tip_forces_n(double frame1_n, double frame2_n);
  // One step; a reason instead when Siconos threw (its message).
  std::optional<std::string> step();
  // Frame f's hinge angles [rad] and rates [rad/s] now.
  void hinge_state(int f, Eigen::VectorXd& angles_rad, Eigen::VectorXd& rates_rad_s) const;
  // The impulse between the tips over the last step [N s] (Newton's law; 0 without it).
  double impulse_n_s() const;
  // The time step Siconos's time discretisation advances by [s].
  double time_step_s() const;
  // The Newton iterations of the last step (1 for a linear system).
  int newton_iterations() const;

 private:
  struct Objects;  // the Siconos objects (siconos_rig.cpp)
  std::unique_ptr<Objects> objects_;
  double impulse_n_s_ = 0;  // lambda(1) of the last step: the impulse of its velocity-level LCP on the gap [N s]
};

// A function of Siconos's kernel library (provenance.json: the file this process loaded).
const void* kernel_library_function();
// The restitution of NewtonImpactNSL as its users leave it (its default constructor's), read from the library.
double default_impact_restitution();
// MoreauJeanOSI's default theta, read from the library.
double default_theta();

}  // namespace ib::siconos
