#include "cli/commands.h"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "harness/jobs/run_job.h"
#include "harness/scoring/metrics.h"
#include "model/scenario_toml.h"

namespace cli {

namespace {

struct ScoreOptions {
  std::string folder, scenario_path, reference_folder;
  bool json = false;
  MeasurementOptions measurement;
};

// A run made elsewhere (series.csv and events.csv in the harness's format, run_files.h), measured with the
// harness's own metric code exactly as every simulator's run is; with a reference folder, its errors
// against it too (the vs_reference_* figures of runs.csv).
int command_score(const std::string& folder, const std::string& scenario_path, const std::string& reference_folder,
                  bool json, const MeasurementOptions& measurement_options) {
  const ib::Scenario scenario = ib::load_scenario(scenario_path);
  const ib::Measurement measurement = measurement_options.build();
  const ib::MetricSettings metric_settings = ib::metric_settings(scenario, measurement);
  const ib::ReferenceData run = ib::load_reference(folder, scenario, measurement);
  std::vector<std::pair<std::string, double>> figures = ib::flatten(run.metrics);
  if (!reference_folder.empty()) {
    const ib::ReferenceData reference = ib::load_reference(reference_folder, scenario, measurement);
    const ib::MetricErrors errors =
        ib::compare_metrics(run.metrics, run.trajectory, reference.metrics, reference.trajectory, metric_settings);
    for (const auto& figure : ib::flatten(errors, "vs_reference_")) figures.push_back(figure);
  }
  if (json) {
    nlohmann::ordered_json out;
    out["run_folder"] = folder;
    out["scenario_file"] = scenario_path;
    if (!reference_folder.empty()) out["reference_folder"] = reference_folder;
    out["window_start_s"] = metric_settings.window.start_s;
    out["window_end_s"] = metric_settings.window.end_s;
    for (const auto& [name, value] : figures)
      out[name] = std::isfinite(value) ? nlohmann::ordered_json(value) : nullptr;
    std::cout << out.dump(2) << '\n';
  } else {
    std::printf("%s scored over [%.17g, %.17g] s\n", folder.c_str(), metric_settings.window.start_s,
                metric_settings.window.end_s);
    for (const auto& [name, value] : figures) std::printf("  %-45s %.17g\n", name.c_str(), value);
  }
  return kExitOk;
}

}  // namespace

Command add_score_command(CLI::App& app) {
  auto o = std::make_shared<ScoreOptions>();
  CLI::App* score = app.add_subcommand("score",
                                       "measure a run folder's series.csv and events.csv (from any solver) with "
                                       "the harness's metrics; print them with the names of runs.csv");
  score->add_option("run", o->folder, "folder with series.csv and events.csv in the harness's format")->required();
  score->add_option("--scenario", o->scenario_path, "the scenario file (.toml) the run was made for")->required();
  score->add_option("--reference", o->reference_folder,
                    "a run folder to compare with (adds the vs_reference_* figures)");
  score->add_flag("--json", o->json, "print JSON (NaN as null)");
  o->measurement.add_to(score, /*with_timing=*/false);
  return {score,
          [o] { return command_score(o->folder, o->scenario_path, o->reference_folder, o->json, o->measurement); }};
}

}  // namespace cli
