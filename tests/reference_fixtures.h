// Shared set-ups for the reference's tests: the published scenarios and ideal models whose contact
// problem has a closed form.
#pragma once

#include <cmath>
#include <string>

#include "model/scenario_toml.h"
#include "physics/modal_model.h"
#include "reference/reference_solver.h"

namespace ib::testing {

inline Scenario paper_scenario(const std::string& name) {
  return load_scenario(std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/paper/" + name + ".toml");
}

// One undamped "mode" per frame with a vanishing frequency: two free point masses m1, m2 on a line.
// Their contact is a one-degree-of-freedom problem with the reduced mass m1 m2 / (m1 + m2).
inline ModalModel two_free_masses(double m1_kg, double m2_kg, double gap_m, ContactModel law) {
  ModalModel model;
  const double slow = 1e-4;  // rad/s: the "structure" does nothing within a contact
  for (int f = 0; f < 2; ++f) {
    model.frames[f].omega_rad_s = Eigen::VectorXd::Constant(1, slow);
    model.frames[f].zeta = Eigen::VectorXd::Zero(1);
    model.frames[f].tip = Eigen::VectorXd::Constant(1, 1 / std::sqrt(f == 0 ? m1_kg : m2_kg));
  }
  model.gap_m = gap_m;
  model.contact = law;
  model.finalise();
  return model;
}

// Frame 1 moving toward frame 2 at approach_m_s, both tips at rest position.
inline ModalState approaching(const ModalModel& model, double approach_m_s) {
  ModalState x{Eigen::VectorXd::Zero(model.mode_count()), Eigen::VectorXd::Zero(model.mode_count())};
  x.v[0] = approach_m_s / model.frames[0].tip[0];
  return x;
}

inline ReferenceSolution solve(const ModalModel& model, const ModalState& x0, double duration_s,
                               ReferenceSettings settings = {}, double rate_hz = 1000) {
  OutputWindow window{0, duration_s, rate_hz};
  return solve_reference(model, x0, duration_s, window, settings);
}

}  // namespace ib::testing
