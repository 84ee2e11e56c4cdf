// steps.csv and steps.jsonl (step_search.h): one row per step-search group, written as each search ends,
// found again by its key on --resume, repaired after a kill through the one path of jsonl_table.h.
#include "harness/suite/step_search.h"

#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "harness/records/jsonl_table.h"
#include "harness/records/number_text.h"
#include "harness/records/run_files.h"
#include "harness/records/run_record.h"
#include "harness/scoring/metric_catalog.h"

namespace ib {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
using Json = nlohmann::ordered_json;

// The runs.csv name of each metric's error against a reference (the metric catalog's error_column).
std::string error_name(HeadlineMetric m) { return scored_metric(to_string(m)).error_column; }

double number_or_nan(const Json& j, const std::string& name) {
  return j.contains(name) && j[name].is_number() ? j[name].get<double>() : kNaN;
}

std::string text_or_empty(const Json& j, const std::string& name) {
  return j.contains(name) && j[name].is_string() ? j[name].get<std::string>() : "";
}

std::vector<Field> step_fields(const StepRow& row) {
  const StepGroup& g = row.group;
  const StepSearchSettings& s = row.settings;
  std::vector<Field> out = {
      {"group_id", g.group_id},
      {"scenario", g.scenario},
      {"law", g.law},
      {"engine", g.engine},
      {"options", g.options},
      {"contact_path", contact_path_of(g.engine, g.options)},  // runs.csv's columns (run_record.h)
      {"law_simulated", law_simulated_of(g.engine, contact_path_of(g.engine, g.options))},
      {"chain_links", static_cast<double>(g.chain_links)},
      {"accuracy_reference", g.accuracy_reference},
      {"step_range_min_s", s.min_step_s, true},
      {"step_range_max_s", s.max_step_s, true},
      {"grid_points_per_octave", static_cast<double>(s.points_per_octave)},
      {"search", s.walk ? "walk" : "bisection"},  // a walk down the grid (a front's ladder), or a bisection
  };
  const StepSearch* search = row.search;
  const auto stability = search ? search->stability() : StepSearch::Outcome{"", kNaN, kNaN, kNaN, kNaN};
  out.push_back({"largest_stable_step_s", stability.largest_pass_step_s, true});
  out.push_back({"smallest_unstable_step_s", stability.smallest_fail_step_s, true});
  out.push_back({"stability_status", stability.status});
  for (HeadlineMetric m : kHeadlineMetrics) {
    const std::string name = to_string(m), error = error_name(m);
    const auto a = search ? search->accuracy(m) : StepSearch::Outcome{"", kNaN, kNaN, kNaN, kNaN};
    out.push_back({error + "_tolerance", tolerance_of(s.tolerance, m), true});
    out.push_back({name + "_largest_step_within_tolerance_s", a.largest_pass_step_s, true});
    out.push_back({name + "_smallest_step_beyond_tolerance_s", a.smallest_fail_step_s, true});
    out.push_back({error + "_at_largest_step", a.error_at_largest_pass});
    out.push_back({error + "_vs_beam_reference_at_largest_step", a.beam_error_at_largest_pass});
    out.push_back({name + "_status", a.status});
  }
  std::string notes;
  if (search)
    for (const std::string& n : search->notes()) notes += (notes.empty() ? "" : "; ") + n;
  out.push_back({"probes", search ? static_cast<double>(search->probes()) : 0.0});
  out.push_back({"probes_wall_time_s", search ? search->probes_wall_time_s() : 0.0});
  out.push_back({"probe_outcomes", search ? search->probe_list() : ""});
  out.push_back({"notes", notes});
  return out;
}

// The key's numbers exactly: a row is found again only under the same range and tolerances.
std::string key_text(const std::string& group_id, double min_s, double max_s, double points, bool walk,
                     const std::vector<double>& tolerances) {
  std::string key =
      group_id + "|" + exact_number_text(min_s) + "|" + exact_number_text(max_s) + "|" + exact_number_text(points);
  if (walk) key += "|walk";
  for (double t : tolerances) key += "|" + exact_number_text(t);
  return key;
}

}  // namespace

// ---- steps.csv and steps.jsonl ----------------------------------------------------------------------

std::string steps_csv_header() {
  return csv_header_line(step_fields(StepRow{StepGroup{}, StepSearchSettings{}, nullptr}));
}

std::string steps_csv_row(const StepRow& row) { return csv_row_line(step_fields(row)); }

std::string steps_json_line(const StepRow& row) { return json_object(step_fields(row)).dump() + "\n"; }

void append_step_row(const std::string& folder, const StepRow& row) {
  append_table_row(folder + "/steps.jsonl", folder + "/steps.csv", steps_csv_header(), steps_csv_row(row),
                   steps_json_line(row));
}

std::string step_row_key(const StepGroup& group, const StepSearchSettings& s) {
  std::vector<double> tolerances;
  for (HeadlineMetric m : kHeadlineMetrics) tolerances.push_back(tolerance_of(s.tolerance, m));
  return key_text(group.group_id, s.min_step_s, s.max_step_s, s.points_per_octave, s.walk, tolerances);
}

RecordedStepRow read_step_row(const std::string& json_line) {
  const Json j = Json::parse(json_line, nullptr, /*allow_exceptions=*/false);
  RecordedStepRow row;
  if (!j.is_object() || !j.contains("notes")) return row;  // "notes" is the last column: a whole row
  std::vector<double> tolerances;
  for (HeadlineMetric m : kHeadlineMetrics)
    tolerances.push_back(number_or_nan(j, std::string(error_name(m)) + "_tolerance"));
  row.readable = true;
  row.group_id = text_or_empty(j, "group_id");
  row.key = key_text(row.group_id, number_or_nan(j, "step_range_min_s"), number_or_nan(j, "step_range_max_s"),
                     number_or_nan(j, "grid_points_per_octave"), text_or_empty(j, "search") == "walk", tolerances);
  return row;
}

std::set<std::string> repair_and_list_step_rows(const std::string& folder) {
  const std::vector<std::string> columns =
      column_names(step_fields(StepRow{StepGroup{}, StepSearchSettings{}, nullptr}));
  const auto key_of = [](const std::string& line, std::string&) { return read_step_row(line).key; };
  return repair_jsonl_table(folder + "/steps.jsonl", folder + "/steps.csv", columns, key_of);
}

}  // namespace ib
