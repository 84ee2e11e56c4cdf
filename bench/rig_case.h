// The rig case the engine benchmarks time: the published resonance case cut to 2 s (impacts start within
// the first second) with the last second scored, on the matched contact path at each engine's default step.
#pragma once

#include <string>

#include "model/scenario_toml.h"
#include "model/simulator.h"

namespace ib::bench {

inline Scenario resonance_for_2_s() {
  Scenario s = load_scenario(std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/paper/resonance.toml");
  s.duration_s = 2;
  s.scoring_window_s = 1;
  return s;
}

inline RunSettings matched_path(ContactLaw law) {
  RunSettings settings;
  settings.law = law;
  settings.options["contact"] = "matched";
  return settings;
}

}  // namespace ib::bench
