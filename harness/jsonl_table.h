// A results table kept twice: as JSON lines, the record every reader and --resume trusts, and as CSV
// for people and spreadsheets (runs.jsonl / runs.csv, steps.jsonl / steps.csv). Both are appended to as
// results arrive; after a kill the one repair path below makes them whole again.
#pragma once

#include <functional>
#include <set>
#include <string>
#include <vector>

namespace ib {

// Drops every line of `jsonl_path` that `key_of` gives no key for (a line a kill cut short, or one that
// is not a record of this table), rewrites the CSV from the lines kept, laid out by `columns` (the
// header's names, whatever the order or the gaps of a line's keys; each number as its shortest exact
// text, which holds the digits the record was written with), and returns the keys. A missing file is
// an empty table; one that cannot be read throws std::runtime_error naming it.
std::set<std::string> repair_jsonl_table(const std::string& jsonl_path, const std::string& csv_path,
                                         const std::vector<std::string>& columns,
                                         const std::function<std::string(const std::string& line)>& key_of);

}  // namespace ib
