// Uncertain-inputs files and the scenario a sample point makes of a published one (uncertain_inputs.h).
#include "model/uncertain_inputs.h"

#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <optional>
#include <sstream>

#include "model/scenario_toml.h"
#include "model/toml_schema.h"

namespace ib {

namespace {

using namespace toml_schema;  // Key, Table, Section and the Checker (model/toml_schema.h)

// One [[input]] as its table gives it; `keys` and the distribution's name are checked apart.
struct InputRow {
  std::string name;
  double nominal = 0;
  std::string distribution;
  std::optional<double> half_width;
  std::optional<double> standard_uncertainty;
  std::string source;
};

const std::vector<Key<InputRow>> kInputKeys = {
    {"name", &InputRow::name, required, identifier(), "what the input is, its unit last, e.g. gap_m"},
    {"nominal", &InputRow::nominal, required, anything(), "the nominal value, in the keys' SI unit"},
    {"distribution", &InputRow::distribution, required, anything(), "uniform or normal"},
    {"half_width", &InputRow::half_width, optional, above(0), "a uniform input's half width, in its unit"},
    {"standard_uncertainty", &InputRow::standard_uncertainty, optional, above(0),
     "a normal input's standard deviation, in its unit"},
    {"source", &InputRow::source, required, anything(), "where the value and its spread come from"},
};
constexpr const char* kKeysMeaning = "the scenario keys the input moves, dotted, e.g. \"frame1.column_thickness_m\"";

struct InputsHeader {
  std::string description;
};
const std::vector<Key<InputsHeader>> kHeaderKeys = {
    {"description", &InputsHeader::description, required, anything(), "what the inputs are"},
};

const std::vector<Table> kTopTables = {
    {"inputs", required, "the file's description"},
    {"input", required, "one table [[input]] per uncertain quantity"},
};

std::vector<std::string> read_keys(const Checker& checker, const Section& section) {
  const std::string dotted = section.dotted("keys");
  const toml::node* node = section.find("keys");
  if (!node) checker.fail(section.line, dotted, dotted + ": missing required key; allowed: " + kKeysMeaning);
  const toml::array* array = node->as_array();
  std::vector<std::string> keys;
  if (array)
    for (const toml::node& item : *array) {
      const auto* text = item.as_string();
      const std::string key = text ? text->get() : "";
      const auto dot = key.find('.');
      if (!text || dot == std::string::npos || dot == 0 || key.back() == '.') {
        keys.clear();
        break;
      }
      keys.push_back(key);
    }
  if (keys.empty())
    checker.fail(line_of(*node), dotted,
                 checker.show(dotted, *node) + ": not allowed; allowed: a non-empty array of " + kKeysMeaning);
  return keys;
}

UncertainInput read_input(const Checker& checker, const toml::table& table, int index) {
  const Section section{&table, "input[" + std::to_string(index + 1) + "]", line_of(table)};
  std::vector<std::string> names = Checker::names_of(kInputKeys);
  names.push_back("keys");  // an array, read apart: the schema's reader takes scalars
  checker.reject_unknown(section, names, "allowed keys in [[input]]: " + join(names));
  InputRow row;
  for (const Key<InputRow>& key : kInputKeys) {
    const Rule rule = Checker::rule_of(section, key);
    if (const toml::node* node = section.find(key.name))
      key.fill(checker, rule, *node, row);
    else if (key.need == required)
      checker.fail(section.line, rule.dotted, rule.dotted + ": missing required key; allowed: " + rule.allowed_text());
  }
  UncertainInput input;
  input.name = row.name;
  input.keys = read_keys(checker, section);
  input.nominal = row.nominal;
  input.source = row.source;
  input.line = section.line;
  const auto spread_fail = [&](const char* key, const std::string& message) {
    const toml::node* node = table.get(key);
    checker.fail(node ? line_of(*node) : section.line, section.dotted(key), section.dotted(key) + ": " + message);
  };
  if (row.distribution == "uniform") {
    input.distribution = InputDistribution::uniform;
    if (!row.half_width) spread_fail("half_width", "missing required key for a uniform input; allowed: a number > 0");
    if (row.standard_uncertainty)
      spread_fail("standard_uncertainty", "not allowed for a uniform input; allowed: half_width");
    input.half_width = *row.half_width;
  } else if (row.distribution == "normal") {
    input.distribution = InputDistribution::normal;
    if (!row.standard_uncertainty)
      spread_fail("standard_uncertainty", "missing required key for a normal input; allowed: a number > 0");
    if (row.half_width) spread_fail("half_width", "not allowed for a normal input; allowed: standard_uncertainty");
    input.standard_uncertainty = *row.standard_uncertainty;
  } else {
    const toml::node& node = *table.get("distribution");
    checker.fail(line_of(node), section.dotted("distribution"),
                 checker.show(section.dotted("distribution"), node) + ": not allowed; allowed: uniform or normal");
  }
  return input;
}

}  // namespace

double UncertainInput::standard_deviation() const {
  return distribution == InputDistribution::uniform ? half_width / std::sqrt(3.0) : standard_uncertainty;
}

double UncertainInput::value_at(double u) const {
  if (distribution == InputDistribution::uniform) return nominal + (2 * u - 1) * half_width;
  return boost::math::quantile(boost::math::normal_distribution<double>(nominal, standard_uncertainty), u);
}

UncertainInputs parse_uncertain_inputs(std::string_view toml_text, const std::string& path) {
  const Checker checker(path, toml_text);
  const toml::table document = checker.parse();
  const Section top{&document, "", 1};
  checker.reject_unknown(top, names_of(kTopTables), "allowed: [inputs] and [[input]] tables");
  UncertainInputs result;
  result.path = path;
  InputsHeader header;
  checker.read(*checker.section(top, kTopTables, "inputs"), kHeaderKeys, header);
  result.description = header.description;
  const toml::node* node = document.get("input");
  const toml::array* tables = node ? node->as_array() : nullptr;
  if (!tables || !tables->is_array_of_tables() || tables->empty())
    checker.fail(node ? line_of(*node) : 1, "input",
                 "input: missing or not tables; allowed: one or more tables [[input]] (one per uncertain quantity)");
  for (std::size_t i = 0; i < tables->size(); ++i) {
    UncertainInput input = read_input(checker, *(*tables)[i].as_table(), static_cast<int>(i));
    for (const UncertainInput& earlier : result.inputs)
      if (earlier.name == input.name)
        checker.fail(input.line, "input.name",
                     "input.name = \"" + input.name + "\": already the name of the input at line " +
                         std::to_string(earlier.line) + "; allowed: a name of its own (the sample's column)");
    result.inputs.push_back(std::move(input));
  }
  return result;
}

UncertainInputs load_uncertain_inputs(const std::string& path) {
  return parse_uncertain_inputs(read_toml_file(path, "uncertain-inputs file"), path);
}

std::string scenario_with_inputs(const std::string& base_text, const std::string& base_path,
                                 const UncertainInputs& inputs, const std::vector<double>& values,
                                 const std::string& name) {
  toml::table document = Checker(base_path, base_text).parse();
  for (std::size_t i = 0; i < inputs.inputs.size(); ++i) {
    const UncertainInput& input = inputs.inputs[i];
    for (const std::string& key : input.keys) {
      toml::table* table = &document;
      std::string rest = key;
      for (auto dot = rest.find('.'); table && dot != std::string::npos; dot = rest.find('.')) {
        table = table->get_as<toml::table>(rest.substr(0, dot));
        rest = rest.substr(dot + 1);
      }
      if (!table) continue;  // the scenario has no such table: the input does not apply to it
      const toml::node* node = table->get(rest);
      if (!node || !node->is_floating_point())
        throw ScenarioError(inputs.path, input.line, key,
                            "input \"" + input.name + "\" moves " + key + ", which " + base_path +
                                (node ? " holds as another type than a real number" : " does not give") +
                                "; allowed: a key with a real value in every table of the scenario it names");
      table->insert_or_assign(rest, node->value<double>().value() + values[i] - input.nominal);
    }
  }
  if (toml::table* scenario = document.get_as<toml::table>("scenario")) scenario->insert_or_assign("name", name);
  std::ostringstream text;
  text << "# " << name << ": " << base_path << " with the inputs of " << inputs.path << " (a validation's sample)\n"
       << document << "\n";
  parse_scenario(text.str(), base_path + " (" + name + ")");  // its values in range, or a message naming it
  return text.str();
}

}  // namespace ib
