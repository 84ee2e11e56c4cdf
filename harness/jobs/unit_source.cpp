#include "harness/jobs/unit_source.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <thread>

#include "harness/jobs/worker_process.h"

namespace ib {

namespace {

// The source of the costliest ready unit (ties: the first source), or null when nothing is ready.
UnitSource* costliest_ready(const std::vector<UnitSource*>& sources) {
  UnitSource* best = nullptr;
  double best_cost = -1;
  for (UnitSource* source : sources) {
    const std::optional<double> cost = source->next_cost();
    if (cost && *cost > best_cost) best = source, best_cost = *cost;
  }
  return best;
}

}  // namespace

void run_units(const std::vector<UnitSource*>& sources, int workers) {
  ProcessPool pool;  // on an exception, its destructor stops every process
  std::map<std::string, UnitSource*> owner;
  const auto hand_over = [&](const ProcessEnd& end) {
    UnitSource* source = owner.at(end.unit);
    owner.erase(end.unit);
    source->ended(end);
  };
  while (!interrupted()) {
    bool started = false;
    while (!interrupted() && static_cast<int>(pool.running()) < std::max(1, workers)) {
      UnitSource* source = costliest_ready(sources);
      if (!source) break;
      const std::string unit = source->start_next(pool);
      if (!unit.empty()) owner[unit] = source;
      started = true;
    }
    if (pool.running() == 0) {
      if (!started) break;  // nothing runs and nothing was ready: every source has ended
      continue;
    }
    if (const std::optional<ProcessEnd> end = pool.next_end()) {
      hand_over(*end);
      continue;
    }
    for (UnitSource* source : sources) source->tick(pool);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (interrupted())
    for (const ProcessEnd& end : pool.stop()) hand_over(end);
  for (UnitSource* source : sources) source->tick(pool);
}

}  // namespace ib
