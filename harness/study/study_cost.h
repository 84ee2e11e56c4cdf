// `study --plan`'s CPU estimate: a run's CPU time from its simulator's measured cost per simulated second
// (model/simulator_descriptor.h, cpu_s_per_simulated_s: one number per simulator, at its default step on the
// resonance with matched Hertz contact), scaled by the run's steps. An estimate within a factor of about 2 on
// the published cases: a law, a contact path, a case, an option that changes the model (links, an adaptive
// integrator's accuracy) and the machine's own speed that day are not in it (docs/performance.md, "The plan's
// CPU estimate", measures how far it is from what the default and the smoke studies took).
#pragma once

#include <map>
#include <optional>
#include <string>

#include "model/simulator.h"

namespace ib {

// The CPU time [s] a run of `engine` with `options` at time step `time_step_s` (0: its default) over
// `simulated_s` simulated seconds is estimated to take: the measured cost per simulated second times
// default step / step (a fixed-step engine's work is its steps); for a run on a K-link chain (option "links") of a
// simulator with chain costs, the cost at the nearest measured K, scaled by the ratio of the K's (log-log between
// two measured K). None when the simulator's cost is not measured (its descriptor has no cpu_s_per_simulated_s).
std::optional<double> estimated_cpu_s(const SimulatorCatalog& catalog, const std::string& engine,
                                      const std::map<std::string, std::string>& options, double time_step_s,
                                      double simulated_s);

}  // namespace ib
