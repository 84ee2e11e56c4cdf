// `modes`: each frame's natural frequencies and tip modal values, as the reference builds them.
#include "cli/commands.h"

#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "model/scenario_toml.h"
#include "physics/modal_model.h"
#include "reference/reference_simulator.h"

namespace cli {

namespace {

struct ModesOptions {
  std::string scenario_path;
  bool json = false;
  std::vector<std::string> option_pairs;
};

int command_modes(const std::string& path, bool json, const std::vector<std::string>& option_pairs) {
  const ib::Scenario scenario = ib::load_scenario(path);
  const ib::ReferenceSettings settings =
      ib::reference_settings_from_options(parse_engine_options(option_pairs, "reference"));
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
      for (int n = 0; n < basis.size(); ++n) std::printf("  %4d %16.6f %22.9f %14.6g\n", n + 1, hz[n], tip[n], zeta[n]);
    }
  }
  if (json) std::cout << out.dump(2) << '\n';
  return kExitOk;
}

}  // namespace

Command add_modes_command(CLI::App& app) {
  auto o = std::make_shared<ModesOptions>();
  CLI::App* modes = app.add_subcommand("modes", "each frame's natural frequencies [Hz] and tip modal values");
  modes->add_option("scenario", o->scenario_path, "scenario file (.toml)")->required();
  modes->add_flag("--json", o->json, "print JSON");
  modes->add_option("--option", o->option_pairs,
                    "reference option name=value (modes=beam|beam_paper|chain, n=N, links=K)");
  return {modes, [o] { return command_modes(o->scenario_path, o->json, o->option_pairs); }};
}

}  // namespace cli
