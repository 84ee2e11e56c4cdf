// `study FILE --out DIR`: a study file's parts (study_file.h) into one folder (run_study, harness/study/study.h),
// then its report. The suites and step searches go into DIR (each after the first adds its own settings record:
// --extend), the sweeps into DIR/sweeps/NAME, all as one plan on one pool of workers; --jobs, --shard and
// --resume apply to every part. Here: the options, the file read into typed parts, the exit code and the report.
#include <algorithm>
#include <cstdio>
#include <iterator>
#include <memory>
#include <optional>
#include <stdexcept>
#include <variant>

#include "cli/commands.h"
#include "cli/study_file.h"
#include "cli/study_keys.h"
#include "harness/study/study.h"
#include "model/scenario_toml.h"
#include "simulators/catalog.h"

namespace cli {

namespace {

// `study FILE --out DIR`: every part of a study file (study_file.h) into one folder, then its report.
struct StudyOptions {
  std::string file, out, shard;
  std::string skip;             // kinds of parts left out, comma-separated: suite, search, sweep, validation
  std::string reference_cache;  // a folder sharing reference runs between output folders
  int jobs = static_cast<int>(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN)));
  bool resume = false, no_report = false;
  bool plan = false;  // --plan: check the file and say what each part runs, run nothing
};

// --skip's kinds, each named as the study file's tables are.
std::vector<ib::StudyPartKind> kinds_left_out(const std::string& skip) {
  std::vector<ib::StudyPartKind> kinds;
  if (skip.empty()) return kinds;
  const std::vector<ib::StudyPartKind>& all = study_file_kinds();
  std::string names;
  for (ib::StudyPartKind k : all) names += (names.empty() ? "" : ", ") + std::string(ib::to_string(k));
  for (const std::string& kind : split_list(skip, "--skip", names)) {
    const auto known = std::find_if(all.begin(), all.end(), [&](auto k) { return kind == ib::to_string(k); });
    if (known == all.end()) throw std::invalid_argument("--skip " + kind + ": allowed: " + names + ", comma-separated");
    kinds.push_back(*known);
  }
  return kinds;
}

// --shard K/N, checked. Each part checked it as its own option when the study ran in this command, so a bad one
// is still named at the first part run, as it was.
std::optional<ib::Shard> shard_of(const Study& study, const std::string& text) {
  if (text.empty() || study.parts.empty()) return std::nullopt;
  try {
    return ib::parse_shard(text);
  } catch (const std::invalid_argument& error) {
    const ib::StudyPart& first = study.parts.front();
    throw ib::ScenarioError(study.file, study.lines.front(), "",
                            std::string(ib::to_string(first.kind)) + " \"" + first.name + "\": " + error.what());
  }
}

int command_study(const StudyOptions& o) {
  if (o.out.empty() && !o.plan) throw std::invalid_argument("--out '': allowed: a folder path");
  if (o.jobs < 1 || o.jobs > 1024)
    throw std::invalid_argument("--jobs " + std::to_string(o.jobs) + ": allowed: 1 to 1024");
  ib::StudySettings settings;
  settings.left_out = kinds_left_out(o.skip);
  // Every part's settings checked as it is read: a bad value anywhere stops the study before anything runs.
  const Study study = read_study(o.file, ib::simulator_names(), settings.left_out);
  settings.out = o.out.empty() ? "OUT" : o.out;  // --plan alone names no folder
  settings.jobs = o.jobs;
  settings.shard = shard_of(study, o.shard);
  settings.resume = o.resume;
  settings.reference_cache = o.reference_cache;
  if (o.plan) {
    // each part's settings, then under it what it runs and costs (in the same order), then the total
    const std::vector<std::string> lines = ib::describe_study(study.parts, settings);
    const std::vector<std::string> work = ib::describe_study_work(study.parts, settings);
    for (std::size_t i = 0; i < lines.size(); ++i)
      std::printf("%s\n%s\n", lines[i].c_str(), i + 1 < work.size() ? work[i].c_str() : "");
    std::printf("%s\n", work.back().c_str());
    return kExitOk;
  }
  const std::vector<ib::StudyPart> parts = ib::place_study_parts(study.parts, settings);
  std::vector<const ib::SuiteSettings*> suites;
  std::vector<const ib::SweepSettings*> sweeps;
  for (const ib::StudyPart& part : parts)
    if (const auto* suite = std::get_if<ib::SuiteSettings>(&part.settings))
      suites.push_back(suite);
    else if (const auto* sweep = std::get_if<ib::SweepSettings>(&part.settings))
      sweeps.push_back(sweep);
  std::fprintf(stderr, "study: %s, %zu suites and searches into %s, %zu sweeps into %s/sweeps/, %zu other parts\n",
               o.file.c_str(), suites.size(), o.out.c_str(), sweeps.size(), o.out.c_str(),
               parts.size() - suites.size() - sweeps.size());
  // the report names the commands that produced its folder: each suite or search part as one
  for (const ib::StudyPart& part : parts)
    if (const auto* suite = std::get_if<ib::SuiteSettings>(&part.settings))
      record_command(o.out, suite->measurement.verdicts, o.file + ": " + part.name);
  const ib::StudyOutcome outcome = ib::run_study(study.parts, settings);
  // each part says how it ended; the study ends as the worst of them (one rule: harness/jobs/campaign_folder.h)
  if (outcome.suites) suite_exit_code(*suites.front(), *outcome.suites);
  for (std::size_t i = 0; i < sweeps.size(); ++i) sweep_exit_code(*sweeps[i], outcome.sweeps[i].outcome);
  std::size_t other = 0;
  for (const ib::StudyPart& part : parts)
    if (const auto* own = std::get_if<std::shared_ptr<const ib::PartOfItsOwnKind>>(&part.settings)) {
      const ib::CampaignEnd& end = outcome.others.at(other++).end;
      std::printf("%s \"%s\": recorded in %s, %d unstable or failed there%s\n", (*own)->kind().c_str(),
                  part.name.c_str(), ib::folder_of(**own, part.name, settings).c_str(), end.not_ok_recorded,
                  end.interrupted_by || end.units_stopped ? " (stopped early: --resume continues)" : "");
    }
  const ib::CampaignResult result = ib::result_of(outcome);
  const int status = exit_code(result);
  if (result.status == ib::CampaignStatus::stopped) return status;  // interrupted: no report of a part of it
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
  study->add_option("--skip", o->skip, "kinds of parts left out, comma-separated: suite, search, sweep, validation");
  study->add_flag("--no-report", o->no_report, "leave the report out");
  study->add_flag("--plan", o->plan,
                  "check the file and print what each part runs, its runs and their estimated CPU time; run nothing");
  return {study, [o] { return command_study(*o); }};
}

}  // namespace cli
