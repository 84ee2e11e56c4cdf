// The scored metrics as plain data: the one C++ list of what a run's accuracy is judged on, each with its
// name, runs.csv's columns, unit, how an error is taken, its tolerance and which references it is scored
// against. DIR/metrics.json (harness/records/metrics_file.h) writes it into every result folder so that the
// report and compare (reports/impactbench_report/metric_catalog.py) read the vocabulary of the build that
// made the folder rather than a list of their own. The verdict (verdict.h) judges these metrics; the step
// search (harness/suite/step_search.h) searches those marked step_searched.
#pragma once

#include <string>
#include <vector>

#include "harness/scoring/metrics.h"
#include "harness/scoring/verdict.h"

namespace ib {

// How a run's value is compared with a reference's: (run - ref) / |ref| (a fraction) or run - ref (in the
// metric's unit).
enum class ErrorKind { relative, difference };
const char* to_string(ErrorKind kind);  // "relative", "difference"

// A reference a run is scored against; runs.csv's columns of the errors against it carry its prefix.
struct ScoringReference {
  std::string name;          // as the verdict's reason names it: "beam", "own chain"
  std::string error_prefix;  // "vs_reference_", "vs_chain_reference_"
  std::string meaning;
};
const std::vector<ScoringReference>& scoring_references();

// Every scored metric: the error is the smaller the better whatever its sign (a larger peak is not better,
// a peak nearer the reference's is).
constexpr const char* kSmallerErrorIsBetter = "smaller |error|";

struct ScoredMetric {
  std::string name;          // "frame1_sensor_peak": metrics.json's key, steps.csv's column prefix if searched
  std::string label;         // "frame 1 sensor peak": in tables, sentences and summary.json
  std::string column;        // runs.csv's column of the value (sweep.csv's too, where a sweep measures it)
  std::string unit;          // of the value: "g", "s", "-"
  std::string error_column;  // runs.csv's column of the error, without a reference's error_prefix
  ErrorKind kind = ErrorKind::relative;
  std::string tolerance_key;                          // in commands.jsonl's verdict_tolerances
  double AccuracyTolerances::*tolerance = nullptr;    // its value in the settings in force
  double (*error_of)(const MetricErrors&) = nullptr;  // the error the verdict judges (flatten()'s error_column)
  bool step_searched = false;                         // --find-steps searches its largest accurate step
  std::vector<std::string> scored_against;            // names of scoring_references()
};

// The metrics the verdict judges, in the order the report lists them.
const std::vector<ScoredMetric>& scored_metrics();

// The metric of a name; throws std::invalid_argument for another.
const ScoredMetric& scored_metric(const std::string& name);

// The metric's tolerance in `tolerances` (the VerdictSettings in force).
double tolerance_of(const ScoredMetric& metric, const AccuracyTolerances& tolerances);

// Each tolerance once, in the catalog's order of their first metric (sensor peak, contact duration, impacts per
// cycle, log decrement): the array a suite's settings record and the reference cache's key hold.
std::vector<double> tolerance_values(const AccuracyTolerances& tolerances);

}  // namespace ib
