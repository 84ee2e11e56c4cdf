// Study files (study_file.h): the schema of a part's keys, and their translation into the commands'
// options, whose one checking code then decides every range.
#include "cli/study_file.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "cli/option_rules.h"
#include "model/scenario_toml.h"
#include "model/toml_schema.h"

namespace cli {

namespace {

namespace fs = std::filesystem;
using ib::toml_schema::Checker;
using ib::toml_schema::line_of;
using ib::toml_schema::type_name;

const char* kind_name(StudyPart::Kind kind) {
  switch (kind) {
    case StudyPart::Kind::suite:
      return "suite";
    case StudyPart::Kind::search:
      return "search";
    case StudyPart::Kind::sweep:
      return "sweep";
  }
  return "";
}

// What a key takes; the option it stands for (its messages start with that option) and what it means.
enum class Type { text, number, integer, boolean, texts, numbers, texts_or_all };
struct KeySpec {
  const char* key;
  Type type;
  const char* option;  // the command's option the value is checked as ("" for a key of the study alone)
  const char* meaning;
  const char* also = "";  // another start of the messages about it ("engine 'x': not in this build")
};

// The keys of each kind of part. Every key is optional but `scenarios` (suite, search) and `name`,
// `scenario` (sweep): a part left to its defaults is the command's defaults.
const std::vector<KeySpec> kCommonKeys = {
    {"name", Type::text, "", "the part's name, in messages (a sweep's: its folder below OUT/sweeps/)"},
    {"engines", Type::texts_or_all, "--engines", "\"all\" (every simulator of the build) or a list of simulators",
     "engine"},
    {"skip_engines", Type::texts, "--engines", "simulators left out of `engines`"},
    {"laws", Type::texts_or_all, "--laws", "\"all\" or a list of contact laws: hertz, viscoelastic, newton", "law"},
    {"paths", Type::texts_or_all, "--paths", "\"all\" or a list of contact paths: matched, injected, native"},
    {"dt_s", Type::numbers, "--dt", "time steps of the fixed-step engines [s]"},
    {"options", Type::texts, "--option", "engine.name=value settings", "engine"},
    {"rate_hz", Type::number, "--rate", "output series sample rate [Hz]"},
    {"sensor_rate_hz", Type::number, "--sensor-rate", "accelerometer sample rate [Hz]"},
    {"series", Type::text, "--series", "what a run keeps of its series: window, all or none"},
    {"series_rate_hz", Type::number, "--series-rate", "the rate an engine run's series file keeps [Hz]; 0: rate_hz"},
    {"time_limit_s", Type::number, "--time-limit", "per job (a sweep: per ratio) [s]"},
    {"window_s", Type::number, "--window", "the last S seconds of each run are scored [s]"},
    {"duration_s", Type::number, "--duration",
     "suite: runs cut to this length [s]; sweep: each continued ratio's run [s]"},
};
const std::vector<KeySpec> kSuiteKeys = {
    {"scenarios", Type::texts, "scenarios", "scenario files or folders"},
    {"ensemble_starts", Type::integer, "--ensemble", "every configuration from N starts (1: single runs)"},
    {"reference_ensemble_starts", Type::integer, "--reference-ensemble",
     "the references' starts (at least ensemble_starts)"},
    {"ensemble_step_m", Type::number, "--ensemble-step", "frame 1's initial tip displacement between two starts [m]"},
    {"recommended", Type::boolean, "--recommended",
     "each engine in its authors' recommended configuration per law (not with paths or dt_s)"},
    {"reference_chains", Type::numbers, "--reference-chains",
     "links K per frame: the reference alone on each K-link chain, every start"},
};
const std::vector<KeySpec> kSearchKeys = {
    {"scenarios", Type::texts, "scenarios", "scenario files or folders"},
    {"steps_per_octave", Type::integer, "--steps-per-octave", "grid steps per halving of the step"},
    {"step_range_s", Type::numbers, "--step-range", "[MIN, MAX] step searched [s]"},
    {"keep_series", Type::boolean, "--keep-series", "keep every probe's series"},
    {"walk", Type::boolean, "--step-walk",
     "walk down the grid until the error stops falling (a front's ladder), not bisect"},
};
const std::vector<KeySpec> kSweepKeys = {
    {"scenario", Type::text, "scenario", "a scenario file with a motor"},
    {"ratios", Type::text, "--ratios", "FROM:TO:STEP, the motor speed over f_1"},
    {"starts", Type::texts, "--start", "rest, up, down or both"},
    {"rest_duration_s", Type::number, "--rest-duration", "a start from rest's run [s]"},
    {"reference_ensemble_starts", Type::integer, "--reference-ensemble",
     "the reference's starts from rest at each ensemble ratio (1: one)"},
    {"ensemble_step_m", Type::number, "--ensemble-step", "frame 1's initial tip displacement between two starts [m]"},
    {"ensemble_ratios", Type::texts, "--ensemble-ratios",
     "FROM:TO:STEP ranges or single ratios where the reference's ensemble runs"},
};

std::vector<KeySpec> keys_of(StudyPart::Kind kind) {
  std::vector<KeySpec> keys = kCommonKeys;
  const auto& own = kind == StudyPart::Kind::suite    ? kSuiteKeys
                    : kind == StudyPart::Kind::search ? kSearchKeys
                                                      : kSweepKeys;
  keys.insert(keys.end(), own.begin(), own.end());
  return keys;
}

std::string number_text(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", x);  // read back by the options' parser exactly
  return text;
}

std::string joined(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ",") + item;
  return text;
}

class PartReader {
 public:
  PartReader(const Checker& checker, const toml::table& table, std::string dotted)
      : checker_(checker), table_(table), dotted_(std::move(dotted)) {}

  // The key's value as the command's option text; nullopt when absent. Wrong types fail here.
  std::optional<std::string> text(const KeySpec& spec, StudyPart& part) const {
    const toml::node* node = table_.get(spec.key);
    if (!node) return std::nullopt;
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
          wrong(spec, *node, "\"all\" or an array of strings");
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
              wrong(spec, *node, spec.type == Type::numbers ? "an array of numbers" : "an array of strings");
          }
          part.key_items[spec.key] = items;
          return joined(items);
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
    wrong(spec, *node, expected[static_cast<int>(spec.type)]);
  }

  [[noreturn]] void wrong(const KeySpec& spec, const toml::node& node, const std::string& expected) const {
    const std::string dotted = dotted_ + "." + spec.key;
    checker_.fail(line_of(node), dotted,
                  checker_.show(dotted, node) + ": wrong type (" + type_name(node) + "); expected " + expected + " (" +
                      spec.meaning + ")");
  }

 private:
  const Checker& checker_;
  const toml::table& table_;
  std::string dotted_;
};

// "all" spelled out: every simulator of the build (less skip_engines), every law, every path.
std::string expand_all(const std::string& key, const std::string& value, const std::vector<std::string>& engines) {
  if (value != "all") return value;
  if (key == "engines") return joined(engines);
  if (key == "laws") return "hertz,viscoelastic,newton";
  return "matched,injected,native";
}

std::string without(const std::string& list, const std::string& skipped) {
  std::vector<std::string> kept;
  const std::vector<std::string> skip = split(skipped, ',');
  for (const std::string& item : split(list, ','))
    if (std::find(skip.begin(), skip.end(), item) == skip.end()) kept.push_back(item);
  return joined(kept);
}

// A relative scenario path: from the study file's folder if it names a file or folder there, else from the
// project's folder.
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

StudyPart read_part(const Checker& checker, const toml::table& table, StudyPart::Kind kind, int index,
                    const std::string& file, const std::vector<std::string>& engines) {
  StudyPart part;
  part.kind = kind;
  part.file = file;
  part.line = line_of(table);
  const std::string dotted = std::string(kind_name(kind)) + " " + std::to_string(index + 1);
  const std::vector<KeySpec> keys = keys_of(kind);
  std::vector<std::string> names;
  for (const KeySpec& k : keys) names.push_back(k.key);
  checker.reject_unknown(ib::toml_schema::Section{&table, dotted, part.line}, names,
                         "allowed keys in [[" + std::string(kind_name(kind)) + "]]: " + ib::toml_schema::join(names));
  const PartReader reader(checker, table, dotted);
  std::map<std::string, std::string> given;
  for (const KeySpec& k : keys)
    if (auto value = reader.text(k, part)) given[k.key] = *value;
  const auto require = [&](const char* key, const char* meaning) {
    if (!given.count(key))
      checker.fail(part.line, dotted + "." + key, dotted + "." + key + ": missing required key; allowed: " + meaning);
  };
  part.name = given.count("name") ? given["name"] : std::string(kind_name(kind)) + " " + std::to_string(index + 1);
  // Each number is checked as its command-line option is, as soon as it is read (cli/option_rules.h).
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
  std::string engine_list = given.count("engines") ? expand_all("engines", given["engines"], engines) : "";
  if (given.count("skip_engines"))
    engine_list = without(engine_list.empty() ? joined(engines) : engine_list, given["skip_engines"]);
  MeasurementOptions& m = part.measurement;
  if (given.count("sensor_rate_hz")) m.sensor_rate_hz = std::stod(given["sensor_rate_hz"]);
  if (given.count("series")) m.series = given["series"];
  if (given.count("series_rate_hz")) m.series_rate_hz = std::stod(given["series_rate_hz"]);
  // The keys every kind of part has, into the options suite and sweep share.
  MatrixOptions& shared = kind == StudyPart::Kind::sweep ? static_cast<MatrixOptions&>(part.sweep) : part.suite;
  if (!engine_list.empty()) shared.engines = engine_list;
  if (given.count("laws")) shared.laws = expand_all("laws", given["laws"], engines);
  if (given.count("paths")) shared.paths = expand_all("paths", given["paths"], engines);
  if (given.count("dt_s")) shared.time_steps = given["dt_s"];
  if (given.count("options")) shared.options = part.key_items["options"];
  if (given.count("rate_hz")) shared.rate_hz = std::stod(given["rate_hz"]);
  if (given.count("time_limit_s")) shared.time_limit_s = std::stod(given["time_limit_s"]);
  if (kind == StudyPart::Kind::sweep) {
    require("name", "the sweep's folder below OUT/sweeps/ (a-z, 0-9, _ and -)");
    require("scenario", "a scenario file with a motor");
    if (part.name.empty() || part.name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") != std::string::npos)
      checker.fail(part.key_lines["name"], dotted + ".name",
                   dotted + ".name = \"" + part.name +
                       "\": not allowed; allowed: 1 or more of a-z, 0-9, _ and - (the sweep's folder)");
    SweepOptions& s = part.sweep;
    m.series = given.count("series") ? given["series"] : "none";  // a sweep's tables are its results
    s.scenario = scenario_path(file, given["scenario"]);
    if (given.count("ratios")) s.ratios = given["ratios"];
    if (given.count("starts")) s.start = given["starts"];
    if (given.count("duration_s")) s.duration_s = std::stod(given["duration_s"]);
    if (given.count("rest_duration_s")) s.rest_duration_s = std::stod(given["rest_duration_s"]);
    if (given.count("window_s")) s.window_s = std::stod(given["window_s"]);
    if (given.count("reference_ensemble_starts"))
      s.reference_ensemble_starts = std::stoi(given["reference_ensemble_starts"]);
    if (given.count("ensemble_step_m")) s.ensemble_step_m = std::stod(given["ensemble_step_m"]);
    if (given.count("ensemble_ratios")) s.ensemble_ratios = given["ensemble_ratios"];
    return part;
  }
  require("scenarios", "scenario files or folders");
  SuiteOptions& s = part.suite;
  const std::vector<std::string> scenarios =
      part.key_items.count("scenarios") ? part.key_items["scenarios"] : std::vector<std::string>{given["scenarios"]};
  for (const std::string& path : scenarios) s.inputs.push_back(scenario_path(file, path));
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
  if (kind == StudyPart::Kind::search) {
    s.find_steps = true;
    if (given.count("steps_per_octave")) s.steps_per_octave = std::stoi(given["steps_per_octave"]);
    if (given.count("step_range_s")) s.step_range = given["step_range_s"];
    if (given.count("keep_series")) s.keep_series = given["keep_series"] == "true";
    if (given.count("walk")) s.step_walk = given["walk"] == "true";
  }
  return part;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ib::ScenarioError(path, 0, "", "cannot read the study file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Which key a command's message is about: its option starts the message ("--dt 0: ...").
const KeySpec* key_of_message(const StudyPart& part, const std::string& message) {
  const auto starts_with = [&](const std::string& option) {
    return !option.empty() && message.rfind(option, 0) == 0 &&
           (message.size() == option.size() || message[option.size()] == ' ' || message[option.size()] == ':');
  };
  static const std::vector<KeySpec> keys[] = {keys_of(StudyPart::Kind::suite), keys_of(StudyPart::Kind::search),
                                              keys_of(StudyPart::Kind::sweep)};
  for (const KeySpec& k : keys[static_cast<int>(part.kind)])
    if (part.key_lines.count(k.key) && (starts_with(k.option) || starts_with(k.also))) return &k;
  return nullptr;
}

template <class Settings, class Make>
Settings checked(const StudyPart& part, Make make) {
  try {
    return make();
  } catch (const ib::ScenarioError&) {
    throw;  // a scenario file's own message names that file
  } catch (const std::invalid_argument& error) {
    const KeySpec* key = key_of_message(part, error.what());
    const std::string dotted =
        std::string(kind_name(part.kind)) + " \"" + part.name + "\"" + (key ? std::string(".") + key->key : "");
    throw ib::ScenarioError(part.file, key ? part.key_lines.at(key->key) : part.line, key ? key->key : "",
                            dotted + ": " + error.what());
  }
}

}  // namespace

Study read_study(const std::string& path, const std::vector<std::string>& engines) {
  const std::string text = read_text(path);
  const Checker checker(path, text);
  const toml::table document = checker.parse();
  const ib::toml_schema::Section top{&document, "", 1};
  checker.reject_unknown(top, {"study", "suite", "search", "sweep"},
                         "allowed: [study], [[suite]], [[search]], [[sweep]] (docs/studies.md, \"Study files\")");
  Study study;
  study.file = path;
  if (const toml::node* node = document.get("study")) {
    if (!node->is_table())
      checker.fail(line_of(*node), "study",
                   "study: wrong type (" + std::string(type_name(*node)) + "); expected a table [study]");
    const ib::toml_schema::Section section{node->as_table(), "study", line_of(*node)};
    checker.reject_unknown(section, {"description"}, "allowed keys in [study]: description");
    if (const toml::node* d = node->as_table()->get("description")) {
      if (!d->is_string())
        checker.fail(line_of(*d), "study.description",
                     checker.show("study.description", *d) + ": wrong type (" + type_name(*d) + "); expected a string");
      study.description = d->as_string()->get();
    }
  }
  for (StudyPart::Kind kind : {StudyPart::Kind::suite, StudyPart::Kind::search, StudyPart::Kind::sweep}) {
    const toml::node* node = document.get(kind_name(kind));
    if (!node) continue;
    const toml::array* tables = node->as_array();
    if (!tables || !tables->is_array_of_tables())
      checker.fail(line_of(*node), kind_name(kind),
                   std::string(kind_name(kind)) + ": wrong type (" + type_name(*node) + "); expected tables [[" +
                       kind_name(kind) + "]]");
    int index = 0;
    for (const toml::node& table : *tables)
      study.parts.push_back(read_part(checker, *table.as_table(), kind, index++, path, engines));
  }
  if (study.parts.empty())
    throw ib::ScenarioError(path, 1, "", "a study needs at least one [[suite]], [[search]] or [[sweep]]");
  // Sweeps write into OUT/sweeps/NAME: two of one name would share a folder.
  std::map<std::string, int> sweep_lines;
  for (const StudyPart& part : study.parts)
    if (part.kind == StudyPart::Kind::sweep && !sweep_lines.emplace(part.name, part.line).second)
      throw ib::ScenarioError(path, part.line, "sweep.name",
                              "sweep.name = \"" + part.name + "\": already the name of the sweep at line " +
                                  std::to_string(sweep_lines[part.name]) + "; allowed: a name of its own (its folder)");
  return study;
}

ib::SuiteSettings settings_of_suite_part(const StudyPart& part) {
  return checked<ib::SuiteSettings>(part, [&] { return suite_settings_from(part.suite, part.measurement); });
}

ib::SweepSettings settings_of_sweep_part(const StudyPart& part) {
  return checked<ib::SweepSettings>(part, [&] { return sweep_settings_from(part.sweep, part.measurement); });
}

}  // namespace cli
