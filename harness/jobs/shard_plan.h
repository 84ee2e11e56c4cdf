// A suite divided over several machines (suite --shard K/N, e.g. a Slurm job array): shard K runs every
// N-th unit of work of the suite, counted in the suite's planned order (deterministic for the same
// inputs), plus the references those units are compared with, so that each shard's folder is a
// complete suite result of its own. Units: the jobs that cannot run (a malformed scenario, a law it
// lacks), then the engine jobs (with --find-steps: the step-search groups); a suite of references
// alone divides its references. Each shard's folder keeps its plan in DIR/shard.jsonl, one line per
// suite command run into it, so that `impactbench merge` (merge.h) can tell a finished shard from one
// that stopped early and say how to finish it.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace ib {

struct Shard {
  int index = 1;  // this shard's number, 1 .. count (1-based, as Slurm's --array=1-N numbers tasks)
  int count = 1;  // the number of shards the suite is divided into
  bool operator==(const Shard& other) const { return index == other.index && count == other.count; }
  bool operator!=(const Shard& other) const { return !(*this == other); }
};

// "K/N", as --shard takes it.
std::string to_string(const Shard& shard);

// "K/N" as the command line takes it; throws std::invalid_argument naming --shard, the value and what is allowed.
Shard parse_shard(const std::string& text);
// Whether unit `unit` (0-based, in planned order) belongs to `shard`: every count-th unit, from index - 1.
bool in_shard(std::size_t unit, const Shard& shard);

struct ShardPlan {
  Shard shard;
  std::string suite;                       // a digest of the whole suite's plan: equal in every shard of one suite
  std::vector<std::string> jobs;           // the job ids this shard records in runs.jsonl (references included)
  std::vector<std::string> step_searches;  // the keys (step_row_key) of the rows it records in steps.jsonl
  std::string resume_command;              // the command that finishes this shard (with --resume)
};

// The digest of a suite's planned job ids and step-search keys (FNV-1a, 64 bits, as 16 hex digits).
std::string plan_digest(const std::vector<std::string>& planned);

// The digest of a file's bytes (plan_digest of its text), "unreadable" when it cannot be read: what a suite's
// settings and a run's record keep of its scenario file, so that another file of the same name is told apart.
std::string file_digest(const std::string& path);

// Appends `plan` to DIR/shard.jsonl unless a line for the same suite and shard is there already (a
// --resume). Throws OutputError (run_files.h) naming the file.
void record_shard_plan(const std::string& folder, const ShardPlan& plan);
// The plans in DIR/shard.jsonl, in order; none when there is no such file. A line that is not a plan
// (damage: the file is replaced whole, never cut) throws std::runtime_error naming the file and line.
std::vector<ShardPlan> read_shard_plans(const std::string& folder);

}  // namespace ib
