// Physical plausibility of what a command is asked to run, checked before any run starts: the ranges of
// the options every command takes, and the size of each run (its steps, its samples) from its scenario and
// settings. A value outside throws std::invalid_argument naming the option or the scenario's file, the
// value and what is allowed (exit 2). The scenario's own keys are checked where it is read
// (model/scenario_toml.cpp); these are the rules for what the command line adds.
#pragma once

#include <string>

#include "model/scenario.h"
#include "model/simulator.h"

namespace ib {

struct Plausible {
  static constexpr double kMinTimeStep_s = 1e-9, kMaxTimeStep_s = 1e-2;  // an engine's fixed step
  static constexpr double kMaxSteps = 1e10;                              // steps of one run (hours of CPU)
  static constexpr double kMinRate_hz = 1, kMaxRate_hz = 1e6;            // output and sensor rates
  static constexpr double kMaxSamples = 2e7;                             // samples of one series (about 1.6 GB)
  static constexpr double kMaxDuration_s = 3600;                         // run lengths, windows (an hour of rig time)
  static constexpr double kMaxMergeWindow_s = 1;                         // onsets merged into one impact
  static constexpr double kMaxTimeLimit_s = 7 * 24 * 3600;               // a job's time limit
};

// lo < value <= hi (lo <= value with lo_included), finite; else "OPTION VALUE: allowed: ...".
void check_option(const std::string& option, double value, double lo, double hi, const std::string& unit,
                  bool lo_included = false);

// A run of `scenario` with `settings`: its fixed step (if any) within the range and at most a tenth of the
// run, its steps and its series' samples within their limits, its first sample inside the run.
void check_run_size(const Scenario& scenario, const RunSettings& settings);

}  // namespace ib
