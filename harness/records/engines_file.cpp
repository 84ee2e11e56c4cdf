#include "harness/records/engines_file.h"

#include <nlohmann/json.hpp>

#include "harness/records/run_files.h"

namespace ib {

namespace {

nlohmann::ordered_json pairs_object(const std::vector<std::pair<std::string, std::string>>& pairs) {
  nlohmann::ordered_json object = nlohmann::ordered_json::object();
  for (const auto& [name, value] : pairs) object[name] = value;
  return object;
}

nlohmann::ordered_json descriptor_json(const SimulatorDescriptor& d, const std::string& version) {
  nlohmann::ordered_json keys = nlohmann::ordered_json::array();
  for (const DiagnosticsKey& k : d.diagnostics) {
    nlohmann::ordered_json key = {{"key", k.key}, {"label", k.label}, {"meaning", k.meaning}, {"unit", k.unit}};
    if (!k.values.empty()) key["values"] = pairs_object(k.values);
    keys.push_back(std::move(key));
  }
  nlohmann::ordered_json record = {
      {"name", d.name},         {"display_name", d.display_name},     {"summary", d.summary}, {"version", version},
      {"packages", d.packages}, {"colours", pairs_object(d.colours)}, {"diagnostics", keys}};
  // the step of a run without --dt; null for an adaptive simulator (the reference), which takes none
  record["default_time_step_s"] = d.default_time_step_s > 0 ? nlohmann::ordered_json(d.default_time_step_s) : nullptr;
  if (!d.default_time_step_note.empty()) record["default_time_step_note"] = d.default_time_step_note;
  // the authors' recommended configuration with each setting's source, for the report to cite
  if (!d.recommended_json.empty()) record["recommended"] = nlohmann::ordered_json::parse(d.recommended_json);
  return record;
}

}  // namespace

std::string engines_json(const SimulatorCatalog& catalog) {
  nlohmann::ordered_json simulators = nlohmann::ordered_json::array();
  // the version is the library's own answer at run time, not the descriptor file's (which has none)
  for (const std::string& name : catalog.names)
    simulators.push_back(descriptor_json(descriptor_of(catalog, name), version_of(catalog, name)));
  return nlohmann::ordered_json{{"simulators", simulators}}.dump(2) + "\n";
}

void write_engines_file(const std::string& dir, const SimulatorCatalog& catalog) {
  replace_text_file(dir + "/engines.json", engines_json(catalog));
}

}  // namespace ib
