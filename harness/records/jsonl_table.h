// A results table kept twice: as JSON lines, the record every reader and --resume trusts, and as CSV
// for people and spreadsheets (runs.jsonl / runs.csv, steps.jsonl / steps.csv). Both are written by the
// one writer below, from a row laid out as named fields, and appended to as results arrive; after a
// kill the one repair path below makes them whole again.
#pragma once

#include <functional>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

namespace ib {

// One cell of a row: every row of a table yields the same names in the same order.
struct Field {
  std::string name;                         // with its unit, e.g. "frame1_sensor_peak_acceleration_g"
  std::variant<std::string, double> value;  // NaN: not applicable or not measured
  bool exact = false;                       // a setting (a time step, a window): written with every digit it has
};

std::vector<std::string> column_names(const std::vector<Field>& row);
// The CSV header and a CSV row, each with its line break: text escaped (csv_escape), numbers as
// number_text, or exact_number_text when exact; NaN as an empty cell.
std::string csv_header_line(const std::vector<Field>& row);
std::string csv_row_line(const std::vector<Field>& row);
// The row as a JSON object in column order: numbers as json_number (NaN is null).
nlohmann::ordered_json json_object(const std::vector<Field>& row);

// The keys whose values differ between two records (a key in one only counts), `ignored` aside,
// comma-separated in the first record's order: what a refused --resume names (a suite's or a sweep's).
std::string differing_keys(const nlohmann::ordered_json& a, const nlohmann::ordered_json& b,
                           const std::set<std::string>& ignored = {});

// Appends one row: its JSON line to `jsonl_path` first (the record), then its CSV row to `csv_path`,
// with `csv_header` before it when the CSV is new or empty; each flushed at once, so that nothing
// finished is lost. Throws OutputError (run_files.h) naming the file.
void append_table_row(const std::string& jsonl_path, const std::string& csv_path, const std::string& csv_header,
                      const std::string& csv_row, const std::string& json_line);

// A record's key, or "" with why the line is not a whole record of this table: a line a kill cut short,
// a value of the wrong type, a run folder that is gone. One record per key, always.
using KeyOf = std::function<std::string(const std::string& line, std::string& problem)>;

// The table as read: its whole records in order, one per key, and what was wrong with the others. A key
// on several identical lines is kept once; a key on lines that disagree is kept on none (which of them
// is the job's result cannot be told). A missing JSONL is an empty table, unless the CSV beside it holds
// rows (the record is gone, the copy is not: std::runtime_error, so that nothing runs twice); a file
// that cannot be read throws std::runtime_error naming it.
struct JsonlTable {
  std::vector<std::pair<std::string, std::string>> records;  // (key, line)
  std::vector<std::string> problems;                         // "<file> line N: <what>; <what was done>"
};
JsonlTable scan_jsonl_table(const std::string& jsonl_path, const std::string& csv_path, const KeyOf& key_of);

// Keeps only the whole records (scan_jsonl_table), rewrites the CSV from them, laid out by `columns` (the
// header's names, whatever the order or the gaps of a line's keys; each number as its shortest exact
// text, which holds the digits the record was written with), and returns the keys; `repairs` (when
// given) gets what was dropped and why. A dropped record's job runs again.
std::set<std::string> repair_jsonl_table(const std::string& jsonl_path, const std::string& csv_path,
                                         const std::vector<std::string>& columns, const KeyOf& key_of,
                                         std::vector<std::string>* repairs = nullptr);

}  // namespace ib
