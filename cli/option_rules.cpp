#include "cli/option_rules.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "cli/arguments.h"
#include "harness/scoring/plausibility.h"

namespace cli {

namespace {

using ib::Plausible;

// One row per option, each range decided once (the why beside it). The harness checks the same quantities
// again where it sizes a run (harness/scoring/plausibility.h: steps, samples, a step at most a tenth of the run);
// where its bounds are wider (a rate of 1 Hz), this table is the one a user meets.
const OptionRule kOptionRules[] = {
    // Contacts last 0.3 to 1 ms (docs/step-search.md): a 1e-2 s step is ten contacts long and a fourteenth of
    // the rig's first period; below 1e-9 s a run of 10 s takes the harness's limit of 1e10 steps.
    {"--dt", Plausible::kMinTimeStep_s, Plausible::kMaxTimeStep_s, true, false, "s",
     "the time step of fixed-step engines"},
    // The series is what every metric reads (harness/scoring/metrics.h). At 256 Hz (sweep's floor so far) its Nyquist
    // frequency, 128 Hz, is above the published rig's first two bending modes (6.95 and 73.2 Hz with the tip
    // mass, `impactbench modes`); below 146 Hz the second mode aliases. Its use in a run is bounded from
    // below by --sensor-rate too (option_rules.h), 2048 Hz by default.
    {"--rate", 256, Plausible::kMaxRate_hz, true, false, "Hz", "the output series' sample rate"},
    // The sensor's reading over 1/f_s (docs/rig.md section 5) sees what changes slower than f_s / 2: the same
    // floor as the series it reads. The experiment's accelerometers ran at 2048 Hz (the default).
    {"--sensor-rate", 256, Plausible::kMaxRate_hz, true, false, "Hz", "the accelerometer's sample rate"},
    // Wall time: a week is longer than any cluster's job limit; beyond it a value is a typo.
    {"--time-limit", 0, Plausible::kMaxTimeLimit_s, false, false, "s", "the wall time of one run before it is stopped"},
    // Rig time: up to an hour, the longest a scenario may be (model/scenario_toml.cpp: duration_s).
    {"--duration", 0, Plausible::kMaxDuration_s, false, false, "s", "the simulated time of a run"},
    {"--rest-duration", 0, Plausible::kMaxDuration_s, false, false, "s", "the simulated time of a start from rest"},
    // A part of the run: the same bounds as the run; inside the run is checked with the run's length.
    {"--window", 0, Plausible::kMaxDuration_s, false, false, "s", "the scored last part of a run"},
    {"--series-start", 0, Plausible::kMaxDuration_s, true, false, "s", "the time of the first output sample"},
    // 0 merges nothing; 1 s is several motor periods, every impact of a period in one.
    {"--merge-window", 0, Plausible::kMaxMergeWindow_s, true, false, "s", "onsets closer than this are one impact"},
    // One process each: more than 1024 on one machine (or one Slurm task) is a typo.
    {"--jobs", 1, 1024, true, true, "", "worker processes"},
    {"--repeat", 0, 100, true, true, "", "timed runs after the logged one"},
    // What an engine run's series.csv.gz keeps (0: every output sample); the metrics read the full series first.
    {"--series-rate", 0, Plausible::kMaxRate_hz, true, false, "Hz",
     "the rate an engine run's series file keeps, 0 for --rate"},
};
static_assert(sizeof kOptionRules / sizeof kOptionRules[0] == static_cast<int>(Shared::series_rate) + 1,
              "one rule per Shared, in its order");

std::string range_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

[[noreturn]] void refuse_value(Shared option, const std::string& shown) {
  throw std::invalid_argument(std::string(rule(option).name) + " " + shown + ": allowed: " + allowed_text(option));
}

bool within_rule(const OptionRule& r, double value) {
  const bool above = r.lo_included ? value >= r.lo : value > r.lo;
  return std::isfinite(value) && above && value <= r.hi && (!r.whole || value == std::floor(value));
}

// The default a --help shows, as the table writes numbers.
// and the type it names: the option is read as text only so that its message is the table's
template <typename T>
CLI::Option* with_default_shown(CLI::Option* option, T value, bool show) {
  option->type_name(std::is_integral_v<T> ? "INT" : "FLOAT");
  return show ? option->default_str(value_text(static_cast<double>(value))) : option;
}

}  // namespace

const OptionRule& rule(Shared option) { return kOptionRules[static_cast<int>(option)]; }

std::string allowed_text(Shared option) {
  const OptionRule& r = rule(option);
  std::string text = range_number(r.lo) + (r.lo_included ? " <= x <= " : " < x <= ") + range_number(r.hi);
  if (*r.unit) text += std::string(" ") + r.unit;
  if (r.whole) text += ", a whole number";
  return text + " (" + r.meaning + ")";
}

std::string value_text(double value) {
  if (!std::isfinite(value)) return range_number(value);
  char text[32];
  for (int digits = 6; digits <= 17; ++digits) {  // the shortest that reads back as the same double
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    if (std::strtod(text, nullptr) == value) break;
  }
  return text;
}

double parse_value(Shared option, const std::string& text) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (text.empty() || end == begin || *end != '\0')
    refuse_value(option, text.empty() ? "''" : text);  // not a number: as typed
  if (!within_rule(rule(option), value)) refuse_value(option, value_text(value));
  return value;
}

std::vector<double> parse_values(Shared option, const std::string& text) {
  std::vector<double> values;
  for (const std::string& item : split_list(text, rule(option).name, allowed_text(option)))
    values.push_back(parse_value(option, item));
  return values;
}

CLI::Option* add_shared_option(CLI::App* command, Shared option, double& target, const std::string& description,
                               bool show_default) {
  CLI::Option* added = command->add_option_function<std::string>(
      rule(option).name, [option, &target](const std::string& text) { target = parse_value(option, text); },
      description);
  return with_default_shown(added, target, show_default);
}

CLI::Option* add_shared_option(CLI::App* command, Shared option, int& target, const std::string& description,
                               bool show_default) {
  CLI::Option* added = command->add_option_function<std::string>(
      rule(option).name,
      [option, &target](const std::string& text) { target = static_cast<int>(parse_value(option, text)); },
      description);
  return with_default_shown(added, target, show_default);
}

CLI::Option* add_shared_list_option(CLI::App* command, Shared option, std::string& target,
                                    const std::string& description) {
  return command->add_option_function<std::string>(
      rule(option).name,
      [option, &target](const std::string& text) {
        parse_values(option, text);
        target = text;
      },
      description);
}

void require_at_most(Shared option, double value, double limit, const std::string& limit_text) {
  if (!(value <= limit))
    throw std::invalid_argument(std::string(rule(option).name) + " " + value_text(value) + ": allowed: at most " +
                                limit_text);
}

void require_series_resolves_sensor(double rate_hz, double sensor_rate_hz) {
  if (rate_hz < sensor_rate_hz)
    throw std::invalid_argument("--rate " + value_text(rate_hz) + ": allowed: at least --sensor-rate (" +
                                value_text(sensor_rate_hz) +
                                " Hz; the sensor reads the series, and a coarser series underestimates its peaks)");
}

}  // namespace cli
