// Writes one run's files: summary.json (metrics, status, cost, settings), series.csv and events.csv.
// Units are named in every column and key.
#pragma once

#include <string>

#include "metrics.h"
#include "simulator.h"

namespace ib {

struct RunRecord {
  const Scenario& scenario;
  std::string engine;
  std::string engine_version;
  const RunSettings& settings;
  const RunResult& result;
  const Metrics& metrics;
};

// Throws std::runtime_error naming the file when it cannot be written.
void write_summary_json(const std::string& path, const RunRecord& record);
void write_series_csv(const std::string& path, const Trajectory& trajectory);
void write_events_csv(const std::string& path, const Trajectory& trajectory);
// All three into folder (created if missing).
void write_run_folder(const std::string& folder, const RunRecord& record);

}  // namespace ib
