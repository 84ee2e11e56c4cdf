#include "adapters/common/step_recorder.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ib {

StepRecorder::StepRecorder(double series_start_s, double end_s, double rate_hz)
    : start_s_(series_start_s), end_s_(end_s), rate_hz_(rate_hz) {
  out_.output_rate_hz = rate_hz;
  out_.start_time_s = series_start_s;
  total_samples_ =
      end_s >= series_start_s ? static_cast<long long>(std::floor((end_s - series_start_s) * rate_hz + 1e-9)) + 1 : 0;
  out_.reserve(static_cast<std::size_t>(total_samples_));
}

namespace {
constexpr double kZoomMargin_s = 1e-3;         // before the onset and after the end of the zoomed impact
constexpr std::size_t kZoomMaxSteps = 200000;  // a sticking contact must not fill the memory
}  // namespace

bool StepRecorder::needs_energy(double t, double step_s) const {
  // the state before the first sample is at most one step earlier; the zoom's steps start at most one
  // margin before an onset in the window
  return steps_ < 0 || t + step_s >= start_s_ - kZoomMargin_s;
}

void StepRecorder::record(const StepState& s) {
  ++steps_;
  if (steps_ == 0) {  // the initial state
    previous_ = s;
    out_.initial_mechanical_energy_j = s.energy_j;
    sample_between(s, s, {0, 0});
    return;
  }
  const double h = s.t - previous_.t;
  const std::array<double, 2> acceleration = {(s.velocity_m_s[0] - previous_.velocity_m_s[0]) / h,
                                              (s.velocity_m_s[1] - previous_.velocity_m_s[1]) / h};
  for (int f = 0; f < 2; ++f) peak_acc_[f] = std::max(peak_acc_[f], std::abs(acceleration[f]));
  peak_force_ = std::max(peak_force_, s.contact_force_n);
  // contact episodes: maximal runs of steps with a force
  const bool was_in_contact = in_contact_;
  if (s.contact_force_n != 0) {
    if (!in_contact_) {
      in_contact_ = true;
      episode_ = ContactEvent{};
      episode_.onset_time_s = previous_.t;
      // closing speed at the onset: from the tips' velocities before the step
      episode_.approach_velocity_m_s = previous_.velocity_m_s[0] - previous_.velocity_m_s[1];
    }
    episode_.peak_force_n = std::max(episode_.peak_force_n, s.contact_force_n);
    episode_.impulse_n_s += s.contact_force_n * h;
    episode_.max_indentation_m = std::max(episode_.max_indentation_m, s.indentation_m);
  } else if (in_contact_) {
    close_episode(previous_);
  }
  sample_between(previous_, s, acceleration);
  keep_for_zoom({s.t, s.displacement_m, s.velocity_m_s, acceleration, s.contact_force_n, s.energy_j},
                in_contact_ && !was_in_contact, was_in_contact && !in_contact_);
  previous_ = s;
}

void StepRecorder::keep_for_zoom(const StepSample& sample, bool episode_started, bool episode_ended) {
  if (zoom_done_) return;  // the first impact of the window is kept; nothing more to capture
  if (episode_started && !capturing_ && episode_.onset_time_s >= start_s_) {
    capturing_ = true;
    // the steps from the margin before the onset on (recent_ may still hold older ones, dropped in batches)
    capture_.assign(recent_.begin() + static_cast<std::ptrdiff_t>(recent_stale_), recent_.end());
    capture_until_ = std::numeric_limits<double>::infinity();
  }
  if (capturing_) {
    capture_.push_back(sample);
    if (episode_ended) capture_until_ = std::min(capture_until_, sample.t + kZoomMargin_s);
    if (sample.t >= capture_until_ || capture_.size() >= kZoomMaxSteps) end_capture();
    return;
  }
  recent_.push_back(sample);
  // steps older than the margin are dropped in batches of more than 64 (one move per batch, not one per
  // step); the scan resumes where it stopped instead of rereading the stale ones every step
  while (recent_stale_ < recent_.size() && recent_[recent_stale_].t < sample.t - kZoomMargin_s) ++recent_stale_;
  if (recent_stale_ > 64) {
    recent_.erase(recent_.begin(), recent_.begin() + static_cast<std::ptrdiff_t>(recent_stale_));
    recent_stale_ = 0;
  }
}

void StepRecorder::end_capture() {
  capturing_ = false;
  zoom_done_ = true;
  zoomed_.swap(capture_);
  capture_.clear();
  recent_.clear();
  recent_stale_ = 0;
}

Trajectory StepRecorder::impact_zoom() const {
  Trajectory z;
  z.reserve(zoomed_.size());
  for (const StepSample& s : zoomed_) {
    z.time_s.push_back(s.t);
    for (int f = 0; f < 2; ++f) {
      z.displacement_m[f].push_back(s.displacement[f]);
      z.velocity_m_s[f].push_back(s.velocity[f]);
      z.acceleration_m_s2[f].push_back(s.acceleration[f]);
      z.peak_abs_acceleration_m_s2[f].push_back(std::abs(s.acceleration[f]));
    }
    z.contact_force_n.push_back(s.force);
    z.peak_contact_force_n.push_back(s.force);
    z.mechanical_energy_j.push_back(s.energy);
  }
  if (z.size() >= 2) {
    z.start_time_s = z.time_s.front();
    z.output_rate_hz = static_cast<double>(z.size() - 1) / (z.time_s.back() - z.time_s.front());
  }
  return z;
}

void StepRecorder::close_episode(const StepState& last) {
  in_contact_ = false;
  episode_.end_time_s = last.t;
  episode_.rebound_velocity_m_s = last.velocity_m_s[1] - last.velocity_m_s[0];
  episode_.restitution =
      episode_.approach_velocity_m_s > 0 ? episode_.rebound_velocity_m_s / episode_.approach_velocity_m_s : 0;
  out_.events.push_back(episode_);
}

void StepRecorder::sample_between(const StepState& a, const StepState& b, const std::array<double, 2>& acceleration) {
  for (; next_sample_ < total_samples_; ++next_sample_) {
    const double t = start_s_ + static_cast<double>(next_sample_) / rate_hz_;
    if (t > b.t + 1e-12 * std::max(1.0, std::abs(b.t))) break;
    const double w = b.t > a.t ? std::clamp((t - a.t) / (b.t - a.t), 0.0, 1.0) : 1.0;
    out_.time_s.push_back(t);
    for (int f = 0; f < 2; ++f) {
      out_.displacement_m[f].push_back(a.displacement_m[f] + w * (b.displacement_m[f] - a.displacement_m[f]));
      out_.velocity_m_s[f].push_back(a.velocity_m_s[f] + w * (b.velocity_m_s[f] - a.velocity_m_s[f]));
      out_.acceleration_m_s2[f].push_back(acceleration[f]);
      // the first sample has no interval before it; later ones carry the largest step acceleration since
      out_.peak_abs_acceleration_m_s2[f].push_back(next_sample_ == 0 ? std::abs(acceleration[f]) : peak_acc_[f]);
    }
    out_.contact_force_n.push_back(b.contact_force_n);
    out_.peak_contact_force_n.push_back(next_sample_ == 0 ? b.contact_force_n : peak_force_);
    // a step that goes on past the sample belongs to the next interval too
    const bool step_continues = t < b.t;
    for (int f = 0; f < 2; ++f) peak_acc_[f] = step_continues ? std::abs(acceleration[f]) : 0;
    peak_force_ = step_continues ? b.contact_force_n : 0;
    out_.mechanical_energy_j.push_back(a.energy_j + w * (b.energy_j - a.energy_j));
  }
}

Trajectory StepRecorder::finish() {
  if (in_contact_) close_episode(previous_);
  if (capturing_) end_capture();
  return std::move(out_);
}

}  // namespace ib
