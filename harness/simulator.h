// The one interface every simulator implements, the reference included: a scenario and run settings
// in, a trajectory and its contact events out. Metrics are computed outside every simulator.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <memory>
#include <string>
#include <vector>

#include "scenario.h"
#include "trajectory.h"

namespace ib {

// How a run is carried out. Physics lives in the Scenario; this is numerics and bookkeeping.
struct RunSettings {
  ContactLaw law = ContactLaw::hertz;
  double output_rate_hz = 4096;       // samples per second of the written series [Hz]
  double series_start_s = -1;         // first sample time [s]; < 0: the scenario's scoring window start
  double time_step_s = 0;             // fixed-step engines [s]; the adaptive reference ignores it
  // Simulator-specific options as name=value text, each validated by the simulator that reads it
  // (e.g. the reference's "modes", "rtol"; an engine's "integrator"). Unknown names are an error.
  std::map<std::string, std::string> options;
};

class Simulator {
 public:
  virtual ~Simulator() = default;
  virtual std::string name() const = 0;          // e.g. "reference", "mujoco"
  virtual std::string version() const = 0;       // library version, for reports
  // The options this simulator accepts, with a one-line description each (for --help and errors).
  virtual std::vector<std::pair<std::string, std::string>> option_help() const = 0;
  // Runs one scenario. Throws std::invalid_argument for settings it cannot take (bad option, law
  // without parameters in the scenario); instability is reported in the result, not thrown.
  virtual RunResult run(const Scenario& scenario, const RunSettings& settings) = 0;
  // The number of links K of the chain this simulator builds for a run, if it builds one: the suite
  // then also scores it against the reference on exactly that chain.
  virtual std::optional<int> chain_links(const Scenario&, const RunSettings&) const { return std::nullopt; }
};

// The simulators built into this binary, by name.
std::vector<std::string> simulator_names();
std::unique_ptr<Simulator> make_simulator(const std::string& name);  // nullptr when unknown

// Makes simulators by name: make_simulator, or a test's own.
using SimulatorFactory = std::function<std::unique_ptr<Simulator>(const std::string& name)>;

}  // namespace ib
