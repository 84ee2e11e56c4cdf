// How the result files write numbers (with the digits the data holds) and text cells, in one place for
// every writer (runs.csv, runs.jsonl, summary.json, steps.csv, series and events files).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace ib {

// A measured or derived value: 9 significant digits ("%.9g"), more than any metric here resolves
// (solver tolerances are 1e-9 relative at best) and half the text of 17 digits; an integer (a count)
// whole. "" when not finite.
std::string number_text(double value);

// A value that locates something (a sample time, an onset): the shortest text that reads back as the
// same double, so that a sample written and read back lies exactly on its grid. "" when not finite.
std::string exact_number_text(double value);

// A value for a JSON record: null when not finite, an integer when it is one (counts, steps), else
// rounded to number_text's 9 digits (nlohmann writes the shortest text of the rounded double); with
// exact, the value itself (a setting or a time step: read back, it is the same step).
nlohmann::ordered_json json_number(double value, bool exact = false);

// A text cell of a CSV file: as it is, or quoted (with "" for ") when it holds a comma, a quote or a
// line break (RFC 4180), so that a reason such as "off by 12 %; ..." stays one cell.
std::string csv_escape(const std::string& text);

}  // namespace ib
