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

// "name=value" pairs from --option.
std::map<std::string, std::string> parse_options(const std::vector<std::string>& pairs) {
  std::map<std::string, std::string> options;
  for (const std::string& pair : pairs) {
    const auto eq = pair.find('=');
    if (eq == std::string::npos || eq == 0) throw std::invalid_argument("--option " + pair + ": expected name=value");
    options[pair.substr(0, eq)] = pair.substr(eq + 1);
  }
  return options;
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
  s.engines = split_list(o.engines, "--engines", engine_names);
  for (const auto& e : s.engines) require_engine(e);
  s.laws.clear();
  for (const auto& l : split_list(o.laws, "--laws", "hertz, viscoelastic, newton")) s.laws.push_back(parse_law(l));
  if (!o.time_steps.empty()) s.time_steps_s = parse_values(Shared::dt, o.time_steps);
  for (const auto& path :
       o.paths.empty() ? std::vector<std::string>{} : split_list(o.paths, "--paths", ib::contact_path_names())) {
    if (!ib::contact_path_from_string(path))
      throw std::invalid_argument("--paths " + path + ": allowed: " + ib::contact_path_names() + ", comma-separated");
    s.contact_paths.push_back(path);
  }
  for (const auto& pair : o.options) {
    const auto dot = pair.find('.'), eq = pair.find('=');
    if (dot == std::string::npos || eq == std::string::npos || dot > eq)
      throw std::invalid_argument("--option " + pair + ": expected engine.name=value, e.g. reference.n=5");
    const std::string engine = pair.substr(0, dot);
    require_engine(engine);
    auto& target = engine == "reference" ? s.reference_options : s.engine_options[engine];
    target[pair.substr(dot + 1, eq - dot - 1)] = pair.substr(eq + 1);
  }
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
