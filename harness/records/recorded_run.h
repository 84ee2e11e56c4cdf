// A runs.jsonl line read back as a struct: the one decoder of the records that cross a process boundary
// (a job's process -> the suite) or a file boundary (a suite -> its --resume). The suite's progress, the
// step search's probes and their references read what they need from here, never by key strings.
#pragma once

#include <limits>
#include <map>
#include <string>

#include "harness/scoring/verdict.h"

namespace ib {

// The headline errors of a run against one reference (runs.csv's vs_reference_* or vs_chain_reference_*).
struct HeadlineErrors {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double frame1_sensor_peak_relative = kNaN;  // NaN: not measured
  double contact_duration_relative = kNaN;
  double impacts_per_cycle_difference = kNaN;
};

struct RecordedRun {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  bool readable = false;  // false: not a run's record (a line a kill cut short); nothing else is set
  std::string job_id;
  Verdict verdict = Verdict::failed;
  std::string reason;
  bool timed_out = false;     // stopped at the suite's time limit: it decided nothing about the engine
  double steps = kNaN;        // the simulator's steps (fewer than planned when it stopped unstable)
  double wall_time_s = kNaN;  // the simulator's own time [s]
  double frame1_sensor_peak_g = kNaN, contact_duration_mean_s = kNaN, impacts_per_cycle = kNaN;
  HeadlineErrors vs_reference;        // against the continuous-beam reference
  HeadlineErrors vs_chain_reference;  // against the reference on the engine's own chain
};

RecordedRun read_recorded_run(const std::string& json_line);

// Every readable line of DIR/runs.jsonl by job id, as written (the last one of a job wins); empty
// without the file. What --resume, the step search and merge start from.
std::map<std::string, std::string> recorded_run_lines(const std::string& folder);

}  // namespace ib
