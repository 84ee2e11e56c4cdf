#include "harness/records/reporters.h"

#include <filesystem>
#include <variant>

#include <nlohmann/json.hpp>

#include "harness/records/jsonl_table.h"
#include "harness/records/number_text.h"
#include "harness/records/recorded_run.h"
#include "harness/records/run_files.h"

namespace ib {
namespace {

using Json = nlohmann::ordered_json;

Json to_json(const RunRecord& record) {
  Json j = json_object(fields(record));
  j["timed_out"] = record.timed_out;
  j["scenario_digest"] = record.scenario_digest;
  j["scenario_file_absolute"] = record.scenario_file_absolute;
  // A list, in the JSON records only (runs.csv has one line per run and no column for it): docs/results.md.
  j["warnings"] = record.warnings;
  Json diagnostics = Json::object();
  for (const auto& [name, value] : record.diagnostics) diagnostics[name] = json_number(value);
  j["diagnostics"] = diagnostics;
  return j;
}

}  // namespace

std::string csv_header(const RunRecord& record) { return csv_header_line(fields(record)); }

std::string csv_row(const RunRecord& record) { return csv_row_line(fields(record)); }

// Invalid UTF-8 in a text field (a scenario name, a reason quoting an engine's message) is replaced,
// not an exception that would lose the run.
std::string json_line(const RunRecord& record) {
  return to_json(record).dump(-1, ' ', false, Json::error_handler_t::replace) + "\n";
}

void write_summary_json(const std::string& path, const RunRecord& record) {
  write_text_file(path, to_json(record).dump(2, ' ', false, Json::error_handler_t::replace) + "\n");
}

void append_run(const std::string& folder, const RunRecord& record) {
  append_table_row(folder + "/runs.jsonl", folder + "/runs.csv", csv_header(RunRecord{}), csv_row(record),
                   json_line(record));
}

static KeyOf run_key_of(const std::string& folder) {
  return [folder](const std::string& line, std::string& problem) -> std::string {
    const RecordedRun run = read_recorded_run(line);
    if (!run.readable || run.job_id.empty()) return "";  // cut short by a kill, or not a run's record
    const Json j = Json::parse(line);                    // readable: it parsed
    // every column of this build's layout that the line has, of its type (a number may be null: NaN)
    for (const Field& f : fields(RunRecord{})) {
      const auto value = j.find(f.name);
      if (value == j.end()) continue;
      const bool text = std::holds_alternative<std::string>(f.value);
      if (text ? !value->is_string() : !(value->is_number() || value->is_null())) {
        problem = run.job_id + ": " + f.name + " is " + value->dump() + ", expected " + (text ? "text" : "a number");
        return "";
      }
    }
    // a run that ran has its folder (a job that could not start has none)
    if ((run.verdict == Verdict::ok || run.verdict == Verdict::inaccurate || run.verdict == Verdict::unstable) &&
        !std::filesystem::exists(folder + "/runs/" + run.job_id + "/summary.json")) {
      problem = run.job_id + ": its run folder " + folder + "/runs/" + run.job_id + "/ (summary.json) is gone";
      return "";
    }
    return run.job_id;
  };
}

std::set<std::string> repair_and_list_runs(const std::string& folder, std::vector<std::string>* repairs) {
  return repair_jsonl_table(folder + "/runs.jsonl", folder + "/runs.csv", column_names(fields(RunRecord{})),
                            run_key_of(folder), repairs);
}

void drop_runs(const std::string& folder, const std::set<std::string>& job_ids) {
  const KeyOf keep = [&job_ids](const std::string& line, std::string&) {
    const RecordedRun run = read_recorded_run(line);
    return run.readable && !job_ids.count(run.job_id) ? run.job_id : std::string();
  };
  repair_jsonl_table(folder + "/runs.jsonl", folder + "/runs.csv", column_names(fields(RunRecord{})), keep);
  std::error_code error;
  for (const std::string& id : job_ids) std::filesystem::remove_all(folder + "/runs/" + id, error);
}

std::vector<std::string> runs_table_problems(const std::string& folder) {
  return scan_jsonl_table(folder + "/runs.jsonl", folder + "/runs.csv", run_key_of(folder)).problems;
}

}  // namespace ib
