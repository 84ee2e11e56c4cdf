// DIR/engines.json: the descriptor of every simulator of the catalog (model/simulator_descriptor.h) with
// its library's version, written into a suite's or a sweep's folder so that the report reads the names,
// colours, packages and diagnostics keys of the engines that made the results, not a list of its own.
#pragma once

#include <string>

#include "harness/records/metrics_file.h"
#include "harness/records/provenance_file.h"
#include "model/simulator.h"

namespace ib {

// The descriptors as JSON text: {"simulators": [{"name", "display_name", "summary", "version",
// "packages", "colours", "diagnostics": [{"key", "label", "meaning", "unit", "values"}], "default_time_step_s"
// (null: adaptive), "default_time_step_note" (where there is one), "recommended"}]}, in the
// catalog's order (docs/diagnostics.md). `impactbench engines --json` prints the same text.
std::string engines_json(const SimulatorCatalog& catalog);

// Writes engines_json(catalog) to DIR/engines.json (replacing an older one: the engines of the last
// command that wrote into the folder). Throws OutputError when the file cannot be written.
void write_engines_file(const std::string& dir, const SimulatorCatalog& catalog);

// Writes DIR/engines.json, DIR/metrics.json (metrics_file.h) and DIR/provenance.json (provenance_file.h) and
// passes `outcome` through: the one line run_suite and run_sweep add. Only a suite or sweep that returns writes them
// (one that throws, exit 3, or is killed leaves none until --resume); `merge` copies a shard's (cli/command_merge.cpp).
// The report takes a folder without engines.json as an old one (names, spare colours, no engine settings).
template <class Outcome>
Outcome with_engines_file(const std::string& dir, const SimulatorCatalog& catalog, Outcome outcome) {
  write_engines_file(dir, catalog);
  write_metrics_file(dir);
  write_provenance_file(dir, catalog);
  return outcome;
}

}  // namespace ib
