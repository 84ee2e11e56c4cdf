#include "harness/jsonl_table.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "harness/number_text.h"
#include "harness/run_files.h"

namespace ib {

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
