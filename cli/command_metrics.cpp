// `metrics [--json]`: the scored metrics of this build (harness/scoring/metric_catalog.h): each with its
// runs.csv column and unit, its error column and kind, its tolerance key and default, and whether the step
// search searches it. --json prints the text a suite or sweep writes to DIR/metrics.json.
#include "cli/commands.h"

#include <cstdio>
#include <memory>

#include "harness/records/metrics_file.h"

namespace cli {

namespace {

int command_metrics(bool json) {
  if (json) {
    std::fputs(ib::metrics_json().c_str(), stdout);
    return kExitOk;
  }
  const ib::AccuracyTolerances defaults;
  for (const ib::ScoredMetric& m : ib::scored_metrics()) {
    std::printf("%s (%s): runs.csv %s [%s]\n", m.name.c_str(), m.label.c_str(), m.column.c_str(), m.unit.c_str());
    std::printf("  error: %s, %s; tolerance %s = %g by default%s\n", m.error_column.c_str(), ib::to_string(m.kind),
                m.tolerance_key.c_str(), ib::tolerance_of(m, defaults),
                m.step_searched ? "; the step search searches it" : "");
  }
  std::printf("each against the references:");
  for (const ib::ScoringReference& r : ib::scoring_references())
    std::printf(" %s (columns %s*);", r.name.c_str(), r.error_prefix.c_str());
  std::printf("\n");
  return kExitOk;
}

}  // namespace

Command add_metrics_command(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  CLI::App* metrics = app.add_subcommand(
      "metrics", "the scored metrics: runs.csv columns, units, error columns and kinds, tolerance keys and defaults");
  metrics->add_flag("--json", *json, "print them as JSON (what a suite or sweep writes to DIR/metrics.json)");
  return {metrics, [json] { return command_metrics(*json); }};
}

}  // namespace cli
