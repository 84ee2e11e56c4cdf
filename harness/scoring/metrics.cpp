// Metrics from a trajectory and its contact events (rig.md section 5), the same for every simulator.
#include "harness/scoring/metrics.h"

#include "harness/scoring/amplitude_decay.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>

namespace ib {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A time that lies within this fraction of a sample interval of a sample is that sample: sensor window
// edges computed as start + k T land a rounding error away from the series' samples, and reading
// them as exact samples keeps a velocity jump between samples in exactly one sensor window.
constexpr double kSampleTolerance = 1e-6;

// ---- reading the series at any time ----------------------------------------------------------------

// The position of time t on the series' sample grid, in samples from the first one.
double sample_coordinate(const Trajectory& trajectory, double t) {
  return (t - trajectory.start_time_s) * trajectory.output_rate_hz;
}

bool covers(const Trajectory& trajectory, double t) {
  if (trajectory.size() == 0 || trajectory.output_rate_hz <= 0) return false;
  const double x = sample_coordinate(trajectory, t);
  return x >= -kSampleTolerance && x <= static_cast<double>(trajectory.size() - 1) + kSampleTolerance;
}

// The series' value at time t: the sample itself when t is (to the tolerance) a sample time, else the
// linear interpolation between the two neighbouring samples. Nothing outside the series' time span.
std::optional<double> value_at(const Trajectory& trajectory, const std::vector<double>& series, double t) {
  if (!covers(trajectory, t) || series.size() != trajectory.size()) return std::nullopt;
  const double x = sample_coordinate(trajectory, t);
  const double nearest = std::round(x);
  const std::size_t last = series.size() - 1;
  if (std::abs(x - nearest) < kSampleTolerance)
    return series[std::min(static_cast<std::size_t>(std::max(nearest, 0.0)), last)];
  const std::size_t i = std::min(static_cast<std::size_t>(std::floor(x)), last - 1);
  const double fraction = x - static_cast<double>(i);
  return series[i] + fraction * (series[i + 1] - series[i]);
}

// ---- samples in the window -------------------------------------------------------------------------

// The half-open index range [first, last) of the samples whose times lie in [start, end].
struct SampleRange {
  std::size_t first = 0;
  std::size_t last = 0;
  bool empty() const { return first >= last; }
};

SampleRange samples_in(const Trajectory& trajectory, double start_s, double end_s) {
  // the same tolerance as value_at, so that a sample on a window edge is inside the window
  const double tolerance = trajectory.output_rate_hz > 0 ? kSampleTolerance / trajectory.output_rate_hz : 0;
  const auto& t = trajectory.time_s;
  const auto first = std::lower_bound(t.begin(), t.end(), start_s - tolerance);
  const auto last = std::upper_bound(first, t.end(), end_s + tolerance);
  return {static_cast<std::size_t>(first - t.begin()), static_cast<std::size_t>(last - t.begin())};
}

// ---- per-frame figures -----------------------------------------------------------------------------

double max_abs(const std::vector<double>& values) {
  double peak = 0;
  for (double v : values) peak = std::max(peak, std::abs(v));
  return peak;
}

double max_abs(const std::vector<double>& series, SampleRange range) {
  double peak = 0;
  for (std::size_t k = range.first; k < range.last; ++k) peak = std::max(peak, std::abs(series[k]));
  return peak;
}

double rms(const std::vector<double>& series, SampleRange range) {
  double sum_of_squares = 0;
  for (std::size_t k = range.first; k < range.last; ++k) sum_of_squares += series[k] * series[k];
  return std::sqrt(sum_of_squares / static_cast<double>(range.last - range.first));
}

// The largest |acceleration| the simulator resolved in the window, between samples too. The peak
// column of the window's first sample covers the interval before it, outside the window, so that
// sample contributes its own value only. Without peak columns the samples are all there is.
double true_peak_acceleration(const Trajectory& trajectory, int frame, SampleRange range) {
  const std::vector<double>& sampled = trajectory.acceleration_m_s2[frame];
  const std::vector<double>& peaks = trajectory.peak_abs_acceleration_m_s2[frame];
  if (peaks.size() != trajectory.size()) return max_abs(sampled, range);
  double peak = std::abs(sampled[range.first]);
  for (std::size_t k = range.first + 1; k < range.last; ++k) peak = std::max(peak, peaks[k]);
  return peak;
}

FrameMetrics frame_metrics(const Trajectory& trajectory, int frame, const MetricSettings& settings,
                           const SensorSeries& sensor) {
  const SampleRange range = samples_in(trajectory, settings.window.start_s, settings.window.end_s);
  FrameMetrics m;
  // an empty window measures nothing: NaN, not a misleading zero
  m.sensor_peak_acceleration_g =
      sensor.acceleration_m_s2.empty() ? kNaN : max_abs(sensor.acceleration_m_s2) / kStandardGravity_m_s2;
  if (range.empty()) {
    m.true_peak_acceleration_g = m.rms_acceleration_g = m.peak_displacement_m = kNaN;
    return m;
  }
  m.true_peak_acceleration_g = true_peak_acceleration(trajectory, frame, range) / kStandardGravity_m_s2;
  m.rms_acceleration_g = rms(trajectory.acceleration_m_s2[frame], range) / kStandardGravity_m_s2;
  m.peak_displacement_m = max_abs(trajectory.displacement_m[frame], range);
  return m;
}

// ---- impacts ---------------------------------------------------------------------------------------

Impact start_impact(const ContactEvent& e) {
  Impact impact;
  impact.onset_time_s = e.onset_time_s;
  impact.end_time_s = e.end_time_s;
  impact.approach_velocity_m_s = e.approach_velocity_m_s;
  impact.rebound_velocity_m_s = e.rebound_velocity_m_s;
  impact.peak_force_n = e.peak_force_n;
  impact.impulse_n_s = e.impulse_n_s;
  impact.max_indentation_m = e.max_indentation_m;
  impact.onsets = 1;
  return impact;
}

// The larger of two peak forces, where NaN means "not defined" and loses to any number.
double larger_force(double a, double b) {
  if (std::isnan(a)) return b;
  if (std::isnan(b)) return a;
  return std::max(a, b);
}

// A later episode of the same impact: the impact now ends, and rebounds, where this episode does.
void join_impact(Impact& impact, const ContactEvent& e) {
  impact.end_time_s = e.end_time_s;
  impact.rebound_velocity_m_s = e.rebound_velocity_m_s;
  impact.peak_force_n = larger_force(impact.peak_force_n, e.peak_force_n);
  impact.impulse_n_s += e.impulse_n_s;
  impact.max_indentation_m = std::max(impact.max_indentation_m, e.max_indentation_m);
  ++impact.onsets;
}

void finish_impact(Impact& impact) {
  impact.restitution =
      impact.approach_velocity_m_s != 0 ? impact.rebound_velocity_m_s / impact.approach_velocity_m_s : 0;
}

bool in_window(double t, double start_s, double end_s) { return t >= start_s && t <= end_s; }

int onsets_in(const std::vector<ContactEvent>& events, double start_s, double end_s) {
  return static_cast<int>(std::count_if(
      events.begin(), events.end(), [&](const ContactEvent& e) { return in_window(e.onset_time_s, start_s, end_s); }));
}

double mean_of(const std::vector<Impact>& impacts, double (*field)(const Impact&)) {
  if (impacts.empty()) return kNaN;
  double sum = 0;
  for (const Impact& i : impacts) sum += field(i);
  return sum / static_cast<double>(impacts.size());
}

double duration(const Impact& i) { return i.end_time_s - i.onset_time_s; }

void add_impact_metrics(Metrics& m, const std::vector<Impact>& impacts) {
  m.impacts = static_cast<int>(impacts.size());
  m.contact_duration_mean_s = mean_of(impacts, duration);
  m.contact_duration_min_s = m.contact_duration_max_s = impacts.empty() ? kNaN : duration(impacts.front());
  for (const Impact& i : impacts) {
    m.contact_duration_min_s = std::min(m.contact_duration_min_s, duration(i));
    m.contact_duration_max_s = std::max(m.contact_duration_max_s, duration(i));
  }
  m.mean_restitution = mean_of(impacts, [](const Impact& i) { return i.restitution; });
  m.mean_approach_velocity_m_s = mean_of(impacts, [](const Impact& i) { return i.approach_velocity_m_s; });
  m.mean_impulse_n_s = mean_of(impacts, [](const Impact& i) { return i.impulse_n_s; });
  m.max_penetration_m = 0;
  for (const Impact& i : impacts) m.max_penetration_m = std::max(m.max_penetration_m, i.max_indentation_m);
}

// ---- per cycle and per beat ------------------------------------------------------------------------

void add_rate_metrics(Metrics& m, const MetricSettings& settings) {
  const double window_s = settings.window.end_s - settings.window.start_s;
  const double f_exc = settings.excitation_frequency_hz, f_1 = settings.natural_frequency_hz;
  m.excitation_cycles = window_s * f_exc;
  m.impacts_per_cycle = f_exc > 0 && m.excitation_cycles > 0 ? m.impacts / m.excitation_cycles : kNaN;

  // Beating is only meaningful with an excitation and a natural frequency apart from it, and can only
  // be counted when the window holds two beats at least (the tolerance keeps exactly two in).
  m.beat_period_s = m.impacts_per_beat = kNaN;
  const double beat_frequency_hz = std::abs(f_exc - f_1);
  if (f_exc <= 0 || f_1 <= 0 || beat_frequency_hz <= 0) return;
  const double beats = window_s * beat_frequency_hz;
  if (beats < 2 * (1 - 1e-9)) return;
  m.beat_period_s = 1 / beat_frequency_hz;
  m.impacts_per_beat = m.impacts / beats;
}

// ---- against a reference ---------------------------------------------------------------------------

double relative_error(double run, double reference) {
  if (std::isnan(reference) || reference == 0) return kNaN;
  return (run - reference) / reference;
}

// RMS(u - u_ref) / RMS(u_ref) over the reference's samples in the window, the run read at the
// reference's sample times. NaN where the run does not reach every such time or the reference is at rest.
double displacement_relative_rms_error(const Trajectory& run, const Trajectory& reference, int frame,
                                       const MetricSettings& settings) {
  const SampleRange range = samples_in(reference, settings.window.start_s, settings.window.end_s);
  if (range.empty()) return kNaN;
  double difference_squares = 0, reference_squares = 0;
  for (std::size_t k = range.first; k < range.last; ++k) {
    const std::optional<double> u = value_at(run, run.displacement_m[frame], reference.time_s[k]);
    if (!u) return kNaN;
    const double u_ref = reference.displacement_m[frame][k];
    difference_squares += (*u - u_ref) * (*u - u_ref);
    reference_squares += u_ref * u_ref;
  }
  if (reference_squares == 0) return kNaN;
  return std::sqrt(difference_squares / reference_squares);
}

}  // namespace

std::vector<Impact> merge_impacts(const std::vector<ContactEvent>& events, double start_s, double end_s,
                                  double merge_window_s) {
  std::vector<ContactEvent> sorted = events;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const ContactEvent& a, const ContactEvent& b) { return a.onset_time_s < b.onset_time_s; });
  // Merge over the whole run, then select: an episode just inside the window that belongs to an impact
  // begun before it is part of that impact, not a new one.
  std::vector<Impact> all;
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    const bool joins = i > 0 && sorted[i].onset_time_s - sorted[i - 1].onset_time_s < merge_window_s;
    if (joins)
      join_impact(all.back(), sorted[i]);
    else
      all.push_back(start_impact(sorted[i]));
  }
  std::vector<Impact> selected;
  for (Impact& impact : all) {
    if (!in_window(impact.onset_time_s, start_s, end_s)) continue;
    finish_impact(impact);
    selected.push_back(impact);
  }
  return selected;
}

SensorSeries sensor_acceleration(const Trajectory& trajectory, int frame, double start_s, double end_s,
                                 double sensor_rate_hz, double grid_phase) {
  SensorSeries out;
  if (sensor_rate_hz <= 0 || end_s <= start_s) return out;
  const double T = 1 / sensor_rate_hz;
  start_s += grid_phase * T;
  const std::vector<double>& velocity = trajectory.velocity_m_s[frame];
  // windows [start + k T, start + (k+1) T] that end by `end`, to a rounding error
  const auto windows = static_cast<long long>(std::floor((end_s - start_s) * sensor_rate_hz + kSampleTolerance));
  if (windows <= 0) return out;
  out.time_s.reserve(static_cast<std::size_t>(windows));
  out.acceleration_m_s2.reserve(static_cast<std::size_t>(windows));
  // each edge from k directly, so that no rounding accumulates over a long window; a window's end is the
  // next one's start, the same number, read once
  std::optional<double> v_lo = value_at(trajectory, velocity, start_s);
  for (long long k = 0; k < windows; ++k) {
    const std::optional<double> v_hi = value_at(trajectory, velocity, start_s + static_cast<double>(k + 1) * T);
    if (v_lo && v_hi) {  // else the series does not reach this window
      out.time_s.push_back(start_s + (static_cast<double>(k) + 0.5) * T);
      out.acceleration_m_s2.push_back((*v_hi - *v_lo) / T);
    }
    v_lo = v_hi;
  }
  return out;
}

// ---- energy ----------------------------------------------------------------------------------------

// Read at the last sample of the window where the tips exchange no force: inside a contact the stored
// elastic energy depends on how a step resolved the overlap (the verdict reads energy the same way).
void add_energy_metric(Metrics& m, const Trajectory& t, const MetricSettings& settings) {
  m.energy_change_relative = kNaN;
  if (settings.excitation_frequency_hz > 0 || t.mechanical_energy_j.size() != t.size()) return;
  const double initial = t.initial_mechanical_energy_j;
  if (!std::isfinite(initial) || initial <= 0) return;
  for (std::size_t k = t.size(); k-- > 0;) {
    if (t.time_s[k] > settings.window.end_s) continue;
    if (t.time_s[k] < settings.window.start_s) break;
    if (t.contact_force_n[k] != 0) continue;
    m.energy_change_relative = (t.mechanical_energy_j[k] - initial) / initial;
    return;
  }
}

Metrics compute_metrics(const Trajectory& trajectory, const MetricSettings& settings) {
  Metrics m;
  const double start_s = settings.window.start_s, end_s = settings.window.end_s;
  const std::array<SensorSeries, 2> sensor = {
      sensor_acceleration(trajectory, 0, start_s, end_s, settings.sensor_rate_hz),
      sensor_acceleration(trajectory, 1, start_s, end_s, settings.sensor_rate_hz)};
  for (int f = 0; f < 2; ++f) {
    m.frames[f] = frame_metrics(trajectory, f, settings, sensor[f]);
    m.sensor_peak_over_grid_phases[f] = sensor_peak_over_grid_phases(
        trajectory, f, sensor[f], start_s, end_s, settings.sensor_rate_hz, settings.sensor_grid_phases);
    m.frames[f].log_decrement = settings.excitation_frequency_hz > 0
                                    ? kNaN
                                    : log_decrement(trajectory.time_s, trajectory.displacement_m[f],
                                                    settings.window.start_s, settings.window.end_s);
  }
  const std::vector<Impact> impacts = merge_impacts(trajectory.events, start_s, end_s, settings.merge_window_s);
  add_impact_metrics(m, impacts);
  m.impact_samples = impact_samples(trajectory, impacts, sensor, settings.sensor_rate_hz, start_s, end_s);
  m.raw_onsets = onsets_in(trajectory.events, settings.window.start_s, settings.window.end_s);
  add_rate_metrics(m, settings);
  add_energy_metric(m, trajectory, settings);
  return m;
}

MetricErrors compare_metrics(const Metrics& run, const Trajectory& run_trajectory, const Metrics& reference,
                             const Trajectory& reference_trajectory, const MetricSettings& settings) {
  MetricErrors e;
  for (int f = 0; f < 2; ++f) {
    e.sensor_peak_relative_error[f] =
        relative_error(run.frames[f].sensor_peak_acceleration_g, reference.frames[f].sensor_peak_acceleration_g);
    e.displacement_relative_rms_error[f] =
        displacement_relative_rms_error(run_trajectory, reference_trajectory, f, settings);
    e.log_decrement_relative_error[f] = relative_error(run.frames[f].log_decrement, reference.frames[f].log_decrement);
    e.sensor_peak_phase_mean_relative_error[f] =
        relative_error(run.sensor_peak_over_grid_phases[f].mean_g, reference.sensor_peak_over_grid_phases[f].mean_g);
  }
  e.impact_distribution_distances = distribution_distances(run.impact_samples, reference.impact_samples);
  e.contact_duration_relative_error = relative_error(run.contact_duration_mean_s, reference.contact_duration_mean_s);
  e.impacts_per_cycle_difference = std::isnan(run.impacts_per_cycle) || std::isnan(reference.impacts_per_cycle)
                                       ? kNaN
                                       : run.impacts_per_cycle - reference.impacts_per_cycle;
  return e;
}

std::vector<std::pair<std::string, double>> flatten(const Metrics& m) {
  std::vector<std::pair<std::string, double>> out;
  for (int f = 0; f < 2; ++f) {
    const std::string frame = "frame" + std::to_string(f + 1) + "_";
    out.emplace_back(frame + "sensor_peak_acceleration_g", m.frames[f].sensor_peak_acceleration_g);
    out.emplace_back(frame + "true_peak_acceleration_g", m.frames[f].true_peak_acceleration_g);
    out.emplace_back(frame + "rms_acceleration_g", m.frames[f].rms_acceleration_g);
    out.emplace_back(frame + "peak_displacement_m", m.frames[f].peak_displacement_m);
    out.emplace_back(frame + "log_decrement", m.frames[f].log_decrement);
  }
  out.emplace_back("impacts", m.impacts);
  out.emplace_back("raw_onsets", m.raw_onsets);
  out.emplace_back("contact_duration_mean_s", m.contact_duration_mean_s);
  out.emplace_back("contact_duration_min_s", m.contact_duration_min_s);
  out.emplace_back("contact_duration_max_s", m.contact_duration_max_s);
  out.emplace_back("excitation_cycles", m.excitation_cycles);
  out.emplace_back("impacts_per_cycle", m.impacts_per_cycle);
  out.emplace_back("beat_period_s", m.beat_period_s);
  out.emplace_back("impacts_per_beat", m.impacts_per_beat);
  out.emplace_back("mean_restitution", m.mean_restitution);
  out.emplace_back("mean_approach_velocity_m_s", m.mean_approach_velocity_m_s);
  out.emplace_back("max_penetration_m", m.max_penetration_m);
  out.emplace_back("mean_impulse_n_s", m.mean_impulse_n_s);
  out.emplace_back("energy_change_relative", m.energy_change_relative);
  // the statistics beside the maxima, after every column above (impact_statistics.h)
  for (int f = 0; f < 2; ++f) {
    const std::string frame = "frame" + std::to_string(f + 1) + "_";
    out.emplace_back(frame + "sensor_peak_phase_mean_g", m.sensor_peak_over_grid_phases[f].mean_g);
    out.emplace_back(frame + "sensor_peak_phase_min_g", m.sensor_peak_over_grid_phases[f].min_g);
    out.emplace_back(frame + "sensor_peak_phase_max_g", m.sensor_peak_over_grid_phases[f].max_g);
  }
  out.emplace_back("sensor_peak_phases_read", m.sensor_peak_over_grid_phases[0].phases_read);
  for (auto& figure : flatten_percentiles(m.impact_samples)) out.push_back(std::move(figure));
  return out;
}

std::vector<std::pair<std::string, double>> flatten(const MetricErrors& e, const std::string& prefix) {
  std::vector<std::pair<std::string, double>> out = {
      {prefix + "frame1_sensor_peak_relative_error", e.sensor_peak_relative_error[0]},
      {prefix + "frame2_sensor_peak_relative_error", e.sensor_peak_relative_error[1]},
      {prefix + "contact_duration_relative_error", e.contact_duration_relative_error},
      {prefix + "impacts_per_cycle_difference", e.impacts_per_cycle_difference},
      {prefix + "frame1_displacement_relative_rms_error", e.displacement_relative_rms_error[0]},
      {prefix + "frame2_displacement_relative_rms_error", e.displacement_relative_rms_error[1]},
      {prefix + "frame1_log_decrement_relative_error", e.log_decrement_relative_error[0]},
      {prefix + "frame2_log_decrement_relative_error", e.log_decrement_relative_error[1]},
      {prefix + "frame1_sensor_peak_phase_mean_relative_error", e.sensor_peak_phase_mean_relative_error[0]},
      {prefix + "frame2_sensor_peak_phase_mean_relative_error", e.sensor_peak_phase_mean_relative_error[1]},
  };
  for (auto& figure : flatten(e.impact_distribution_distances, prefix)) out.push_back(std::move(figure));
  return out;
}

}  // namespace ib
