#include "harness/jobs/recorder.h"

#include <filesystem>
#include <map>
#include <stdexcept>
#include <system_error>

#include <nlohmann/json.hpp>

#include "harness/records/jsonl_table.h"
#include "harness/records/number_text.h"
#include "harness/records/run_files.h"

namespace ib {

namespace {

std::string csv_cell(const nlohmann::ordered_json& value) {
  if (value.is_null()) return "";
  if (value.is_string()) return csv_escape(value.get<std::string>());
  return value.dump();
}

// The row's values that are not lists or objects, comma-separated: its keys (header) or its values.
std::string csv_line(const nlohmann::ordered_json& row, bool header) {
  std::string line;
  bool first = true;
  for (auto it = row.begin(); it != row.end(); ++it) {
    if (it.value().is_structured()) continue;
    line += (first ? "" : ",") + (header ? it.key() : csv_cell(it.value()));
    first = false;
  }
  return line + "\n";
}

}  // namespace

std::string collect_row(const ResultTable& table, const std::string& csv_header, const std::string& unit_folder) {
  const std::string json = read_text_file(unit_folder + "/row.jsonl"), csv = read_text_file(unit_folder + "/row.csv");
  append_table_row(table.jsonl_path(), table.csv_path(), csv_header, csv, json);
  remove_row_files(unit_folder);
  return json;
}

void remove_row_files(const std::string& unit_folder) {
  std::error_code error;
  std::filesystem::remove(unit_folder + "/row.jsonl", error);
  std::filesystem::remove(unit_folder + "/row.csv", error);
}

int write_table_in_plan_order(const ResultTable& table, const std::vector<std::string>& unit_folders,
                              const std::string& row_file, const std::vector<std::string>& sample_files) {
  std::string jsonl, csv;
  std::map<std::string, std::string> samples;  // by file name
  int rows = 0;
  for (const std::string& folder : unit_folders) {
    const std::string text = read_text_file(folder + "/" + row_file);
    if (text.empty()) continue;
    const auto row = nlohmann::ordered_json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (!row.is_object())
      throw std::runtime_error(folder + "/" + row_file +
                               ": not a JSON object; remove the folder and run with --resume");
    if (csv.empty()) csv = csv_line(row, /*header=*/true);
    csv += csv_line(row, /*header=*/false);
    jsonl += row.dump() + "\n";
    for (const std::string& name : sample_files) {
      const std::string these = read_text_file(folder + "/" + name);
      const auto header_end = these.find('\n');
      if (header_end == std::string::npos) continue;
      std::string& all = samples[name];
      all += all.empty() ? these : these.substr(header_end + 1);
    }
    ++rows;
  }
  replace_text_file(table.jsonl_path(), jsonl);
  replace_text_file(table.csv_path(), csv);
  for (const std::string& name : sample_files) replace_text_file(table.dir + "/" + name, samples[name]);
  return rows;
}

}  // namespace ib
