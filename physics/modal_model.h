// The reference's model of one run: both frames' modes, the gap, the motor (if any) and the chosen
// contact law, in the unified form the solver integrates. What does not change during a run.
//
// The modes of both frames are stacked, frame 1's first: q = [W_1..W_N1, V_1..V_N2]. With
//   contact_lever b = [phi_n(L), -psi_n(L)]  and  motor_lever p = [phi_n(L), 0],
// the equations of rig.md section 2 read, for every stacked mode m,
//   q_m'' + 2 zeta_m omega_m q_m' + omega_m^2 q_m = p_m F_m(t) - b_m F_c,
//   indentation delta = b . q - d,  its rate delta' = b . q'.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>

#include "model/scenario.h"
#include "physics/contact_laws.h"
#include "physics/link_chain.h"
#include "physics/modal_basis.h"

namespace ib {

// Which modes the reference runs on.
enum class ModeSet {
  beam,        // continuous beam, corrected shapes (rig.md section 2): the physical ground truth
  beam_paper,  // continuous beam, the paper's eq. 2.5 shapes (opt-in, to reproduce the publication)
  chain,       // the K-link chain the engines build (rig.md section 4): isolates an engine's contact handling
};
const char* to_string(ModeSet set);

struct ModeSelection {
  ModeSet set = ModeSet::beam;
  int modes_per_frame = 10;                          // N, for the beam mode sets
  int chain_links = 16;                              // K, for the chain (all K modes are used)
  ChainDamping chain_damping = ChainDamping::modal;  // the chain's damping, as the engine's (rig.md section 4)
};

// F_m(t) = amplitude cos(omega t).
struct MotorForce {
  double amplitude_n = 0;  // m_u e_u Omega^2 [N]
  double omega_rad_s = 0;  // Omega [rad/s]
  double at(double t) const;
  double rate_at(double t) const;  // dF_m/dt [N/s]
};

// The unbalanced motor of a scenario as a force on frame 1's tip: m_u e_u Omega^2 at Omega = 2 pi
// motor_frequency_hz. The one place that writes it; absent without a motor.
std::optional<MotorForce> motor_force(const Scenario& scenario);

struct ModalModel {
  std::array<ModalBasis, 2> frames;
  double gap_m = 0;
  std::optional<MotorForce> motor;  // absent: no motor force at all
  ContactModel contact;

  // The stacked form (derived from the above by finalise()).
  Eigen::VectorXd omega_rad_s, zeta, contact_lever, motor_lever;
  int mode_count() const { return static_cast<int>(omega_rad_s.size()); }
  int frame_mode_count(int frame) const { return frames[frame].size(); }
  // 1 / sum b_m^2: effective mass of the relative tip motion for an impulse [kg]
  double contact_effective_mass_kg() const { return 1.0 / contact_lever.squaredNorm(); }
  void finalise();
};

// Frame 1's first natural frequency as a continuous beam with its tip mass [Hz]: what a scenario's
// speed_ratio_to_f1 refers to, whatever model a run uses.
double frame1_first_frequency_hz(const Scenario& scenario);
// The motor speed of a scenario [Hz]; 0 when it has no motor.
double motor_frequency_hz(const Scenario& scenario);
// How long a start from rest takes to settle without impacts [s]: the time in which each frame's first
// mode's free response decays to 5 % of its start, ln(20) / (zeta omega_1), the longer of the two frames
// (impacts dissipate too, so an impacting case may settle sooner). 0 without a motor (nothing to settle
// to); infinite for an undamped frame.
double start_up_transient_s(const Scenario& scenario);

ModalBasis frame_modes(const FrameSpec& frame, const ModeSelection& selection);
ModalModel build_modal_model(const Scenario& scenario, ContactLaw law, const ModeSelection& selection);

// The state of the stacked modes: displacements q and velocities q'.
struct ModalState {
  Eigen::VectorXd q, v;
};

// Initial state of a scenario: frame 1 in its static tip-load shape with the scenario's tip
// displacement (the shape that a static tip force gives in this mode set, q_n = phi_n(L) P / omega_n^2),
// everything at rest.
ModalState initial_state(const Scenario& scenario, const ModalModel& model);

}  // namespace ib
