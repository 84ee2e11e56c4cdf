#include "harness/scoring/metric_catalog.h"

#include <algorithm>
#include <stdexcept>

namespace ib {

const char* to_string(ErrorKind kind) { return kind == ErrorKind::relative ? "relative" : "difference"; }

const std::vector<ScoringReference>& scoring_references() {
  static const std::vector<ScoringReference> references = {
      {"beam", "vs_reference_", "the analytical reference on the beam (reference/): the whole error a user sees"},
      {"own chain", "vs_chain_reference_",
       "the reference on the engine's own K-link chain: the engine's contact handling and time stepping alone; "
       "the verdict judges against it where there is one, against the beam otherwise"}};
  return references;
}

const std::vector<ScoredMetric>& scored_metrics() {
  const std::vector<std::string> both = {"beam", "own chain"};
  // Frame 1's decay only: frame 2 starts at rest and first gains from the impacts, so a fitted decrement
  // of its peaks is not a decay rate (verdict.cpp).
  static const std::vector<ScoredMetric> metrics = {
      {"frame1_sensor_peak", "frame 1 sensor peak", "frame1_sensor_peak_acceleration_g", "g",
       "frame1_sensor_peak_relative_error", ErrorKind::relative, "sensor_peak_relative_error",
       &AccuracyTolerances::sensor_peak_relative, [](const MetricErrors& e) { return e.sensor_peak_relative_error[0]; },
       true, both},
      {"frame2_sensor_peak", "frame 2 sensor peak", "frame2_sensor_peak_acceleration_g", "g",
       "frame2_sensor_peak_relative_error", ErrorKind::relative, "sensor_peak_relative_error",
       &AccuracyTolerances::sensor_peak_relative, [](const MetricErrors& e) { return e.sensor_peak_relative_error[1]; },
       false, both},
      {"contact_duration", "contact duration", "contact_duration_mean_s", "s", "contact_duration_relative_error",
       ErrorKind::relative, "contact_duration_relative_error", &AccuracyTolerances::contact_duration_relative,
       [](const MetricErrors& e) { return e.contact_duration_relative_error; }, true, both},
      {"impacts_per_cycle", "impacts per cycle", "impacts_per_cycle", "-", "impacts_per_cycle_difference",
       ErrorKind::difference, "impacts_per_cycle_difference", &AccuracyTolerances::impacts_per_cycle_difference,
       [](const MetricErrors& e) { return e.impacts_per_cycle_difference; }, true, both},
      {"frame1_log_decrement", "frame 1 log decrement", "frame1_log_decrement", "-",
       "frame1_log_decrement_relative_error", ErrorKind::relative, "log_decrement_relative_error",
       &AccuracyTolerances::log_decrement_relative,
       [](const MetricErrors& e) { return e.log_decrement_relative_error[0]; }, false, both},
  };
  return metrics;
}

const ScoredMetric& scored_metric(const std::string& name) {
  for (const ScoredMetric& m : scored_metrics())
    if (m.name == name) return m;
  throw std::invalid_argument("no scored metric is called " + name);
}

double tolerance_of(const ScoredMetric& metric, const AccuracyTolerances& tolerances) {
  return tolerances.*metric.tolerance;
}

std::vector<double> tolerance_values(const AccuracyTolerances& tolerances) {
  std::vector<double AccuracyTolerances::*> seen;
  std::vector<double> values;
  for (const ScoredMetric& m : scored_metrics()) {
    if (std::find(seen.begin(), seen.end(), m.tolerance) != seen.end()) continue;  // both frames' sensor peaks
    seen.push_back(m.tolerance);
    values.push_back(tolerances.*m.tolerance);
  }
  return values;
}

}  // namespace ib
