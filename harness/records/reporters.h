// Reporters: turn run records into files. They read records and nothing else, so a new output
// format touches nothing but this module.
#pragma once

#include <set>
#include <string>
#include <vector>

#include "harness/records/run_record.h"

namespace ib {

// runs.csv: a header line, then one row per run (values with full precision; NaN as empty).
std::string csv_header(const RunRecord& record);
std::string csv_row(const RunRecord& record);

// runs.jsonl: one compact JSON object per line; summary.json: the same, indented. NaN is null.
std::string json_line(const RunRecord& record);
void write_summary_json(const std::string& path, const RunRecord& record);

// Appends one run to DIR/runs.jsonl and DIR/runs.csv (writing the header first if the file is new),
// flushed at once, so that nothing finished is lost. Throws OutputError (run_files.h) naming the file. (A row a
// job's own process rendered is collected by the recorder, jobs/recorder.h.)
void append_run(const std::string& folder, const RunRecord& record);

// For --resume: runs.jsonl is the record of what finished. One record per job, always: drops a line a
// kill cut short, a line with a value of the wrong type, a record whose run folder is gone, a job
// recorded twice with other values (all its lines) and a repeated identical line (kept once), says so in
// `repairs`, rewrites runs.csv from runs.jsonl (so the two agree whatever moment the kill came), and
// returns the job ids recorded. A dropped job runs again. Empty when there is no runs.jsonl; throws
// std::runtime_error when runs.jsonl is gone but runs.csv holds rows.
std::set<std::string> repair_and_list_runs(const std::string& folder, std::vector<std::string>* repairs = nullptr);
// Removes these jobs' records (runs.jsonl, runs.csv) and run folders: the rows of a scenario file that
// could not be read, once it can.
void drop_runs(const std::string& folder, const std::set<std::string>& job_ids);
// The same checks without changing anything (merge refuses a damaged shard): the problems found.
std::vector<std::string> runs_table_problems(const std::string& folder);

}  // namespace ib
