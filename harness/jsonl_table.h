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
  std::string name;                    // with its unit, e.g. "frame1_sensor_peak_acceleration_g"
  std::variant<std::string, double> value;  // NaN: not applicable or not measured
  bool exact = false;                  // a setting (a time step, a window): written with every digit it has
};

std::vector<std::string> column_names(const std::vector<Field>& row);
// The CSV header and a CSV row, each with its line break: text escaped (csv_escape), numbers as
// number_text, or exact_number_text when exact; NaN as an empty cell.
std::string csv_header_line(const std::vector<Field>& row);
std::string csv_row_line(const std::vector<Field>& row);
// The row as a JSON object in column order: numbers as json_number (NaN is null).
nlohmann::ordered_json json_object(const std::vector<Field>& row);

// Appends one row: its JSON line to `jsonl_path` first (the record), then its CSV row to `csv_path`,
// with `csv_header` before it when the CSV is new or empty; each flushed at once, so that nothing
// finished is lost. Throws OutputError (run_files.h) naming the file.
void append_table_row(const std::string& jsonl_path, const std::string& csv_path, const std::string& csv_header,
                      const std::string& csv_row, const std::string& json_line);

// Drops every line of `jsonl_path` that `key_of` gives no key for (a line a kill cut short, or one that
// is not a record of this table), rewrites the CSV from the lines kept, laid out by `columns` (the
// header's names, whatever the order or the gaps of a line's keys; each number as its shortest exact
// text, which holds the digits the record was written with), and returns the keys. A missing file is
// an empty table; one that cannot be read throws std::runtime_error naming it.
std::set<std::string> repair_jsonl_table(const std::string& jsonl_path, const std::string& csv_path,
                                         const std::vector<std::string>& columns,
                                         const std::function<std::string(const std::string& line)>& key_of);

}  // namespace ib
