// What a suite and a sweep both say (suite/suite.h, sweep/sweep.h): which configurations run (engines,
// laws, contact paths, time steps, options) and how (output rate, measurement, workers, time limit, the
// folder, a shard). SuiteSettings and SweepSettings are this with their own settings added; the commands
// fill it from the options they share (cli/arguments.h), and their settings records (suite.jsonl,
// sweep.json) hold its configurations under the same keys, written by the one function below.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/jobs/run_job.h"
#include "harness/jobs/shard_plan.h"
#include "model/simulator.h"
#include "physics/contact_laws.h"

namespace ib {

struct MatrixSettings {
  std::vector<std::string> engines = {"reference"};
  std::vector<ContactLaw> laws = {ContactLaw::hertz};  // a suite's default: every law (SuiteSettings)
  std::vector<double> time_steps_s;                    // fixed-step engines; empty: each engine's default
  std::vector<std::string> contact_paths;  // engines' option "contact" (matched, injected, native); empty: default
  std::map<std::string, std::string> reference_options;                      // options of every reference run
  std::map<std::string, std::map<std::string, std::string>> engine_options;  // per engine
  double output_rate_hz = 4096;
  int jobs = 1;               // worker processes
  double time_limit_s = 600;  // per job (a sweep: per ratio); then it is stopped and recorded
  std::string out;            // output folder
  bool resume = false;
  // Set: runs only this shard (shard_plan.h); --resume then continues the same shard.
  std::optional<Shard> shard;
  std::string resume_command;   // the command that continues this run, kept in a shard's plan for merge's messages
  Measurement measurement;      // sensor rate, merge window, verdicts, series kept
  SimulatorCatalog simulators;  // what runs the jobs (simulators/catalog.h: this binary's)
};

// The configurations into a settings record, in this order: engines, laws (by name), time_steps_s,
// contact_paths, engine_options, reference_options. A suite's --resume compares its records key by key
// and in order, so the order is kept as suites have always written it.
void record_configurations(const MatrixSettings& settings, nlohmann::ordered_json& record);

}  // namespace ib
