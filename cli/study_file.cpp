// Study files (study_file.h): the schema of a part's keys, and their translation into the commands'
// options, whose one checking code then decides every range and makes each part's settings.
#include "cli/study_file.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "cli/commands.h"
#include "cli/option_rules.h"
#include "cli/study_keys.h"
#include "cli/study_part_options.h"
#include "cli/study_validation.h"
#include "model/scenario_toml.h"
#include "model/toml_schema.h"

namespace cli {

namespace fs = std::filesystem;
using ib::toml_schema::Checker;

std::string scenario_path(const std::string& study_file, const std::string& path) {
  if (fs::path(path).is_absolute()) return path;
  const fs::path beside = fs::path(study_file).parent_path() / path;
  if (fs::exists(beside)) return beside.lexically_normal().string();
  const fs::path in_project = (fs::path(IMPACTBENCH_SOURCE_DIR) / path).lexically_normal();
  // as the command line would name it from the project's folder: runs.csv's scenario_file stays short
  std::error_code error;
  const fs::path relative = fs::proximate(in_project, fs::current_path(error), error);
  return !error && !relative.empty() && *relative.begin() != ".." ? relative.string() : in_project.string();
}

void require_key(const Checker& checker, const GivenKeys& given, const PartOptions& part, const std::string& dotted,
                 const char* key, const char* meaning) {
  if (!given.count(key))
    checker.fail(part.line, dotted + "." + key, dotted + "." + key + ": missing required key; allowed: " + meaning);
}

void require_folder_name(const Checker& checker, const GivenKeys& given, PartOptions& part, const std::string& dotted,
                         const std::string& folder_below) {
  const std::string kind = ib::to_string(part.kind);
  const std::string meaning = "the " + kind + "'s folder below " + folder_below + " (a-z, 0-9, _ and -)";
  require_key(checker, given, part, dotted, "name", meaning.c_str());
  if (part.name.empty() || part.name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") != std::string::npos)
    checker.fail(part.key_lines["name"], dotted + ".name",
                 dotted + ".name = \"" + part.name + "\": not allowed; allowed: 1 or more of a-z, 0-9, _ and - (the " +
                     kind + "'s folder)");
}

namespace {

using ib::toml_schema::line_of;
using ib::toml_schema::type_name;

std::string number_text(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", x);  // read back by the options' parser exactly
  return text;
}

class PartReader {
 public:
  // defaults: the study's [defaults] table (null: none), read for a key the part's own table does not hold.
  PartReader(const Checker& checker, const toml::table& table, std::string dotted,
             const toml::table* defaults = nullptr)
      : checker_(checker), table_(table), dotted_(std::move(dotted)), defaults_(defaults) {}

  // The key's value as the command's option text, from the part's table, else from [defaults]; nullopt when
  // neither holds it. Wrong types fail here, named where the value is written.
  std::optional<std::string> text(const KeySpec& spec, PartOptions& part) const {
    const toml::node* node = table_.get(spec.key);
    const std::string& dotted = node || !defaults_ ? dotted_ : kDefaults;
    if (!node && defaults_) node = defaults_->get(spec.key);
    if (!node) return std::nullopt;
    return value_text(spec, *node, dotted, part);
  }

 private:
  static inline const std::string kDefaults = "defaults";

  std::string value_text(const KeySpec& spec, const toml::node& value, const std::string& dotted,
                         PartOptions& part) const {
    const toml::node* node = &value;
    part.key_lines[spec.key] = line_of(*node);
    switch (spec.type) {
      case Type::text:
        if (const auto* s = node->as_string()) return s->get();
        break;
      case Type::number:
        if (node->is_number()) return number_text(node->value<double>().value());
        break;
      case Type::integer:
        if (const auto* i = node->as_integer()) return std::to_string(i->get());
        break;
      case Type::boolean:
        if (const auto* b = node->as_boolean()) return b->get() ? "true" : "false";
        break;
      case Type::texts_or_all:
        if (const auto* s = node->as_string()) {
          if (s->get() == "all") return std::string("all");
          wrong(spec, *node, dotted, "\"all\" or an array of strings");
        }
        [[fallthrough]];
      case Type::texts:
      case Type::numbers:
        if (const auto* array = node->as_array()) {
          std::vector<std::string> items;
          for (const toml::node& item : *array) {
            if (spec.type == Type::numbers && item.is_number())
              items.push_back(number_text(item.value<double>().value()));
            else if (spec.type != Type::numbers && item.is_string())
              items.push_back(item.as_string()->get());
            else
              wrong(spec, *node, dotted, spec.type == Type::numbers ? "an array of numbers" : "an array of strings");
          }
          part.key_items[spec.key] = items;
          return join_list(items);
        }
        if (spec.type == Type::numbers && node->is_number()) return number_text(node->value<double>().value());
        break;
    }
    static const char* expected[] = {"a string",
                                     "a number",
                                     "an integer",
                                     "true or false",
                                     "an array of strings",
                                     "an array of numbers",
                                     "\"all\" or an array of strings"};
    wrong(spec, *node, dotted, expected[static_cast<int>(spec.type)]);
  }

  [[noreturn]] void wrong(const KeySpec& spec, const toml::node& node, const std::string& table,
                          const std::string& expected) const {
    const std::string dotted = table + "." + spec.key;
    checker_.fail(line_of(node), dotted,
                  checker_.show(dotted, node) + ": wrong type (" + type_name(node) + "); expected " + expected + " (" +
                      spec.meaning + ")");
  }

  const Checker& checker_;
  const toml::table& table_;
  std::string dotted_;
  const toml::table* defaults_;
};

// The keys every kind of part has: the measurement, and the engines, laws, paths, steps and options that a
// suite and a sweep share. Each number is checked as its command-line option is, as soon as it is read
// (cli/option_rules.h).
void read_shared_keys(const Checker& checker, GivenKeys& given, const std::string& dotted,
                      const std::vector<std::string>& engines, PartOptions& part) {
  const std::pair<const char*, Shared> numbers[] = {{"rate_hz", Shared::rate},
                                                    {"sensor_rate_hz", Shared::sensor_rate},
                                                    {"time_limit_s", Shared::time_limit},
                                                    {"window_s", Shared::window},
                                                    {"duration_s", Shared::duration},
                                                    {"rest_duration_s", Shared::rest_duration},
                                                    {"series_rate_hz", Shared::series_rate}};
  for (const auto& [key, option] : numbers) {
    if (!given.count(key)) continue;
    try {
      parse_value(option, given[key]);
    } catch (const std::invalid_argument& error) {
      checker.fail(part.key_lines[key], dotted + "." + key, dotted + "." + key + ": " + error.what());
    }
  }
  std::string engine_list;
  try {
    engine_list = part_engines(given, engines);
  } catch (const std::invalid_argument& error) {
    const char* key = given.count("skip_engines") ? "skip_engines" : "engines";
    checker.fail(part.key_lines[key], dotted + "." + key, dotted + "." + key + ": " + error.what());
  }
  MeasurementOptions& m = part.measurement;
  if (given.count("sensor_rate_hz")) m.sensor_rate_hz = std::stod(given["sensor_rate_hz"]);
  if (given.count("series")) m.series = given["series"];
  if (given.count("series_rate_hz")) m.series_rate_hz = std::stod(given["series_rate_hz"]);
  MatrixOptions& shared = part.kind == ib::StudyPartKind::sweep ? static_cast<MatrixOptions&>(part.sweep) : part.suite;
  if (!engine_list.empty()) shared.engines = engine_list;
  if (given.count("laws")) shared.laws = expand_all("laws", given["laws"], engines);
  if (given.count("paths")) shared.paths = expand_all("paths", given["paths"], engines);
  if (given.count("dt_s")) shared.time_steps = given["dt_s"];
  if (given.count("options")) shared.options = part.key_items["options"];
  if (given.count("rate_hz")) shared.rate_hz = std::stod(given["rate_hz"]);
  if (given.count("time_limit_s")) shared.time_limit_s = std::stod(given["time_limit_s"]);
}

// A [[sweep]]'s own keys: its folder's name, its scenario, its ratios, starts and lengths.
void read_sweep_keys(const Checker& checker, GivenKeys& given, const std::string& dotted, PartOptions& part) {
  require_folder_name(checker, given, part, dotted, "OUT/sweeps/");
  require_key(checker, given, part, dotted, "scenario", "a scenario file with a motor");
  SweepOptions& s = part.sweep;
  part.measurement.series = given.count("series") ? given["series"] : "none";  // a sweep's tables are its results
  s.scenario = scenario_path(part.file, given["scenario"]);
  if (given.count("ratios")) s.ratios = given["ratios"];
  if (given.count("starts")) s.start = given["starts"];
  if (given.count("duration_s")) s.duration_s = std::stod(given["duration_s"]);
  if (given.count("rest_duration_s")) s.rest_duration_s = std::stod(given["rest_duration_s"]);
  if (given.count("window_s")) s.window_s = std::stod(given["window_s"]);
  if (given.count("reference_ensemble_starts"))
    s.reference_ensemble_starts = std::stoi(given["reference_ensemble_starts"]);
  if (given.count("ensemble_step_m")) s.ensemble_step_m = std::stod(given["ensemble_step_m"]);
  if (given.count("ensemble_ratios")) s.ensemble_ratios = given["ensemble_ratios"];
}

// A [[suite]]'s or [[search]]'s own keys: its scenarios, lengths and ensembles, and a search's grid.
void read_suite_keys(const Checker& checker, GivenKeys& given, const std::string& dotted, PartOptions& part) {
  require_key(checker, given, part, dotted, "scenarios", "scenario files or folders");
  SuiteOptions& s = part.suite;
  MeasurementOptions& m = part.measurement;
  const std::vector<std::string> scenarios =
      part.key_items.count("scenarios") ? part.key_items["scenarios"] : std::vector<std::string>{given["scenarios"]};
  for (const std::string& path : scenarios) s.inputs.push_back(scenario_path(part.file, path));
  if (given.count("duration_s")) s.max_duration_s = std::stod(given["duration_s"]);
  if (given.count("window_s")) {
    m.window_s = std::stod(given["window_s"]);
    m.window_given = true;
  }
  if (given.count("ensemble_starts")) s.ensemble_starts = std::stoi(given["ensemble_starts"]);
  if (given.count("reference_ensemble_starts"))
    s.reference_ensemble_starts = std::stoi(given["reference_ensemble_starts"]);
  if (given.count("ensemble_step_m")) s.ensemble_step_m = std::stod(given["ensemble_step_m"]);
  if (given.count("recommended")) s.recommended = given["recommended"] == "true";
  if (given.count("reference_chains")) s.reference_chains = given["reference_chains"];
  if (part.kind == ib::StudyPartKind::search) {
    s.find_steps = true;
    if (given.count("steps_per_octave")) s.steps_per_octave = std::stoi(given["steps_per_octave"]);
    if (given.count("step_range_s")) s.step_range = given["step_range_s"];
    if (given.count("keep_series")) s.keep_series = given["keep_series"] == "true";
    if (given.count("walk")) s.step_walk = given["walk"] == "true";
  }
}

PartOptions read_part(const Checker& checker, const toml::table& table, const toml::table* defaults,
                      ib::StudyPartKind kind, int index, const std::string& file,
                      const std::vector<std::string>& engines) {
  PartOptions part;
  part.kind = kind;
  part.file = file;
  part.line = line_of(table);
  const std::string dotted = std::string(ib::to_string(kind)) + " " + std::to_string(index + 1);
  const std::vector<KeySpec> keys = keys_of(kind);
  std::vector<std::string> names;
  for (const KeySpec& k : keys) names.push_back(k.key);
  checker.reject_unknown(
      ib::toml_schema::Section{&table, dotted, part.line}, names,
      "allowed keys in [[" + std::string(ib::to_string(kind)) + "]]: " + ib::toml_schema::join(names));
  const PartReader reader(checker, table, dotted, defaults);
  GivenKeys given;
  for (const KeySpec& k : keys)
    if (auto value = reader.text(k, part)) given[k.key] = *value;
  part.name = given.count("name") ? given["name"] : std::string(ib::to_string(kind)) + " " + std::to_string(index + 1);
  if (kind == ib::StudyPartKind::validation) part.suite.laws = "hertz";  // the published model's law
  read_shared_keys(checker, given, dotted, engines, part);
  if (kind == ib::StudyPartKind::sweep)
    read_sweep_keys(checker, given, dotted, part);
  else
    read_suite_keys(checker, given, dotted, part);
  if (kind == ib::StudyPartKind::validation) read_validation_keys(checker, given, dotted, part);
  return part;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ib::ScenarioError(path, 0, "", "cannot read the study file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The study's [defaults] (null: none): its keys checked by name and type here, once, whether or not a part
// takes them; their values then by each part that does, as its own.
const toml::table* read_defaults(const Checker& checker, const toml::table& document) {
  const toml::node* node = document.get("defaults");
  if (!node) return nullptr;
  if (!node->is_table())
    checker.fail(line_of(*node), "defaults",
                 "defaults: wrong type (" + std::string(type_name(*node)) + "); expected a table [defaults]");
  const std::vector<KeySpec> keys = default_keys();
  std::vector<std::string> names;
  for (const KeySpec& k : keys) names.push_back(k.key);
  checker.reject_unknown(
      ib::toml_schema::Section{node->as_table(), "defaults", line_of(*node)}, names,
      "allowed keys in [defaults]: " + ib::toml_schema::join(names) + " (a part's name and scenarios are its own)");
  const PartReader reader(checker, *node->as_table(), "defaults");
  PartOptions scratch;
  for (const KeySpec& k : keys) reader.text(k, scratch);
  return node->as_table();
}

// The part's settings, checked as the command's options are; an error names the study file, the part's key and
// its line (the key an option's message is about, else the part's header). The folder is a stand-in: run_study
// places each part (the command checks --out).
ib::StudyPart typed_part(PartOptions part) {
  part.suite.out = part.sweep.out = "OUT";
  try {
    if (part.kind == ib::StudyPartKind::sweep)
      return {part.kind, part.name, sweep_settings_from(part.sweep, part.measurement)};
    if (part.kind == ib::StudyPartKind::validation) return validation_part(part);
    return {part.kind, part.name, suite_settings_from(part.suite, part.measurement)};
  } catch (const ib::ScenarioError&) {
    throw;  // a scenario file's own message names that file
  } catch (const std::invalid_argument& error) {
    const KeySpec* key = key_of_message(part.kind, part.key_lines, error.what());
    const std::string dotted =
        std::string(ib::to_string(part.kind)) + " \"" + part.name + "\"" + (key ? std::string(".") + key->key : "");
    throw ib::ScenarioError(part.file, key ? part.key_lines.at(key->key) : part.line, key ? key->key : "",
                            dotted + ": " + error.what());
  }
}

// [study]: its description, if any.
std::string read_description(const Checker& checker, const toml::table& document) {
  const toml::node* node = document.get("study");
  if (!node) return "";
  if (!node->is_table())
    checker.fail(line_of(*node), "study",
                 "study: wrong type (" + std::string(type_name(*node)) + "); expected a table [study]");
  const ib::toml_schema::Section section{node->as_table(), "study", line_of(*node)};
  checker.reject_unknown(section, {"description"}, "allowed keys in [study]: description");
  const toml::node* d = node->as_table()->get("description");
  if (!d) return "";
  if (!d->is_string())
    checker.fail(line_of(*d), "study.description",
                 checker.show("study.description", *d) + ": wrong type (" + type_name(*d) + "); expected a string");
  return d->as_string()->get();
}

}  // namespace

Study read_study(const std::string& path, const std::vector<std::string>& engines,
                 const std::vector<ib::StudyPartKind>& left_out) {
  const std::string text = read_text(path);
  const Checker checker(path, text);
  const toml::table document = checker.parse();
  const ib::toml_schema::Section top{&document, "", 1};
  checker.reject_unknown(
      top, {"study", "defaults", "suite", "search", "sweep", "validation"},
      "allowed: [study], [defaults], [[suite]], [[search]], [[sweep]], [[validation]] (docs/studies.md, \"Study "
      "files\")");
  Study study;
  study.file = path;
  study.description = read_description(checker, document);
  const toml::table* defaults = read_defaults(checker, document);
  std::vector<PartOptions> parts;
  for (ib::StudyPartKind kind : study_file_kinds()) {
    const toml::node* node = document.get(ib::to_string(kind));
    if (!node) continue;
    const toml::array* tables = node->as_array();
    if (!tables || !tables->is_array_of_tables())
      checker.fail(line_of(*node), ib::to_string(kind),
                   std::string(ib::to_string(kind)) + ": wrong type (" + type_name(*node) + "); expected tables [[" +
                       ib::to_string(kind) + "]]");
    int index = 0;
    for (const toml::node& table : *tables)
      parts.push_back(read_part(checker, *table.as_table(), defaults, kind, index++, path, engines));
  }
  if (parts.empty())
    throw ib::ScenarioError(path, 1, "",
                            "a study needs at least one [[suite]], [[search]], [[sweep]] or [[validation]]");
  // Sweeps write into OUT/sweeps/NAME, validations into OUT/validation/NAME: two of one name would share a folder.
  std::map<std::pair<ib::StudyPartKind, std::string>, int> folder_lines;
  for (const PartOptions& part : parts) {
    if (part.kind != ib::StudyPartKind::sweep && part.kind != ib::StudyPartKind::validation) continue;
    const std::string kind = ib::to_string(part.kind);
    if (!folder_lines.emplace(std::pair(part.kind, part.name), part.line).second)
      throw ib::ScenarioError(path, part.line, kind + ".name",
                              kind + ".name = \"" + part.name + "\": already the name of the " + kind + " at line " +
                                  std::to_string(folder_lines[{part.kind, part.name}]) +
                                  "; allowed: a name of its own (its folder)");
  }
  // Every kept part's values, in order, before anything runs; a kind left out is not checked (as if absent).
  for (const PartOptions& part : parts) {
    if (std::find(left_out.begin(), left_out.end(), part.kind) != left_out.end()) continue;
    study.parts.push_back(typed_part(part));
    study.lines.push_back(part.line);
  }
  return study;
}

}  // namespace cli
