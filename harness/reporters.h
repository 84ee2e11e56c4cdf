// Reporters: turn run records into files. They read records and nothing else, so a new output
// format touches nothing but this module.
#pragma once

#include <set>
#include <string>

#include "harness/run_record.h"

namespace ib {

// runs.csv: a header line, then one row per run (values with full precision; NaN as empty).
std::string csv_header(const RunRecord& record);
std::string csv_row(const RunRecord& record);

// runs.jsonl: one compact JSON object per line; summary.json: the same, indented. NaN is null.
std::string json_line(const RunRecord& record);
void write_summary_json(const std::string& path, const RunRecord& record);

// Appends one run to DIR/runs.jsonl and DIR/runs.csv (writing the header first if the file is new),
// flushed at once, so that nothing finished is lost. Throws OutputError (run_files.h) naming the file.
void append_run(const std::string& folder, const RunRecord& record);
// The same with the row and line already rendered (by a job's own process).
void append_rows(const std::string& folder, const std::string& csv_row_text, const std::string& json_line_text);

// For --resume: runs.jsonl is the record of what finished. Drops a line a kill cut short, rewrites
// runs.csv from runs.jsonl (so the two agree whatever moment the kill came), and returns the job ids
// recorded. Empty when there is no runs.jsonl.
std::set<std::string> repair_and_list_runs(const std::string& folder);

}  // namespace ib
