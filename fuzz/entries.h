// The entries the fuzz targets feed (one per reader of a user file), shared with
// tests/fuzz_regressions_test.cpp, which feeds every saved finding through the same entry in the normal
// build. Each returns "" when the input was read, or the error message it gave; any other outcome (an
// exception of another kind, a crash, a sanitizer report, a hang) is a finding.
#pragma once

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

#include "harness/records/reporters.h"
#include "harness/records/run_files.h"
#include "harness/scoring/metrics.h"
#include "model/scenario_toml.h"
#include "model/trajectory.h"
#include "physics/modal_model.h"

namespace ib::fuzz {

// The scoring window the saved runs are measured in: 0.05 s, with a motor at frame 1's frequency.
inline MetricSettings window_settings() {
  MetricSettings s;
  s.window = {0, 0.05};
  s.excitation_frequency_hz = 6.9498;
  s.natural_frequency_hz = 6.9498;
  return s;
}

// 0.05 s of a 20 Hz oscillation at 4096 Hz with one contact episode: a valid run to compare with.
inline const Trajectory& small_run() {
  static const Trajectory run = [] {
    Trajectory t;
    t.output_rate_hz = 4096;
    const int n = 206;
    for (int k = 0; k < n; ++k) {
      const double time = k / 4096.0, w = 2 * M_PI * 20;
      t.time_s.push_back(time);
      for (int f = 0; f < 2; ++f) {
        t.displacement_m[f].push_back(1e-3 * std::sin(w * time));
        t.velocity_m_s[f].push_back(1e-3 * w * std::cos(w * time));
        t.acceleration_m_s2[f].push_back(-1e-3 * w * w * std::sin(w * time));
        t.peak_abs_acceleration_m_s2[f].push_back(1e-3 * w * w * std::abs(std::sin(w * time)));
      }
      t.contact_force_n.push_back(0);
      t.peak_contact_force_n.push_back(0);
    }
    ContactEvent e;
    e.onset_time_s = 0.01;
    e.end_time_s = 0.0102;
    e.approach_velocity_m_s = 0.1;
    e.rebound_velocity_m_s = 0.08;
    e.restitution = 0.8;
    e.peak_force_n = 50;
    e.impulse_n_s = 0.01;
    e.max_indentation_m = 1e-6;
    t.events.push_back(e);
    return t;
  }();
  return run;
}

// A scenario file's text (load_scenario reads the file and calls parse_scenario).
inline std::string feed_scenario_toml(std::string_view text) {
  try {
    parse_scenario(text, "fuzz.toml");
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "";
}

// A scenario file's text, and if it is accepted, the first thing every run computes from it: the
// frames' first natural frequencies and the motor's (the beam roots with the tip mass). A scenario the
// loader accepts must not crash or hang them.
inline std::string feed_scenario_frequencies(std::string_view text) {
  Scenario scenario;
  try {
    scenario = parse_scenario(text, "fuzz.toml");
  } catch (const ScenarioError& e) {
    return e.what();
  }
  try {
    frame1_first_frequency_hz(scenario);
    motor_frequency_hz(scenario);
  } catch (const std::exception& e) {
    return std::string("fuzz.toml: ") + e.what();  // a clear refusal, if not the loader's
  }
  return "";
}

// A saved run's series.csv as the suite reads a reference back (load_reference): read, measured,
// and compared with a run.
inline std::string feed_series_csv(std::string_view text) {
  std::istringstream in{std::string(text)};
  Trajectory saved;
  try {
    read_series_csv(in, "series.csv", saved);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  const MetricSettings settings = window_settings();
  const Metrics metrics = compute_metrics(saved, settings);
  const Trajectory& run = small_run();
  compare_metrics(compute_metrics(run, settings), run, metrics, saved, settings);
  return "";
}

// A saved run's events.csv, read into a valid run's trajectory and measured (impacts merged, durations).
inline std::string feed_events_csv(std::string_view text) {
  std::istringstream in{std::string(text)};
  Trajectory saved = small_run();
  try {
    read_events_csv(in, "events.csv", saved);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  compute_metrics(saved, window_settings());
  return "";
}

// A suite's runs.jsonl as `suite --resume` reads it (repair_and_list_runs), in a folder of its own;
// the repaired files must be a fixed point (a second resume finds the same finished jobs).
inline std::string feed_runs_jsonl(std::string_view text, const std::string& folder) {
  std::filesystem::create_directories(folder);
  {
    std::ofstream out(folder + "/runs.jsonl", std::ios::binary | std::ios::trunc);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
  }
  std::filesystem::remove(folder + "/runs.csv");
  const std::set<std::string> ids = repair_and_list_runs(folder);
  if (repair_and_list_runs(folder) != ids) std::abort();
  return "";
}

}  // namespace ib::fuzz
