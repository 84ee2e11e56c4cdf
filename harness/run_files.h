// A run's own files: series.csv (the sampled trajectory) and events.csv (one row per contact episode),
// written and read back (reports and errors against a saved reference read them). Units are named in
// every column.
#pragma once

#include <string>

#include "trajectory.h"

namespace ib {

// Throw std::runtime_error naming the file when it cannot be written or read.
void write_series_csv(const std::string& path, const Trajectory& trajectory);
void write_events_csv(const std::string& path, const Trajectory& trajectory);
// Fills the series (and output rate, start time) or the events of `trajectory` from a file written above.
void read_series_csv(const std::string& path, Trajectory& trajectory);
void read_events_csv(const std::string& path, Trajectory& trajectory);

}  // namespace ib
