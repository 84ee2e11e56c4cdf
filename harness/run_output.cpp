#include "run_output.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace ib {
namespace {

using Json = nlohmann::ordered_json;

// NaN and infinities have no JSON form: they are written as null.
Json number(double value) { return std::isfinite(value) ? Json(value) : Json(nullptr); }

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

File open_for_writing(const std::string& path) {
  File f(std::fopen(path.c_str(), "w"));
  if (!f) throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
  return f;
}

void finish(File& f, const std::string& path) {
  if (std::fflush(f.get()) != 0 || std::ferror(f.get()))
    throw std::runtime_error(path + ": write failed: " + std::strerror(errno));
}

}  // namespace

void write_summary_json(const std::string& path, const RunRecord& r) {
  const Metrics& m = r.metrics;
  Json j;
  j["scenario"] = r.scenario.name;
  j["scenario_file"] = r.scenario.source_path;
  j["engine"] = r.engine;
  j["engine_version"] = r.engine_version;
  j["law"] = to_string(r.settings.law);
  j["status"] = to_string(r.result.status);
  j["reason"] = r.result.reason;
  j["duration_s"] = r.scenario.duration_s;
  j["window_start_s"] = m.window_start_s;
  j["window_end_s"] = m.window_end_s;
  j["impacts"] = m.impacts;
  j["excitation_cycles"] = number(m.excitation_cycles);
  j["impacts_per_cycle"] = number(m.impacts_per_cycle);
  j["mean_contact_duration_s"] = number(m.mean_contact_duration_s);
  j["frame1_true_peak_acceleration_g"] = number(m.true_peak_acceleration_g[0]);
  j["frame2_true_peak_acceleration_g"] = number(m.true_peak_acceleration_g[1]);
  j["wall_time_s"] = r.result.cost.wall_time_s;
  j["cpu_time_s"] = r.result.cost.cpu_time_s;
  j["steps"] = r.result.cost.steps;
  Json settings;
  settings["output_rate_hz"] = r.settings.output_rate_hz;
  settings["time_step_s"] = r.settings.time_step_s;
  Json options = Json::object();
  for (const auto& [k, v] : r.settings.options) options[k] = v;
  settings["options"] = options;
  j["settings"] = settings;
  Json diagnostics = Json::object();
  for (const auto& [k, v] : r.result.diagnostics) diagnostics[k] = number(v);
  j["diagnostics"] = diagnostics;
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
  out << j.dump(2) << '\n';
  if (!out) throw std::runtime_error(path + ": write failed: " + std::strerror(errno));
}

void write_series_csv(const std::string& path, const Trajectory& t) {
  File f = open_for_writing(path);
  std::fputs(
      "time_s,frame1_displacement_m,frame1_velocity_m_s,frame1_acceleration_m_s2,"
      "frame2_displacement_m,frame2_velocity_m_s,frame2_acceleration_m_s2,contact_force_n,"
      "frame1_peak_abs_acceleration_m_s2,frame2_peak_abs_acceleration_m_s2,peak_contact_force_n\n",
      f.get());
  for (std::size_t k = 0; k < t.size(); ++k) {
    std::fprintf(f.get(), "%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g\n", t.time_s[k],
                 t.displacement_m[0][k], t.velocity_m_s[0][k], t.acceleration_m_s2[0][k], t.displacement_m[1][k],
                 t.velocity_m_s[1][k], t.acceleration_m_s2[1][k], t.contact_force_n[k],
                 t.peak_abs_acceleration_m_s2[0][k], t.peak_abs_acceleration_m_s2[1][k], t.peak_contact_force_n[k]);
  }
  finish(f, path);
}

void write_events_csv(const std::string& path, const Trajectory& t) {
  File f = open_for_writing(path);
  std::fputs(
      "onset_time_s,end_time_s,duration_s,approach_velocity_m_s,rebound_velocity_m_s,restitution,"
      "peak_force_n,impulse_n_s,max_indentation_m\n",
      f.get());
  for (const ContactEvent& e : t.events) {
    std::fprintf(f.get(), "%.15g,%.15g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g\n", e.onset_time_s, e.end_time_s,
                 e.end_time_s - e.onset_time_s, e.approach_velocity_m_s, e.rebound_velocity_m_s, e.restitution,
                 e.peak_force_n, e.impulse_n_s, e.max_indentation_m);
  }
  finish(f, path);
}

void write_run_folder(const std::string& folder, const RunRecord& record) {
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error) throw std::runtime_error(folder + ": cannot create the output folder: " + error.message());
  write_series_csv(folder + "/series.csv", record.result.trajectory);
  write_events_csv(folder + "/events.csv", record.result.trajectory);
  write_summary_json(folder + "/summary.json", record);
}

}  // namespace ib
