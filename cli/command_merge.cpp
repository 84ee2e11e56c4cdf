#include "cli/commands.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "harness/records/engines_file.h"
#include "harness/records/run_files.h"
#include "harness/study/merge.h"
#include "simulators/catalog.h"

namespace cli {

namespace {

struct MergeOptions {
  std::string out;
  std::vector<std::string> shards;
  bool no_report = false;
};

// The shards' folders joined into one suite folder (harness/study/merge.h), then its report, made as `report` makes it.
int command_merge(const std::string& out, const std::vector<std::string>& shards, bool no_report) {
  const ib::MergeOutcome outcome = ib::merge_suites(ib::MergeSettings{shards, out});
  // The engines that made the results (engines.json): a shard's, which every shard of one suite writes
  // alike; this binary's only when no shard has one (shards of an older build).
  namespace fs = std::filesystem;
  const auto made_by =
      std::find_if(shards.begin(), shards.end(), [](const std::string& s) { return fs::exists(s + "/engines.json"); });
  const auto copy_from_shard = [&out](const std::string& shard, const std::string& name) {
    std::error_code error;
    fs::copy_file(shard + "/" + name, out + "/" + name, fs::copy_options::overwrite_existing, error);
    if (error)
      throw ib::OutputError(ib::output_error_text(out + "/" + name, "copy " + shard + "/" + name, error.value()));
  };
  if (made_by == shards.end())
    ib::write_engines_file(out, ib::simulator_catalog());
  else
    copy_from_shard(*made_by, "engines.json");
  // Where they were made (provenance.json): the first shard's that has one, never this binary's (the merge
  // made no result). Shards of one suite come from one build; their machines may differ.
  const auto described = std::find_if(shards.begin(), shards.end(),
                                      [](const std::string& s) { return fs::exists(s + "/provenance.json"); });
  if (described != shards.end()) copy_from_shard(*described, "provenance.json");
  // The metrics they were scored on (metrics.json): a shard's; none when no shard has one (shards of a build
  // before metrics.json, which the report reads with its catalog of those folders).
  const auto scored =
      std::find_if(shards.begin(), shards.end(), [](const std::string& s) { return fs::exists(s + "/metrics.json"); });
  if (scored != shards.end()) copy_from_shard(*scored, "metrics.json");
  if (std::filesystem::exists(out + "/sweep.json"))
    std::printf("merge: %d sweep rows in %s/sweep.csv from %zu folders\n", outcome.runs, out.c_str(), shards.size());
  else
    std::printf(
        "merge: %d runs in %s/runs.csv from %zu folders (%d recorded in several, such as the references, kept once)\n",
        outcome.runs, out.c_str(), shards.size(), outcome.runs_in_several);
  if (outcome.step_rows > 0) std::printf("merge: %d step searches in %s/steps.csv\n", outcome.step_rows, out.c_str());
  std::fflush(stdout);
  for (const std::string& line : ib::merge_messages(outcome)) std::fprintf(stderr, "impactbench: %s\n", line.c_str());
  if (!no_report) command_report(out, "");
  if (outcome.complete()) return kExitOk;
  std::fprintf(stderr,
               "impactbench: merged what exists, but shards are incomplete or absent (see above; exit code %d)\n",
               kExitIncompleteMerge);
  return kExitIncompleteMerge;
}

}  // namespace

Command add_merge_command(CLI::App& app) {
  auto o = std::make_shared<MergeOptions>();
  CLI::App* merge = app.add_subcommand("merge",
                                       "join the folders of a suite's shards (suite --shard K/N) into one "
                                       "suite folder, then make its report");
  merge->add_option("out", o->out, "a new or empty folder for the joined suite")->required();
  merge->add_option("shards", o->shards, "the shards' folders")->required();
  merge->add_flag("--no-report", o->no_report, "join only; make the report later with 'report OUT'");
  return {merge, [o] { return command_merge(o->out, o->shards, o->no_report); }};
}

}  // namespace cli
