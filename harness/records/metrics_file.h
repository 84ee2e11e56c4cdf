// DIR/metrics.json: the scored metrics (harness/scoring/metric_catalog.h), written into a suite's or a
// sweep's folder beside engines.json so that the report and compare read the metrics, columns, units,
// error kinds and tolerance keys of the build that made the results (docs/results.md#metricsjson).
#pragma once

#include <string>
#include <vector>

#include "harness/scoring/metric_catalog.h"

namespace ib {

// The catalog as JSON text: {"tolerances": (where the folder's tolerances are), "references": [{"name",
// "error_prefix", "meaning"}], "metrics": [{"name", "label", "column", "unit", "error_column", "kind",
// "tolerance_key", "default_tolerance", "better", "scored_against", "step_searched"}]}, in the catalog's order.
// The tolerances are the defaults (`defaults`): a folder's parts may each have their own (a study's), and
// commands.jsonl records each command's. `impactbench metrics --json` prints the same text.
std::string metrics_json(const std::vector<ScoredMetric>& metrics = scored_metrics(),
                         const AccuracyTolerances& defaults = {});

// Writes metrics_json() to DIR/metrics.json (replacing an older one). Throws OutputError when the file cannot
// be written.
void write_metrics_file(const std::string& dir);

}  // namespace ib
