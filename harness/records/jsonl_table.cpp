#include "harness/records/jsonl_table.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "harness/records/number_text.h"
#include "harness/records/run_files.h"

namespace ib {

std::vector<std::string> column_names(const std::vector<Field>& row) {
  std::vector<std::string> names;
  for (const Field& f : row) names.push_back(f.name);
  return names;
}

std::string csv_header_line(const std::vector<Field>& row) {
  std::string line;
  for (const Field& f : row) line += (line.empty() ? "" : ",") + f.name;
  return line + "\n";
}

std::string csv_row_line(const std::vector<Field>& row) {
  std::string line;
  bool first = true;
  for (const Field& f : row) {
    line += first ? "" : ",";
    first = false;
    if (const auto* text = std::get_if<std::string>(&f.value))
      line += csv_escape(*text);
    else
      line += f.exact ? exact_number_text(std::get<double>(f.value)) : number_text(std::get<double>(f.value));
  }
  return line + "\n";
}

nlohmann::ordered_json json_object(const std::vector<Field>& row) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const Field& f : row) {
    if (const auto* text = std::get_if<std::string>(&f.value))
      j[f.name] = *text;
    else
      j[f.name] = json_number(std::get<double>(f.value), f.exact);
  }
  return j;
}

std::string differing_keys(const nlohmann::ordered_json& a, const nlohmann::ordered_json& b,
                           const std::set<std::string>& ignored) {
  std::string keys;
  for (const auto& [key, value] : a.items())
    if (!ignored.count(key) && (!b.contains(key) || b[key] != value)) keys += (keys.empty() ? "" : ", ") + key;
  for (const auto& [key, value] : b.items())
    if (!ignored.count(key) && !a.contains(key)) keys += (keys.empty() ? "" : ", ") + key;
  return keys;
}

void append_table_row(const std::string& jsonl_path, const std::string& csv_path, const std::string& csv_header,
                      const std::string& csv_row, const std::string& json_line) {
  append_text_file(jsonl_path, json_line);
  std::ifstream existing(csv_path);
  const bool fresh = !existing.good() || existing.peek() == std::ifstream::traits_type::eof();
  append_text_file(csv_path, (fresh ? csv_header : "") + csv_row);
}

JsonlTable scan_jsonl_table(const std::string& jsonl_path, const std::string& csv_path, const KeyOf& key_of) {
  JsonlTable table;
  std::error_code kind_error;
  if (std::filesystem::exists(jsonl_path, kind_error) && !std::filesystem::is_regular_file(jsonl_path, kind_error))
    throw std::runtime_error(jsonl_path + ": not a file (a folder?); expected the results' JSON lines");
  errno = 0;
  std::ifstream in(jsonl_path, std::ios::binary);
  if (!in) {
    if (errno != ENOENT) throw std::runtime_error(jsonl_path + ": cannot read: " + std::strerror(errno));
    std::ifstream csv(csv_path);
    std::string header, row;
    if (std::getline(csv, header) && std::getline(csv, row) && !row.empty())
      throw std::runtime_error(
          jsonl_path + ": missing, but " + csv_path +
          " holds results: the record of these results "
          "(which every reader and --resume trusts) is gone; restore it, or choose another folder");
    return table;
  }
  std::map<std::string, std::size_t> at;  // key -> index in records
  std::set<std::string> conflicting;
  int line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    if (line.empty()) continue;
    std::string problem;
    const std::string key = key_of(line, problem);
    const std::string where = jsonl_path + " line " + std::to_string(line_number) + ": ";
    if (key.empty()) {
      table.problems.push_back(where + (problem.empty() ? "not a whole record (cut short?)" : problem) +
                               "; dropped: its job runs again");
      continue;
    }
    const auto found = at.find(key);
    if (found == at.end()) {
      at[key] = table.records.size();
      table.records.emplace_back(key, line);
    } else if (table.records[found->second].second == line) {
      table.problems.push_back(where + key + " recorded again, the same; kept once");
    } else if (conflicting.insert(key).second) {
      table.problems.push_back(where + key + " recorded again with other values; both dropped: its job runs again");
    }
  }
  if (in.bad()) throw std::runtime_error(jsonl_path + ": read error");
  if (!conflicting.empty())
    table.records.erase(std::remove_if(table.records.begin(), table.records.end(),
                                       [&](const auto& record) { return conflicting.count(record.first) > 0; }),
                        table.records.end());
  return table;
}

std::set<std::string> repair_jsonl_table(const std::string& jsonl_path, const std::string& csv_path,
                                         const std::vector<std::string>& columns, const KeyOf& key_of,
                                         std::vector<std::string>* repairs) {
  std::set<std::string> keys;
  const JsonlTable table =
      scan_jsonl_table(jsonl_path, csv_path, key_of);     // throws: unreadable, or CSV rows without record
  if (!std::filesystem::exists(jsonl_path)) return keys;  // no table yet
  if (repairs) repairs->insert(repairs->end(), table.problems.begin(), table.problems.end());
  std::string jsonl, csv;
  for (const std::string& name : columns) csv += (csv.empty() ? "" : ",") + name;
  csv += "\n";
  for (const auto& [key, line] : table.records) {
    keys.insert(key);
    jsonl += line + "\n";
    const nlohmann::json j = nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false);
    std::string row;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (c) row += ",";
      const auto value = j.find(columns[c]);
      if (value == j.end()) continue;
      if (value->is_string())
        row += csv_escape(value->get<std::string>());
      else if (value->is_number())
        row += exact_number_text(value->get<double>());
    }
    csv += row + "\n";
  }
  replace_text_file(jsonl_path, jsonl);
  replace_text_file(csv_path, csv);
  return keys;
}

}  // namespace ib
