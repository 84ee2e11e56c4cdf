// The keys of a study file's parts (study_keys.h).
#include "cli/study_keys.h"

#include "cli/arguments.h"

#include <algorithm>
#include <set>
#include <stdexcept>
#include <string>

namespace cli {

namespace {

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
// A [[validation]] runs the reference alone (docs/validation.md): of the common keys, those that say how it runs
// and is scored; the engines, paths and steps are not its.
const std::vector<std::string> kValidationCommonKeys = {
    "name", "laws", "options", "rate_hz", "sensor_rate_hz", "series", "time_limit_s", "window_s", "duration_s"};
const std::vector<KeySpec> kValidationKeys = {
    {"scenarios", Type::texts, "scenarios", "the published cases' scenario files"},
    {"inputs", Type::text, "", "an uncertain-inputs file (scenarios/paper_inputs.toml)"},
    {"points", Type::integer, "", "sample points per case (>= 1)"},
    {"nominal_starts", Type::integer, "", "the nominal cases' starts, whose spread is their chaos (>= 1)"},
};

}  // namespace

const std::vector<ib::StudyPartKind>& study_file_kinds() {
  static const std::vector<ib::StudyPartKind> kinds = {ib::StudyPartKind::suite, ib::StudyPartKind::search,
                                                       ib::StudyPartKind::sweep, ib::StudyPartKind::validation};
  return kinds;
}

std::vector<KeySpec> keys_of(ib::StudyPartKind kind) {
  std::vector<KeySpec> keys;
  if (kind == ib::StudyPartKind::validation) {
    for (const KeySpec& k : kCommonKeys)
      if (std::find(kValidationCommonKeys.begin(), kValidationCommonKeys.end(), k.key) != kValidationCommonKeys.end())
        keys.push_back(k);
    keys.insert(keys.end(), kValidationKeys.begin(), kValidationKeys.end());
    return keys;
  }
  keys = kCommonKeys;
  const auto& own = kind == ib::StudyPartKind::suite    ? kSuiteKeys
                    : kind == ib::StudyPartKind::search ? kSearchKeys
                                                        : kSweepKeys;
  keys.insert(keys.end(), own.begin(), own.end());
  return keys;
}

std::vector<KeySpec> default_keys() {
  std::vector<KeySpec> keys;
  std::set<std::string> seen = {"name", "scenario", "scenarios"};  // what makes a part itself
  for (ib::StudyPartKind kind : study_file_kinds())
    for (const KeySpec& k : keys_of(kind))
      if (seen.insert(k.key).second) keys.push_back(k);
  return keys;
}

const KeySpec* key_of_message(ib::StudyPartKind kind, const std::map<std::string, int>& key_lines,
                              const std::string& message) {
  const auto starts_with = [&](const std::string& option) {
    return !option.empty() && message.rfind(option, 0) == 0 &&
           (message.size() == option.size() || message[option.size()] == ' ' || message[option.size()] == ':');
  };
  static const std::vector<KeySpec> keys[] = {keys_of(ib::StudyPartKind::suite),
                                              keys_of(ib::StudyPartKind::search),
                                              keys_of(ib::StudyPartKind::sweep),
                                              {},
                                              keys_of(ib::StudyPartKind::validation)};
  if (kind == ib::StudyPartKind::other) return nullptr;  // not a study file's: its messages are its own
  for (const KeySpec& k : keys[static_cast<int>(kind)])
    if (key_lines.count(k.key) && (starts_with(k.option) || starts_with(k.also))) return &k;
  return nullptr;
}

// "all" spelled out: every simulator of the build (less skip_engines), every law, every path.
std::string expand_all(const std::string& key, const std::string& value, const std::vector<std::string>& engines) {
  if (value != "all") return value;
  if (key == "engines") return join_list(engines);
  if (key == "laws") return "hertz,viscoelastic,newton";
  return "matched,injected,native";
}

namespace {

std::string without(const std::string& list, const std::string& skipped) {
  std::vector<std::string> kept;
  const std::vector<std::string> skip = split(skipped, ',');
  for (const std::string& item : split(list, ','))
    if (std::find(skip.begin(), skip.end(), item) == skip.end()) kept.push_back(item);
  return join_list(kept);
}

}  // namespace

std::string part_engines(const std::map<std::string, std::string>& given, const std::vector<std::string>& engines) {
  if (!given.count("engines") && !given.count("skip_engines")) return "";
  const std::string listed =
      given.count("engines") ? expand_all("engines", given.at("engines"), engines) : join_list(engines);
  const std::string kept = given.count("skip_engines") ? without(listed, given.at("skip_engines")) : listed;
  if (kept.empty())
    throw std::invalid_argument("leaves no engine to run (engines: [" + listed + "], skip_engines: [" +
                                (given.count("skip_engines") ? given.at("skip_engines") : "") +
                                "]); allowed: at least one engine of the build (" + join_list(engines) + ")");
  return kept;
}

}  // namespace cli
