// The one runner: every unit of work of a study (a suite's jobs, a step search's probes, a sweep's chains)
// comes from a source, and run_units starts them on one pool of processes, the costliest ready unit first,
// whatever source it comes from: no part waits for another to end. A source knows its own plan (what is ready,
// what depends on what) and records what its units did; the runner knows only costs and processes.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "harness/jobs/process_pool.h"

namespace ib {

// A cost the runner cannot estimate yet: such a unit goes first, so that its kind's cost is measured early.
constexpr double kUnknownCost = std::numeric_limits<double>::infinity();

class UnitSource {
 public:
  virtual ~UnitSource() = default;
  // The expected cost [s] of the unit this source would start next, kUnknownCost when not known yet; none
  // when nothing of it is ready now (it waits for a unit that runs, or it has ended).
  virtual std::optional<double> next_cost() = 0;
  // Starts that unit in the pool and returns its id; "" when it ended without a process (a cached result,
  // a record of a unit that cannot run): next_cost is then asked again.
  virtual std::string start_next(ProcessPool& pool) = 0;
  // A unit this source started has ended: record it (and what it makes ready).
  virtual void ended(const ProcessEnd& end) = 0;
  // Called every few tens of milliseconds while units run (a sweep refreshes its tables, restarts clocks).
  virtual void tick(ProcessPool& /*pool*/) {}
};

// Runs the sources' units on at most `workers` processes until none is ready and none runs, or the runner is
// interrupted (worker_process.h); then the processes that had ended are handed to their sources and the
// rest are stopped unrecorded (a resume runs them). An exception from a source stops every process first.
void run_units(const std::vector<UnitSource*>& sources, int workers);

}  // namespace ib
