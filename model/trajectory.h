// What every simulator returns: sampled tip motion, the exact extrema between samples, and one record
// per contact episode. Plain records; the metrics are computed from these alone (rig.md section 5).
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "model/saved_state.h"

namespace ib {

// One contact episode: from the first onset to the separation (rig.md section 5).
// For the instantaneous Newton law onset == end and the peak force is not defined (NaN).
struct ContactEvent {
  double onset_time_s = 0;
  double end_time_s = 0;
  double approach_velocity_m_s = 0;  // delta' at onset (> 0: closing)
  double rebound_velocity_m_s = 0;   // -delta' at separation (> 0: opening)
  double restitution = 0;            // rebound / approach [-]
  double peak_force_n = 0;           // max contact force [N]
  double impulse_n_s = 0;            // integral of the contact force [N s]
  double max_indentation_m = 0;      // max delta [m]
};

// Uniform samples at output_rate_hz from start_time_s; column k of frame f is series[f][k].
// The peak_* columns hold the exact maximum over the interval that ends at the sample,
// (t_{k-1}, t_k], so that true peaks between samples are not lost; at k = 0 they hold the sample value.
struct Trajectory {
  double output_rate_hz = 0;
  double start_time_s = 0;
  std::vector<double> time_s;
  std::array<std::vector<double>, 2> displacement_m;  // tip displacement, positive toward frame 2
  std::array<std::vector<double>, 2> velocity_m_s;
  std::array<std::vector<double>, 2> acceleration_m_s2;
  std::vector<double> contact_force_n;
  std::array<std::vector<double>, 2> peak_abs_acceleration_m_s2;
  std::vector<double> peak_contact_force_n;
  // Mechanical energy of the whole rig at each sample [J] (kinetic + elastic, contact spring included),
  // for the "energy grows without input" verdict; empty when a simulator cannot provide it.
  std::vector<double> mechanical_energy_j;
  // The rig's mechanical energy at t = 0 [J] (NaN when unknown): the baseline of the energy verdict and
  // of the energy change, since the series itself may start long after the run did.
  double initial_mechanical_energy_j = std::numeric_limits<double>::quiet_NaN();

  std::vector<ContactEvent> events;  // every contact episode of the whole run, in time order

  std::size_t size() const { return time_s.size(); }
  void reserve(std::size_t n);
};

// Where a run ended and why; an unstable or failed run still returns what it computed.
enum class RunStatus { ok, unstable, failed };
const char* to_string(RunStatus status);

struct RunCost {
  double wall_time_s = 0;
  double cpu_time_s = 0;
  long long steps = 0;  // time steps (engines) or accepted integrator steps (reference)
};

struct RunResult {
  Trajectory trajectory;
  // The first impact in the scoring window, finely resolved: every step of a fixed-step engine (the
  // reference: 1 MHz samples) from 1 ms before its onset to 1 ms after its end. Series only; may be empty.
  Trajectory impact_zoom;
  RunStatus status = RunStatus::ok;
  std::string reason;  // why the run is not ok, in words a person can check
  RunCost cost;
  // The fixed step the run advanced by, the one its record carries (runs.csv time_step_s) [s]; 0 for an
  // adaptive run (the reference) or one that never reached the loop (a model that did not build).
  double time_step_s = 0;
  std::vector<std::pair<std::string, double>> diagnostics;  // simulator-specific figures (named, SI)
  // The simulator's state at the run's end, to continue from (RunSettings::initial_state); empty when
  // the run did not reach its end.
  std::optional<SavedState> final_state;
};

}  // namespace ib
