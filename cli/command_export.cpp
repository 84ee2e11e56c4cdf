#include "cli/commands.h"

#include <cerrno>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>

#include "harness/records/run_files.h"
#include "model/scenario_toml.h"
#include "simulators/catalog.h"

namespace cli {

namespace {

struct ExportOptions {
  std::string path, engine, law = "hertz", out;
  double time_step_s = 0;  // 0: the engine's default
  double rate_hz = 4096;
  std::vector<std::string> option_pairs;
};

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
  settings.options = parse_engine_options(option_pairs, engine);
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

}  // namespace

Command add_export_command(CLI::App& app) {
  auto o = std::make_shared<ExportOptions>();
  // default: the build's first engine (the catalog's order: adapters/CMakeLists.txt), the reference when it has none
  const std::vector<std::string> simulators = ib::simulator_names();
  o->engine = simulators.size() > 1 ? simulators[1] : simulators.front();
  CLI::App* export_model =
      app.add_subcommand("export",
                         "write the model a simulator builds for a scenario, in its own format "
                         "(an engine's for its viewer, e.g. MJCF; reference: its modal model as JSON)");
  export_model->add_option("scenario", o->path, "scenario file (.toml)")->required();
  export_model->add_option("--engine", o->engine, "engine (engines --names)")->capture_default_str();
  export_model->add_option("--law", o->law, "contact law: hertz, viscoelastic or newton")->capture_default_str();
  add_shared_option(export_model, Shared::dt, o->time_step_s, "time step [s]; default: the engine's", false);
  export_model->add_option("--option", o->option_pairs,
                           "engine option name=value or ENGINE.name=value (ENGINE: --engine's), repeatable");
  export_model->add_option("--out", o->out, "output file; default: standard output");
  add_shared_option(export_model, Shared::rate, o->rate_hz,
                    "reference: output sample rate of the run the model is for [Hz]");
  return {export_model, [o] {
            return command_export(o->path, o->engine, o->law, o->out, o->time_step_s, o->rate_hz, o->option_pairs);
          }};
}

}  // namespace cli
