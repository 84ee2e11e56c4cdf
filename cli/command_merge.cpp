#include "cli/commands.h"

#include <cstdio>
#include <filesystem>

#include "harness/merge.h"

namespace cli {

// The shards' folders joined into one suite folder (harness/merge.h), then its report, made as `report` makes it.
int command_merge(const std::string& out, const std::vector<std::string>& shards, bool no_report) {
  const ib::MergeOutcome outcome = ib::merge_suites(ib::MergeSettings{shards, out});
  if (std::filesystem::exists(out + "/sweep.json"))
    std::printf("merge: %d sweep rows in %s/sweep.csv from %zu folders\n", outcome.runs, out.c_str(), shards.size());
  else
    std::printf("merge: %d runs in %s/runs.csv from %zu folders (%d recorded in several, such as the references, kept once)\n",
              outcome.runs, out.c_str(), shards.size(), outcome.runs_in_several);
  if (outcome.step_rows > 0) std::printf("merge: %d step searches in %s/steps.csv\n", outcome.step_rows, out.c_str());
  std::fflush(stdout);
  for (const std::string& line : ib::merge_messages(outcome)) std::fprintf(stderr, "impactbench: %s\n", line.c_str());
  if (!no_report) command_report(out, "");
  if (outcome.complete()) return kExitOk;
  std::fprintf(stderr, "impactbench: merged what exists, but shards are incomplete or absent (see above; exit code %d)\n",
               kExitIncompleteMerge);
  return kExitIncompleteMerge;
}

}  // namespace cli
