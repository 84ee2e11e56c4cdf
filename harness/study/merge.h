// `impactbench merge OUT SHARD_FOLDER ...`: joins the folders of a suite's shards (suite --shard K/N,
// shard_plan.h) into one suite folder, as if the suite had run on one machine: runs.jsonl and runs.csv
// with one record per job id, the runs/<job id>/ folders (files hard-linked where the file system
// allows, copied otherwise), steps.jsonl and steps.csv. A job recorded in several folders (the
// references every shard runs for its own jobs) is kept once, and only if its records agree in every
// field but the timing ones. The shards' folders are only read. A shard that did not record all its
// plan (a failed or unfinished array task), or a shard of a suite that none of the folders holds, is
// reported with what it lacks and the command that finishes it; what exists is joined all the same.
#pragma once

#include <string>
#include <vector>

#include "harness/jobs/shard_plan.h"

namespace ib {

struct MergeSettings {
  std::vector<std::string> inputs;  // the shards' folders (any suite's folder is accepted)
  std::string out;                  // a new or empty folder
};

// A shard whose folder lacks some of its planned results.
struct IncompleteShard {
  std::string folder;
  Shard shard;
  int jobs_planned = 0, jobs_missing = 0;
  int step_searches_planned = 0, step_searches_missing = 0;
  std::string resume_command;  // what finishes it
};

// Shards first .. last of a suite's N that none of the folders given holds (their tasks failed before
// they began): a range, so that a large array that did not start is one line.
struct AbsentShards {
  int first = 1, last = 1, count = 1;
  std::string sibling_command;  // how another shard of the same suite was run
};

struct MergeOutcome {
  int runs = 0;             // records in OUT/runs.jsonl
  int runs_in_several = 0;  // of which recorded in more than one folder (and equal there)
  int step_rows = 0;        // rows in OUT/steps.jsonl
  std::vector<IncompleteShard> incomplete;
  std::vector<AbsentShards> absent;
  std::vector<std::string> without_plan;  // folders not made with --shard: joined, completeness not checked
  bool complete() const { return incomplete.empty() && absent.empty(); }
};

// Joins the folders into settings.out. Shards of a sweep (sweep --shard K/N, sweep.h) are joined as a sweep:
// their row folders, then sweep.jsonl, sweep.csv and poincare.csv in the plan's order (runs: its rows). Throws
// std::runtime_error before writing anything for bad input, naming the folder or file: a folder that does not exist or
// holds no suite, one given twice, an OUT that is not empty, a runs.csv or steps.csv header other than this build's,
// two records of one job that differ in a field other than timing. Throws OutputError (run_files.h) when OUT cannot be
// written.
MergeOutcome merge_suites(const MergeSettings& settings);

// One line per incomplete shard, per range of absent shards and per folder without a plan, saying what to do.
std::vector<std::string> merge_messages(const MergeOutcome& outcome);

}  // namespace ib
