#include "harness/records/run_record.h"

#include <algorithm>
#include <limits>

#include "model/simulator_options.h"

namespace ib {

std::string contact_path_of(const std::string& engine, const std::string& options_text) {
  if (engine.empty() || engine == "reference") return "";
  const std::string key = "contact=";
  for (std::size_t start = 0; start <= options_text.size();) {
    const std::size_t end = std::min(options_text.find(';', start), options_text.size());
    if (options_text.compare(start, key.size(), key) == 0 && end - start > key.size())
      return options_text.substr(start + key.size(), end - start - key.size());
    start = end + 1;
  }
  return to_string(ContactPath::matched);
}

std::string law_simulated_of(const std::string& engine, const std::string& contact_path) {
  if (engine.empty()) return "";
  return contact_path == to_string(ContactPath::native) ? "no" : "yes";
}

std::vector<Field> fields(const RunRecord& r) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Field> out = {
      {"job_id", r.job_id},
      {"scenario", r.scenario},
      {"law", r.law},
      {"engine", r.engine},
      {"time_step_s", r.time_step_s, true},
      {"options", r.options},
      {"contact_path", contact_path_of(r.engine, r.options)},
      {"law_simulated", law_simulated_of(r.engine, contact_path_of(r.engine, r.options))},
      {"same_run_as", r.same_run_as},
      {"chain_links", static_cast<double>(r.chain_links)},
      {"verdict", std::string(to_string(r.verdict))},
      {"reason", r.reason},
      {"duration_s", r.duration_s, true},
      {"window_start_s", r.window.start_s, true},
      {"window_end_s", r.window.end_s, true},
  };
  // Metric and error names come from one place (metrics.h); a run without metrics gets NaN in each.
  const auto metric_fields = flatten(r.metrics.value_or(Metrics{}));
  for (const auto& [name, value] : metric_fields) out.push_back({name, r.metrics ? value : nan});
  for (const auto& [prefix, errors] : {std::pair{"vs_reference_", &r.errors_vs_reference},
                                       std::pair{"vs_chain_reference_", &r.errors_vs_chain_reference}}) {
    for (const auto& [name, value] : flatten(errors->value_or(MetricErrors{}), prefix))
      out.push_back({name, errors->has_value() ? value : nan});
  }
  // Cost per simulated second: what compares runs of different lengths (CPU time first: on a shared
  // machine the wall time also holds the other processes' turns). Per second actually simulated: a
  // fixed-step run stopped as unstable after 0.02 s of 20 s cost what it cost for 0.02 s, not a
  // thousandth of a full run's.
  const double simulated_s = r.time_step_s > 0 && r.cost.steps > 0
                                 ? std::min(r.duration_s, static_cast<double>(r.cost.steps) * r.time_step_s)
                                 : r.duration_s;
  const auto per_simulated_second = [&](double time_s) { return simulated_s > 0 ? time_s / simulated_s : nan; };
  out.push_back({"wall_time_s", r.cost.wall_time_s});
  out.push_back({"cpu_time_s", r.cost.cpu_time_s});
  out.push_back({"steps", static_cast<double>(r.cost.steps)});
  out.push_back({"simulated_time_s", simulated_s});
  out.push_back({"wall_time_per_simulated_s", per_simulated_second(r.cost.wall_time_s)});
  out.push_back({"cpu_time_per_simulated_s", per_simulated_second(r.cost.cpu_time_s)});
  out.push_back({"load_average", r.load_average});
  out.push_back({"timed_runs", static_cast<double>(r.timed_runs)});
  out.push_back({"wall_time_min_s", r.timed_runs > 0 ? r.wall_time_min_s : nan});
  out.push_back({"wall_time_max_s", r.timed_runs > 0 ? r.wall_time_max_s : nan});
  out.push_back({"cpu_time_min_s", r.timed_runs > 0 ? r.cpu_time_min_s : nan});
  out.push_back({"cpu_time_max_s", r.timed_runs > 0 ? r.cpu_time_max_s : nan});
  out.push_back({"logged_wall_time_s", r.logged_wall_time_s});
  out.push_back({"logged_cpu_time_s", r.logged_cpu_time_s});
  out.push_back({"output_rate_hz", r.output_rate_hz, true});
  out.push_back({"scenario_file", r.scenario_file});
  out.push_back({"engine_version", r.engine_version});
  out.push_back({"ensemble_start", static_cast<double>(r.start.index)});
  out.push_back({"ensemble_starts", static_cast<double>(r.start.count)});
  out.push_back({"initial_displacement_offset_m", r.start.initial_displacement_offset_m, true});
  return out;
}

const std::vector<std::string>& timing_field_names() {
  static const std::vector<std::string> names = {
      "wall_time_s",    "cpu_time_s",         "wall_time_per_simulated_s", "cpu_time_per_simulated_s",
      "load_average",   "wall_time_min_s",    "wall_time_max_s",           "cpu_time_min_s",
      "cpu_time_max_s", "logged_wall_time_s", "logged_cpu_time_s"};
  return names;
}

}  // namespace ib
