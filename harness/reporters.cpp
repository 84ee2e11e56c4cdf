#include "reporters.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace ib {
namespace {

using Json = nlohmann::ordered_json;

std::string csv_escape(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string number_text(double value) {
  if (!std::isfinite(value)) return "";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

Json to_json(const RunRecord& record) {
  Json j;
  for (const Field& f : fields(record)) {
    if (const auto* text = std::get_if<std::string>(&f.value)) j[f.name] = *text;
    else {
      const double v = std::get<double>(f.value);
      j[f.name] = std::isfinite(v) ? Json(v) : Json(nullptr);
    }
  }
  Json diagnostics = Json::object();
  for (const auto& [name, value] : record.diagnostics) diagnostics[name] = std::isfinite(value) ? Json(value) : Json(nullptr);
  j["diagnostics"] = diagnostics;
  return j;
}

void append_text(const std::string& path, const std::string& text) {
  std::FILE* f = std::fopen(path.c_str(), "a");
  if (!f) throw std::runtime_error(path + ": cannot append: " + std::strerror(errno));
  const bool written = std::fputs(text.c_str(), f) >= 0 && std::fflush(f) == 0;
  const int error = errno;
  std::fclose(f);
  if (!written) throw std::runtime_error(path + ": write failed: " + std::strerror(error));
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
    else line += number_text(std::get<double>(f.value));
  }
  return line + "\n";
}

std::string json_line(const RunRecord& record) { return to_json(record).dump() + "\n"; }

void write_summary_json(const std::string& path, const RunRecord& record) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
  out << to_json(record).dump(2) << '\n';
  if (!out) throw std::runtime_error(path + ": write failed: " + std::strerror(errno));
}

void append_rows(const std::string& folder, const std::string& csv_row_text, const std::string& json_line_text) {
  append_text(folder + "/runs.jsonl", json_line_text);
  const std::string csv = folder + "/runs.csv";
  std::ifstream existing(csv);
  const bool fresh = !existing.good() || existing.peek() == std::ifstream::traits_type::eof();
  append_text(csv, (fresh ? csv_header(RunRecord{}) : "") + csv_row_text);
}

void append_run(const std::string& folder, const RunRecord& record) {
  append_rows(folder, csv_row(record), json_line(record));
}

std::set<std::string> repair_and_list_runs(const std::string& folder) {
  std::set<std::string> ids;
  std::ifstream in(folder + "/runs.jsonl");
  if (!in) return ids;
  std::string jsonl, csv = csv_header(RunRecord{});
  for (std::string line; std::getline(in, line);) {
    const Json j = Json::parse(line, nullptr, /*allow_exceptions=*/false);
    if (!j.is_object() || !j.contains("job_id") || !j["job_id"].is_string()) continue;  // cut short by a kill
    ids.insert(j["job_id"].get<std::string>());
    jsonl += line + "\n";
    std::string row;
    for (const auto& [name, value] : j.items()) {
      if (name == "diagnostics") continue;
      row += row.empty() ? "" : ",";
      if (value.is_string()) row += csv_escape(value.get<std::string>());
      else if (value.is_number()) row += number_text(value.get<double>());
    }
    csv += row + "\n";
  }
  in.close();
  for (const auto& [name, text] : {std::pair{"/runs.jsonl", &jsonl}, std::pair{"/runs.csv", &csv}}) {
    const std::string path = folder + name, temporary = path + ".tmp";
    std::ofstream out(temporary, std::ios::trunc);
    out << *text;
    out.close();
    if (!out || std::rename(temporary.c_str(), path.c_str()) != 0)
      throw std::runtime_error(path + ": cannot rewrite: " + std::strerror(errno));
  }
  return ids;
}

}  // namespace ib
