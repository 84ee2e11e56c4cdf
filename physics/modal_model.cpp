#include "physics/modal_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "physics/beam_modes.h"
#include "physics/link_chain.h"

namespace ib {

namespace {
constexpr double kTwoPi = 6.28318530717958647692;
}

const char* to_string(ModeSet set) {
  switch (set) {
    case ModeSet::beam:
      return "beam";
    case ModeSet::beam_paper:
      return "beam_paper";
    case ModeSet::chain:
      return "chain";
  }
  return "?";
}

double MotorForce::at(double t) const { return amplitude_n * std::cos(omega_rad_s * t); }
double MotorForce::rate_at(double t) const { return -amplitude_n * omega_rad_s * std::sin(omega_rad_s * t); }

void ModalModel::finalise() {
  const int n1 = frames[0].size(), n2 = frames[1].size();
  omega_rad_s.resize(n1 + n2);
  zeta.resize(n1 + n2);
  contact_lever.resize(n1 + n2);
  motor_lever.setZero(n1 + n2);
  omega_rad_s << frames[0].omega_rad_s, frames[1].omega_rad_s;
  zeta << frames[0].zeta, frames[1].zeta;
  contact_lever << frames[0].tip, -frames[1].tip;
  motor_lever.head(n1) = frames[0].tip;
}

double frame1_first_frequency_hz(const Scenario& scenario) {
  return CantileverModes(scenario.frames[0], 1).omega_rad_s(0) / kTwoPi;
}

double motor_frequency_hz(const Scenario& scenario) {
  if (!scenario.motor) return 0;
  if (scenario.motor->frequency_hz) return *scenario.motor->frequency_hz;
  return *scenario.motor->speed_ratio_to_f1 * frame1_first_frequency_hz(scenario);
}

double start_up_transient_s(const Scenario& scenario) {
  if (!scenario.motor) return 0;
  double longest = 0;
  for (const FrameSpec& frame : scenario.frames) {
    const double omega_1 = CantileverModes(frame, 1).omega_rad_s(0);
    // Undamped, a start-up transient never decays.
    longest = frame.damping_ratio > 0 ? std::max(longest, std::log(20.0) / (frame.damping_ratio * omega_1))
                                      : std::numeric_limits<double>::infinity();
  }
  return longest;
}

ModalBasis frame_modes(const FrameSpec& frame, const ModeSelection& selection) {
  switch (selection.set) {
    case ModeSet::beam:
      return CantileverModes(frame, selection.modes_per_frame).basis();
    case ModeSet::beam_paper:
      return CantileverModes(frame, selection.modes_per_frame, BeamShapes::paper_eq_2_5).basis();
    case ModeSet::chain:
      return chain_modes(build_link_chain(frame, selection.chain_links, selection.chain_damping));
  }
  throw std::logic_error("unknown mode set");
}

std::optional<MotorForce> motor_force(const Scenario& scenario) {
  if (!scenario.motor) return std::nullopt;
  const double omega = kTwoPi * motor_frequency_hz(scenario);
  return MotorForce{scenario.motor->unbalance_mass_kg * scenario.motor->unbalance_radius_m * omega * omega, omega};
}

ModalModel build_modal_model(const Scenario& scenario, ContactLaw law, const ModeSelection& selection) {
  ModalModel model;
  for (int f = 0; f < 2; ++f) model.frames[f] = frame_modes(scenario.frames[f], selection);
  model.gap_m = scenario.gap_m;
  model.motor = motor_force(scenario);
  model.contact = make_contact_model(scenario, law);
  model.finalise();
  return model;
}

ModalState initial_state(const Scenario& scenario, const ModalModel& model) {
  const int n = model.mode_count(), n1 = model.frame_mode_count(0);
  ModalState state{Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n)};
  const double tip = scenario.initial.frame1_tip_displacement_m;
  if (tip != 0) {
    const ModalBasis& frame1 = model.frames[0];
    const double tip_force = tip / frame1.tip_static_compliance_m_per_n();  // P such that u(L) = tip
    state.q.head(n1) = (frame1.tip.array() * tip_force / frame1.omega_rad_s.array().square()).matrix();
  }
  return state;
}

}  // namespace ib
