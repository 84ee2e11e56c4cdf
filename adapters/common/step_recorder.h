// Turns a fixed-step engine's per-step states into the harness's Trajectory, the same way for every
// engine: output samples by linear interpolation between steps, the tip acceleration of each step from
// its velocity change (what a fixed-step engine resolves), the largest of those per output interval as
// the true peak, and one contact episode per run of steps with a contact force (a contact counts when
// the engine applies a force, not when the bodies are merely within a margin). The reference counts
// an episode the same way: while the tips exchange a force.
#pragma once

#include <array>
#include <limits>

#include "model/trajectory.h"

namespace ib {

// The state after a step (or at t = 0).
struct StepState {
  double t = 0;
  std::array<double, 2> displacement_m{};  // tip displacement along x from rest, positive toward frame 2
  std::array<double, 2> velocity_m_s{};
  double contact_force_n = 0;  // force between the tips during the step [N]: > 0 compressive,
                               // < 0 only where a law pulls (the published spring-dashpot, injected)
  double indentation_m = 0;    // u1 - u2 - gap at the end of the step [m]
  double energy_j = 0;         // mechanical energy at the end of the step [J]
};

class StepRecorder {
 public:
  // Samples at rate_hz from series_start_s to end_s (inclusive).
  StepRecorder(double series_start_s, double end_s, double rate_hz);

  // Every state in time order, the initial one first. A step's acceleration and force are attributed
  // to the interval since the previous state.
  void record(const StepState& state);

  // Whether the next state recorded, at time t after a step of step_s, needs its energy_j: the initial
  // state does (the initial energy), and so does every state from the impact zoom's margin before the
  // series start on (samples interpolate it, the zoom keeps it). Before that nothing reads it.
  bool needs_energy(double t, double step_s) const;
  // energy_j for that state: energy() where it is needed, NaN elsewhere, so that the engines skip the
  // chain's quadratic forms (every step) where nothing reads them.
  template <class Energy>
  double energy_where_needed(double t, double step_s, Energy&& energy) const {
    return needs_energy(t, step_s) ? energy() : std::numeric_limits<double>::quiet_NaN();
  }

  long long steps() const { return steps_; }
  Trajectory finish();
  // The first impact whose onset lies in the series window: every step from 1 ms before its onset to
  // 1 ms after its end (call after finish()). The first, not the strongest: every simulator then shows
  // the same impact (in a free vibration the same physical one; in a chaotic forced case the window's
  // first), which the report compares like with like.
  Trajectory impact_zoom() const;

 private:
  struct StepSample {
    double t;
    std::array<double, 2> displacement, velocity, acceleration;
    double force, energy;
  };
  void keep_for_zoom(const StepSample& sample, bool episode_started, bool episode_ended);
  void end_capture();

  void sample_between(const StepState& a, const StepState& b, const std::array<double, 2>& acceleration);
  void close_episode(const StepState& last);

  Trajectory out_;
  double start_s_, end_s_, rate_hz_;
  long long next_sample_ = 0, total_samples_ = 0, steps_ = -1;
  StepState previous_{};
  std::array<double, 2> peak_acc_{};
  double peak_force_ = 0;
  bool in_contact_ = false;
  ContactEvent episode_;
  // impact zoom: the last 1 ms of steps, the impact being captured, the impact kept
  std::vector<StepSample> recent_, capture_, zoomed_;
  std::size_t recent_stale_ = 0;  // recent_[0, recent_stale_) are older than the zoom's margin
  bool capturing_ = false, zoom_done_ = false;
  double capture_until_ = 0;
};

}  // namespace ib
