// What a suite's folder remembers of the suites run into it (suite_runner.h): DIR/suite.jsonl, one line
// per suite command (a study runs several into one folder), its settings and the job ids it planned.
// --resume continues a suite whose settings equal one of them; --extend adds a suite with other settings,
// provided no job it shares with the folder was recorded under other result-deciding settings. So a
// resumed suite never mixes runs of another duration, rate, window or scenario file.
#include "harness/suite/suite_runner.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "harness/jobs/campaign_folder.h"
#include "harness/records/jsonl_table.h"
#include "harness/records/reporters.h"
#include "harness/records/run_files.h"
#include "harness/scoring/metric_catalog.h"

namespace ib::suite_internal {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

constexpr const char* kSettingsFile = "/suite.jsonl";

// The keys of a settings record that choose which jobs a suite has (they are in the job ids), how a result
// is judged rather than measured (the accuracy tolerances: a step search under other tolerances reuses the
// probes it shares), or which files a run keeps (the series: a reference keeps its window whatever it says,
// and a study's 1e-4 s runs keep none), or how many starts an ensemble has (a start is the same run in any
// ensemble of the same step), as opposed to how every job is run and measured (the result-deciding ones).
const std::set<std::string> kMatrixKeys = {"scenario_files",
                                           "engines",
                                           "laws",
                                           "time_steps_s",
                                           "contact_paths",
                                           "engine_options",
                                           "step_search",
                                           "verdict_tolerances",
                                           "series",
                                           "series_rate_hz",
                                           "ensemble",
                                           "recommended",
                                           "reference_chain_links"};

// An ensemble's starts K >= 1 are the same runs in two parts only with the same displacement step (their job ids
// name K, not the step); start 0, the scenario as written, is the same run whatever the ensemble.
std::string differing_ensemble_step(const nlohmann::ordered_json& a, const nlohmann::ordered_json& b) {
  if (!a.contains("ensemble") || !b.contains("ensemble")) return "";
  return a["ensemble"]["displacement_step_m"] == b["ensemble"]["displacement_step_m"] ? ""
                                                                                      : "ensemble displacement_step_m";
}

struct SuitePart {
  Json settings;
  std::set<std::string> jobs;
  std::string command;
};

// DIR/suite.jsonl's lines. A line cut short by a kill (the last, without its line break) is skipped;
// any other line that is not a suite's record makes the folder unreadable: say where.
std::vector<SuitePart> read_parts(const std::string& folder) {
  std::vector<SuitePart> parts;
  std::ifstream in(folder + kSettingsFile, std::ios::binary);
  if (!in) return parts;
  std::stringstream whole;
  whole << in.rdbuf();
  const std::string text = whole.str();
  std::size_t at = 0;
  for (int line_number = 1; at < text.size(); ++line_number) {
    const std::size_t end = text.find('\n', at);
    if (end == std::string::npos) break;  // cut short while being written: the command writes it again
    const std::string line = text.substr(at, end - at);
    at = end + 1;
    const Json j = Json::parse(line, nullptr, /*allow_exceptions=*/false);
    if (!j.is_object() || !j.contains("settings") || !j["settings"].is_object() || !j.contains("jobs") ||
        !j["jobs"].is_array())
      throw std::invalid_argument(folder + kSettingsFile + " line " + std::to_string(line_number) +
                                  ": not a suite's settings record (expected {\"settings\": {...}, \"jobs\": [...]}); "
                                  "the folder is damaged: restore the file or choose another --out");
    SuitePart part;
    part.settings = j["settings"];
    for (const auto& id : j["jobs"])
      if (id.is_string()) part.jobs.insert(id.get<std::string>());
    part.command = j.value("command", "");
    parts.push_back(std::move(part));
  }
  return parts;
}

}  // namespace

nlohmann::ordered_json settings_record(const SuitePlan& plan, std::size_t part) {
  const SuiteSettings& settings = plan.parts[part];
  Json s;
  Json files = Json::object();
  for (std::size_t i = 0; i < plan.scenarios.size(); ++i)
    if (plan.scenario_part[i] == part)
      files[plan.scenarios[i].source_path] = file_digest(plan.scenarios[i].source_path);
  // a file that cannot be read is "unreadable" whatever it holds: a --resume after fixing it runs it
  for (const std::string& file : plan.part_files[part])
    if (!files.contains(file)) files[file] = "unreadable";
  s["scenario_files"] = files;
  record_configurations(settings, s);
  s["output_rate_hz"] = settings.output_rate_hz;
  s["max_duration_s"] = settings.max_duration_s;
  const Measurement& m = settings.measurement;
  s["window_s"] = m.window_s ? Json(*m.window_s) : Json(nullptr);
  s["sensor_rate_hz"] = m.sensor_rate_hz;
  s["merge_window_s"] = m.merge_window_s;
  s["timed_repeats"] = m.timed_repeats;
  s["series"] = m.series == SeriesOutput::all ? "all" : m.series == SeriesOutput::none ? "none" : "window";
  if (m.series_rate_hz > 0) s["series_rate_hz"] = m.series_rate_hz;  // absent when unused: older folders resume
  s["verdict_tolerances"] = tolerance_values(m.verdicts.accuracy);   // the metric catalog's, in its order
  s["stability_bounds"] = {m.verdicts.stability.displacement_bound_fraction_of_length,
                           m.verdicts.stability.penetration_bound_gaps, m.verdicts.stability.penetration_bound_floor_m,
                           m.verdicts.stability.energy_growth_tolerance};
  if (settings.ensemble.reference_starts > 1)  // absent for single runs: older folders resume
    s["ensemble"] = {{"engine_starts", settings.ensemble.engine_starts},
                     {"reference_starts", settings.ensemble.reference_starts},
                     {"displacement_step_m", settings.ensemble.displacement_step_m}};
  if (settings.recommended) s["recommended"] = true;  // absent otherwise: older folders resume
  if (!settings.reference_chain_links.empty()) s["reference_chain_links"] = settings.reference_chain_links;  // likewise
  if (settings.step_search) {
    s["step_search"] = {settings.step_search->min_step_s, settings.step_search->max_step_s,
                        settings.step_search->points_per_octave};
    if (settings.step_search->walk) s["step_search"].push_back("walk");  // absent for a bisection: older folders resume
  } else
    s["step_search"] = nullptr;
  return s;
}

namespace {

// The same suite but for scenario files that could not be read then and can now (fixed since).
bool same_but_fixed(const Json& then, const Json& now) {
  if (!differing_keys(then, now, {"scenario_files"}).empty()) return false;
  const Json& a = then["scenario_files"];
  const Json& b = now["scenario_files"];
  if (a.size() != b.size()) return false;
  for (const auto& [file, digest] : a.items())
    if (!b.contains(file) || (b[file] != digest && digest != "unreadable")) return false;
  return true;
}

std::string line_of(const Json& settings, const std::vector<std::string>& jobs, const std::string& command) {
  Json line;
  line["settings"] = settings;
  line["jobs"] = jobs;
  line["command"] = command;
  return line.dump(-1, ' ', false, Json::error_handler_t::replace) + "\n";
}

// A job an earlier part of this run planned runs once, under that part's settings: they must decide its
// result as this part's would. part_jobs: each part's job ids; record_of(part): a part's settings record, made
// only for an earlier part that shares a job (it reads and digests the part's scenario files).
template <class RecordOf>
void refuse_a_job_planned_under_other_settings(const std::vector<std::vector<std::string>>& part_jobs,
                                               std::size_t this_part, const Json& current,
                                               const std::vector<std::string>& planned, RecordOf&& record_of) {
  for (std::size_t earlier = 0; earlier < this_part; ++earlier) {
    const std::set<std::string> theirs(part_jobs[earlier].begin(), part_jobs[earlier].end());
    for (const std::string& id : planned) {
      if (!theirs.count(id)) continue;
      const Json settings = record_of(earlier);
      std::string keys = differing_keys(settings, current, kMatrixKeys);
      if (keys.empty()) keys = differing_ensemble_step(settings, current);
      if (!keys.empty())
        throw std::invalid_argument("job " + id + " is planned by two parts with other settings (" + keys +
                                    " differ): give them other scenarios, laws or steps, or the same settings");
      break;
    }
  }
}

// A suite of the folder whose scenario file was fixed since (same_but_fixed): the rows saying it could not be
// read go (unless another suite of the folder plans them) and this suite's line replaces the old one. Returns
// whether there was one; recorded loses the dropped rows.
bool replace_a_fixed_suite(const std::string& folder, std::vector<SuitePart>& parts, const Json& current,
                           const std::vector<std::string>& planned, const std::string& command,
                           std::set<std::string>& recorded) {
  for (SuitePart& part : parts) {
    if (!same_but_fixed(part.settings, current)) continue;
    std::set<std::string> stale, kept(planned.begin(), planned.end());
    for (const SuitePart& other : parts)
      if (&other != &part) kept.insert(other.jobs.begin(), other.jobs.end());
    for (const std::string& id : part.jobs)
      if (!kept.count(id) && recorded.count(id)) stale.insert(id);
    if (!stale.empty()) {
      drop_runs(folder, stale);
      for (const std::string& id : stale) {
        recorded.erase(id);
        std::fprintf(stderr, "suite: %s dropped: its scenario file can be read now\n", id.c_str());
      }
    }
    part.settings = current;
    part.jobs = std::set<std::string>(planned.begin(), planned.end());
    part.command = command;
    std::string text;
    for (const SuitePart& p : parts)
      text += line_of(p.settings, std::vector<std::string>(p.jobs.begin(), p.jobs.end()), p.command);
    replace_text_file(folder + kSettingsFile, text);
    return true;
  }
  return false;
}

// A suite of other settings in the folder without --extend: refused, naming the keys that differ from the
// folder's suite closest to this one.
[[noreturn]] void refuse_another_suite(const std::string& folder, const std::vector<SuitePart>& parts,
                                       const Json& current) {
  std::string keys, command;
  for (const SuitePart& part : parts) {
    const std::string k = differing_keys(part.settings, current);
    if (keys.empty() || std::count(k.begin(), k.end(), ',') < std::count(keys.begin(), keys.end(), ','))
      keys = k, command = part.command;
  }
  refuse_other_settings(folder, CampaignKind::suite, keys, command);
}

// --extend: a job this suite shares with the folder must have been recorded under the same result-deciding
// settings and from the same scenario file (file_of: a planned job's scenario file), or the folder would mix them.
void refuse_mixed_settings(const std::string& folder, const std::vector<SuitePart>& parts, const Json& current,
                           const std::vector<std::string>& planned, const std::set<std::string>& recorded,
                           const std::map<std::string, std::string>& file_of) {
  for (const std::string& id : planned) {
    if (!recorded.count(id)) continue;
    for (const SuitePart& part : parts) {
      if (!part.jobs.count(id)) continue;
      std::string keys = differing_keys(part.settings, current, kMatrixKeys);
      if (keys.empty()) keys = differing_ensemble_step(part.settings, current);
      if (const auto f = file_of.find(id); f != file_of.end()) {
        const Json& then = part.settings["scenario_files"];
        if (then.contains(f->second) && then[f->second] != current["scenario_files"][f->second])
          keys += (keys.empty() ? "" : ", ") + ("the scenario file " + f->second + " (changed since)");
      }
      if (!keys.empty())
        throw std::invalid_argument(folder + ": job " + id + " was recorded with other settings (" + keys +
                                    (part.command.empty() ? "" : ", by: " + part.command) +
                                    "); --extend adds jobs, it does not mix settings: choose another --out");
      break;
    }
  }
}

}  // namespace

void SuiteRunner::check_and_record_settings(std::size_t this_part) {
  const Json current = settings_record(plan_, this_part);
  std::vector<SuitePart> parts = read_parts(settings_.out);
  // this part's jobs in planned order (a shard's: those it kept), also those an earlier part plans
  const std::set<std::string> mine(plan_.part_jobs[this_part].begin(), plan_.part_jobs[this_part].end());
  std::vector<std::string> planned;
  for (const std::string& id : planned_job_ids(plan_))
    if (mine.count(id)) planned.push_back(id);
  refuse_a_job_planned_under_other_settings(plan_.part_jobs, this_part, current, planned,
                                            [this](std::size_t part) { return settings_record(plan_, part); });
  for (const SuitePart& part : parts)
    if (part.settings == current) return;  // the same suite: --resume continues it
  if (replace_a_fixed_suite(settings_.out, parts, current, planned, settings_.resume_command, recorded_)) return;
  if (!parts.empty() && !settings_.extend && this_part == 0) refuse_another_suite(settings_.out, parts, current);
  std::map<std::string, std::string> file_of;
  for (const PlannedJob& job : plan_.jobs) file_of[job.id] = plan_.scenarios[job.scenario].source_path;
  refuse_mixed_settings(settings_.out, parts, current, planned, recorded_, file_of);
  append_text_file(settings_.out + kSettingsFile, line_of(current, planned, settings_.resume_command));
}

}  // namespace ib::suite_internal
