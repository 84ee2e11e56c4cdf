// `study FILE --out DIR`: a study file's parts (study_file.h) into one folder, then its report. The suites
// and step searches go into DIR (each after the first adds its own settings record: --extend), the sweeps
// into DIR/sweeps/NAME, all as one plan on one pool of workers; --jobs, --shard and --resume apply to every part.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "cli/commands.h"
#include "cli/study_file.h"
#include "harness/jobs/unit_source.h"
#include "harness/jobs/worker_process.h"
#include "harness/records/engines_file.h"
#include "harness/records/number_text.h"
#include "simulators/catalog.h"

namespace cli {

namespace {

// `study FILE --out DIR`: every part of a study file (study_file.h) into one folder, then its report.
struct StudyOptions {
  std::string file, out, shard;
  std::string skip;             // kinds of parts left out, comma-separated: suite, search, sweep
  std::string reference_cache;  // a folder sharing reference runs between output folders
  int jobs = static_cast<int>(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN)));
  bool resume = false, no_report = false;
  bool plan = false;  // --plan: check the file and say what each part runs, run nothing
};

// What decides a part's runs beyond its matrix, for its plan line: the window, the rates, what is kept, the
// options and the time limit, so that two study files with the same plan lines run the same runs.
// (A sweep's window is its own: with_window false.)
std::string measured_text(const ib::MatrixSettings& s, bool with_window = true) {
  const ib::Measurement& m = s.measurement;
  std::string text = "; rate " + ib::number_text(s.output_rate_hz) + " Hz, sensor " +
                     ib::number_text(m.sensor_rate_hz) + " Hz" +
                     (!with_window ? ""
                      : m.window_s ? "; window " + ib::number_text(*m.window_s) + " s"
                                   : std::string("; window the scenario's")) +
                     "; series " +
                     (m.series == ib::SeriesOutput::none  ? "none"
                      : m.series == ib::SeriesOutput::all ? "all"
                                                          : "window");
  if (m.series_rate_hz > 0) text += " at " + ib::number_text(m.series_rate_hz) + " Hz";
  std::vector<std::string> options;
  for (const auto& [name, value] : s.reference_options) options.push_back("reference." + name + "=" + value);
  for (const auto& [engine, set] : s.engine_options)
    for (const auto& [name, value] : set) options.push_back(engine + "." + name + "=" + value);
  if (!options.empty()) text += "; options " + join_list(options);
  return text + "; time limit " + ib::number_text(s.time_limit_s) + " s";
}

// One line per part: what it runs, "all" spelled out as this build has it, and what decides its runs beyond that.
void print_plan(const std::vector<ib::SuiteSettings>& suites, const std::vector<std::string>& suite_names,
                const std::vector<ib::SweepSettings>& sweeps, const std::vector<std::string>& sweep_names) {
  const auto laws = [](const std::vector<ib::ContactLaw>& list) {
    std::vector<std::string> names;
    for (ib::ContactLaw law : list) names.push_back(ib::to_string(law));
    return join_list(names);
  };
  const auto steps = [](const std::vector<double>& list) {
    std::vector<std::string> texts;
    for (double dt : list) texts.push_back(ib::number_text(dt));
    return texts.empty() ? std::string("default") : join_list(texts);
  };
  for (std::size_t i = 0; i < suites.size(); ++i) {
    const ib::SuiteSettings& s = suites[i];
    const std::string starts = s.ensemble.reference_starts == 1
                                   ? ""
                                   : "; starts " + std::to_string(s.ensemble.engine_starts) + " (references " +
                                         std::to_string(s.ensemble.reference_starts) + ")";
    std::vector<std::string> links;
    for (int k : s.reference_chain_links) links.push_back(std::to_string(k));
    const std::string chains = links.empty() ? "" : "; the reference on chains of " + join_list(links) + " links";
    std::string more =
        (s.max_duration_s > 0 ? "; cut to " + ib::number_text(s.max_duration_s) + " s" : "") + measured_text(s);
    if (s.ensemble.reference_starts > 1)
      more += "; start step " + ib::number_text(s.ensemble.displacement_step_m) + " m";
    if (s.step_search)
      more += "; " + std::string(s.step_search->walk ? "walk" : "bisection") + " over " +
              ib::number_text(s.step_search->min_step_s) + " to " + ib::number_text(s.step_search->max_step_s) +
              " s, " + std::to_string(s.step_search->points_per_octave) + " per octave" +
              (s.keep_probe_series ? ", probes' series kept" : "");
    std::printf("%s \"%s\": %s; engines %s; laws %s; paths %s; dt_s %s%s%s%s\n", s.step_search ? "search" : "suite",
                suite_names[i].c_str(), join_list(s.inputs).c_str(), join_list(s.engines).c_str(), laws(s.laws).c_str(),
                s.recommended             ? "recommended"
                : s.contact_paths.empty() ? "default"
                                          : join_list(s.contact_paths).c_str(),
                s.step_search   ? "searched"
                : s.recommended ? "recommended"
                                : steps(s.time_steps_s).c_str(),
                starts.c_str(), chains.c_str(), more.c_str());
  }
  for (std::size_t i = 0; i < sweeps.size(); ++i) {
    const ib::SweepSettings& s = sweeps[i];
    std::vector<std::string> starts, ratios;
    for (ib::SweepStart start : s.starts) starts.push_back(ib::to_string(start));
    for (double ratio : s.ensemble.ratios) ratios.push_back(ib::number_text(ratio));
    std::string more =
        "; starts " + join_list(starts) + "; from rest " +
        (s.rest_duration_s ? ib::number_text(*s.rest_duration_s) + " s" : std::string("the scenario's")) +
        ", continued " + ib::number_text(s.continuation_duration_s) + " s, window " + ib::number_text(s.window_s) +
        " s";
    if (s.ensemble.reference_starts > 1)
      more += "; the reference from " + std::to_string(s.ensemble.reference_starts) + " starts " +
              ib::number_text(s.ensemble.displacement_step_m) + " m apart at " +
              (ratios.empty() ? std::string("every ratio") : join_list(ratios));
    more += measured_text(s, false);
    std::printf("sweep \"%s\": %s; %zu ratios; engines %s; laws %s; paths %s; dt_s %s%s -> %s\n",
                sweep_names[i].c_str(), s.scenario_path.c_str(), s.ratios.size(), join_list(s.engines).c_str(),
                laws(s.laws).c_str(), s.contact_paths.empty() ? "default" : join_list(s.contact_paths).c_str(),
                steps(s.time_steps_s).c_str(), more.c_str(), s.out.c_str());
  }
}

int command_study(const StudyOptions& o) {
  if (o.out.empty() && !o.plan) throw std::invalid_argument("--out '': allowed: a folder path");
  if (o.jobs < 1 || o.jobs > 1024)
    throw std::invalid_argument("--jobs " + std::to_string(o.jobs) + ": allowed: 1 to 1024");
  const Study study = read_study(o.file, ib::simulator_names());
  const std::string out = o.out.empty() ? "OUT" : o.out;  // --plan alone names no folder
  std::vector<std::string> skipped;
  if (!o.skip.empty())
    for (const std::string& kind : split_list(o.skip, "--skip", "suite, search, sweep")) {
      if (kind != "suite" && kind != "search" && kind != "sweep")
        throw std::invalid_argument("--skip " + kind + ": allowed: suite, search, sweep, comma-separated");
      skipped.push_back(kind);
    }
  const auto left_out = [&](StudyPart::Kind kind) {
    const char* name = kind == StudyPart::Kind::suite ? "suite" : kind == StudyPart::Kind::search ? "search" : "sweep";
    return std::find(skipped.begin(), skipped.end(), name) != skipped.end();
  };
  // Every part's settings first: a bad value anywhere stops the study before anything runs.
  std::vector<ib::SuiteSettings> suites;
  std::vector<ib::SweepSettings> sweeps;
  std::vector<std::string> suite_names, sweep_names;
  for (StudyPart part : study.parts) {
    if (left_out(part.kind)) continue;
    if (part.kind == StudyPart::Kind::sweep) {
      part.sweep.out = out + "/sweeps/" + part.name;
      part.sweep.jobs = o.jobs;
      part.sweep.shard = o.shard;
      part.sweep.resume = o.resume;
      sweeps.push_back(settings_of_sweep_part(part));
      sweep_names.push_back(part.name);
      continue;
    }
    part.suite.out = out;
    part.suite.jobs = o.jobs;
    part.suite.shard = o.shard;
    part.suite.resume = o.resume;
    part.suite.reference_cache = o.reference_cache;
    part.suite.extend = !suites.empty();  // the later parts have other settings: each adds its suite to the folder
    suites.push_back(settings_of_suite_part(part));
    suite_names.push_back(part.name);
  }
  if (o.plan) {
    print_plan(suites, suite_names, sweeps, sweep_names);
    return kExitOk;
  }
  std::fprintf(stderr, "study: %s, %zu suites and searches into %s, %zu sweeps into %s/sweeps/\n", o.file.c_str(),
               suites.size(), o.out.c_str(), sweeps.size(), o.out.c_str());
  int status = kExitOk;
  const auto worst = [&](int code) {
    status = std::max(status, code);
    return code == kExitBadInput || code >= kExitOutputError;  // stop: bad input, a write error, an interruption
  };
  // One plan on one pool of workers: the suites and searches into one folder (a job two parts plan runs
  // once), each sweep into its own; no part waits for another, the costliest ready unit starts first.
  for (std::size_t i = 0; i < suites.size(); ++i)
    record_command(o.out, suites[i].measurement.verdicts, o.file + ": " + suite_names[i]);
  const ib::InterruptionHandler handler;  // outlives the pool, which stops its workers when it ends
  std::unique_ptr<ib::SuiteSource> suite_source = suites.empty() ? nullptr : ib::prepare_suites(suites);
  std::vector<std::unique_ptr<ib::SweepSource>> sweep_sources;
  for (const ib::SweepSettings& sweep : sweeps) sweep_sources.push_back(ib::prepare_sweep(sweep));
  std::vector<ib::UnitSource*> sources;
  if (suite_source) sources.push_back(suite_source.get());
  for (const auto& sweep : sweep_sources) sources.push_back(sweep.get());
  ib::run_units(sources, o.jobs);
  if (suite_source)
    worst(
        suite_exit_code(suites.front(), ib::with_engines_file(out, suites.front().simulators, suite_source->finish())));
  for (std::size_t i = 0; i < sweeps.size(); ++i)
    worst(sweep_exit_code(sweeps[i],
                          ib::with_engines_file(sweeps[i].out, sweeps[i].simulators, sweep_sources[i]->finish())));
  if (status == kExitBadInput || status >= kExitOutputError) return status;
  if (!o.no_report && o.shard.empty()) {
    const int report = command_report(o.out, "");
    if (report != kExitOk) return report;
  }
  return status;
}

}  // namespace

Command add_study_command(CLI::App& app) {
  auto o = std::make_shared<StudyOptions>();
  CLI::App* study = app.add_subcommand("study",
                                       "run a study file's suites, step searches and sweeps into one folder, "
                                       "then make its report (docs/studies.md, \"Study files\")");
  study->add_option("file", o->file, "a study file (.toml), e.g. studies/default.toml")->required();
  study->add_option("--out", o->out, "output folder (required unless --plan)");
  study->add_option("--jobs", o->jobs, "worker processes")->capture_default_str();
  study->add_option("--shard", o->shard, "K/N: every part's K-th of N shares, for a job array (merge joins them)");
  study->add_flag("--resume", o->resume, "continue the study recorded in --out");
  study->add_option("--reference-cache", o->reference_cache,
                    "a folder that shares reference runs between output folders (as suite --reference-cache)");
  study->add_option("--skip", o->skip, "kinds of parts left out, comma-separated: suite, search, sweep");
  study->add_flag("--no-report", o->no_report, "leave the report out");
  study->add_flag("--plan", o->plan, "check the file and print what each part runs; run nothing");
  return {study, [o] { return command_study(*o); }};
}

}  // namespace cli
