// The one interface every simulator implements, the reference included: a scenario and run settings
// in, a trajectory and its contact events out. Metrics are computed outside every simulator.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "model/saved_state.h"
#include "model/scenario.h"
#include "model/simulator_descriptor.h"
#include "model/trajectory.h"

namespace ib {

// When a run is unstable: the one record that both the simulators' divergence guard (which stops a run
// early) and the verdict (harness/scoring/verdict.h) read.
struct StabilityBounds {
  double displacement_bound_fraction_of_length = 0.1;  // |u| beyond this x frame length: unstable [-]
  double penetration_bound_gaps = 10;                  // delta beyond this x gap, and beyond the floor below [-]
  // The bound's floor: a zero or tiny gap (1e-7 m) must not make a micrometre contact "unstable". A
  // centimetre of overlap: no contact of this rig (tens of micrometres) comes near it. [m]
  double penetration_bound_floor_m = 1e-2;
  double energy_growth_tolerance = 1e-3;  // relative rise of energy allowed without a motor [-]
};

// How a run is carried out. Physics lives in the Scenario; this is numerics and bookkeeping.
struct RunSettings {
  ContactLaw law = ContactLaw::hertz;
  double output_rate_hz = 4096;  // samples per second of the written series [Hz]
  double series_start_s = -1;    // first sample time [s]; < 0: the scenario's scoring window's start
  double time_step_s = 0;        // fixed-step engines [s]; the adaptive reference ignores it
  StabilityBounds stability;     // a fixed-step engine stops when a tip leaves these bounds
  // Simulator-specific options as name=value text, each validated by the simulator that reads it
  // (e.g. the reference's "modes", "rtol"; an engine's "integrator"). Unknown names are an error.
  std::map<std::string, std::string> options;
  // Set: the run starts from this state (a previous run's RunResult::final_state, same simulator and
  // rig) instead of the scenario's initial state, at t = 0 with the motor at phase 0. A sweep's
  // continuation ends every run at a whole number of motor periods, so the forcing stays phase-continuous.
  std::optional<SavedState> initial_state;
  // Whether the caller reads the exact peaks between samples (the series' peak columns, the true peak
  // metric): off, a simulator may leave out the work they cost (the reference does). A sweep's row that
  // keeps no series reads none of them.
  bool peaks_between_samples = true;
};

// The first sample time of a run's series: settings.series_start_s, or the scenario's scoring window
// start when that is < 0. The one place that resolves the default.
double series_start_s(const RunSettings& settings, const Scenario& scenario);

// Which build of an engine's library a simulator runs, as its adapter knows it: recorded in every result folder
// (provenance.json) because two builds of one version string (a patched or rebuilt library) can differ in results.
struct LibraryBuild {
  // A function of the engine's library: the records find the file it was loaded from (dladdr) and hash it, so
  // the answer is the file this process runs, not the one a search path would find. nullptr: no library of its
  // own (the reference, built into impactbench).
  const void* library_function = nullptr;
  std::string install_prefix;  // the prefix the adapter was built against (adapters/CMakeLists.txt)
  // The version macro of the headers the adapter was compiled with, as text ("not given by its headers" where
  // there is none): a library loaded at run time other than the one compiled against shows as a difference.
  std::string header_version;
};

class Simulator {
 public:
  virtual ~Simulator() = default;
  virtual std::string name() const = 0;     // e.g. "reference", "mujoco"
  virtual std::string version() const = 0;  // library version, for reports
  // The options this simulator accepts, with a one-line description each (for --help and errors).
  virtual std::vector<std::pair<std::string, std::string>> option_help() const = 0;
  // Runs one scenario. Throws std::invalid_argument for settings it cannot take (bad option, law
  // without parameters in the scenario); instability is reported in the result, not thrown.
  virtual RunResult run(const Scenario& scenario, const RunSettings& settings) = 0;
  // The number of links K of the chain this simulator builds for a run, if it builds one: the suite
  // then also scores it against the reference on exactly that chain.
  virtual std::optional<int> chain_links(const Scenario&, const RunSettings&) const { return std::nullopt; }
  // Checks a run's settings as run() would, without running: throws std::invalid_argument naming the
  // option, the value and what is allowed (a suite refuses bad options before its first job).
  virtual void check_settings(const RunSettings&) const {}
  // The model this simulator builds for a run, in its own format, for a person to open in the
  // simulator's own tools (MuJoCo: MJCF; the reference: its modal model as JSON); empty when it has none.
  virtual std::string export_model(const Scenario&, const RunSettings&) const { return {}; }
  // The build of its library this simulator runs (see LibraryBuild); none by default.
  virtual LibraryBuild library_build() const { return {}; }
};

// Makes simulators by name (nullptr when unknown): the catalog's, or a test's own.
using SimulatorFactory = std::function<std::unique_ptr<Simulator>(const std::string& name)>;

// What the layers above know of the simulators, handed to them by the caller: the harness runs
// whatever a catalog makes and never names an engine. simulators/catalog.h makes the catalog of this
// binary; a test may build its own.
struct SimulatorCatalog {
  std::vector<std::string> names;  // in the order reports list them, the reference first
  SimulatorFactory make;
  // The options that make the reference run on the K-link chain an engine builds, so that the engine
  // is also scored against exactly the system it simulates (Simulator::chain_links).
  std::function<std::map<std::string, std::string>(int links)> chain_reference_options;
  // Each simulator's descriptor (model/simulator_descriptor.h), in the order of `names`; a test's own
  // catalog may leave it empty (then a simulator is known by its name alone).
  std::vector<SimulatorDescriptor> descriptors;
};

// The descriptor of `name` in the catalog, or one holding the name alone when the catalog has none.
SimulatorDescriptor descriptor_of(const SimulatorCatalog& catalog, const std::string& name);

// The library version of `name` as the simulator reports it at run time (Simulator::version), "" when the
// catalog cannot make it: what a result folder records (engines.json, provenance.json).
std::string version_of(const SimulatorCatalog& catalog, const std::string& name);

// The build of `name`'s library (Simulator::library_build), empty when the catalog cannot make it.
LibraryBuild library_build_of(const SimulatorCatalog& catalog, const std::string& name);

}  // namespace ib
