// The reference's modal model with the Newton law integrated by Siconos's event-driven scheme (issue 49):
// a second Newton reference, written in another library than the CVODE comparator (cvode_reference.cpp)
// and the reference itself; bench/reference_siconos.py tabulates its agreement with the reference.
//
//   impactbench export SCENARIO --engine reference --law newton --out model.json
//   build/bench/siconos_reference model.json --out DIR [--max-impacts N] [--duration S] [--rtol R] [--atol A]
//                                 [--samples]
//
// Writes DIR/events.csv in the harness's format (as cvode_reference's; an impact has zero duration, no
// force and no indentation), DIR/siconos_run.json (CPU and wall time of the integration, why it stopped,
// the tolerances, the Siconos version) and, with --samples, DIR/samples.csv: both tips' displacement and
// velocity at the model's output samples. It stops after --max-impacts impacts, at the model's duration, or
// where impacts accumulate (the reference makes the tips stick there). Exit 1 with a message naming the
// file or option on bad input or when Siconos fails; the events up to the failure are still written.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "cvode_modal_model.h"
#include "siconos_event_driven.h"

namespace {

using ib::bench::SiconosResult;

// A value as the harness writes it: 17 significant digits, empty for NaN.
std::string number(double value) {
  if (!std::isfinite(value)) return "";
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

void write_events(const std::string& path, const SiconosResult& result) {
  const double none = std::numeric_limits<double>::quiet_NaN();
  std::ofstream out(path);
  out << "onset_time_s,end_time_s,duration_s,approach_velocity_m_s,rebound_velocity_m_s,restitution,peak_force_n,"
         "impulse_n_s,max_indentation_m\n";
  for (const auto& e : result.impacts)
    out << number(e.time_s) << ',' << number(e.time_s) << ",0," << number(e.approach_velocity_m_s) << ','
        << number(e.rebound_velocity_m_s) << ',' << number(e.restitution) << ',' << number(none) << ','
        << number(e.impulse_n_s) << ",0\n";
  if (!out) throw std::runtime_error(path + ": cannot write");
}

void write_samples(const std::string& path, const SiconosResult& result) {
  std::ofstream out(path);
  out << "time_s,frame1_displacement_m,frame2_displacement_m,frame1_velocity_m_s,frame2_velocity_m_s\n";
  for (const auto& s : result.samples)
    out << number(s.time_s) << ',' << number(s.displacement1_m) << ',' << number(s.displacement2_m) << ','
        << number(s.velocity1_m_s) << ',' << number(s.velocity2_m_s) << '\n';
  if (!out) throw std::runtime_error(path + ": cannot write");
}

nlohmann::ordered_json run_summary(const ib::bench::ModalModel& model, const std::string& model_path,
                                   const ib::bench::SiconosSettings& settings, const SiconosResult& result) {
  nlohmann::ordered_json j;
  j["status"] = result.ok ? "ok" : "failed";
  j["reason"] = result.reason;
  j["stopped_by"] = result.stop;
  j["model"] = std::filesystem::absolute(model_path).string();
  j["scenario"] = model.scenario;
  j["law"] = model.law.name;
  j["method"] = "Siconos EventDriven, LsodarOSI, LCP (Lemke) at impact and acceleration levels";
  j["rtol"] = settings.rtol;
  j["atol"] = settings.atol;
  j["max_impacts"] = settings.max_impacts;
  j["duration_s"] = settings.duration > 0 ? std::min(settings.duration, model.duration) : model.duration;
  j["end_time_s"] = result.end_time_s;
  j["modes"] = model.modes();
  j["integration_cpu_time_s"] = result.cpu_time_s;
  j["integration_wall_time_s"] = result.wall_time_s;
  j["cpu_time_per_simulated_s"] = result.end_time_s > 0 ? result.cpu_time_s / result.end_time_s : 0.0;
  j["siconos_events_processed"] = result.events_processed;
  j["impacts"] = result.impacts.size();
  j["versions"] = {{"siconos", ib::bench::siconos_version()}};
  return j;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "The reference's modal model with the Newton law integrated by Siconos's event-driven scheme (Lsodar, "
      "LCPs at impact and acceleration level): events.csv and the integration's cost"};
  std::string model_path, out;
  ib::bench::SiconosSettings settings;
  app.add_option("model", model_path, "the JSON of `impactbench export SCENARIO --engine reference --law newton`")
      ->required();
  app.add_option("--out", out, "folder for events.csv, siconos_run.json (and samples.csv)")->required();
  app.add_option("--max-impacts", settings.max_impacts, "stop after this many impacts (default 20)")
      ->check(CLI::Range(1, 100000000));
  app.add_option("--duration", settings.duration, "stop at this time if the model's duration is longer [s]")
      ->check(CLI::PositiveNumber);
  app.add_option("--rtol", settings.rtol, "Lsodar's relative tolerance (default 1e-12)")->check(CLI::PositiveNumber);
  app.add_option("--atol", settings.atol, "Lsodar's absolute tolerance on q [m sqrt(kg)] and q' (default 1e-14)")
      ->check(CLI::PositiveNumber);
  app.add_flag("--samples", settings.record_samples, "also write samples.csv: the tips at the model's output samples");
  CLI11_PARSE(app, argc, argv);

  try {
    const ib::bench::ModalModel model = ib::bench::read_modal_model(model_path);
    const SiconosResult result = ib::bench::solve_with_siconos(model, settings);
    std::filesystem::create_directories(out);
    write_events(out + "/events.csv", result);
    if (settings.record_samples) write_samples(out + "/samples.csv", result);
    std::ofstream summary(out + "/siconos_run.json");
    summary << run_summary(model, model_path, settings, result).dump(2) << "\n";
    if (!summary) throw std::runtime_error(out + "/siconos_run.json: cannot write");
    if (!result.ok) {
      std::fprintf(stderr, "siconos_reference: %s: %s\n", model_path.c_str(), result.reason.c_str());
      return 1;
    }
    std::printf("siconos_reference: %s: CPU %.4f s to t = %.6g s, %zu impacts (stopped by %s); files in %s\n",
                model.scenario.c_str(), result.cpu_time_s, result.end_time_s, result.impacts.size(),
                result.stop.c_str(), out.c_str());
  } catch (const std::exception& error) {
    std::fprintf(stderr, "siconos_reference: %s\n", error.what());
    return 1;
  }
  return 0;
}
