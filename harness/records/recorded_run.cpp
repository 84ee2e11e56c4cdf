#include "harness/records/recorded_run.h"

#include <fstream>
#include <nlohmann/json.hpp>

namespace ib {

namespace {

using Json = nlohmann::json;

double number_or_nan(const Json& j, const std::string& key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : RecordedRun::kNaN;
}

std::string text_or_empty(const Json& j, const std::string& key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_string() ? it->get<std::string>() : "";
}

HeadlineErrors errors(const Json& j, const std::string& prefix) {
  HeadlineErrors e;
  e.frame1_sensor_peak_relative = number_or_nan(j, prefix + "frame1_sensor_peak_relative_error");
  e.contact_duration_relative = number_or_nan(j, prefix + "contact_duration_relative_error");
  e.impacts_per_cycle_difference = number_or_nan(j, prefix + "impacts_per_cycle_difference");
  return e;
}

}  // namespace

RecordedRun read_recorded_run(const std::string& json_line) {
  const Json j = Json::parse(json_line, nullptr, /*allow_exceptions=*/false);
  RecordedRun r;
  if (!j.is_object()) return r;
  const auto verdict = verdict_from_string(text_or_empty(j, "verdict"));
  if (!verdict) return r;
  r.readable = true;
  r.job_id = text_or_empty(j, "job_id");
  r.verdict = *verdict;
  r.reason = text_or_empty(j, "reason");
  const auto timed_out = j.find("timed_out");
  r.timed_out = timed_out != j.end() && timed_out->is_boolean() && timed_out->get<bool>();
  r.steps = number_or_nan(j, "steps");
  r.wall_time_s = number_or_nan(j, "wall_time_s");
  r.frame1_sensor_peak_g = number_or_nan(j, "frame1_sensor_peak_acceleration_g");
  r.contact_duration_mean_s = number_or_nan(j, "contact_duration_mean_s");
  r.impacts_per_cycle = number_or_nan(j, "impacts_per_cycle");
  r.vs_reference = errors(j, "vs_reference_");
  r.vs_chain_reference = errors(j, "vs_chain_reference_");
  return r;
}

std::map<std::string, std::string> recorded_run_lines(const std::string& folder) {
  std::map<std::string, std::string> lines;
  std::ifstream in(folder + "/runs.jsonl");
  for (std::string line; std::getline(in, line);)
    if (const RecordedRun run = read_recorded_run(line); run.readable) lines[run.job_id] = line;
  return lines;
}

}  // namespace ib
