// The one clock every simulator times its run with: the process's CPU time (std::clock, the headline
// cost on a shared, noisy machine) and the wall time, both from construction.
#pragma once

#include <chrono>
#include <ctime>

#include "model/trajectory.h"

namespace ib {

class RunClock {
 public:
  RunClock() : cpu_start_(std::clock()), wall_start_(std::chrono::steady_clock::now()) {}
  // The time since construction into a run's cost (its steps are the simulator's to count).
  void stop_into(RunCost& cost) const {
    cost.cpu_time_s = static_cast<double>(std::clock() - cpu_start_) / CLOCKS_PER_SEC;
    cost.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count();
  }

 private:
  std::clock_t cpu_start_;
  std::chrono::steady_clock::time_point wall_start_;
};

}  // namespace ib
