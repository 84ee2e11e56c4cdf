#include "bench/contact_onsets.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "model/scenario_toml.h"
#include "reference/free_flight.h"
#include "reference/reference_solver.h"

namespace ib::bench {

CaseContacts contacts_of(const std::string& scenario_path, ContactLaw law, int max_contacts) {
  const Scenario scenario = load_scenario(scenario_path);
  ReferenceSettings settings;  // the defaults every run uses
  CaseContacts out;
  out.model = build_modal_model(scenario, law, settings.modes);
  const ModalModel& model = out.model;
  // The reference's largest contact step (reference/event_solver.h, Solver's constructor).
  double fastest = model.omega_rad_s.maxCoeff();
  if (model.motor) fastest = std::max(fastest, model.motor->omega_rad_s);
  out.max_step_s = std::min(2 * M_PI / fastest / settings.grid_points_per_period, settings.max_grid_step_s);

  settings.keep_flight_starts_from_s = 0;  // every free flight's start
  settings.track_energy = false;           // neither changes the phases, only what is recorded along
  settings.peaks_between_samples = false;
  const ModalState initial = initial_state(scenario, model);
  const OutputWindow one_sample{scenario.duration_s, scenario.duration_s, 4096};
  const ReferenceSolution run = solve_reference(model, initial, scenario.duration_s, one_sample, settings);
  if (run.status != RunStatus::ok)
    throw std::runtime_error(scenario_path + ": the reference run failed: " + run.reason);
  const std::vector<ContactEvent>& events = run.trajectory.events;
  out.contacts_in_run = static_cast<int>(events.size());
  if (events.empty()) throw std::runtime_error(scenario_path + ": the reference run has no contacts");

  const int chosen = std::min<int>(max_contacts, static_cast<int>(events.size()));
  const FreeFlight flight(model);
  ModalState x;
  for (int i = 0; i < chosen; ++i) {
    // evenly spread, the last contact included
    const std::size_t k = chosen == 1 ? 0 : static_cast<std::size_t>(i) * (events.size() - 1) / (chosen - 1);
    const ContactEvent& e = events[k];
    double t0 = 0;
    const ModalState* x0 = &initial;
    for (const FlightStart& f : run.flight_starts)  // the last flight that began before this onset
      if (f.t_s < e.onset_time_s) t0 = f.t_s, x0 = &f.state;
    // One closed-form advance over the whole flight rounds differently from the reference's grid steps: delta
    // there is off zero by ~1e-14 m, 1e-8 of a 10 us contact's duration. Newton on the closed form puts the onset
    // back on delta = 0 (a shift of ~1e-13 s), so that each phase starts where a contact starts.
    double t = e.onset_time_s, delta = 0;
    for (int iteration = 0; iteration < 4; ++iteration) {
      flight.advance(*x0, t0, t - t0, x);
      delta = model.contact_lever.dot(x.q) - model.gap_m;
      t -= delta / model.contact_lever.dot(x.v);
    }
    flight.advance(*x0, t0, t - t0, x);
    delta = model.contact_lever.dot(x.q) - model.gap_m;
    out.onsets.push_back({t, x});
    out.reference_events.push_back(e);
    out.worst_onset_indentation_m = std::max(out.worst_onset_indentation_m, std::abs(delta));
    out.largest_onset_shift_s = std::max(out.largest_onset_shift_s, std::abs(t - e.onset_time_s));
  }
  return out;
}

}  // namespace ib::bench
