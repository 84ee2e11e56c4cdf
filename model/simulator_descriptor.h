// What the layers above need to know of a simulator besides its runs: its name for people, its colours,
// where it comes from and what its diagnostics keys mean. The data lives in one file per simulator
// (adapters/<engine>/descriptor.json, reference/descriptor.json), read by simulators/CMakeLists.txt at
// configure time, so that the report and the scripts read the same file and nothing else names an engine
// (docs/adding-an-engine.md).
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace ib {

// One key a simulator writes into a run's diagnostics (RunResult::diagnostics, runs.jsonl), documented.
struct DiagnosticsKey {
  std::string key;      // as written, e.g. "frame1_joint_stiffness_n_m_per_rad"
  std::string label;    // the setting it shows in the report, e.g. "integrator"
  std::string meaning;  // one sentence
  std::string unit;     // SI unit, "" for a count, a ratio or a flag
  // For flags and codes: value -> text ({"1", "RK4"}, {"0", "Euler (MuJoCo's default)"}); empty: a number
  std::vector<std::pair<std::string, std::string>> values;
};

// The engine's authors' recommended configuration for one contact law (descriptor.json "recommended"): the
// options to set and the time step; each setting's source is in the descriptor's text (recommended_json).
struct RecommendedConfiguration {
  std::string law;                             // "hertz", "viscoelastic", "newton"
  std::map<std::string, std::string> options;  // e.g. {"contact", "matched"}, {"length_unit", "cm"}
  double time_step_s = 0;                      // 0: the engine's default step
};

struct SimulatorDescriptor {
  std::string name;                   // the catalog name, e.g. "mujoco"
  std::string display_name;           // e.g. "MuJoCo"
  std::string summary;                // one line: what the engine is and how the rig is built in it
  std::vector<std::string> packages;  // the Debian package(s) it is built from
  // contact path (matched, injected, native) -> "#rrggbb": the same in every figure of the report
  std::vector<std::pair<std::string, std::string>> colours;
  std::vector<DiagnosticsKey> diagnostics;
  std::vector<RecommendedConfiguration> recommended;  // one per law it names; empty: none
  std::string recommended_json;  // the descriptor's "recommended" object as written (with its sources), "" if none
  // The step of a run without --dt [s] (descriptor.json "default_time_step_s", which the adapter is compiled
  // with: adapters/CMakeLists.txt); 0 for an adaptive simulator (the reference, null in its descriptor)
  double default_time_step_s = 0;
  std::string default_time_step_note;  // how the step is chosen where a number cannot say it, "" if none
  // Measured CPU time per simulated second [s] at the default step (an adaptive simulator: at its own steps), on
  // the resonance with matched Hertz contact (descriptor.json "cpu_s_per_simulated_s"; the command, date and
  // machine: docs/performance.md, "The plan's CPU estimate"); 0: not measured. `study --plan` estimates from it.
  double cpu_s_per_simulated_s = 0;
  // The same for the simulator on a K-link chain (the reference's "chain_cpu_s_per_simulated_s": K -> cost), in
  // increasing K; empty: none measured.
  std::vector<std::pair<int, double>> chain_cpu_s_per_simulated_s;
};

}  // namespace ib
