// The recorder: how the results of a campaign's units reach its tables, for suites and sweeps alike. A unit's
// process leaves its row in its own folder (runs/ID/); only the campaign's process writes the tables, so that a
// unit killed while writing leaves no half row in them. It writes them in one of two orders:
//  - as the units end (a suite's runs.jsonl and runs.csv): a finished unit's row is appended and its row files
//    removed; the JSON lines are the record --resume trusts (jsonl_table.h repairs them after a kill);
//  - in the plan's order (a sweep's sweep.jsonl, sweep.csv and poincare.csv): the tables are written again from
//    the unit folders, whose row files stay the record, one row per unit whatever interruptions, resumes or shards
//    produced them.
#pragma once

#include <string>
#include <vector>

namespace ib {

// A table of DIR: NAME.jsonl and NAME.csv ("runs", "sweep").
struct ResultTable {
  std::string dir;
  std::string name;
  std::string jsonl_path() const { return dir + "/" + name + ".jsonl"; }
  std::string csv_path() const { return dir + "/" + name + ".csv"; }
};

// As the units end. The row a finished unit left in UNIT_FOLDER (its process wrote row.jsonl and row.csv, the
// CSV row laid out under csv_header) appended to the table, then its row files removed. Returns the JSON line,
// "" when the unit left none. Throws OutputError (run_files.h) naming a table that cannot be written.
std::string collect_row(const ResultTable& table, const std::string& csv_header, const std::string& unit_folder);
// The row files a unit's process leaves (a row collected, or one written again by a rerun).
void remove_row_files(const std::string& unit_folder);

// In the plan's order. The table written again from UNIT_FOLDERS, in their order: each one's ROW_FILE holds its
// row as a JSON object (a folder without one is left out). The CSV's columns are the first row's keys whose values
// are not lists or objects (a list, a row's warnings, is in the JSON lines alone: a CSV cell holds one value);
// each file of SAMPLE_FILES (CSV files a row may leave beside its row, poincare.csv) becomes DIR's file of that
// name, the rows' files under the first one's header. Returns the rows written. Throws std::runtime_error naming a
// row file that is not a JSON object, OutputError a file that cannot be written.
int write_table_in_plan_order(const ResultTable& table, const std::vector<std::string>& unit_folders,
                              const std::string& row_file, const std::vector<std::string>& sample_files);

}  // namespace ib
