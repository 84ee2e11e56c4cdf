// The numeric options that several commands share, each with one range, unit and meaning, and the one
// place that registers, parses and checks them: `run --dt 0` and `suite --dt 0` get the same message,
// "--dt 0: allowed: 1e-09 <= x <= 0.01 s (the time step of fixed-step engines)", and exit 2.
//
// An option registered here takes its text from the command line and is parsed and checked as soon as
// the command line is read, only when it is given (a default is never a user's value): a value outside
// its range, not a number, nan or inf throws std::invalid_argument naming the option, the value and what
// is allowed (main prints it and exits 2). Rules between options or with the scenario (a window inside
// the run, the series no coarser than the sensor) are the functions below, checked by each command.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace cli {

enum class Shared {
  dt,
  rate,
  sensor_rate,
  time_limit,
  duration,
  rest_duration,
  window,
  series_start,
  merge_window,
  jobs,
  repeat,
  series_rate
};

struct OptionRule {
  const char* name;  // as typed: "--dt"
  double lo, hi;     // lo < x <= hi, or lo <= x <= hi with lo_included
  bool lo_included;
  bool whole;        // a count: a whole number
  const char* unit;  // SI: "s", "Hz"; "" for a count
  const char* meaning;
};

const OptionRule& rule(Shared option);

// "1e-09 <= x <= 0.01 s (the time step of fixed-step engines)": what the messages say is allowed.
std::string allowed_text(Shared option);

// A value as the messages show it: the shortest text that reads back as the same double ("1e+12", "nan").
std::string value_text(double value);

// The text of one value, parsed and checked; throws "NAME TEXT: allowed: ...".
double parse_value(Shared option, const std::string& text);

// A comma-separated list of values (suite's and sweep's --dt), each checked as parse_value does; empty
// items are refused as split_list refuses them.
std::vector<double> parse_values(Shared option, const std::string& text);

// Registers the option on `command`; when given, its value is parsed, checked and stored in target.
// show_default: --help shows the target's value as the default (not for a value that means "not given").
CLI::Option* add_shared_option(CLI::App* command, Shared option, double& target, const std::string& description,
                               bool show_default = true);
CLI::Option* add_shared_option(CLI::App* command, Shared option, int& target, const std::string& description,
                               bool show_default = true);
// A comma-separated list of values: each is checked when given; target keeps the text.
CLI::Option* add_shared_list_option(CLI::App* command, Shared option, std::string& target,
                                    const std::string& description);

// value <= limit, else "NAME VALUE: allowed: at most LIMIT_TEXT" (e.g. a window at most the run).
void require_at_most(Shared option, double value, double limit, const std::string& limit_text);

// The series at --rate is what the sensor reading reads (harness/scoring/metrics.h): between samples the velocity
// is interpolated linearly, so a series coarser than the sensor turns it into a sensor at --rate and its
// peak is underestimated. Where a run is measured (run, suite, sweep): --rate >= --sensor-rate.
void require_series_resolves_sensor(double rate_hz, double sensor_rate_hz);

}  // namespace cli
