#include "cli/commands.h"

#include <cerrno>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "harness/records/run_files.h"
#include "model/scenario_toml.h"
#include "simulators/catalog.h"

namespace cli {

// The model an engine builds for a run, in the engine's own format, for a person to open in the
// engine's tools (MuJoCo: MJCF for its viewer; the reference: its modal model as JSON).
int command_export(const std::string& path, const std::string& engine, const std::string& law_name,
                   const std::string& out, double time_step_s, double rate_hz,
                   const std::vector<std::string>& option_pairs) {
  const ib::Scenario scenario = ib::load_scenario(path);
  ib::RunSettings settings;
  settings.law = parse_law(law_name);
  settings.time_step_s = time_step_s;
  settings.output_rate_hz = rate_hz;
  settings.options = parse_options(option_pairs);
  require_engine(engine);
  const std::string text = ib::make_simulator(engine)->export_model(scenario, settings);
  if (text.empty()) {
    std::string exportable;
    for (const auto& name : ib::simulator_names())
      if (!ib::make_simulator(name)->export_model(scenario, settings).empty())
        exportable += (exportable.empty() ? "" : ", ") + name;
    throw std::invalid_argument("--engine " + engine + ": no exportable model; allowed: " + exportable);
  }
  if (out.empty() || out == "-") {
    std::cout << text;
  } else {
    std::ofstream file(out);
    if (!file) throw ib::OutputError(ib::output_error_text(out, "create", errno));
    file << text;
    file.close();
    if (!file) throw ib::OutputError(ib::output_error_text(out, "write", errno));
    std::fprintf(stderr, "model written to %s\n", out.c_str());
  }
  return kExitOk;
}

}  // namespace cli
