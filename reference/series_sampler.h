// The reference's output, internal to the reference solver: the state of both tips at one instant, and
// the sampler that turns the states the solver visits, in time order, into the series with the exact
// peaks between samples.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "model/trajectory.h"
#include "reference/reference_solver.h"

namespace ib::reference_internal {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Kinematics of both tips and the contact at one instant; derivatives included so that extrema
// between samples can be located (jerk for acceleration peaks, dF/dt for force peaks).
struct TipState {
  double t = 0;
  std::array<double, 2> displacement{}, velocity{}, acceleration{}, jerk{};
  double indentation = 0, indentation_rate = 0;  // delta [m], delta' [m/s]
  double force = 0, force_rate = 0;              // F_c [N], dF_c/dt [N/s]
  double energy = 0;                             // mechanical energy [J]
};

// Samples the output series and keeps the exact maximum of |acceleration| and of the force over
// each output interval [t_{k-1}, t_k] (the sample that opens it included) from every value it is fed in time order.
class SeriesRecorder {
 public:
  SeriesRecorder(const OutputWindow& window, Trajectory& out) : window_(window), out_(out) {
    out_.output_rate_hz = window.rate_hz;
    out_.start_time_s = window.start_s;
    const double count = std::floor((window.end_s - window.start_s) * window.rate_hz + 1e-9) + 1;
    total_ = window.end_s >= window.start_s ? static_cast<long long>(count) : 0;
    out_.reserve(static_cast<std::size_t>(total_));
  }
  double sample_interval_s() const { return 1 / window_.rate_hz; }
  double next_sample_time() const {
    return index_ < total_ ? window_.start_s + static_cast<double>(index_) / window_.rate_hz : kInf;
  }
  // Whether an interval ending at t holds anything to record (samples or peaks).
  bool wants(double t) const { return index_ < total_ && (index_ > 0 || t >= window_.start_s); }
  void feed(const TipState& s) {
    if (index_ == 0) return;  // peaks count from the first sample on
    for (int f = 0; f < 2; ++f) peak_acc_[f] = std::max(peak_acc_[f], std::abs(s.acceleration[f]));
    peak_force_ = std::max(peak_force_, s.force);
  }
  void sample(const TipState& s) {
    out_.time_s.push_back(s.t);
    for (int f = 0; f < 2; ++f) {
      out_.displacement_m[f].push_back(s.displacement[f]);
      out_.velocity_m_s[f].push_back(s.velocity[f]);
      out_.acceleration_m_s2[f].push_back(s.acceleration[f]);
      const double a = std::abs(s.acceleration[f]);
      out_.peak_abs_acceleration_m_s2[f].push_back(index_ == 0 ? a : std::max(peak_acc_[f], a));
      peak_acc_[f] = a;  // the sample opens the next interval
    }
    out_.contact_force_n.push_back(s.force);
    out_.mechanical_energy_j.push_back(s.energy);
    out_.peak_contact_force_n.push_back(index_ == 0 ? s.force : std::max(peak_force_, s.force));
    peak_force_ = s.force;
    ++index_;
  }

 private:
  OutputWindow window_;
  Trajectory& out_;
  long long index_ = 0, total_ = 0;
  std::array<double, 2> peak_acc_{};
  double peak_force_ = 0;
};

}  // namespace ib::reference_internal
