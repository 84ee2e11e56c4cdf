// The input sample of a validation (input_sample.h).
#include "harness/validation/input_sample.h"

#include <boost/random/sobol.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "harness/records/number_text.h"
#include "harness/records/run_files.h"
#include "model/scenario_toml.h"

namespace ib {

std::vector<std::vector<double>> sobol_input_values(const UncertainInputs& inputs, int points) {
  const std::size_t dimension = inputs.inputs.size();
  boost::random::sobol sequence(dimension);  // Boost's starts at the centre: the corner 0 is not drawn
  const double scale = std::ldexp(1.0, -static_cast<int>(sizeof(boost::random::sobol::result_type) * 8));
  std::vector<std::vector<double>> values(points, std::vector<double>(dimension));
  for (auto& point : values)
    for (std::size_t i = 0; i < dimension; ++i) point[i] = inputs.inputs[i].value_at(sequence() * scale);
  return values;
}

namespace {

std::string point_name(const std::string& case_name, int point) {
  char suffix[16];
  std::snprintf(suffix, sizeof suffix, "_p%03d", point);
  return case_name + suffix;
}

// A file left as it is when it holds the text already (a resumed study's), so its digest and time stay.
void write_if_changed(const std::string& path, const std::string& text) {
  std::error_code error;
  if (std::filesystem::exists(path, error) && read_text_file(path) == text) return;
  write_text_file(path, text);
}

std::string inputs_json(const UncertainInputs& inputs, int points) {
  nlohmann::json j;
  j["inputs_file"] = inputs.path;
  j["description"] = inputs.description;
  j["design"] = "sobol";
  j["points"] = points;
  for (const UncertainInput& input : inputs.inputs) {
    nlohmann::json row = {{"name", input.name},
                          {"keys", input.keys},
                          {"nominal", input.nominal},
                          {"standard_deviation", input.standard_deviation()},
                          {"source", input.source}};
    if (input.distribution == InputDistribution::uniform) {
      row["distribution"] = "uniform";
      row["half_width"] = input.half_width;
    } else {
      row["distribution"] = "normal";
      row["standard_uncertainty"] = input.standard_uncertainty;
    }
    j["inputs"].push_back(row);
  }
  return j.dump(2) + "\n";
}

}  // namespace

InputSampleFiles write_input_sample(const UncertainInputs& inputs, const std::vector<std::string>& case_files,
                                    int points, const std::string& folder) {
  const std::vector<std::vector<double>> values = sobol_input_values(inputs, points);
  std::ostringstream csv;
  csv << "case,point,scenario,scenario_file";
  for (const UncertainInput& input : inputs.inputs) csv << "," << input.name;
  csv << "\n";
  InputSampleFiles files;
  for (const std::string& case_file : case_files) {
    const std::string base_text = read_text_file(case_file);
    const std::string case_name = parse_scenario(base_text, case_file).name;
    const std::string case_folder = folder + "/scenarios/" + case_name;
    std::filesystem::create_directories(case_folder);
    for (int p = 0; p < points; ++p) {
      const std::string name = point_name(case_name, p);
      const std::string file = case_folder + "/" + name + ".toml";
      write_if_changed(file, scenario_with_inputs(base_text, case_file, inputs, values[p], name));
      files.scenario_files.push_back(file);
      csv << case_name << "," << p << "," << name << "," << csv_escape(file);
      for (double value : values[p]) csv << "," << exact_number_text(value);
      csv << "\n";
    }
  }
  write_if_changed(folder + "/sample.csv", csv.str());
  write_if_changed(folder + "/inputs.json", inputs_json(inputs, points));
  return files;
}

}  // namespace ib
