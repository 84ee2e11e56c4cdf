// The reference's modal model as JSON, for another solver to integrate the same equations
// (`impactbench export SCENARIO --engine reference`; bench/scipy_reference.py reads it):
//
//   q_m'' + 2 zeta_m omega_m q_m' + omega_m^2 q_m = p_m F_m(t) - b_m F_c,   m over both frames' stacked modes,
//   indentation delta = b . q - gap,  F_m(t) = amplitude cos(omega t),  F_c from the chosen law,
//   recorded tip displacement of frame f = lever_f . q (velocity lever_f . q', acceleration lever_f . q'').
//
// Every key names its unit; modal coordinates are in m sqrt(kg) (the modes are mass-normalised, their
// tip values in 1/sqrt(kg)). Only the chosen law's parameters are written; "motor" is absent when the
// scenario has none.
#pragma once

#include <string>

#include "model/scenario.h"
#include "physics/modal_model.h"
#include "reference/reference_solver.h"

namespace ib {

// Which run the model is for: the scenario, how long, which samples, which window is scored.
struct ModelRunInfo {
  std::string scenario_name, scenario_file;
  double duration_s = 0;
  double series_start_s = 0;     // first output sample [s]
  double output_rate_hz = 4096;  // output samples per second [Hz]
  ScoringWindow scoring_window;  // metrics over [start, end] (keys scoring_window_start_s, _end_s)
};

// The model, its initial state, the run and the reference's own settings (its tolerances, for
// a solver that wants to match them), as indented JSON text.
std::string modal_model_json(const ModalModel& model, const ModalState& initial, const ModelRunInfo& run,
                             const ReferenceSettings& settings);

}  // namespace ib
