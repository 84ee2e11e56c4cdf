// The sweep's stages, internal to the harness (sweep.h is the interface):
//   sweep_plan.cpp    the ratios, chains and rows in planned order
//   sweep_row.cpp     one ratio run and recorded in its folder (row.json, poincare.csv, state.txt); the tables
//                     (sweep.jsonl, sweep.csv, poincare.csv) the recorder (jobs/recorder.h) makes from the folders
//   sweep_runner.cpp  the chains' processes, resume, shards, time limits, signals
#pragma once

#include <optional>
#include <string>

#include "harness/sweep/sweep.h"
#include "model/saved_state.h"

namespace ib::sweep_internal {

// A row's scenario: the motor at the row's ratio, the run and its scoring window (scenario.scoring_window_s,
// from SweepSettings::window_s) whole numbers of motor periods (so that a continued run starts at the phase
// the last one ended at: 0).
struct RowScenario {
  Scenario scenario;
  double motor_frequency_hz = 0;
};
RowScenario row_scenario(const Scenario& base, const SweepRow& row, const SweepSettings& settings);

// Runs a row from `from` (its chain's previous final state; none: from rest) and writes its folder:
// summary.json, events.csv (and series.csv.gz unless --series none) by run_job, then poincare.csv,
// state.txt (the final state) and, last, row.json (what marks the row done). Returns the final state
// when the chain can continue from it (the run reached its end). Throws OutputError for a write error.
std::optional<SavedState> run_sweep_row(const Scenario& base, const SweepRow& row, const SweepSettings& settings,
                                        const std::optional<SavedState>& from, const std::string& folder);

// A row that did not run or did not end (its chain broke off earlier, its process died, its time limit):
// its row.json with the verdict "failed" and the reason, so that the tables say what happened.
void record_row_not_run(const Scenario& base, const SweepRow& row, const SweepSettings& settings,
                        const std::string& folder, const std::string& reason, bool timed_out);

// The final state a row left (state.txt), for its chain's next row; none when the row has none.
std::optional<SavedState> read_row_state(const std::string& folder);

bool row_done(const std::string& folder);  // row.json is there

}  // namespace ib::sweep_internal
