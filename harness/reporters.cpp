#include "harness/reporters.h"

#include <nlohmann/json.hpp>

#include "harness/jsonl_table.h"
#include "harness/number_text.h"
#include "harness/recorded_run.h"
#include "harness/run_files.h"

namespace ib {
namespace {

using Json = nlohmann::ordered_json;

Json to_json(const RunRecord& record) {
  Json j = json_object(fields(record));
  j["timed_out"] = record.timed_out;
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

void append_rows(const std::string& folder, const std::string& csv_row_text, const std::string& json_line_text) {
  append_table_row(folder + "/runs.jsonl", folder + "/runs.csv", csv_header(RunRecord{}), csv_row_text, json_line_text);
}

void append_run(const std::string& folder, const RunRecord& record) {
  append_rows(folder, csv_row(record), json_line(record));
}

std::set<std::string> repair_and_list_runs(const std::string& folder) {
  // A line that is not a run's record (cut short by a kill) is dropped: its job runs again.
  const auto job_id_of = [](const std::string& line) {
    const RecordedRun run = read_recorded_run(line);
    return run.readable ? run.job_id : std::string();
  };
  return repair_jsonl_table(folder + "/runs.jsonl", folder + "/runs.csv", column_names(fields(RunRecord{})), job_id_of);
}

}  // namespace ib
