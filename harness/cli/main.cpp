// impactbench: the command line. Exit codes: 0 all ok, 1 a run was unstable or failed, 2 bad usage or input.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "metrics.h"
#include "modal_model.h"
#include "reference_simulator.h"
#include "run_output.h"
#include "scenario_toml.h"
#include "simulator.h"

namespace {

constexpr int kExitOk = 0, kExitRunNotOk = 1, kExitBadInput = 2;

// "key=value" pairs from --option.
std::map<std::string, std::string> parse_options(const std::vector<std::string>& pairs) {
  std::map<std::string, std::string> options;
  for (const std::string& pair : pairs) {
    const auto eq = pair.find('=');
    if (eq == std::string::npos || eq == 0)
      throw std::invalid_argument("--option " + pair + ": expected name=value");
    options[pair.substr(0, eq)] = pair.substr(eq + 1);
  }
  return options;
}

int command_modes(const std::string& path, bool json, const std::vector<std::string>& option_pairs) {
  const ib::Scenario scenario = ib::load_scenario(path);
  const ib::ReferenceSettings settings = ib::reference_settings_from_options(parse_options(option_pairs));
  nlohmann::ordered_json out;
  out["scenario"] = scenario.name;
  out["mode_set"] = ib::to_string(settings.modes.set);
  for (int f = 0; f < 2; ++f) {
    const ib::ModalBasis basis = ib::frame_modes(scenario.frames[f], settings.modes);
    nlohmann::ordered_json frame;
    frame["origin"] = basis.origin;
    frame["tip_mass_kg"] = scenario.frames[f].tip_mass_kg;
    frame["tip_effective_mass_kg"] = basis.tip_effective_mass_kg();
    std::vector<double> hz, tip, zeta;
    for (int n = 0; n < basis.size(); ++n) {
      hz.push_back(basis.omega_rad_s[n] / (2 * M_PI));
      tip.push_back(basis.tip[n]);
      zeta.push_back(basis.zeta[n]);
    }
    frame["frequency_hz"] = hz;
    frame["tip_value_per_sqrt_kg"] = tip;
    frame["damping_ratio"] = zeta;
    out["frame" + std::to_string(f + 1)] = frame;
    if (!json) {
      std::printf("frame %d (%s, tip mass %.5f kg, tip effective mass %.5f kg)\n", f + 1, basis.origin.c_str(),
                  scenario.frames[f].tip_mass_kg, basis.tip_effective_mass_kg());
      std::printf("  %4s %16s %22s %14s\n", "mode", "frequency [Hz]", "tip value [1/sqrt(kg)]", "damping [-]");
      for (int n = 0; n < basis.size(); ++n)
        std::printf("  %4d %16.6f %22.9f %14.6g\n", n + 1, hz[n], tip[n], zeta[n]);
    }
  }
  if (json) std::cout << out.dump(2) << '\n';
  return kExitOk;
}

int command_run(const std::string& path, const std::string& engine, const std::string& law_name,
                const std::string& out_dir, double rate_hz, double series_start_s, double time_step_s,
                const std::vector<std::string>& option_pairs) {
  const ib::Scenario scenario = ib::load_scenario(path);
  const auto law = ib::contact_law_from_string(law_name);
  if (!law) throw std::invalid_argument("--law " + law_name + ": unknown law; allowed: hertz, viscoelastic, newton");
  auto simulator = ib::make_simulator(engine);
  if (!simulator) {
    std::string names;
    for (const auto& n : ib::simulator_names()) names += (names.empty() ? "" : ", ") + n;
    throw std::invalid_argument("--engine " + engine + ": not in this build; allowed: " + names);
  }
  ib::RunSettings settings;
  settings.law = *law;
  settings.output_rate_hz = rate_hz;
  settings.series_start_s = series_start_s;
  settings.time_step_s = time_step_s;
  settings.options = parse_options(option_pairs);
  if (!(rate_hz > 0)) throw std::invalid_argument("--rate " + std::to_string(rate_hz) + ": allowed: > 0 Hz");
  const ib::RunResult result = simulator->run(scenario, settings);
  ib::MetricWindow window;
  window.start_s = scenario.scoring_start_s();
  window.end_s = scenario.duration_s;
  window.excitation_frequency_hz = ib::motor_frequency_hz(scenario);
  const ib::Metrics metrics = ib::compute_metrics(result.trajectory, window);
  ib::write_run_folder(out_dir, {scenario, simulator->name(), simulator->version(), settings, result, metrics});
  std::printf("%s %s %s: %s%s%s\n", scenario.name.c_str(), engine.c_str(), law_name.c_str(),
              ib::to_string(result.status), result.reason.empty() ? "" : ": ", result.reason.c_str());
  std::printf("  impacts %d, impacts per cycle %.4g, mean contact duration %.6g s, true peak |a| %.4g g / %.4g g\n",
              metrics.impacts, metrics.impacts_per_cycle, metrics.mean_contact_duration_s,
              metrics.true_peak_acceleration_g[0], metrics.true_peak_acceleration_g[1]);
  std::printf("  wall time %.3f s; files in %s\n", result.cost.wall_time_s, out_dir.c_str());
  return result.status == ib::RunStatus::ok ? kExitOk : kExitRunNotOk;
}

int command_list() {
  std::printf("engines:");
  for (const auto& n : ib::simulator_names()) std::printf(" %s", n.c_str());
  std::printf("\nlaws: hertz viscoelastic newton\n");
  for (const auto& n : ib::simulator_names()) {
    std::printf("options of %s:\n", n.c_str());
    for (const auto& [key, help] : ib::make_simulator(n)->option_help()) std::printf("  %-18s %s\n", key.c_str(), help.c_str());
  }
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"impactbench: a benchmark of physics engines on a two-frame vibro-impact rig"};
  app.require_subcommand(1);

  std::string scenario_path, engine = "reference", law = "hertz", out_dir;
  bool json = false;
  double rate_hz = 4096, series_start_s = -1, time_step_s = 0;
  std::vector<std::string> options;

  CLI::App* modes = app.add_subcommand("modes", "each frame's natural frequencies [Hz] and tip modal values");
  modes->add_option("scenario", scenario_path, "scenario file (.toml)")->required();
  modes->add_flag("--json", json, "print JSON");
  modes->add_option("--option", options, "reference option name=value (modes=beam|beam_paper|chain, n=N, links=K)");

  CLI::App* run = app.add_subcommand("run", "run one scenario with one engine and law; write DIR/summary.json, series.csv, events.csv");
  run->add_option("scenario", scenario_path, "scenario file (.toml)")->required();
  run->add_option("--engine", engine, "simulator (see 'impactbench list')")->capture_default_str();
  run->add_option("--law", law, "contact law: hertz, viscoelastic or newton")->capture_default_str();
  run->add_option("--out", out_dir, "output folder")->required();
  run->add_option("--rate", rate_hz, "output series sample rate [Hz]")->capture_default_str();
  run->add_option("--series-start", series_start_s, "first output sample [s]; default: start of the scoring window");
  run->add_option("--dt", time_step_s, "time step of fixed-step engines [s]");
  run->add_option("--option", options, "simulator option name=value, repeatable (see 'impactbench list')");

  CLI::App* list = app.add_subcommand("list", "the engines, laws and simulator options of this build");
  (void)list;

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? kExitOk : kExitBadInput;
  }
  try {
    if (modes->parsed()) return command_modes(scenario_path, json, options);
    if (run->parsed()) return command_run(scenario_path, engine, law, out_dir, rate_hz, series_start_s, time_step_s, options);
    return command_list();
  } catch (const std::invalid_argument& error) {
    std::fprintf(stderr, "impactbench: %s\n", error.what());
    return kExitBadInput;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "impactbench: %s\n", error.what());
    return kExitBadInput;
  }
}
