// The reference solver: event-driven integration of the modal equations with contact.
//
//  - Free flight (no contact force): exact closed-form propagation (FreeFlight), in steps that bounds on
//    the modal amplitudes prove contact-free where they can, else on a grid of grid_points_per_period
//    steps per period of the fastest mode; contact onset located by TOMS 748 on the closed form, with
//    the indentation's local maxima between grid points checked so that grazing contacts are not missed.
//  - Compliant contact (Hertz, spring-dashpot): adaptive Dormand-Prince 5(4) with dense output
//    (Boost.Odeint) at the given tolerances; separation located on the dense output, then the last
//    step is retaken exactly to the separation time.
//  - Newton: the modal impulse map at each located impact; when the impacts would accumulate within
//    accumulation_time_s the tips are made to stick (plastic impulse) and a sticking phase holds
//    delta = 0 with the constraint force until that force would turn tensile.
// Deterministic: no threads, no randomness; the same input gives the same bits.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "model/trajectory.h"
#include "physics/modal_model.h"

namespace ib {

struct ReferenceSettings {
  ModeSelection modes;
  double relative_tolerance = 1e-9;   // Dormand-Prince rtol [-]
  double absolute_tolerance = 1e-12;  // Dormand-Prince atol, on modal coordinates [sqrt(kg) m, sqrt(kg) m/s]
  int grid_points_per_period = 8;     // free-flight scan grid per period of the fastest mode [-]
  double max_grid_step_s = 1e-3;      // and never coarser than this [s] (bounds the step for slow models)
  // Outside the output window, free flight first tries steps sized for the slowest modes
  // (this many per frame), taken only where a bound on the faster modes proves that no contact can
  // start within them, and multiples of them (up to 2^long_step_doublings) where the slow modes' closing
  // speed cannot cover the distance left within them; elsewhere it scans the fine grid. 0: always the fine grid.
  int slow_modes_per_frame = 3;
  int long_step_doublings = 6;                  // 0: coarse steps only
  double accumulation_time_s = 1e-6;            // Newton: stick when impacts would accumulate within this [s]
  long long max_contact_episodes = 50'000'000;  // a run that needs more is stopped, never loops forever
  bool track_energy = true;                     // energy ledger (motor work, dissipations) alongside
  // The exact peaks of |acceleration| and force between output samples in free flight (the series' peak
  // columns, the true peak metric). Off: free flight's peak columns hold the samples' own values (contacts keep
  // their exact peaks), and free flight steps over the output window as it does outside it, where no contact
  // can start, sampling along: for a caller that reads only the samples and the events.
  bool peaks_between_samples = true;
  // Keep the free-flight starts from this time on and the last one before it (ReferenceSolution::flight_starts),
  // so that a later stretch of the run can be solved again from there; infinity: none kept [s].
  double keep_flight_starts_from_s = std::numeric_limits<double>::infinity();
};

// Where a free flight began after a contact: the time and the state the contact (or the Newton impulse) left.
struct FlightStart {
  double t_s = 0;
  ModalState state;
};

// Where the output series is sampled: uniform samples at rate_hz from start_s to end_s (inclusive).
struct OutputWindow {
  double start_s = 0;
  double end_s = 0;
  double rate_hz = 4096;
};

// Energy bookkeeping over the whole run [J]: motor work = change of mechanical energy + structural
// dissipation + contact dissipation. Mechanical energy is modal kinetic and strain energy plus the
// elastic contact energy while in contact.
struct EnergyLedger {
  double initial_energy_j = 0;
  double final_energy_j = 0;
  double motor_work_j = 0;
  double structural_dissipation_j = 0;
  double contact_dissipation_j = 0;
  // |work - (dE + dissipations)| / max(|work|, the largest term): the balance's relative residual
  double relative_residual() const;
};

struct ReferenceSolution {
  Trajectory trajectory;
  EnergyLedger energy;
  RunStatus status = RunStatus::ok;
  std::string reason;
  long long integrator_steps = 0;  // accepted Dormand-Prince steps
  long long grid_intervals = 0;    // free-flight fine-grid intervals scanned
  long long coarse_intervals = 0;  // free-flight coarse (and longer) steps taken on the bounds
  long long impacts = 0;           // contact episodes (Newton: impulses)
  long long sticking_phases = 0;
  double grid_step_s = 0;
  ModalState final_state;                  // the state at duration_s (a run that ended early: where it stopped)
  std::vector<FlightStart> flight_starts;  // in time order, as ReferenceSettings::keep_flight_starts_from_s asks
};

ReferenceSolution solve_reference(const ModalModel& model, const ModalState& initial, double duration_s,
                                  const OutputWindow& output, const ReferenceSettings& settings);

// A run continued from one of an earlier run's free-flight starts up to duration_s: the same phases as that
// run took from there (to rounding, where a different output window changes the free flight's steps). Its
// energy ledger covers [start.t_s, duration_s]. For a stretch of a long run solved again at another rate.
ReferenceSolution solve_reference_after_contact(const ModalModel& model, const FlightStart& start, double duration_s,
                                                const OutputWindow& output, const ReferenceSettings& settings);

}  // namespace ib
