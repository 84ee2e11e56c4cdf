// sweep.jsonl, sweep.csv and poincare.csv, made from the row folders in planned order: one row per
// ratio whatever interruptions, resumes or shards produced them.
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "harness/records/number_text.h"
#include "harness/records/run_files.h"
#include "harness/sweep/sweep.h"

namespace ib {

namespace {

std::string csv_cell(const nlohmann::ordered_json& value) {
  if (value.is_null()) return "";
  if (value.is_string()) return csv_escape(value.get<std::string>());
  return value.dump();
}

}  // namespace

int write_sweep_tables(const std::string& folder, const std::vector<std::string>& row_ids) {
  std::string jsonl, csv, poincare;
  int rows = 0;
  for (const std::string& id : row_ids) {
    const std::string row_folder = folder + "/runs/" + id;
    const std::string text = read_text_file(row_folder + "/row.json");
    if (text.empty()) continue;
    const auto row = nlohmann::ordered_json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (!row.is_object())
      throw std::runtime_error(row_folder + "/row.json: not a JSON object; remove the folder and run with --resume");
    // A list (the row's warnings) is in sweep.jsonl alone: a CSV cell holds one value (runs.csv does the same).
    if (csv.empty()) {
      bool first = true;
      for (auto it = row.begin(); it != row.end(); ++it)
        if (!it.value().is_structured()) csv += (first ? "" : ",") + it.key(), first = false;
      csv += "\n";
    }
    bool first = true;
    for (auto it = row.begin(); it != row.end(); ++it)
      if (!it.value().is_structured()) csv += (first ? "" : ",") + csv_cell(it.value()), first = false;
    csv += "\n";
    jsonl += row.dump() + "\n";
    const std::string samples = read_text_file(row_folder + "/poincare.csv");
    const auto header_end = samples.find('\n');
    if (poincare.empty() && header_end != std::string::npos) poincare = samples.substr(0, header_end + 1);
    if (header_end != std::string::npos) poincare += samples.substr(header_end + 1);
    ++rows;
  }
  replace_text_file(folder + "/sweep.jsonl", jsonl);
  replace_text_file(folder + "/sweep.csv", csv);
  replace_text_file(folder + "/poincare.csv", poincare);
  return rows;
}

}  // namespace ib
