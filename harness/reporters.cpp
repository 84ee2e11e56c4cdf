#include "harness/reporters.h"

#include "harness/jsonl_table.h"
#include "harness/recorded_run.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

#include "harness/number_text.h"
#include "harness/run_files.h"

namespace ib {
namespace {

using Json = nlohmann::ordered_json;

Json to_json(const RunRecord& record) {
  Json j;
  for (const Field& f : fields(record)) {
    if (const auto* text = std::get_if<std::string>(&f.value)) j[f.name] = *text;
    else {
      j[f.name] = json_number(std::get<double>(f.value), f.exact);
    }
  }
  j["timed_out"] = record.timed_out;
  Json diagnostics = Json::object();
  for (const auto& [name, value] : record.diagnostics) diagnostics[name] = json_number(value);
  j["diagnostics"] = diagnostics;
  return j;
}

}  // namespace

std::string csv_header(const RunRecord& record) {
  std::string line;
  for (const Field& f : fields(record)) line += (line.empty() ? "" : ",") + f.name;
  return line + "\n";
}

std::string csv_row(const RunRecord& record) {
  std::string line;
  bool first = true;
  for (const Field& f : fields(record)) {
    if (!first) line += ",";
    first = false;
    if (const auto* text = std::get_if<std::string>(&f.value)) line += csv_escape(*text);
    else line += f.exact ? exact_number_text(std::get<double>(f.value)) : number_text(std::get<double>(f.value));
  }
  return line + "\n";
}

// Invalid UTF-8 in a text field (a scenario name, a reason quoting an engine's message) is replaced,
// not an exception that would lose the run.
std::string json_line(const RunRecord& record) {
  return to_json(record).dump(-1, ' ', false, Json::error_handler_t::replace) + "\n";
}

void write_summary_json(const std::string& path, const RunRecord& record) {
  write_text_file(path, to_json(record).dump(2, ' ', false, Json::error_handler_t::replace) + "\n");
}

void append_rows(const std::string& folder, const std::string& csv_row_text, const std::string& json_line_text) {
  append_text_file(folder + "/runs.jsonl", json_line_text);
  const std::string csv = folder + "/runs.csv";
  std::ifstream existing(csv);
  const bool fresh = !existing.good() || existing.peek() == std::ifstream::traits_type::eof();
  append_text_file(csv, (fresh ? csv_header(RunRecord{}) : "") + csv_row_text);
}

void append_run(const std::string& folder, const RunRecord& record) {
  append_rows(folder, csv_row(record), json_line(record));
}

std::set<std::string> repair_and_list_runs(const std::string& folder) {
  // A line that is not a run's record (cut short by a kill) is dropped: its job runs again.
  std::vector<std::string> columns;
  for (const Field& f : fields(RunRecord{})) columns.push_back(f.name);
  return repair_jsonl_table(folder + "/runs.jsonl", folder + "/runs.csv", columns, [](const std::string& line) {
    const RecordedRun run = read_recorded_run(line);
    return run.readable ? run.job_id : std::string();
  });
}

}  // namespace ib
