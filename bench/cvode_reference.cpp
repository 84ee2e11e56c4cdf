// The reference's modal equations integrated with SUNDIALS CVODE and its root finding, a C comparator
// beside SciPy's solve_ivp (bench/scipy_reference.py); bench/reference_cvode_scipy.py times the three.
//
//   impactbench export SCENARIO --engine reference --law LAW --out model.json
//   build/bench/cvode_reference model.json --out DIR [--method adams] [--rtol R] [--atol A] [--repeat N] [--samples]
//
// Writes DIR/events.csv in the harness's format (harness/records/run_files.h; every contact episode,
// as events.csv of `impactbench run`), DIR/cvode_run.json (the cost: CPU and wall time of the integration,
// the median of --repeat runs, steps, right-hand side and root function evaluations; the versions) and,
// with --samples, DIR/samples.csv: both tips' displacement and velocity at the model's output samples.
// No series.csv: its exact peaks between samples are the SciPy comparator's business; this one compares
// events, and times the integration alone. Exit 1 with a message naming the file or option on bad input.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cvode_modal_model.h"
#include "cvode_solver.h"

namespace {

using ib::bench::CvodeResult;

// A value as the harness writes it: 17 significant digits, empty for NaN.
std::string number(double value) {
  if (!std::isfinite(value)) return "";
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

void write_events(const std::string& path, const CvodeResult& result) {
  std::ofstream out(path);
  out << "onset_time_s,end_time_s,duration_s,approach_velocity_m_s,rebound_velocity_m_s,restitution,peak_force_n,"
         "impulse_n_s,max_indentation_m\n";
  for (const auto& e : result.events)
    out << number(e.onset) << ',' << number(e.end) << ',' << number(e.end - e.onset) << ',' << number(e.approach) << ','
        << number(e.rebound) << ',' << number(e.restitution) << ',' << number(e.peak_force) << ',' << number(e.impulse)
        << ',' << number(e.max_indentation) << '\n';
  if (!out) throw std::runtime_error(path + ": cannot write");
}

void write_samples(const std::string& path, const CvodeResult& result) {
  std::ofstream out(path);
  out << "time_s,frame1_displacement_m,frame2_displacement_m,frame1_velocity_m_s,frame2_velocity_m_s\n";
  for (const auto& s : result.samples)
    out << number(s.t) << ',' << number(s.displacement1) << ',' << number(s.displacement2) << ',' << number(s.velocity1)
        << ',' << number(s.velocity2) << '\n';
  if (!out) throw std::runtime_error(path + ": cannot write");
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// cvode_run.json: what ran, its cost (the median of the timed integrations) and its solver's counts.
nlohmann::ordered_json run_summary(const ib::bench::ModalModel& model, const std::string& model_path,
                                   const ib::bench::CvodeSettings& settings, const CvodeResult& result,
                                   const std::vector<double>& cpu, const std::vector<double>& wall) {
  const double cpu_s = cpu.empty() ? result.cpu_time_s : median(cpu);
  nlohmann::ordered_json j;
  j["status"] = result.ok ? "ok" : "failed";
  j["reason"] = result.reason;
  j["model"] = std::filesystem::absolute(model_path).string();
  j["scenario"] = model.scenario;
  j["law"] = model.law.name;
  j["method"] = settings.method;
  j["rtol"] = settings.rtol;
  j["atol_m_sqrt_kg"] = settings.atol;
  j["duration_s"] = model.duration;
  j["modes"] = model.modes();
  j["integration_cpu_time_s"] = cpu_s;
  j["integration_cpu_times_s"] = cpu;
  j["integration_wall_time_s"] = wall.empty() ? result.wall_time_s : median(wall);
  j["cpu_time_per_simulated_s"] = cpu_s / model.duration;
  j["steps"] = result.steps;
  j["rhs_evaluations"] = result.rhs_evaluations;
  j["root_function_evaluations"] = result.root_evaluations;
  j["nonlinear_iterations"] = result.nonlinear_iterations;
  j["jacobian_evaluations"] = result.jacobian_evaluations;
  j["phases"] = result.phases;
  j["contact_episodes"] = result.events.size();
  j["versions"] = {{"sundials", ib::bench::sundials_version()}};
  return j;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "The reference's modal equations integrated with SUNDIALS CVODE (root finding for contact onset and "
      "release): events.csv and the integration's cost"};
  std::string model_path, out;
  ib::bench::CvodeSettings settings;
  double rtol = 0, atol = 0;
  int repeat = 1;
  bool samples = false;
  app.add_option("model", model_path, "the JSON of `impactbench export SCENARIO --engine reference`")->required();
  app.add_option("--out", out, "folder for events.csv, cvode_run.json (and samples.csv)")->required();
  app.add_option("--method", settings.method,
                 "adams (Adams-Moulton, fixed-point iteration; default), adams-newton, bdf (Newton, dense Jacobian)")
      ->check(CLI::IsMember({"adams", "adams-newton", "bdf"}));
  app.add_option("--rtol", rtol, "relative tolerance (default: the model's reference rtol)")
      ->check(CLI::PositiveNumber);
  app.add_option("--atol", atol, "absolute tolerance [m sqrt(kg)] (default: the model's reference atol)")
      ->check(CLI::PositiveNumber);
  app.add_option("--repeat", repeat, "integrations timed, the median kept (default 1)")->check(CLI::Range(1, 1000));
  app.add_flag("--samples", samples, "also write samples.csv: the tips at the model's output samples");
  CLI11_PARSE(app, argc, argv);

  try {
    const ib::bench::ModalModel model = ib::bench::read_modal_model(model_path);
    settings.rtol = rtol > 0 ? rtol : model.rtol;
    settings.atol = atol > 0 ? atol : model.atol;
    std::vector<double> cpu, wall;
    CvodeResult result;
    for (int i = 0; i < repeat; ++i) {
      // the samples are recorded in the last run only: the timed runs integrate as the comparison does
      result = ib::bench::solve_with_cvode(model, settings, samples && i == repeat - 1);
      if (!result.ok) break;
      if (!(samples && i == repeat - 1) || repeat == 1) {
        cpu.push_back(result.cpu_time_s);
        wall.push_back(result.wall_time_s);
      }
    }
    std::filesystem::create_directories(out);
    if (result.ok) {
      write_events(out + "/events.csv", result);
      if (samples) write_samples(out + "/samples.csv", result);
    }
    const double cpu_s = cpu.empty() ? result.cpu_time_s : median(cpu);
    const nlohmann::ordered_json j = run_summary(model, model_path, settings, result, cpu, wall);
    std::ofstream summary(out + "/cvode_run.json");
    summary << j.dump(2) << "\n";
    if (!summary) throw std::runtime_error(out + "/cvode_run.json: cannot write");
    if (!result.ok) {
      std::fprintf(stderr, "cvode_reference: %s\n", result.reason.c_str());
      return 1;
    }
    std::printf(
        "cvode_reference: %s %s %s: CPU %.4f s (%.3g s per simulated s), %ld steps, %ld f evaluations, "
        "%zu contact episodes; files in %s\n",
        model.scenario.c_str(), model.law.name.c_str(), settings.method.c_str(), cpu_s, cpu_s / model.duration,
        result.steps, result.rhs_evaluations, result.events.size(), out.c_str());
  } catch (const std::exception& error) {
    std::fprintf(stderr, "cvode_reference: %s\n", error.what());
    return 1;
  }
  return 0;
}
