#include "harness/jsonl_table.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "harness/number_text.h"
#include "harness/run_files.h"

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
    if (const auto* text = std::get_if<std::string>(&f.value)) line += csv_escape(*text);
    else line += f.exact ? exact_number_text(std::get<double>(f.value)) : number_text(std::get<double>(f.value));
  }
  return line + "\n";
}

nlohmann::ordered_json json_object(const std::vector<Field>& row) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const Field& f : row) {
    if (const auto* text = std::get_if<std::string>(&f.value)) j[f.name] = *text;
    else j[f.name] = json_number(std::get<double>(f.value), f.exact);
  }
  return j;
}

void append_table_row(const std::string& jsonl_path, const std::string& csv_path, const std::string& csv_header,
                      const std::string& csv_row, const std::string& json_line) {
  append_text_file(jsonl_path, json_line);
  std::ifstream existing(csv_path);
  const bool fresh = !existing.good() || existing.peek() == std::ifstream::traits_type::eof();
  append_text_file(csv_path, (fresh ? csv_header : "") + csv_row);
}

std::set<std::string> repair_jsonl_table(const std::string& jsonl_path, const std::string& csv_path,
                                         const std::vector<std::string>& columns,
                                         const std::function<std::string(const std::string& line)>& key_of) {
  std::set<std::string> keys;
  errno = 0;
  std::ifstream in(jsonl_path, std::ios::binary);
  if (!in) {
    if (errno == ENOENT) return keys;
    throw std::runtime_error(jsonl_path + ": cannot read: " + std::strerror(errno));
  }
  std::string jsonl, csv;
  for (const std::string& name : columns) csv += (csv.empty() ? "" : ",") + name;
  csv += "\n";
  for (std::string line; std::getline(in, line);) {
    const std::string key = key_of(line);
    if (key.empty()) continue;  // its job (or search) runs again
    keys.insert(key);
    jsonl += line + "\n";
    const nlohmann::json j = nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false);
    std::string row;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (c) row += ",";
      const auto value = j.find(columns[c]);
      if (value == j.end()) continue;
      if (value->is_string()) row += csv_escape(value->get<std::string>());
      else if (value->is_number()) row += exact_number_text(value->get<double>());
    }
    csv += row + "\n";
  }
  if (in.bad()) throw std::runtime_error(jsonl_path + ": read error");
  in.close();
  replace_text_file(jsonl_path, jsonl);
  replace_text_file(csv_path, csv);
  return keys;
}

}  // namespace ib
