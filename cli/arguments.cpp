#include "cli/arguments.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "model/simulator_options.h"
#include "simulators/catalog.h"

namespace cli {

int g_argc = 0;
char** g_argv = nullptr;

int exit_code(const ib::CampaignResult& result) {
  switch (result.status) {
    case ib::CampaignStatus::ok:
      return kExitOk;
    case ib::CampaignStatus::not_ok:
      return kExitRunNotOk;
    case ib::CampaignStatus::stopped:
      return kExitInterrupted + result.signal;
  }
  return kExitOk;
}

// The command line as typed, with --resume added when missing: what continues an interrupted suite.
std::string resume_command(int argc, char** argv) {
  std::string command = "impactbench";
  bool resume = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    resume = resume || arg == "--resume";
    const bool plain = !arg.empty() && arg.find_first_not_of(
                                           "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                           "0123456789-_=.,/:+@%") == std::string::npos;
    std::string quoted = "'";
    for (char c : arg) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    command += " " + (plain ? arg : quoted + "'");
  }
  return command + (resume ? "" : " --resume");
}

std::optional<std::string> unknown_command(const CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return std::nullopt;
  const std::string name = argv[1];
  std::string allowed;
  for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; })) {
    if (command->get_name() == name) return std::nullopt;
    allowed += (allowed.empty() ? "" : ", ") + command->get_name();
  }
  return "unknown command '" + name + "'; allowed: " + allowed + " (impactbench --help says what each does)";
}

std::vector<std::string> split_list(const std::string& text, const std::string& option, const std::string& allowed) {
  std::vector<std::string> items;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    if (item.empty())
      throw std::invalid_argument(option + " '" + text + "': an empty item; allowed: " + allowed + ", comma-separated");
    items.push_back(item);
  }
  if (items.empty() || text.back() == ',')
    throw std::invalid_argument(option + " '" + text + "': " + (items.empty() ? "empty" : "an empty item") +
                                "; allowed: " + allowed + ", comma-separated");
  return items;
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, separator);)
    if (!part.empty()) parts.push_back(part);
  return parts;
}

std::string join_list(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ",") + item;
  return text;
}

// One --option pair: (engine, name, value), engine "" when the pair is name=value. A dot before the '=' names
// the engine (option names have none; values may: erp=0.2).
struct OptionPair {
  std::string engine, name, value;
};

OptionPair split_option(const std::string& pair) {
  const auto eq = pair.find('=');
  if (eq == std::string::npos || eq == 0)
    throw std::invalid_argument("--option " + pair + ": expected name=value or engine.name=value");
  const auto dot = pair.find('.');
  if (dot == std::string::npos || dot > eq) return {"", pair.substr(0, eq), pair.substr(eq + 1)};
  if (dot == 0 || dot + 1 == eq)
    throw std::invalid_argument("--option " + pair + ": expected name=value or engine.name=value");
  return {pair.substr(0, dot), pair.substr(dot + 1, eq - dot - 1), pair.substr(eq + 1)};
}

std::map<std::string, std::string> parse_engine_options(const std::vector<std::string>& pairs,
                                                        const std::string& engine) {
  std::map<std::string, std::string> options;
  for (const std::string& pair : pairs) {
    const OptionPair option = split_option(pair);
    if (!option.engine.empty() && option.engine != engine)
      throw std::invalid_argument("--option " + pair + ": names engine '" + option.engine + "', but this runs " +
                                  engine + "; allowed: name=value or " + engine + ".name=value");
    options[option.name] = option.value;
  }
  return options;
}

// --option pairs of a matrix (suite, sweep, a study's part) into s: engine.name=value for any engine of the build;
// name=value where the engine is known, the one engine of `engines` (the reference when it lists no other).
void matrix_options_from(const std::vector<std::string>& pairs, ib::MatrixSettings& s) {
  std::vector<std::string> engines;
  for (const auto& e : s.engines)
    if (e != "reference") engines.push_back(e);
  for (const std::string& pair : pairs) {
    OptionPair option = split_option(pair);
    if (option.engine.empty()) {
      if (engines.size() > 1)
        throw std::invalid_argument("--option " + pair + ": which engine? --engines lists " + join_list(engines) +
                                    "; allowed: engine.name=value, e.g. " + engines.front() + "." + pair);
      option.engine = engines.empty() ? "reference" : engines.front();
    }
    require_engine(option.engine);
    auto& target = option.engine == "reference" ? s.reference_options : s.engine_options[option.engine];
    target[option.name] = option.value;
  }
}

ib::ContactLaw parse_law(const std::string& name) {
  const auto law = ib::contact_law_from_string(name);
  if (!law)
    throw std::invalid_argument("law '" + name +
                                "': unknown; allowed: hertz, viscoelastic, newton (spring-dashpot: "
                                "another name for viscoelastic)");
  return *law;
}

void require_engine(const std::string& engine) {
  for (const auto& n : ib::simulator_names())
    if (n == engine) return;
  std::string names;
  for (const auto& n : ib::simulator_names()) names += (names.empty() ? "" : ", ") + n;
  throw std::invalid_argument("engine '" + engine + "': not in this build; allowed: " + names);
}

double parse_positive(const std::string& text, const std::string& option) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
  }
  if (used != text.size() || !(value > 0) || !std::isfinite(value))
    throw std::invalid_argument(option + " " + text + ": allowed: a number > 0");
  return value;
}

ib::Measurement MeasurementOptions::build() const {
  ib::Measurement m;
  // given (and so checked, on the command line as read, in a study file as its key is read): else the scenario's
  if ((app_ && app_->count("--window") > 0) || window_given) m.window_s = window_s;
  m.sensor_rate_hz = sensor_rate_hz;
  m.merge_window_s = merge_window_s;
  m.timed_repeats = timed_repeats;
  m.series_rate_hz = series_rate_hz;
  if (series == "window")
    m.series = ib::SeriesOutput::window;
  else if (series == "all")
    m.series = ib::SeriesOutput::all;
  else if (series == "none")
    m.series = ib::SeriesOutput::none;
  else
    throw std::invalid_argument("--series " + series + ": allowed: window, all, none");
  return m;
}

void matrix_settings_from(const MatrixOptions& o, const MeasurementOptions& measurement_options,
                          ib::MatrixSettings& s) {
  s.simulators = ib::simulator_catalog();
  std::string engine_names;
  for (const auto& n : ib::simulator_names()) engine_names += (engine_names.empty() ? "" : ", ") + n;
  // "all", as a study file's engines and laws take it
  s.engines = o.engines == "all" ? ib::simulator_names() : split_list(o.engines, "--engines", engine_names + " or all");
  for (const auto& e : s.engines) require_engine(e);
  s.laws.clear();
  const std::string laws = o.laws == "all" ? "hertz,viscoelastic,newton" : o.laws;
  for (const auto& l : split_list(laws, "--laws", "hertz, viscoelastic, newton or all")) s.laws.push_back(parse_law(l));
  if (!o.time_steps.empty()) s.time_steps_s = parse_values(Shared::dt, o.time_steps);
  for (const auto& path :
       o.paths.empty() ? std::vector<std::string>{} : split_list(o.paths, "--paths", ib::contact_path_names())) {
    if (!ib::contact_path_from_string(path))
      throw std::invalid_argument("--paths " + path + ": allowed: " + ib::contact_path_names() + ", comma-separated");
    s.contact_paths.push_back(path);
  }
  matrix_options_from(o.options, s);
  for (const auto& engine : s.engines) {  // fail now, not in every job
    ib::RunSettings run;
    run.options = engine == "reference" ? s.reference_options : s.engine_options[engine];
    ib::make_simulator(engine)->check_settings(run);
  }
  if (o.out.empty()) throw std::invalid_argument("--out '': allowed: a folder path");
  s.output_rate_hz = o.rate_hz;  // --rate, --jobs, --time-limit: checked as read (option_rules.h)
  s.jobs = o.jobs;
  s.time_limit_s = o.time_limit_s;
  s.out = o.out;
  s.resume = o.resume;
  s.measurement = measurement_options.build();
  require_series_resolves_sensor(s.output_rate_hz, s.measurement.sensor_rate_hz);
  if (!o.shard.empty()) s.shard = ib::parse_shard(o.shard);
  s.resume_command = resume_command(g_argc, g_argv);
}

}  // namespace cli
